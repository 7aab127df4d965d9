// test_kernel_args.cpp — every argument struct of kernel_args.h names the
// parameters of its kernels, in their order: the names clGetKernelArgInfo
// reports for a program built with -cl-kernel-arg-info, in both the frame
// and the extras program (shared.h, CLR_EXTRAS).
#include "test_support.h"

#include "pipeline/kernel_args.h"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace {

// The parameter names of kernel `name` in whichever of the two programs holds it.
std::vector<std::string> kernelParameterNames(const std::vector<cl::Program>& programs, const char* name)
{
  for (const cl::Program& program : programs) {
    cl::Kernel kernel;
    try {
      kernel = cl::Kernel(program, name);
    } catch (const cl::Error&) {
      continue;  // not in this program
    }
    std::vector<std::string> names;
    const cl_uint count = kernel.getInfo<CL_KERNEL_NUM_ARGS>();
    for (cl_uint i = 0; i < count; ++i) {
      std::string arg = kernel.getArgInfo<CL_KERNEL_ARG_NAME>(i);
      arg.erase(arg.find_last_not_of('\0') + 1);  // some drivers count the terminator
      names.push_back(arg);
    }
    return names;
  }
  FAIL("no program holds kernel " << name);
  return {};
}

template <typename Args>
void checkArgs(const std::vector<cl::Program>& programs, std::initializer_list<const char*> kernels)
{
  const std::vector<std::string> expected = clr::kernelArgNames<Args>();
  for (const char* kernel : kernels) {
    INFO("kernel " << kernel);
    CHECK(kernelParameterNames(programs, kernel) == expected);
  }
}

}  // namespace

TEST_CASE("each kernel's argument struct matches its parameters", "[device]")
{
  const clr::ClContext& ctx = test::context();
  const std::string options = ctx.buildOptions() + " -cl-kernel-arg-info";
  const std::vector<cl::Program> programs{clr::buildProgram(ctx.context, ctx.info.device, options, false),
                                          clr::buildProgram(ctx.context, ctx.info.device, options, true)};
  checkArgs<clr::TransformArgs>(programs, {"transform_vertices"});
  checkArgs<clr::SetupTrianglesArgs>(programs, {"setup_triangles"});
  checkArgs<clr::SetupClipArgs>(programs, {"setup_clip"});
  checkArgs<clr::ScanChunksArgs>(programs, {"scan_chunks"});
  checkArgs<clr::BinFillClippedArgs>(programs, {"bin_fill_clipped"});
  checkArgs<clr::RasterArgs>(programs,
                             {"raster", "raster_hierarchical", "raster_float", "raster_spans", "raster_spans_float"});
  checkArgs<clr::ResolveArgs>(programs, {"resolve", "resolve_lambert"});
  checkArgs<clr::LinesFromSetupArgs>(programs, {"lines_from_setup"});
  checkArgs<clr::LinesBinCountArgs>(programs, {"lines_bin_count"});
  checkArgs<clr::LinesBinFillArgs>(programs, {"lines_bin_fill"});
  checkArgs<clr::LinesDrawArgs>(programs, {"lines_draw"});
  checkArgs<clr::AovArgs>(programs, {"aov"});
  checkArgs<clr::RastOutputsArgs>(programs, {"rast_outputs"});
  checkArgs<clr::PeelArgs>(programs, {"peel_layer"});
  checkArgs<clr::RasterizeGradArgs>(programs, {"rasterize_grad"});
  checkArgs<clr::InterpolateGradArgs>(programs, {"interpolate_grad"});
  checkArgs<clr::TextureFwdArgs>(programs, {"texture_fwd"});
  checkArgs<clr::TextureGradArgs>(programs, {"texture_grad"});
  checkArgs<clr::MipBuildArgs>(programs, {"mip_build"});
  checkArgs<clr::MipGradDownArgs>(programs, {"mip_grad_down"});
  checkArgs<clr::AntialiasFwdArgs>(programs, {"antialias_fwd"});
  checkArgs<clr::AntialiasGradArgs>(programs, {"antialias_grad"});
}
