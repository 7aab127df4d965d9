// test_device.cpp — the device and program contract: the kernels divide and
// take square roots correctly rounded, and a failed build reports the
// device's build log.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

TEST_CASE("the kernels divide and take square roots correctly rounded", "[device]")
{
  // Setup's 1 / w places the vertices, so a division off by an ulp moves a
  // vertex to another subpixel. NVIDIA's driver (H100, 580.159) rounded it
  // so without -cl-fp32-correctly-rounded-divide-sqrt: 1 to 5 pixels of
  // 30,000 took other triangles than the oracle's in the differential tests.
  const clr::ClContext& ctx = test::context();
  const bool offered =
      (ctx.info.device.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
  REQUIRE(offered);  // every device clraster has run on offers it; without it coverage may part from the oracle
  CHECK(ctx.buildOptions().find("-cl-fp32-correctly-rounded-divide-sqrt") != std::string::npos);
  // Step 1: the frame program's options on a kernel of divisions and roots.
  const char* source = R"CLC(
__kernel void divide_sqrt(__global const float* in, __global float* quotient, __global float* root)
{
  const size_t i = get_global_id(0);
  quotient[i] = 1.0f / in[i];
  root[i] = sqrt(in[i]);
}
)CLC";
  cl::Program program(ctx.context, std::string(source));
  program.build({ctx.info.device}, ctx.buildOptions().c_str());
  // Step 2: w values of every magnitude a clip-space w takes, each mantissa random.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> mantissa(1.0f, 2.0f);
  std::uniform_int_distribution<int> exponent(-40, 40);
  const size_t n = 1 << 16;
  std::vector<float> in(n), quotient(n), root(n);
  for (float& w : in) w = std::ldexp(mantissa(rng), exponent(rng));
  cl::Buffer inBuffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(float), in.data());
  cl::Buffer quotientBuffer(ctx.context, CL_MEM_WRITE_ONLY, n * sizeof(float));
  cl::Buffer rootBuffer(ctx.context, CL_MEM_WRITE_ONLY, n * sizeof(float));
  cl::Kernel kernel(program, "divide_sqrt");
  kernel.setArg(0, inBuffer), kernel.setArg(1, quotientBuffer), kernel.setArg(2, rootBuffer);
  ctx.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(n));
  ctx.queue.enqueueReadBuffer(quotientBuffer, CL_TRUE, 0, n * sizeof(float), quotient.data());
  ctx.queue.enqueueReadBuffer(rootBuffer, CL_TRUE, 0, n * sizeof(float), root.data());
  // Step 3: bit for bit what the host's IEEE division and square root give.
  size_t wrongQuotients = 0, wrongRoots = 0;
  for (size_t i = 0; i < n; ++i) {
    wrongQuotients += quotient[i] != 1.0f / in[i];
    wrongRoots += root[i] != std::sqrt(in[i]);
  }
  CHECK(wrongQuotients == 0);
  CHECK(wrongRoots == 0);
}

TEST_CASE("a kernel build failure reports the device's build log", "[device]")
{
  const clr::ClContext& ctx = test::context();
  try {
    // CLR_TILE_SIZE is spliced into array sizes and attributes: a non-number breaks the build.
    clr::buildProgram(ctx.context, ctx.info.device, "-cl-std=CL1.2 -D CLR_TILE_SIZE=not_a_number");
    FAIL("the build should have failed");
  } catch (const clr::Error& e) {
    const std::string message = e.what();
    CHECK(message.find("kernel build failed on " + ctx.info.name) != std::string::npos);
    CHECK(message.find("not_a_number") != std::string::npos);  // quoted by the compiler's log
  }
}
