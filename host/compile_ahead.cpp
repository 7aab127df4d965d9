// compile_ahead.cpp — the helper process that compiles kernels ahead (see
// compile_ahead.h for the contract): its start and the waits in the parent,
// its launches in the helper.
#include "compile_ahead.h"

#include "device.h"
#include "pipeline.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace clr {

bool CompileAhead::allowed()
{
  const char* off = std::getenv("CLRASTER_COMPILE_AHEAD");
  const char* cache = std::getenv("POCL_KERNEL_CACHE");
  return !(off && std::strcmp(off, "0") == 0) && !(cache && std::strcmp(cache, "0") == 0) &&
         std::thread::hardware_concurrency() >= 2;
}

bool CompileAhead::worthwhile(const DeviceInfo& device, int lanes)
{
  return allowed() && device.type == "CPU" && isPocl(device) && lanes == CLR_TILE_SIZE;
}

CompileAhead::CompileAhead(const CompileAheadRequest& request, const std::string& selector, int lanesOverride)
{
  if (request.kernels.empty() || request.executable.empty() || !allowed()) return;
  // Step 1: the command line. The helper selects the device as the parent
  // does, from the same selector and environment, so it starts at once,
  // while the parent still loads the OpenCL platforms (a spawn after the
  // parent's device selection started the helper's build 0.15-0.2 s behind
  // the parent's on the development machine).
  std::vector<std::string> args = {request.executable, "__compile-ahead", "--device",
                                   selector,           "--lanes",         std::to_string(lanesOverride)};
  args.insert(args.end(), request.kernels.begin(), request.kernels.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  // Step 2: spawn it in this environment (PoCL's cache folder), its output
  // into a pipe, no terminal input, and its errors discarded: a failed helper
  // is only a lost head start.
  state_ = State::failed;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return;
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&files, fds[1], 1);
  posix_spawn_file_actions_addopen(&files, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, request.executable.c_str(), &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  close(fds[1]);
  if (error != 0) {
    close(fds[0]);
    return;
  }
  pid_ = pid;
  pipe_ = fds[0];
  asked_.insert(request.kernels.begin(), request.kernels.end());
  warmBuildMs_ = request.warmBuildMs;
  state_ = State::running;
}

void CompileAhead::deviceChosen(const DeviceInfo& device, int lanes)
{
  if (state_ != State::running || worthwhile(device, lanes)) return;
  reap(true);
  state_ = State::off;
}

void CompileAhead::programBuilt(double buildMs)
{
  if (state_ != State::running) return;
  if (buildMs < warmBuildMs_) {
    reap(true);
    return;
  }
  waitLimitMs_ = 500 + buildMs;
}

void CompileAhead::await(const std::string& kernel)
{
  // (A helper that has named every kernel may be reaped already: its kernels
  // are ready, and still count as awaited.)
  if (!asked_.count(kernel)) return;
  awaited_.insert(kernel);
  if (state_ == State::running && !ready_.count(kernel)) readUntil(kernel);
}

void CompileAhead::readUntil(const std::string& kernel)
{
  const auto start = std::chrono::steady_clock::now();
  bool ended = false, late = false;
  while (!ready_.count(kernel)) {
    // Step 1: wait for output, within what is left of the limit.
    const double waited =
        waitedMs_ + std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (waited >= waitLimitMs_) {
      late = true;
      break;
    }
    pollfd p{pipe_, POLLIN, 0};
    const int polled = poll(&p, 1, int(waitLimitMs_ - waited) + 1);
    if (polled < 0 && errno == EINTR) continue;
    if (polled <= 0) continue;
    // Step 2: read; the end of the pipe is the helper's end.
    char chunk[256];
    const ssize_t n = read(pipe_, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      ended = true;
      break;
    }
    pending_.append(chunk, size_t(n));
    for (size_t eol; (eol = pending_.find('\n')) != std::string::npos; pending_.erase(0, eol + 1))
      ready_.insert(pending_.substr(0, eol));
  }
  waitedMs_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  // Step 3: reap a helper that ended or was too slow; one that has named
  // every kernel exits at once (compileAheadCommand), and is reaped here if
  // it already has, else by the destructor.
  if (ended || late)
    reap(late);
  else if (std::includes(ready_.begin(), ready_.end(), asked_.begin(), asked_.end()))
    reap(false, WNOHANG);
}

void CompileAhead::reap(bool stop, int options)
{
  if (stop) kill(pid_, SIGKILL);
  int status = 0;
  const pid_t done = waitpid(pid_, &status, options);
  if (done == 0) return;  // still running (WNOHANG)
  close(pipe_);
  pid_ = -1;
  pipe_ = -1;
  state_ = stop                                                          ? State::stopped
           : done != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0 ? State::succeeded
                                                                         : State::failed;
}

CompileAhead::~CompileAhead()
{
  if (state_ == State::running) reap(true);
}

// The kernels compileKernelsAhead knows the arguments of; another is an error.
static void checkKernelNames(const std::vector<std::string>& kernels)
{
  for (const std::string& name : kernels)
    if (name != "scan_chunks" && name != "raster" && name != "resolve" && name != "resolve_lambert")
      throw Error("__compile-ahead: '" + name + "' is not scan_chunks, raster, resolve or resolve_lambert");
}

void compileKernelsAhead(ClContext& cl, const std::vector<std::string>& kernels, void (*ran)(const std::string& name))
{
  // Step 1: an empty frame of one tile: its parameters, and zeroed buffers
  // for every other argument, larger than what a tile or a scan of nothing
  // touches. Every tile offset is 0, so raster finds no bin entries and
  // writes an empty tile into visibility slot 0 (tileSlot[0] = 0), and
  // resolve paints the background.
  FrameSettings settings;
  settings.width = settings.height = CLR_TILE_SIZE;
  FrameParams params = makeFrameParams(settings, 0, 0);
  const cl::Buffer paramsBuf(cl.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof params, &params);
  std::vector<uint8_t> zeros(size_t(64) << 10, 0);
  auto zeroed = [&] {
    return cl::Buffer(cl.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, zeros.size(), zeros.data());
  };
  const cl::Buffer in = zeroed(), out = zeroed(), visAttr = zeroed(), image = zeroed();
  const cl_uint visPlane = CLR_TILE_SIZE * CLR_TILE_SIZE;
  // Step 2: each kernel, with the arguments and in the work shape of its
  // launches in Pipeline::scanSums, Pipeline::raster and Pipeline::resolve.
  checkKernelNames(kernels);
  for (const std::string& name : kernels) {
    cl::Kernel kernel(cl.program, name.c_str());
    cl::NDRange global, local;
    cl_uint arg = 0;
    auto set = [&](const auto& value) { kernel.setArg(arg++, value); };
    if (name == "scan_chunks") {  // the reduce phase over no counts
      const ScanChunks c = scanChunks(0);
      for (const cl::Buffer* b : {&in, &out}) set(*b);
      for (cl_uint v : {0u, c.size, c.count}) set(v);
      for (const cl::Buffer* b : {&out, &out, &in, &out}) set(*b);  // partials, second, bytes, counters
      for (cl_uint v : {cl_uint(CLR_SCAN_NO_TOTAL), cl_uint(CLR_SCAN_NO_TOTAL), cl_uint(CLR_SCAN_REDUCE), 0u, 0u})
        set(v);
      global = scanChunkItems(cl.lanes, c.count);
      local = cl::NDRange(CLR_SCAN_GROUP(cl.lanes));
    } else if (name == "raster") {
      for (const cl::Buffer* b : {&paramsBuf, &in, &in, &in, &in, &in, &out, &visAttr, &in, &in}) set(*b);
      set(visPlane);
      const WorkShape shape = rasterShape(cl.lanes, params.tilesX, params.tilesY, params.samples);
      global = shape.global, local = shape.local;
    } else {  // resolve, resolve_lambert
      for (const cl::Buffer* b : {&paramsBuf, &out, &visAttr}) set(*b);
      for (int k = 0; k < 13; ++k) set(in);  // tile offsets to texels
      for (const cl::Buffer* b : {&image, &in}) set(*b);
      set(visPlane);
      set(cl_uint(0));  // prefetchRows
      set(in);          // fileTri
      const WorkShape shape = resolveShape(cl.lanes, params.tilesX, params.tilesY);
      global = shape.global, local = shape.local;
    }
    cl.queue.enqueueNDRangeKernel(kernel, cl::NullRange, global, local);
    cl.queue.finish();
    if (ran) ran(name);
  }
}

void compileAheadCommand(const std::vector<std::string>& args)
{
  // args: --device SELECTOR --lanes N KERNEL..., as CompileAhead writes them.
  if (args.size() < 5 || args[0] != "--device" || args[2] != "--lanes")
    throw Error("usage: clraster __compile-ahead --device SELECTOR --lanes N KERNEL...");
  // Step 1: the parent's device and work shape; no build where no help.
  const std::vector<std::string> kernels(args.begin() + 4, args.end());
  checkKernelNames(kernels);
  const int lanesOverride = std::atoi(args[3].c_str());
  const DeviceInfo device = selectDevice(args[1]);
  if (!CompileAhead::worthwhile(device, contextLanes(device.device, lanesOverride))) std::_Exit(3);
  // Step 2: build and launch, naming each kernel as it has run.
  ClContext cl(args[1], lanesOverride);
  compileKernelsAhead(cl, kernels, [](const std::string& name) {
    std::printf("%s\n", name.c_str());
    std::fflush(stdout);
  });
  // Done: PoCL's cache files are complete, so skip tearing the context down.
  std::_Exit(0);
}

}  // namespace clr
