// raster.cpp — host side of kernels/raster.cl: one work-group per tile and
// sample index, with one work-item per pixel sample (GPU) or per tile (CPU),
// writing one visibility plane per sample.
#include "pipeline.h"

namespace clr {

void Pipeline::raster()
{
  const uint64_t samples = uint64_t(params_.width) * params_.height * params_.samples;
  visIndex_.reserve(samples);
  visAttr_.reserve(3 * samples);
  cl::Event event;
  setArgs(rasterKernel_, paramsBuf_.get(), setup_.get(), tileCount_.get(), binEntries_.get(), visIndex_.get(),
          visAttr_.get());
  // One work-item per pixel sample (GPU shape) or per tile and sample index
  // (CPU shape, see raster.cl).
  const bool perPixel = cl_.lanes == 1;
  const cl::NDRange global =
      perPixel ? cl::NDRange(params_.tilesX * CLR_TILE_SIZE, params_.tilesY * CLR_TILE_SIZE, params_.samples)
               : cl::NDRange(params_.tilesX, params_.tilesY, params_.samples);
  const cl::NDRange local = perPixel ? cl::NDRange(CLR_TILE_SIZE, CLR_TILE_SIZE, 1) : cl::NDRange(1, 1, 1);
  cl_.queue.enqueueNDRangeKernel(rasterKernel_, cl::NullRange, global, local, nullptr, &event);
  record("raster", event);
}

}  // namespace clr
