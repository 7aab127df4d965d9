// raster.cpp — host side of kernels/raster.cl: one work-group per tile, one
// work-item per CLR_ROW_PIXELS pixel samples of a row, writing the
// visibility buffer.
#include "pipeline.h"

namespace clr {

void Pipeline::raster()
{
  vis_.reserve(uint64_t(params_.width) * params_.height);
  cl::Event event;
  rasterKernel_.setArg(0, paramsBuf_.get());
  rasterKernel_.setArg(1, setup_.get());
  rasterKernel_.setArg(2, tileCount_.get());
  rasterKernel_.setArg(3, binEntries_.get());
  rasterKernel_.setArg(4, vis_.get());
  const size_t row = size_t(cl_.rowPixels);
  cl_.queue.enqueueNDRangeKernel(rasterKernel_, cl::NullRange,
                                 cl::NDRange(params_.tilesX * CLR_TILE_SIZE / row, params_.tilesY * CLR_TILE_SIZE),
                                 cl::NDRange(CLR_TILE_SIZE / row, CLR_TILE_SIZE), nullptr, &event);
  record("raster", event);
}

}  // namespace clr
