// resolve.cpp — host side of kernels/resolve.cl: perspective-correct
// attribute resolve and shading of the visibility buffer into RGBA8.
#include "pipeline.h"

namespace clr {

void Pipeline::resolve()
{
  image_.reserve(uint64_t(params_.width) * params_.height);
  cl::Event event;
  resolveKernel_.setArg(0, paramsBuf_.get());
  resolveKernel_.setArg(1, visIndex_.get());
  resolveKernel_.setArg(2, visAttr_.get());
  resolveKernel_.setArg(3, tileCount_.get());
  resolveKernel_.setArg(4, setup_.get());
  resolveKernel_.setArg(5, clipBary_.get());
  resolveKernel_.setArg(6, indices_.get());
  resolveKernel_.setArg(7, normals_.get());
  resolveKernel_.setArg(8, image_.get());
  const size_t row = size_t(cl_.lanes);
  cl_.queue.enqueueNDRangeKernel(resolveKernel_, cl::NullRange,
                                 cl::NDRange(params_.tilesX * CLR_TILE_SIZE / row, params_.tilesY * CLR_TILE_SIZE),
                                 cl::NDRange(CLR_TILE_SIZE / row, CLR_TILE_SIZE), nullptr, &event);
  record("resolve", event);
}

}  // namespace clr
