// diff.hpp — the backward passes of clraster::rasterize and interpolate
// (clraster.hpp), for gradient-based optimisation (the Python module
// clraster.torch wraps them as torch.autograd Functions). Both run as one
// OpenCL launch over every pixel of a batch of images on the Context's
// device; gradients are those of the forward formulas at the pixel centres
// with coverage held fixed (a pixel keeps its triangle), as in nvdiffrast.
// Arrays are row-major, images one after another, row 0 at the bottom.
#pragma once

#include "clraster.hpp"

namespace clraster {

// images × height × width pixels.
struct ImageBatch {
  size_t images = 0;
  uint32_t width = 0, height = 0;
};

// d L / d pos from d L / d rast (gradRast, 4 floats per pixel: u, v, z/w,
// id; the id's gradient is ignored) and, when not null, d L / d rast_db
// (gradDb, 4 floats per pixel). pos: posImages × numVertices × 4 floats
// (posImages 1: every image shares pos; else batch.images, instanced);
// rast: rasterize's output for the batch (ids index tri); gradPos: pos's
// shape, overwritten.
CLRASTER_API void rasterizeGrad(Context& ctx, const float* pos, size_t numVertices, size_t posImages,
                                const int32_t* tri, size_t numTriangles, const ImageBatch& batch, const float* rast,
                                const float* gradRast, const float* gradDb, float* gradPos);

// d L / d attr (gradAttr, attr's shape: attrImages × numVertices ×
// numAttrs, attrImages 1 or batch.images), d L / d rast (gradRast, 4 floats
// per pixel; channels z/w and id get 0) and, with diffAttrs (indices, as
// interpolateInto takes them), d L / d rast_db (gradDb, 4 per pixel) from
// d L / d out (gradOut, numAttrs per pixel) and d L / d out_da (gradDa,
// 2 · diffAttrs.size() per pixel).
CLRASTER_API void interpolateGrad(Context& ctx, const float* attr, size_t numVertices, size_t numAttrs,
                                  size_t attrImages, const float* rast, const ImageBatch& batch, const int32_t* tri,
                                  size_t numTriangles, const float* gradOut, const float* db,
                                  const std::vector<int>& diffAttrs, const float* gradDa, float* gradAttr,
                                  float* gradRast, float* gradDb);

}  // namespace clraster
