// peak.cpp — clraster_peak: the OpenCL device's peak arithmetic throughput and memory bandwidth, measured through
// clraster's own OpenCL path (clr::ClContext: same device selection, context and profiling queue).
//
//   clraster_peak [--device SEL] [--repeats N] [--copy-mib M]
//
// Kernels (source inline below), each timed by its profiling event, the best of N runs after one warm-up run:
//   fp32_gflops      float16 FMA chains, 8 independent chains per work-item;
//                    2 flops per lane per FMA
//   int64_mad_gops   long16 a = a * b + c chains, full 64 x 64-bit multiply
//   int64_wmad_gops  long16 a += (long)(int)a * (long)b chains: the
//                    32 x 32 -> 64-bit widening multiply-add that an edge
//                    function (fixed.h) evaluates per sample
//   copy_gbs         uint4 copy of M MiB into another M MiB buffer; bytes
//                    read + bytes written per second (10^9 B)
// The line also names the device, its platform and its driver version. Prints one JSON line on stdout; every failure is
// one line on stderr and exit status 1.
#include "pipeline/cl.h"
#include "render/flags.h"
#include "pipeline/device.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using namespace clr;

namespace {

const char* const kPeakSource = R"CLC(
#define CHAINS8(op) op(0) op(1) op(2) op(3) op(4) op(5) op(6) op(7)
// Every lane starts from its own value and reaches the output, so that a
// compiler that scalarises the vectors (NVIDIA's) cannot compute one lane
// of identical ones, or only the lanes read, and report more than the
// hardware's peak.
#define LANES_F ((float16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15) * 1e-3f)
#define LANES_L ((long16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15) * 977)
#define SUM8(v) ((v).s0 + (v).s1 + (v).s2 + (v).s3 + (v).s4 + (v).s5 + (v).s6 + (v).s7)
#define SUM16(v) (SUM8((v).lo) + SUM8((v).hi))

__kernel void fma_f32(__global float* out, float b, float c, int iterations)
{
  const float seed = (float)get_global_id(0) * 1e-6f;
#define INIT(k) float16 a##k = (float16)(seed + (float)k) + LANES_F;
  CHAINS8(INIT)
  for (int i = 0; i < iterations; ++i) {
#define STEP(k) a##k = fma(a##k, b, c);
    CHAINS8(STEP)
  }
  const float16 s = a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7;
  out[get_global_id(0)] = SUM16(s);
}

__kernel void mad_i64(__global long* out, long b, long c, int iterations)
{
  const long seed = (long)get_global_id(0);
#define INIT_L(k) long16 a##k = (long16)(seed + k) + LANES_L;
  CHAINS8(INIT_L)
  for (int i = 0; i < iterations; ++i) {
#define STEP_L(k) a##k = a##k * b + c;
    CHAINS8(STEP_L)
  }
  const long16 s = a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7;
  out[get_global_id(0)] = SUM16(s);
}

__kernel void wmad_i64(__global long* out, int b, int iterations)
{
  const long seed = (long)get_global_id(0);
#define INIT_W(k) long16 a##k = (long16)(seed + k) + LANES_L;
  CHAINS8(INIT_W)
  for (int i = 0; i < iterations; ++i) {
#define STEP_W(k) a##k += convert_long16(convert_int16(a##k)) * (long)b;
    CHAINS8(STEP_W)
  }
  const long16 s = a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7;
  out[get_global_id(0)] = SUM16(s);
}

__kernel void copy_u4(__global const uint4* src, __global uint4* dst)
{
  dst[get_global_id(0)] = src[get_global_id(0)];
}
)CLC";

struct Args {
  std::string device;
  uint32_t repeats = 10;
  uint32_t copyMib = 256;
};

Args parseArgs(const std::vector<std::string>& args)
{
  Args r;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--device")
      r.device = flagValue(args, i);
    else if (a == "--repeats")
      r.repeats = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 1000));
    else if (a == "--copy-mib")
      r.copyMib = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 65536));
    else
      throw Error("unknown argument '" + a + "'");
  }
  return r;
}

