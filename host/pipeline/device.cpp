// device.cpp — enumerates OpenCL devices, creates the context and queue, and
// builds the embedded kernels (see device.h for the contract).
#include "pipeline/device.h"

#include "pipeline/buffer.h"
#include "pipeline/embedded_kernels.h"
#include "pipeline/program_cache.h"
#include "kernels/shared.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <sstream>

namespace clr {

const char* clErrorName(cl_int code)
{
  switch (code) {
    case CL_DEVICE_NOT_FOUND: return "CL_DEVICE_NOT_FOUND";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE: return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_BUFFER_SIZE: return "CL_INVALID_BUFFER_SIZE";
    case CL_INVALID_WORK_GROUP_SIZE: return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_KERNEL_ARGS: return "CL_INVALID_KERNEL_ARGS";
    case CL_PLATFORM_NOT_FOUND_KHR: return "CL_PLATFORM_NOT_FOUND_KHR (no OpenCL platform installed)";
    default: return "OpenCL error";
  }
}

static std::string typeName(cl_device_type type)
{
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "ACCELERATOR";
  return "OTHER";
}

std::vector<DeviceInfo> listDevices()
{
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    return {};
  }
  std::vector<DeviceInfo> out;
  for (const cl::Platform& platform : platforms) {
    std::vector<cl::Device> devices;
    try {
      platform.getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;
    }
    for (const cl::Device& device : devices) {
      DeviceInfo info;
      info.index = out.size();
      info.platform = platform;
      info.device = device;
      info.platformName = platform.getInfo<CL_PLATFORM_NAME>();
      info.name = device.getInfo<CL_DEVICE_NAME>();
      info.type = typeName(device.getInfo<CL_DEVICE_TYPE>());
      out.push_back(info);
    }
  }
  return out;
}

static std::string lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

DeviceInfo selectDevice(const std::string& selector)
{
  const std::vector<DeviceInfo> devices = listDevices();
  if (devices.empty()) throw Error("no OpenCL device found (is an ICD such as pocl-opencl-icd installed?)");
  // Step 1: the default, first GPU, else first CPU, else the first device.
  if (selector.empty()) {
    for (const char* wanted : {"GPU", "CPU"})
      for (const DeviceInfo& d : devices)
        if (d.type == wanted) return d;
    return devices.front();
  }
  // Step 2: an index.
  if (std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); })) {
    errno = 0;
    const unsigned long long index = std::strtoull(selector.c_str(), nullptr, 10);
    if (errno == ERANGE || index >= devices.size())
      throw Error("--device " + userText(selector) + ": no such device index (there are " +
                  std::to_string(devices.size()) + "; see 'clraster devices')");
    return devices[index];
  }
  // Step 3: a name substring.
  for (const DeviceInfo& d : devices)
    if (lower(d.name + " " + d.platformName).find(lower(selector)) != std::string::npos) return d;
  throw Error("--device " + userText(selector) + ": no device name matches (see 'clraster devices')");
}

int defaultLanes(const cl::Device& device)
{
  return (device.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU) ? 16 : 1;
}

std::string kernelBuildOptions(int lanes, bool prefetch, bool exactDivide, bool clipInput)
{
  std::ostringstream options;
  options << "-cl-std=CL1.2 -D CLR_TILE_SIZE=" << CLR_TILE_SIZE << " -D CLR_LANES=" << lanes;
  if (clipInput) options << " -D CLR_CLIP_INPUT=1";
  // Why exactDivide matters: device.h.
  if (exactDivide) options << " -cl-fp32-correctly-rounded-divide-sqrt";
  // Raster fetches 12 bin entries ahead (the distance is a bench/ab.sh choice); PoCL only: other drivers'
  // compilers need not know the clang builtin.
  if (prefetch) options << " -D CLR_PREFETCH=12";
  return options.str();
}

std::string programOptions(const std::string& options, bool extras)
{
  return options + (extras ? " -D CLR_EXTRAS=1" : " -D CLR_EXTRAS=0");
}

