// temp_files.h — temporary output files, removed when the process is ended
// by SIGINT, SIGTERM or SIGHUP.
//
// Every temporary file an output is staged in (image_io.cpp) is a LiveTemp:
// created with the three signals blocked in the creating thread and listed
// in a fixed table before they are unblocked, and listed until it is renamed
// into place or removed. The signal handler (installed when a file is
// listed, for each signal whose action is the default, so a program that
// handles these signals itself, like Python's SIGINT, keeps its own) marks
// the process as ending, waits for any thread between creating and listing
// a file, unlinks every listed file (only async-signal-safe calls), then
// ends the process by the same signal with its default action.
#pragma once

#include <cstddef>
#include <string>

namespace clr {

// How many temporary files may be live at once (the PNG writer's threads
// and one command's outputs need a handful); more is a clr::Error.
inline constexpr size_t kMaxLiveTemps = 64;

class LiveTemp {
 public:
  // Creates target + ".tmp-XXXXXX" (mode 0600, open: fd()) and lists it; a
  // failure is a clr::Error "TARGET: cannot write (reason)".
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
