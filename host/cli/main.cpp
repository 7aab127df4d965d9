// main.cpp — the clraster command line: `render` (one camera, or a views
// file of many), `info`, `devices`, `cache` and `help` (every command also
// answers --help). A client of the library's public API (clraster.hpp) and
// nothing else: each command is one of its calls.
//
// Every failure, from a bad flag to a device that cannot hold the frame,
// ends as one line on stderr and exit status 1; no output file is left
// half-written.
#include <clraster/clraster.hpp>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>
#include <vector>

namespace {

// Ends a successful render once its outputs are written, flushed and renamed
// into place, without tearing down the device context: on a cold start PoCL
// would free the LLVM modules it compiled the kernels with, a noticeable part
// of a short render. Nothing in that teardown is needed: PoCL's kernel cache
// files are complete by each kernel's first launch. Standard output carries
// --stats, so a failed flush is still a failure.
[[noreturn]] void exitAfterOutput()
{
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::fprintf(stderr, "clraster: cannot write standard output\n");
    std::_Exit(1);
  }
  std::fflush(stderr);
  std::_Exit(0);
}

int listDevicesCommand()
{
  const std::vector<clraster::DeviceInfo> devices = clraster::listDevices();
  if (devices.empty()) throw clraster::Error("no OpenCL platform or device found");
  for (const clraster::DeviceInfo& d : devices)
    std::printf("%zu: [%s] %s (platform: %s)\n", d.index, d.type.c_str(), d.name.c_str(), d.platform.c_str());
  return 0;
}

int renderCommand(const std::vector<std::string>& args)
{
  const clraster::RenderOptions options = clraster::RenderOptions::parseCommandLine(args);
  std::unique_ptr<clraster::Context> context;  // kept to the exit (exitAfterOutput)
  const std::string stats = clraster::renderCommand(options, context);
  std::fputs(stats.c_str(), stdout);
  exitAfterOutput();
}

int run(const std::vector<std::string>& args)
{
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    std::fputs(clraster::usageText(), args.empty() ? stderr : stdout);
    return args.empty() ? 1 : 0;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if ((args[0] == "devices" || args[0] == "render" || args[0] == "info" || args[0] == "cache") &&
      clraster::wantsHelp(rest)) {
    std::fputs(clraster::usageText(), stdout);
    return 0;
  }
  if (args[0] == "devices") {
    if (!rest.empty()) throw clraster::Error("devices: unexpected argument '" + clraster::userText(rest[0]) + "'");
    return listDevicesCommand();
  }
  if (args[0] == "render") return renderCommand(rest);
  if (args[0] == "info") return clraster::infoCommand(rest);
  if (args[0] == "cache") return clraster::cacheCommand(rest);
  throw clraster::Error("unknown command '" + clraster::userText(args[0]) + "' (render, info, devices, cache, help)");
}

}  // namespace

int main(int argc, char** argv)
{
  try {
    return run(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "clraster: out of host memory\n");
  } catch (const std::exception& e) {  // the library's calls throw clraster::Error only
    std::fprintf(stderr, "clraster: %s\n", e.what());
  }
  return 1;
}