// Appends `text` to `out`, each line #include "name" replaced by the embedded file `name`, expanded the same way;
// `included` collects the names so expanded.
static void expandIncludes(const std::string& text, std::string& out, std::vector<std::string>& included, int depth)
{
  if (depth > 16) throw Error("kernel headers include each other more than 16 deep");
  const std::string directive = "#include \"";
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = text.find('\n', begin);
    end = end == std::string::npos ? text.size() : end + 1;
    const std::string line = text.substr(begin, end - begin);
    if (line.compare(0, directive.size(), directive) == 0) {
      const std::string name = line.substr(directive.size(), line.find('"', directive.size()) - directive.size());
      const EmbeddedKernel* header = nullptr;
      for (size_t i = 0; i < kEmbeddedKernelCount; ++i)
        if (name == kEmbeddedKernels[i].name) header = &kEmbeddedKernels[i];
      if (!header) throw Error("kernel source includes " + userText(name) + ", which is not embedded (CMakeLists.txt)");
      included.push_back(name);
      expandIncludes(header->text, out, included, depth + 1);
      out += "\n";
    } else {
      out += line;
    }
    begin = end;
  }
}

std::string programSource()
{
  // Step 1: the .cl files, expanded, and the headers they include.
  std::string body;
  std::vector<std::string> included;
  for (size_t i = 0; i < kEmbeddedKernelCount; ++i) {
    const std::string name = kEmbeddedKernels[i].name;
    if (name.size() > 3 && name.compare(name.size() - 3, 3, ".cl") == 0)
      expandIncludes(kEmbeddedKernels[i].text, body, included, 0);
  }
  // Step 2: the prelude, the headers no .cl file includes, in embedding order.
  std::string prelude;
  for (size_t i = 0; i < kEmbeddedKernelCount; ++i) {
    const std::string name = kEmbeddedKernels[i].name;
    const bool source = name.size() > 3 && name.compare(name.size() - 3, 3, ".cl") == 0;
    if (!source && std::find(included.begin(), included.end(), name) == included.end())
      prelude += kEmbeddedKernels[i].text;
  }
  return prelude + body;
}

cl::Program buildProgram(const cl::Context& context, const cl::Device& device, const std::string& options, bool extras)
{
  // Step 1: the program cache's binary for these sources, options and driver, if it holds one.
  const std::string fullOptions = programOptions(options, extras);
  if (cl::Program cached = loadCachedProgram(context, device, fullOptions); cached()) return cached;
  // Step 2: the embedded sources, their includes resolved (programSource).
  cl::Program program(context, programSource());
  // Step 3: build; on failure report the device's log.
  try {
    program.build({device}, fullOptions.c_str());
  } catch (const cl::Error& e) {
    std::string log;
    try {
      log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
    } catch (const cl::Error&) {
      log = "(no build log)";
    }
    throw Error("kernel build failed on " + device.getInfo<CL_DEVICE_NAME>() + " (" + clErrorName(e.err()) + "):\n" +
                log);
  }
  return program;
}

DeviceNeeds deviceNeeds(int lanes, uint32_t tileSize)
{
  const size_t tilePixels = size_t(tileSize) * tileSize;
  // Raster's GPU shape is a work-group per tile; resolve's a work-item per row of lanes, a tile per group, or a
  // group of one where a row of lanes spans the tile (resolve.cl).
  const size_t raster = lanes == 1 ? tilePixels : 1;
  const size_t resolve = uint32_t(lanes) == tileSize ? 1 : tilePixels / size_t(lanes);
  DeviceNeeds needs;
  needs.workGroupSize = std::max({raster, resolve, size_t(CLR_LINEAR_GROUP)});
  // Raster's batch in local memory (raster.cl: records, bounds, nearest keys, indices and ranks); scan's partials
  // phase sums a value per work-item.
  const uint64_t rasterLocal = lanes == 1 ? tilePixels * (sizeof(TriSetup) + 4 * sizeof(int32_t) + 3 * 4) : 0;
  const uint64_t scanLocal = uint64_t(CLR_SCAN_GROUP(lanes)) * sizeof(uint64_t);
  needs.localMemBytes = std::max(rasterLocal, scanLocal);
  return needs;
}

