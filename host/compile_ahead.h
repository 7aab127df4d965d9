// compile_ahead.h — kernels compiled ahead, in a helper process.
//
// PoCL compiles each kernel at its first launch, and one kernel at a time
// per process (a process-wide lock around its code generation), so a cold
// start compiles setup, the scan, raster and resolve in turn on one core
// while the others wait. A ClContext given a CompileAheadRequest starts,
// before anything else, a helper: this executable as `clraster
// __compile-ahead`, which selects the same device, builds the same program
// with the same options in its own process and launches the named kernels
// once each on an empty one-tile frame (compileKernelsAhead), writing each
// kernel's name to a pipe once it has run. PoCL keeps their machine code in
// its kernel cache, keyed by program, options and work-group size, where the
// parent's first launches of the same kernels find it. Before its first
// launch of a named kernel the parent waits until the helper has named it
// (await); it compiles the others itself meanwhile.
//
// Nothing depends on the helper. If it cannot start, fails, or keeps the
// parent waiting longer than the parent's own build took (and half a second
// more), the parent stops it and its launches compile what the cache lacks,
// as without it; the pixels are the same either way. Where the parent's
// build was quick (CompileAheadRequest::warmBuildMs: the program came from
// PoCL's cache, and so will the kernels), it stops the helper at once. A
// helper starts only with CLRASTER_COMPILE_AHEAD and POCL_KERNEL_CACHE not 0
// and at least two cores, and it stays (in both processes, once each has
// chosen the device) only where it can help: on a PoCL CPU device in the CPU
// work shape (lanes 16).
#pragma once

#include <set>
#include <string>
#include <sys/types.h>
#include <vector>

namespace clr {

struct DeviceInfo;
struct ClContext;

// What ClContext asks a helper to compile (no kernels: no helper).
struct CompileAheadRequest {
  std::string executable;            // this program, run as `EXECUTABLE __compile-ahead ...`
  std::vector<std::string> kernels;  // frame-program kernels (compileKernelsAhead), in this order
  // A program build quicker than this found the program in PoCL's cache
  // (and so will the kernels be found), and stops the helper; tests set 0
  // to keep one with a warm cache.
  double warmBuildMs = 250;
};

class CompileAhead {
 public:
  enum class State { off, running, succeeded, failed, stopped };

  // Starts the helper for the device `selector` picks (selectDevice) and the
  // work shape (contextLanes), unless the request names no kernel or the
  // environment rules a helper out (header); a failure to start leaves the
  // state failed.
  CompileAhead(const CompileAheadRequest& request, const std::string& selector, int lanesOverride);
  CompileAhead(const CompileAhead&) = delete;
  CompileAhead& operator=(const CompileAhead&) = delete;
  ~CompileAhead();  // stops and reaps a helper still running

  // Whether the environment allows a helper: the switches and the cores.
  static bool allowed();
  // Whether a helper would help on this device and work shape (header).
  static bool worthwhile(const DeviceInfo& device, int lanes);
  // The parent chose the device and work shape: stops a helper that would
  // not help there (the state then off).
  void deviceChosen(const DeviceInfo& device, int lanes);
  // The parent's own program build took buildMs: sets the bound on the
  // waits, or stops the helper after a warm build (header).
  void programBuilt(double buildMs);
  // Before a first launch of `kernel`: when the helper was asked for it,
  // waits until the helper has run it or has ended; at once otherwise.
  void await(const std::string& kernel);
  State state() const { return state_; }
  // The kernels the helper has run so far, and those of its kernels the
  // parent awaited before its first launch of them.
  const std::set<std::string>& ready() const { return ready_; }
  const std::set<std::string>& awaited() const { return awaited_; }

 private:
  // Reads the helper's lines until `kernel` is among them or the helper ends.
  void readUntil(const std::string& kernel);
  // Reaps the helper, stopping it first when `stop`, and sets the state;
  // with WNOHANG only if it has ended.
  void reap(bool stop, int options = 0);

  pid_t pid_ = -1;
  int pipe_ = -1;        // read end of the helper's standard output
  std::string pending_;  // a partial line read
  std::set<std::string> asked_, ready_, awaited_;
  double waitedMs_ = 0;         // over all awaits, at most waitLimitMs_
  double waitLimitMs_ = 20000;  // until programBuilt
  double warmBuildMs_ = 0;      // the request's
  State state_ = State::off;
};

// The helper's work: launches each named kernel of cl.program (scan_chunks,
// raster, resolve_lambert or resolve) once, in the work shape a frame
// launches it in, on an empty one-tile 16×16 frame (or a scan of nothing),
// waits for it, and calls ran(name). Throws clr::Error for another name or
// a failed launch.
void compileKernelsAhead(ClContext& cl, const std::vector<std::string>& kernels,
                         void (*ran)(const std::string& name) = nullptr);

// `clraster __compile-ahead --device SELECTOR --lanes N KERNEL...`: the
// helper process's command (main.cpp; N 0 for the default work shape). Where
// a helper would not help it ends at once with status 3; else it prints each
// kernel's name as it has run, then ends with status 0. Throws clr::Error on
// failure.
[[noreturn]] void compileAheadCommand(const std::vector<std::string>& args);

}  // namespace clr
