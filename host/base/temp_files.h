// temp_files.h — temporary output files, removed when SIGINT, SIGTERM or
// SIGHUP ends the process. Each is created with those signals blocked in
// its thread and listed in a fixed table until renamed or removed; the
// handler (installed for a signal whose action is the default) waits for
// threads between creating and listing, unlinks the listed files with
// async-signal-safe calls, then re-raises the signal with its default action.
#pragma once

#include <cstddef>
#include <string>

namespace clr {

// Live temporary files at once (the writer threads need a handful); more is a clr::Error.
inline constexpr size_t kMaxLiveTemps = 64;

class LiveTemp {
 public:
  // Creates and lists target + ".tmp-XXXXXX" (0600, open); else "TARGET: cannot write (reason)".
  explicit LiveTemp(const std::string& target);
  ~LiveTemp() { release(); }
  LiveTemp(const LiveTemp&) = delete;
  LiveTemp& operator=(const LiveTemp&) = delete;
  LiveTemp(LiveTemp&& o) noexcept : name_(std::move(o.name_)), fd_(o.fd_), slot_(o.slot_) { o.slot_ = kNone; }
  const std::string& name() const { return name_; }
  int fd() const { return fd_; }
  // Unlists the file (call after renaming or removing it; the destructor does).
  void release();

 private:
  static constexpr size_t kNone = ~size_t(0);
  std::string name_;
  int fd_ = -1;
  size_t slot_ = kNone;
};

}  // namespace clr