// Runs the kernel once to warm up, then `repeats` times; the shortest
// profiled time in seconds.
double bestSeconds(const ClContext& cl, cl::Kernel& kernel, size_t global, uint32_t repeats)
{
  double best = 1e30;
  for (uint32_t r = 0; r <= repeats; ++r) {
    cl::Event event;
    cl.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global), cl::NullRange, nullptr, &event);
    event.wait();
    const double s = double(event.getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                            event.getProfilingInfo<CL_PROFILING_COMMAND_START>()) *
                     1e-9;
    if (r > 0) best = std::min(best, s);
  }
  return best;
}

int run(const Args& args)
{
  // Step 1: clraster's context, and the peak program built for its device.
  ClContext cl(args.device);
  cl::Program program(cl.context, std::string(kPeakSource));
  try {
    program.build({cl.info.device}, "-cl-std=CL1.2");
  } catch (const cl::Error&) {
    throw Error("peak kernel build failed:\n" + program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(cl.info.device));
  }
  const size_t computeUnits = cl.info.device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();

  // Step 2: arithmetic: enough work-items for every compute unit, enough
  // iterations that one run takes tens of milliseconds.
  const size_t items = std::max<size_t>(1024, computeUnits * 256);
  const int iterations = 8192;
  const double lanesTimesSteps = double(items) * iterations * 8 * 16;
  cl::Buffer out(cl.context, CL_MEM_WRITE_ONLY, items * sizeof(cl_long));
  cl::Kernel fma(program, "fma_f32");
  fma.setArg(0, out), fma.setArg(1, 0.999f), fma.setArg(2, 1e-4f), fma.setArg(3, iterations);
  const double fp32Gflops = 2.0 * lanesTimesSteps / bestSeconds(cl, fma, items, args.repeats) * 1e-9;
  cl::Kernel mad(program, "mad_i64");
  mad.setArg(0, out), mad.setArg(1, cl_long(6364136223846793005LL)), mad.setArg(2, cl_long(1442695040888963407LL));
  mad.setArg(3, iterations);
  const double int64MadGops = lanesTimesSteps / bestSeconds(cl, mad, items, args.repeats) * 1e-9;
  cl::Kernel wmad(program, "wmad_i64");
  wmad.setArg(0, out), wmad.setArg(1, cl_int(40503)), wmad.setArg(2, iterations);
  const double int64WmadGops = lanesTimesSteps / bestSeconds(cl, wmad, items, args.repeats) * 1e-9;

  // Step 3: memory: a copy between two buffers far larger than any cache.
  const size_t bytes = size_t(args.copyMib) << 20;
  cl::Buffer src(cl.context, CL_MEM_READ_WRITE, bytes), dst(cl.context, CL_MEM_READ_WRITE, bytes);
  cl.queue.enqueueFillBuffer(src, cl_uint(1), 0, bytes);
  cl.queue.enqueueFillBuffer(dst, cl_uint(0), 0, bytes);
  cl.queue.finish();
  cl::Kernel copy(program, "copy_u4");
  copy.setArg(0, src), copy.setArg(1, dst);
  const double copyGbs = 2.0 * double(bytes) / bestSeconds(cl, copy, bytes / 16, args.repeats) * 1e-9;

  // Step 4: the report.
  std::printf(
      "{\"device\":\"%s\",\"platform\":\"%s\",\"driver\":\"%s\",\"compute_units\":%zu,\"fp32_gflops\":%.2f,"
      "\"int64_mad_gops\":%.2f,\"int64_wmad_gops\":%.2f,\"copy_gbs\":%.2f,\"copy_mib\":%u}\n",
      cl.info.name.c_str(), cl.info.platformName.c_str(), cl.info.device.getInfo<CL_DRIVER_VERSION>().c_str(),
      computeUnits, fp32Gflops, int64MadGops, int64WmadGops, copyGbs, args.copyMib);
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  return runProgram("clraster_peak", [&] { return run(parseArgs(std::vector<std::string>(argv + 1, argv + argc))); });
}
