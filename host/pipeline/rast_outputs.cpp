// rast_outputs.cpp — host side of kernels/rast_outputs.cl and the clip-space
// scene upload of the library's rasterize (api.cpp): positions are the
// caller's clip coordinates, so setup reads them as they are (transform.cl,
// CLR_CLIP_INPUT), and after raster one work-item per pixel writes
// nvdiffrast's rast, rast_db and the exact triangle ids.
#include "pipeline/pipeline.h"

namespace clr {

void Pipeline::uploadClipScene(const float* positions, size_t numVerts, const uint32_t* indices, size_t numTris)
{
  if (!cl_.clipInput) throw Error("uploadClipScene needs a context built for clip-space input");
  if (numTris > UINT32_MAX / CLR_MAX_SUBTRIS) throw Error("too many triangles");
  if (numVerts > UINT32_MAX / 4) throw Error("too many vertices");
  placeClipScene(positions, numVerts, indices, numTris);
  framedScene_ = false;
  paintOrder_.clear();
  triCount_.reserve(numTris, true);
  params_.numVerts = uint32_t(numVerts);
  params_.numTris = uint32_t(numTris);
}

void Pipeline::rastOutputs(bool ids, bool derivatives)
{
  if (!params_.visAttributes || !cl_.clipInput)
    throw Error("rastOutputs: needs a clip-input frame that kept its visibility attributes");
  const uint64_t n = uint64_t(params_.width) * params_.height;
  rastOut_.reserve(n, true);
  rastIds_.reserve(ids ? n : 1, true);
  rastDb_.reserve(derivatives ? n : 1, true);
  rastIdsWritten_ = ids;
  rastDbWritten_ = derivatives;
  cl::Kernel& kernel = extraKernel(rastOutputsKernel_, "rast_outputs");
  RastOutputsArgs args;
  args.params = paramsBuf_.get(), args.visIndex = visIndex_.get(), args.visAttr = visAttr_.get();
  args.tileOffset = tileCount_.get(), args.source = setupSource_.get(), args.clipBary = clipBary_.get();
  args.indices = indices_.get(), args.positions = positions_.get(), args.tileSlot = tileSlot_.get();
  args.visPlane = visPlane(), args.rast = rastOut_.get(), args.ids = rastIds_.get(), args.db = rastDb_.get();
  args.outputs = (ids ? 1u : 0u) | (derivatives ? 2u : 0u);  // CLR_RAST_OUT_*
  setKernelArgs(kernel, args);
  launchPixels(kernel, "rast_outputs");
}

void Pipeline::readRastOutputs(float* rast, uint32_t* ids, float* db) const
{
  if ((db && !rastDbWritten_) || (ids && !rastIdsWritten_))
    throw Error("readRastOutputs: the frame did not write the ids or derivatives asked for");
  // Each image's rows (a batched frame's padding rows stay behind). Non-blocking reads, then one wait: the in-order
  // queue runs them after the kernel.
  const uint64_t rows = params_.imageTris ? params_.imageRows : params_.height;
  const uint64_t n = uint64_t(params_.width) * params_.imageHeight, stride = uint64_t(params_.width) * rows;
  for (uint64_t k = 0; k < params_.height / rows; ++k) {
    if (rast)
      cl_.queue.enqueueReadBuffer(rastOut_.get(), CL_FALSE, k * stride * sizeof(cl_float4), n * sizeof(cl_float4),
                                  rast + 4 * k * n);
    if (ids)
      cl_.queue.enqueueReadBuffer(rastIds_.get(), CL_FALSE, k * stride * sizeof(uint32_t), n * sizeof(uint32_t),
                                  ids + k * n);
    if (db)
      cl_.queue.enqueueReadBuffer(rastDb_.get(), CL_FALSE, k * stride * sizeof(cl_float4), n * sizeof(cl_float4),
                                  db + 4 * k * n);
  }
  cl_.queue.finish();
}

}  // namespace clr
