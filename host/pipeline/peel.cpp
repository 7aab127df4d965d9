// peel.cpp — host side of kernels/diff_peel.cl: one depth-peeling layer of a
// clip-input frame after setup and bin (the library's DepthPeeler,
// include/clraster/diff.hpp). Uploads the floor depths, runs one work-item
// per pixel over its tile's bin list, reads rast, rast_db and the layer's
// depths back (blocking).
#include "pipeline/pipeline.h"

namespace clr {

void Pipeline::peelLayer(const float* floor, float* rast, float* db, float* next)
{
  if (!cl_.clipInput) throw Error("peelLayer needs a context built for clip-space input");
  if (params_.edgeMode != CLR_EDGES_FIXED || params_.samples != 1 || params_.visibility == CLR_VISIBILITY_PAINTER)
    throw Error("peelLayer: needs one sample, fixed edges and the depth test");
  const uint64_t n = uint64_t(params_.width) * params_.height;
  peelFloor_.reserve(n, true);
  peelNext_.reserve(n, true);
  rastOut_.reserve(n, true);
  rastDb_.reserve(db ? n : 1, true);
  cl_.queue.enqueueWriteBuffer(peelFloor_.get(), CL_FALSE, 0, n * sizeof(float), floor);
  cl::Kernel& kernel = extraKernel(peelKernel_, "peel_layer");
  setArgs(kernel, paramsBuf_.get(), setup_.get(), tileCount_.get(), binEntries_.get(), setupSource_.get(),
          clipBary_.get(), indices_.get(), positions_.get(), peelFloor_.get(), rastOut_.get(), rastDb_.get(),
          cl_uint(db ? 1 : 0), peelNext_.get());
  cl::Event event;
  cl_.queue.enqueueNDRangeKernel(kernel, cl::NullRange,
                                 cl::NDRange(params_.tilesX * CLR_TILE_SIZE, params_.tilesY * CLR_TILE_SIZE),
                                 cl::NDRange(CLR_TILE_SIZE, CLR_TILE_SIZE), nullptr, &event);
  record("peel_layer", event);
  cl_.queue.enqueueReadBuffer(rastOut_.get(), CL_FALSE, 0, n * sizeof(cl_float4), rast);
  if (db) cl_.queue.enqueueReadBuffer(rastDb_.get(), CL_FALSE, 0, n * sizeof(cl_float4), db);
  cl_.queue.enqueueReadBuffer(peelNext_.get(), CL_FALSE, 0, n * sizeof(float), next);
  cl_.queue.finish();
}

}  // namespace clr
