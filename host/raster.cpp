// raster.cpp — host side of kernels/raster.cl: one work-group per tile,
// with one work-item per pixel sample (GPU) or per tile (CPU), writing the
// visibility buffer.
#include "pipeline.h"

namespace clr {

void Pipeline::raster()
{
  const uint64_t pixels = uint64_t(params_.width) * params_.height;
  visIndex_.reserve(pixels);
  visAttr_.reserve(3 * pixels);
  cl::Event event;
  setArgs(rasterKernel_, paramsBuf_.get(), setup_.get(), tileCount_.get(), binEntries_.get(), visIndex_.get(),
          visAttr_.get());
  // One work-item per pixel (GPU shape) or per tile (CPU shape, see raster.cl).
  const bool perPixel = cl_.lanes == 1;
  const cl::NDRange global = perPixel ? cl::NDRange(params_.tilesX * CLR_TILE_SIZE, params_.tilesY * CLR_TILE_SIZE)
                                      : cl::NDRange(params_.tilesX, params_.tilesY);
  const cl::NDRange local = perPixel ? cl::NDRange(CLR_TILE_SIZE, CLR_TILE_SIZE) : cl::NDRange(1, 1);
  cl_.queue.enqueueNDRangeKernel(rasterKernel_, cl::NullRange, global, local, nullptr, &event);
  record("raster", event);
}

}  // namespace clr
