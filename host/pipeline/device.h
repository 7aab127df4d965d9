// device.h — OpenCL device selection and the embedded kernel program.
//
// listDevices() enumerates every platform and device; selectDevice() picks
// one by index or name substring, defaulting to the first GPU and otherwise
// the first CPU. buildProgram() compiles the kernels embedded in the binary
// at build time (never read from disk), specialised only through -D options,
// and throws clr::Error carrying the device's build log on failure.
#pragma once

#include "pipeline/cl.h"

#include <cstdint>
#include <string>
#include <vector>

namespace clr {

struct DeviceInfo {
  size_t index;  // position in the flattened platform-major list
  cl::Platform platform;
  cl::Device device;
  std::string platformName;
  std::string name;
  std::string type;  // "GPU", "CPU", "ACCELERATOR", "OTHER"
};

std::vector<DeviceInfo> listDevices();

// selector: "" (default), a decimal index, or a substring of the device or
// platform name (case-insensitive).
DeviceInfo selectDevice(const std::string& selector);

// Whether the device is PoCL's (its platform's name): the compiler takes
// __builtin_prefetch (kernelBuildOptions).
bool isPocl(const DeviceInfo& device);

// Pixels per work-item of the raster kernel for a device: 16 (one vector
// row) on CPUs, where PoCL vectorises explicit vector types; 1 elsewhere.
int defaultLanes(const cl::Device& device);

// The work shape a context takes: lanesOverride unless 0, else
// CLRASTER_LANES, else defaultLanes; anything but 1 or 16 is an error.
int contextLanes(const cl::Device& device, int lanesOverride);

// The limits of a device that the tile size and the work shape depend on
// (CL_DEVICE_MAX_WORK_GROUP_SIZE, CL_DEVICE_LOCAL_MEM_SIZE).
struct DeviceLimits {
  size_t maxWorkGroupSize = 0;
  uint64_t localMemBytes = 0;
};

// What the kernels built with tileSize and lanes ask of a device: their
// largest work-group (raster's and resolve's tile groups, CLR_LINEAR_GROUP)
// and the local memory of raster's GPU shape (a batch of tileSize² records,
// raster.cl) or of scan_chunks' partials phase.
struct DeviceNeeds {
  size_t workGroupSize = 0;
  uint64_t localMemBytes = 0;
};
DeviceNeeds deviceNeeds(int lanes, uint32_t tileSize);

// Throws a clr::Error naming the device, the tile size and the limit it
// exceeds when a device with these limits cannot run them (ClContext
// checks before it builds).
void checkDeviceLimits(const std::string& deviceName, const DeviceLimits& limits, int lanes, uint32_t tileSize);

// The OpenCL context every stage shares. lanes 0 picks the device's default.
struct ClContext {
  // clipInput: the programs take clip-space float4 positions (-D
  // CLR_CLIP_INPUT=1, transform.cl), for the library's rasterize (api.cpp).
  explicit ClContext(const std::string& selector, int lanes = 0, bool clipInput = false);
  DeviceInfo info;
  int lanes = 1;           // CLR_LANES the program was built with
  bool prefetch = false;   // the program was built with CLR_PREFETCH (kernelBuildOptions)
  bool clipInput = false;  // the programs were built with CLR_CLIP_INPUT=1
  cl::Context context;
  cl::CommandQueue queue;  // in order, profiling enabled
  cl::Program program;     // the frame program (CLR_EXTRAS 0, shared.h)
  // The extras program (CLR_EXTRAS 1, shared.h: the other raster variants,
  // lines, AOVs), built at its first use, so a cold start compiles only the
  // kernels a default frame runs.
  const cl::Program& extras();
  size_t maxAllocBytes = 0;  // the device's, or CLRASTER_MAX_ALLOC_BYTES when lower
  size_t globalMemBytes = 0;
  const std::string& buildOptions() const { return buildOptions_; }

 private:
  std::string buildOptions_;  // without CLR_EXTRAS
  cl::Program extras_;
};

// The compile options every build uses (also the key of PoCL's cache), but
// -D CLR_EXTRAS, which buildProgram adds.
// prefetch: the compiler takes __builtin_prefetch (PoCL's clang does; with
// -D CLR_PREFETCH raster fetches the setup records of later bin entries,
// and resolve_lambert those of later rows, while it works).
// exactDivide: the device divides and takes square roots correctly rounded
// on request (CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT), and the build asks for
// it. OpenCL C otherwise allows 2.5 ulp for x / y and 3 ulp for sqrt, and
// NVIDIA's driver takes that licence: setup's 1 / w then snaps a vertex to
// another subpixel, and coverage and depth part from the oracle's.
// clipInput: -D CLR_CLIP_INPUT=1 (ClContext).
std::string kernelBuildOptions(int lanes, bool prefetch = false, bool exactDivide = false, bool clipInput = false);

// The options of one of the two programs: kernelBuildOptions' and CLR_EXTRAS.
std::string programOptions(const std::string& options, bool extras);

// extras: the extras program rather than the frame program (shared.h).
// Loaded from the program cache when it holds this build (program_cache.h).
cl::Program buildProgram(const cl::Context& context, const cl::Device& device, const std::string& options,
                         bool extras = false);

}  // namespace clr
