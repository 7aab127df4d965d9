// peel.cpp — host side of kernels/diff_peel.cl: one depth-peeling layer of a
// clip-input frame after setup and bin (the library's DepthPeeler,
// include/clraster/diff.hpp). Uploads the floor depths, runs one work-item
// per pixel over its tile's bin list, reads rast, rast_db and the layer's
// depths back (blocking); a batched frame's images one after another.
#include "pipeline/kernel_args.h"
#include "pipeline/pipeline.h"

namespace clr {

void Pipeline::peelLayer(const float* floor, float* rast, float* db, float* next)
{
  if (!cl_.clipInput) throw Error("peelLayer needs a context built for clip-space input");
  if (params_.edgeMode != CLR_EDGES_FIXED || params_.samples != 1 || params_.visibility == CLR_VISIBILITY_PAINTER)
    throw Error("peelLayer: needs one sample, fixed edges and the depth test");
  // A batched frame's images (FrameSettings::imageTris) sit imageRows apart; the caller's arrays hold them back to
  // back, width·imageHeight pixels each.
  const uint64_t n = uint64_t(params_.width) * params_.height;
  const uint64_t rows = params_.imageTris ? params_.imageRows : params_.height, images = params_.height / rows;
  const uint64_t image = uint64_t(params_.width) * params_.imageHeight, stride = uint64_t(params_.width) * rows;
  peelFloor_.reserve(n, true);
  peelNext_.reserve(n, true);
  rastOut_.reserve(n, true);
  rastDb_.reserve(db ? n : 1, true);
  for (uint64_t k = 0; k < images; ++k)
    cl_.queue.enqueueWriteBuffer(peelFloor_.get(), CL_FALSE, k * stride * sizeof(float), image * sizeof(float),
                                 floor + k * image);
  cl::Kernel& kernel = extraKernel(peelKernel_, "peel_layer");
  PeelArgs args;
  args.params = paramsBuf_.get(), args.setup = setup_.get(), args.tileOffset = tileCount_.get();
  args.binEntries = binEntries_.get(), args.source = setupSource_.get(), args.clipBary = clipBary_.get();
  args.indices = indices_.get(), args.positions = positions_.get(), args.floorDepth = peelFloor_.get();
  args.rast = rastOut_.get(), args.db = rastDb_.get(), args.withDb = db ? 1 : 0, args.nextFloor = peelNext_.get();
  setKernelArgs(kernel, args);
  cl::Event event;
  cl_.queue.enqueueNDRangeKernel(kernel, cl::NullRange,
                                 cl::NDRange(params_.tilesX * CLR_TILE_SIZE, params_.tilesY * CLR_TILE_SIZE),
                                 cl::NDRange(CLR_TILE_SIZE, CLR_TILE_SIZE), nullptr, &event);
  record("peel_layer", event);
  for (uint64_t k = 0; k < images; ++k) {
    cl_.queue.enqueueReadBuffer(rastOut_.get(), CL_FALSE, k * stride * sizeof(cl_float4), image * sizeof(cl_float4),
                                rast + 4 * k * image);
    if (db)
      cl_.queue.enqueueReadBuffer(rastDb_.get(), CL_FALSE, k * stride * sizeof(cl_float4), image * sizeof(cl_float4),
                                  db + 4 * k * image);
    cl_.queue.enqueueReadBuffer(peelNext_.get(), CL_FALSE, k * stride * sizeof(float), image * sizeof(float),
                                next + k * image);
  }
  cl_.queue.finish();
}

}  // namespace clr
