// resolve.cpp — host side of kernels/resolve.cl and resolve_lambert.cl: perspective-correct
// attribute resolve and shading of the visibility buffer into RGBA8, with
// the lean resolve_lambert kernel for the common case and resolve for the rest.
#include "pipeline.h"

namespace clr {

void Pipeline::resolve()
{
  image_.reserve(uint64_t(params_.width) * params_.height, true);
  cl::Event event;
  // Step 1: the lean lambert kernel when the frame is its case (resolve_lambert.cl).
  const bool lean = settings_.leanResolve && params_.shadeMode == CLR_SHADE_LAMBERT && params_.samples == 1 &&
                    params_.interpMode == CLR_INTERP_PERSPECTIVE && !params_.pointLightOn &&
                    !(params_.sceneFlags & (CLR_SCENE_TEXTURES | CLR_SCENE_COLORS));
  leanResolve_ = lean;
  cl::Kernel& kernel = lean ? resolveLambertKernel_ : resolveKernel_;
  setArgs(kernel, paramsBuf_.get(), visIndex_.get(), visAttr_.get(), tileCount_.get(), setup_.get(), setupSource_.get(),
          clipBary_.get(), indices_.get(), positions_.get(), normals_.get(), uvs_.get(), colors_.get(),
          triMaterial_.get(), materials_.get(), texDescs_.get(), texels_.get(), image_.get(), tileSlot_.get(),
          visPlane());
  // Step 2: the work shape of resolve.cl's kernels: with rows of lanes as
  // wide as a tile, one work-item per tile; else one per row of lanes, a
  // tile per work-group.
  const size_t row = size_t(cl_.lanes);
  if (row == CLR_TILE_SIZE)
    cl_.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(params_.tilesX, params_.tilesY),
                                   cl::NDRange(1, 1), nullptr, &event);
  else
    cl_.queue.enqueueNDRangeKernel(kernel, cl::NullRange,
                                   cl::NDRange(params_.tilesX * CLR_TILE_SIZE / row, params_.tilesY * CLR_TILE_SIZE),
                                   cl::NDRange(CLR_TILE_SIZE / row, CLR_TILE_SIZE), nullptr, &event);
  record("resolve", event);
}

}  // namespace clr
