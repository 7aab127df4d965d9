// program_cache.cpp — the compiled-program cache (program_cache.h for the
// contract). A file is a 32-byte header, then the driver's binary:
//   magic "CLRBIN01" | key | payload bytes | FNV-1a 64 of the payload
// all little-endian u64 after the magic.
#include "pipeline/program_cache.h"

#include "pipeline/device.h"
#include "pipeline/embedded_kernels.h"
#include "io/file_rule.h"
#include "io/image_io.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace clr {

namespace {

constexpr char kMagic[8] = {'C', 'L', 'R', 'B', 'I', 'N', '0', '1'};
constexpr size_t kHeaderBytes = 32;

struct Fnv64 {
  uint64_t h = 1469598103934665603ull;
  void add(const void* data, size_t n)
  {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  }
  void add(const std::string& s)
  {
    add(s.data(), s.size());
    add("\0", 1);  // so that ("ab","c") and ("a","bc") differ
  }
};

void putU64(std::vector<unsigned char>& out, uint64_t v)
{
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

uint64_t getU64(const std::string& s, size_t at)
{
  uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(s[at + size_t(i)]);
  return v;
}

std::string hex(uint64_t v)
{
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

// The file holding the program of this key ("" without a cache directory).
std::string cachePath(uint64_t key)
{
  const std::string dir = programCacheDir();
  return dir.empty() ? std::string() : dir + "/" + hex(key) + ".bin";
}

}  // namespace

std::string programCacheDir()
{
  if (const char* dir = std::getenv("CLRASTER_CACHE_DIR")) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg == '/') return std::string(xdg) + "/clraster";
  if (const char* home = std::getenv("HOME"); home && *home == '/') return std::string(home) + "/.cache/clraster";
  return "";
}

uint64_t programCacheKey(const cl::Device& device, const std::string& options)
{
  Fnv64 key;
  key.add(std::string(kMagic, sizeof kMagic));
  for (size_t i = 0; i < kEmbeddedKernelCount; ++i) key.add(kEmbeddedKernels[i].text);
  key.add(options);
  const cl::Platform platform(device.getInfo<CL_DEVICE_PLATFORM>());
  key.add(platform.getInfo<CL_PLATFORM_NAME>());
  key.add(platform.getInfo<CL_PLATFORM_VERSION>());
  key.add(device.getInfo<CL_DEVICE_NAME>());
  key.add(device.getInfo<CL_DEVICE_VERSION>());
  key.add(device.getInfo<CL_DRIVER_VERSION>());
  return key.h;
}

cl::Program loadCachedProgram(const cl::Context& context, const cl::Device& device, const std::string& options)
{
  const uint64_t key = programCacheKey(device, options);
  const std::string path = cachePath(key);
  if (path.empty()) return cl::Program();
  try {  // a missing file, like any other, is a miss (readInputFile throws)
    const std::string file = readInputFile(path, kProgramCacheInput);
    if (file.size() <= kHeaderBytes || std::memcmp(file.data(), kMagic, sizeof kMagic) != 0) return cl::Program();
    if (getU64(file, 8) != key) return cl::Program();
    if (getU64(file, 16) != file.size() - kHeaderBytes) return cl::Program();
    Fnv64 sum;
    sum.add(file.data() + kHeaderBytes, file.size() - kHeaderBytes);
    if (getU64(file, 24) != sum.h) return cl::Program();
    const cl::Program::Binaries binaries{std::vector<unsigned char>(file.begin() + kHeaderBytes, file.end())};
    cl::Program program(context, {device}, binaries);
    program.build({device}, options.c_str());
    return program;
  } catch (const std::exception&) {  // cl::Error or clr::Error: build from source instead
    return cl::Program();
  }
}

std::string storeProgramBinary(const cl::Program& program, const cl::Device& device, const std::string& options)
{
  const uint64_t key = programCacheKey(device, options);
  const std::string path = cachePath(key);
  if (path.empty()) throw Error("no kernel cache directory (CLRASTER_CACHE_DIR is empty, HOME unset)");
  const cl::Program::Binaries binaries = program.getInfo<CL_PROGRAM_BINARIES>();
  if (binaries.size() != 1 || binaries[0].empty()) throw Error("the OpenCL driver gave no program binary to cache");
  const std::vector<unsigned char>& payload = binaries[0];
  std::vector<unsigned char> file(kMagic, kMagic + sizeof kMagic);
  putU64(file, key);
  putU64(file, payload.size());
  Fnv64 sum;
  sum.add(payload.data(), payload.size());
  putU64(file, sum.h);
  file.insert(file.end(), payload.begin(), payload.end());
  const std::string dir = programCacheDir();
  std::error_code failed;
  std::filesystem::create_directories(dir, failed);
  if (failed) throw Error(userText(dir) + ": cannot create the kernel cache directory (" + failed.message() + ")");
  writeFileAtomic(path, std::move(file));
  return path;
}

int cacheCommand(const std::vector<std::string>& args)
{
  std::string selector;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--device" && i + 1 < args.size())
      selector = args[++i];
    else
      throw Error("cache: unexpected argument '" + userText(args[i]) + "' (cache [--device SEL])");
  }
  for (const bool clipInput : {false, true}) {
    ClContext ctx(selector, 0, clipInput);
    for (const bool extras : {false, true}) {
      const cl::Program& program = extras ? ctx.extras() : ctx.program;
      std::printf("%s\n",
                  storeProgramBinary(program, ctx.info.device, programOptions(ctx.buildOptions(), extras)).c_str());
    }
  }
  return 0;
}

}  // namespace clr
