// api_diff.cpp — the public backward passes (include/clraster/diff.hpp)
// over the pipeline's DiffKernels (host/pipeline/diff.h), which run on the
// Context's clip-input device context. Arguments are checked here (null
// arrays, index ranges) before anything reaches the device.
#include "api/api_impl.h"

#include "pipeline/diff.h"

#include <clraster/diff.hpp>

namespace clraster {

clr::DiffKernels& Context::Impl::diffKernels()
{
  rasterPipeline();  // builds the clip-input context
  if (!diff) diff = std::make_unique<clr::DiffKernels>(*clip);
  return *diff;
}

namespace {

void checkBatch(const ImageBatch& b, const char* call)
{
  if (b.images && (b.width == 0 || b.height == 0 || b.width > CLR_MAX_VIEWPORT || b.height > CLR_MAX_VIEWPORT))
    throw Error(std::string(call) + ": resolution " + std::to_string(b.height) + "x" + std::to_string(b.width) +
                " outside 1.." + std::to_string(CLR_MAX_VIEWPORT));
}

void checkTri(const int32_t* tri, size_t numTriangles, size_t numVertices)
{
  if (numTriangles && !tri) throw Error("tri: null array");
  for (size_t k = 0; k < 3 * numTriangles; ++k)
    if (tri[k] < 0 || size_t(tri[k]) >= numVertices)
      throw Error("tri: vertex index " + std::to_string(tri[k]) + " outside 0.." +
                  std::to_string(int64_t(numVertices) - 1));
}

void need(const void* p, bool wanted, const char* name)
{
  if (wanted && !p) throw Error(std::string(name) + ": null array");
}

}  // namespace

void rasterizeGrad(Context& ctx, const float* pos, size_t numVertices, size_t posImages, const int32_t* tri,
                   size_t numTriangles, const ImageBatch& batch, const float* rast, const float* gradRast,
                   const float* gradDb, float* gradPos)
{
  guarded([&] {
    checkBatch(batch, "rasterize_grad");
    if (posImages != 1 && posImages != batch.images)
      throw Error("pos: " + std::to_string(posImages) + " images for a batch of " + std::to_string(batch.images));
    checkTri(tri, numTriangles, numVertices);
    const size_t pixels = batch.images * batch.width * batch.height;
    need(pos, numVertices, "pos");
    need(gradPos, numVertices, "grad_pos");
    need(rast, pixels, "rast");
    need(gradRast, pixels, "grad_rast");
    ctx.impl().diffKernels().rasterizeGrad(pos, numVertices, posImages, tri, numTriangles,
                                           {batch.images, batch.width, batch.height}, rast, gradRast, gradDb, gradPos);
  });
}

void interpolateGrad(Context& ctx, const float* attr, size_t numVertices, size_t numAttrs, size_t attrImages,
                     const float* rast, const ImageBatch& batch, const int32_t* tri, size_t numTriangles,
                     const float* gradOut, const float* db, const std::vector<int>& diffAttrs, const float* gradDa,
                     float* gradAttr, float* gradRast, float* gradDb)
{
  guarded([&] {
    checkBatch(batch, "interpolate_grad");
    if (attrImages != 1 && attrImages != batch.images)
      throw Error("attr: " + std::to_string(attrImages) + " images for a batch of " + std::to_string(batch.images));
    checkTri(tri, numTriangles, numVertices);
    std::vector<int> listed;
    for (int j : diffAttrs) {
      const int64_t k = j < 0 ? int64_t(j) + int64_t(numAttrs) : int64_t(j);
      if (k < 0 || k >= int64_t(numAttrs))
        throw Error("diff_attrs: attribute " + std::to_string(j) + " outside 0.." + std::to_string(numAttrs) + " - 1");
      listed.push_back(int(k));
    }
    const size_t pixels = batch.images * batch.width * batch.height;
    need(attr, numVertices != 0 && numAttrs != 0, "attr");
    need(gradAttr, numVertices != 0 && numAttrs != 0, "grad_attr");
    need(rast, pixels, "rast");
    need(gradOut, pixels != 0 && numAttrs != 0, "grad_out");
    need(gradRast, pixels, "grad_rast");
    need(db, pixels && !listed.empty(), "rast_db");
    need(gradDa, pixels && !listed.empty(), "grad_da");
    need(gradDb, pixels && !listed.empty(), "grad_db");
    ctx.impl().diffKernels().interpolateGrad(attr, numVertices, numAttrs, attrImages, rast,
                                             {batch.images, batch.width, batch.height}, tri, numTriangles, gradOut, db,
                                             listed, gradDa, gradAttr, gradRast, gradDb);
  });
}

}  // namespace clraster