void checkDeviceLimits(const std::string& deviceName, const DeviceLimits& limits, int lanes, uint32_t tileSize)
{
  const std::string what = "tile size " + std::to_string(tileSize) + " with " + std::to_string(lanes) + " lane" +
                           (lanes == 1 ? "" : "s") + " on " + userText(deviceName);
  if (tileSize == 0 || tileSize % uint32_t(lanes) != 0) throw Error(what + ": the lanes must divide the tile size");
  const DeviceNeeds needs = deviceNeeds(lanes, tileSize);
  if (needs.workGroupSize > limits.maxWorkGroupSize)
    throw Error(what + " needs work-groups of " + std::to_string(needs.workGroupSize) +
                " work-items; the device allows " + std::to_string(limits.maxWorkGroupSize) +
                " (CL_DEVICE_MAX_WORK_GROUP_SIZE): build with a smaller CLR_TILE_SIZE");
  if (needs.localMemBytes > limits.localMemBytes)
    throw Error(what + " needs " + std::to_string(needs.localMemBytes) + " bytes of local memory; the device has " +
                std::to_string(limits.localMemBytes) +
                " (CL_DEVICE_LOCAL_MEM_SIZE): build with a smaller CLR_TILE_SIZE");
}

bool isPocl(const DeviceInfo& device)
{
  return device.platformName.find("Portable Computing Language") != std::string::npos;
}

int contextLanes(const cl::Device& device, int lanesOverride)
{
  const char* fromEnv = std::getenv("CLRASTER_LANES");
  const int lanes = lanesOverride ? lanesOverride : fromEnv ? std::atoi(fromEnv) : defaultLanes(device);
  if (lanes != 1 && lanes != 16) throw Error("CLRASTER_LANES must be 1 or 16");
  return lanes;
}

ClContext::ClContext(const std::string& selector, int lanesOverride, bool clipInputPrograms)
    : info(selectDevice(selector)), clipInput(clipInputPrograms)
{
  // Step 1: the work shape, the queue and the frame program.
  lanes = contextLanes(info.device, lanesOverride);
  checkDeviceLimits(
      info.name,
      {info.device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>(), info.device.getInfo<CL_DEVICE_LOCAL_MEM_SIZE>()}, lanes,
      CLR_TILE_SIZE);
  context = cl::Context(info.device);
  queue = cl::CommandQueue(context, info.device, CL_QUEUE_PROFILING_ENABLE);
  prefetch = isPocl(info);
  const bool exactDivide =
      (info.device.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
  buildOptions_ = kernelBuildOptions(lanes, prefetch, exactDivide, clipInput);
  program = buildProgram(context, info.device, buildOptions_);
  maxAllocBytes = info.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  globalMemBytes = info.device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  // Step 2: CLRASTER_MAX_ALLOC_BYTES lowers the largest allocation, so tests
  // can meet the device's limit with a small scene.
  if (const char* cap = std::getenv("CLRASTER_MAX_ALLOC_BYTES")) {
    char* end = nullptr;
    const unsigned long long bytes = std::strtoull(cap, &end, 10);
    if (!std::isdigit(static_cast<unsigned char>(*cap)) || *end || bytes == 0)
      throw Error("CLRASTER_MAX_ALLOC_BYTES must be a positive number of bytes");
    maxAllocBytes = std::min<size_t>(maxAllocBytes, bytes);
  }
}

const cl::Program& ClContext::extras()
{
  if (!extras_()) extras_ = buildProgram(context, info.device, buildOptions_, true);
  return extras_;
}

DeviceMemory deviceMemoryOf(const ClContext& cl)
{
  return {cl.context, cl.queue, cl.maxAllocBytes, 0, cl.globalMemBytes, UINT64_MAX, cl.info.type == "CPU"};
}

}  // namespace clr
