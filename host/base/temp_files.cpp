// temp_files.cpp — the table of live temporary files and the signal handler
// that removes them (see temp_files.h).
#include "base/temp_files.h"

#include "base/error.h"

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <pthread.h>
#include <unistd.h>
#include <vector>

namespace clr {

namespace {

// A slot is free (0), being filled (1) or live (2): the handler unlinks
// only live slots, whose path is complete.
struct Slot {
  std::atomic<int> state{0};
  char path[PATH_MAX];
};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads slot states");

Slot g_slots[kMaxLiveTemps];
std::atomic<int> g_creating{0};  // threads between mkstemp and listing
std::atomic<int> g_ending{0};    // a handler runs: the process is ending
const int kSignals[] = {SIGINT, SIGTERM, SIGHUP};

void unlinkLive()
{
  for (Slot& s : g_slots)
    if (s.state.load() == 2) unlink(s.path);
}

void removeLiveTemps(int sig)
{
  g_ending.store(1);
  // A creating thread has the signals blocked, so it is not this one; it
  // lists its file within a few system calls (bounded wait all the same).
  for (int i = 0; i < 100000 && g_creating.load() > 0; ++i) {
    const timespec tick{0, 10000};
    nanosleep(&tick, nullptr);
  }
  unlinkLive();
  struct sigaction dfl = {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  raise(sig);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);  // the raised signal ends the process here
}

// The handler, for each signal whose action is the default; checked at
// every listing, so a child process that resets its signals gets it too.
void installHandlers()
{
  for (int sig : kSignals) {
    struct sigaction old = {};
    if (sigaction(sig, nullptr, &old) != 0 || (old.sa_flags & SA_SIGINFO) || old.sa_handler != SIG_DFL) continue;
    struct sigaction sa = {};
    sa.sa_handler = removeLiveTemps;
    sigemptyset(&sa.sa_mask);
    for (int other : kSignals) sigaddset(&sa.sa_mask, other);
    sigaction(sig, &sa, nullptr);
  }
}

}  // namespace

LiveTemp::LiveTemp(const std::string& target)
{
  const std::string suffix = ".tmp-XXXXXX";
  if (target.size() + suffix.size() >= PATH_MAX)
    throw Error(userText(target) + ": cannot write (" + std::strerror(ENAMETOOLONG) + ")");
  installHandlers();
  std::vector<char> name(target.begin(), target.end());
  name.insert(name.end(), suffix.begin(), suffix.end());
  name.push_back('\0');
  // Step 1: with the signals blocked here, create and list the file.
  sigset_t block, old;
  sigemptyset(&block);
  for (int sig : kSignals) sigaddset(&block, sig);
  pthread_sigmask(SIG_BLOCK, &block, &old);
  g_creating.fetch_add(1);
  fd_ = mkstemp(name.data());
  const int err = errno;
  if (fd_ >= 0)
    for (size_t k = 0; k < kMaxLiveTemps && slot_ == kNone; ++k) {
      int expected = 0;
      if (!g_slots[k].state.compare_exchange_strong(expected, 1)) continue;
      std::memcpy(g_slots[k].path, name.data(), name.size());
      g_slots[k].state.store(2);
      slot_ = k;
    }
  g_creating.fetch_sub(1);
  if (g_ending.load() && fd_ >= 0) unlink(name.data());  // a handler may have scanned before the listing
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  // Step 2: the failures.
  if (fd_ < 0) throw Error(userText(target) + ": cannot write (" + std::strerror(err) + ")");
  if (slot_ == kNone) {
    close(fd_);
    unlink(name.data());
    throw Error(userText(target) + ": cannot write (more than " + std::to_string(kMaxLiveTemps) +
                " temporary files at once)");
  }
  name_ = name.data();
}

void LiveTemp::release()
{
  if (slot_ == kNone) return;
  g_slots[slot_].state.store(0);
  slot_ = kNone;
}

}  // namespace clr
