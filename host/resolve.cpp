// resolve.cpp — host side of kernels/resolve.cl: perspective-correct
// attribute resolve and shading of the visibility buffer into RGBA8.
#include "pipeline.h"

namespace clr {

void Pipeline::resolve()
{
  image_.reserve(uint64_t(params_.width) * params_.height, true);
  cl::Event event;
  cl::Kernel& kernel = resolveKernel_;
  setArgs(kernel, paramsBuf_.get(), visIndex_.get(), visAttr_.get(), tileCount_.get(), setup_.get(), clipBary_.get(),
          indices_.get(), positions_.get(), normals_.get(), uvs_.get(), colors_.get(), triMaterial_.get(),
          materials_.get(), texDescs_.get(), texels_.get(), image_.get(), tileSlot_.get(), visPlane());
  const size_t row = size_t(cl_.lanes);
  cl_.queue.enqueueNDRangeKernel(kernel, cl::NullRange,
                                 cl::NDRange(params_.tilesX * CLR_TILE_SIZE / row, params_.tilesY * CLR_TILE_SIZE),
                                 cl::NDRange(CLR_TILE_SIZE / row, row == 1 ? CLR_TILE_SIZE : 1), nullptr, &event);
  record("resolve", event);
}

}  // namespace clr
