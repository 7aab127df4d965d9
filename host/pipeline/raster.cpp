// raster.cpp — host side of kernels/raster.cl: one work-group per tile and
// sample index, with one work-item per pixel sample (GPU) or per tile (CPU),
// writing one visibility plane per sample. With the painter's algorithm
// (CLR_VISIBILITY_PAINTER) it first sorts the triangles on the host, far to
// near by each triangle's farthest vertex: the largest window-depth
// direction z/w over its vertices with w > 0 (−z/w with the reversed
// projection), from the transform kernel's clip positions (run here: a
// frame otherwise transforms the vertices inside setup). Equal keys put the
// later input triangle first, so the earlier one is drawn last and wins, as an
// exact tie does in the z-buffer (both by the file's order, fileTri). The
// ranks go to the kernel, which keeps the fragment of the latest-drawn
// triangle; a z-buffer frame binds each triangle's index in the file there
// instead, for its ties.
#include "pipeline/pipeline.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <numeric>

namespace clr {

void Pipeline::sortForPainter()
{
  // Step 1: this frame's clip positions, and the indices (the host keeps none, device_scene.h).
  const uint32_t numTris = params_.numTris;
  const std::vector<uint32_t> indices = indices_.download(3 * uint64_t(numTris));
  transform();
  const std::vector<cl_float4> clip = clipPos_.download(params_.numVerts);
  // Step 2: each triangle's farthest vertex depth (−inf when all w <= 0).
  const float sign = params_.depthMode == CLR_DEPTH_REVERSED ? -1.0f : 1.0f;
  std::vector<float> key(numTris, -std::numeric_limits<float>::infinity());
  for (uint32_t t = 0; t < numTris; ++t)
    for (int v = 0; v < 3; ++v) {
      const cl_float4& c = clip[indices[3 * size_t(t) + v]];
      if (c.s[3] > 0.0f) key[t] = std::max(key[t], sign * c.s[2] / c.s[3]);
    }
  // Step 3: far to near; ties: the triangle later in the file first.
  paintOrder_.resize(numTris);
  std::iota(paintOrder_.begin(), paintOrder_.end(), 0u);
  std::sort(paintOrder_.begin(), paintOrder_.end(), [&](uint32_t a, uint32_t b) {
    return key[a] != key[b] ? key[a] > key[b] : fileTriHost_[a] > fileTriHost_[b];
  });
  std::vector<uint32_t> rank(numTris);
  for (uint32_t i = 0; i < numTris; ++i) rank[paintOrder_[i]] = i;
  paintRank_.upload(rank);
  for (uint32_t& t : paintOrder_) t = fileTriHost_[t];  // as the file numbers them
}

uint32_t Pipeline::visIndexBits(const FrameSettings& settings) const
{
  // The fewest bits that hold every setup index of the frame and the all-ones "none" (shared.h, visIndex).
  const uint32_t needed = numSetup_ < 0xFFFFu ? 16 : numSetup_ < 0xFFFFFFu ? 24 : 32;
  return std::max(needed, settings.minVisIndexBits <= 16 ? 16u : settings.minVisIndexBits <= 24 ? 24u : 32u);
}

void Pipeline::raster()
{
  // The visibility buffer: a block per non-empty tile and sample (shared.h),
  // its index entries as narrow as the frame's records allow, which the
  // parameters learn only now.
  const uint64_t samples = uint64_t(visPlane()) * params_.samples;
  if (samples > UINT32_MAX / 3)
    throw Error("the frame needs " + std::to_string(samples) + " visibility samples, more than 32-bit offsets address");
  params_.visIndexBits = visIndexBits(settings_);
  params_.visEntries = uint32_t(samples);
  // At most the whole viewport's tiles: no growth slack past that. (The
  // buffer counts 32-bit words.)
  const uint64_t most = uint64_t(numTiles_) * CLR_TILE_SIZE * CLR_TILE_SIZE * params_.samples;
  const uint64_t bits = params_.visIndexBits;
  visIndex_.reserve((samples * bits + 31) / 32, false, (most * bits + 31) / 32);
  visAttr_.reserve(params_.visAttributes ? 3 * samples : 1, false, 3 * most);  // else a 1-element dummy
  paintRank_.reserve(1);
  // Nothing binned: no tile has a block to write, and resolve paints background only.
  if (numBinEntries_ == 0) {
    paintOrder_.clear();
    return;
  }
  static_assert(offsetof(FrameParams, visEntries) == offsetof(FrameParams, visIndexBits) + sizeof(uint32_t));
  cl_.queue.enqueueWriteBuffer(paramsBuf_.get(), CL_FALSE, offsetof(FrameParams, visIndexBits), 2 * sizeof(uint32_t),
                               &params_.visIndexBits);
  const bool painter = params_.visibility == CLR_VISIBILITY_PAINTER;
  if (painter)
    sortForPainter();
  else
    paintOrder_.clear();
  // The method's variant: the default is in the frame program, the others
  // in the extras program (float edges take the bounding-box scan).
  cl::Kernel* kernel = &rasterKernel_;
  if (params_.edgeMode == CLR_EDGES_FLOAT)
    kernel = &extraKernel(rasterFloatKernel_, "raster_float");
  else if (params_.traversal == CLR_TRAVERSAL_HIERARCHICAL)
    kernel = &extraKernel(rasterHierarchicalKernel_, "raster_hierarchical");
  else if (params_.traversal == CLR_TRAVERSAL_SPANS)
    kernel = &extraKernel(rasterSpansKernel_, "raster_spans");
  else if (params_.traversal == CLR_TRAVERSAL_SPANS_FLOAT)
    kernel = &extraKernel(rasterSpansFloatKernel_, "raster_spans_float");
  RasterArgs args;
  args.params = paramsBuf_.get(), args.setup = setup_.get(), args.source = setupSource_.get();
  args.clipBary = clipBary_.get(), args.tileOffset = tileCount_.get(), args.binEntries = binEntries_.get();
  args.visIndex = visIndex_.get(), args.visAttr = visAttr_.get();
  args.paintRank = painter ? paintRank_.get() : fileTri_.get();
  args.tileSlot = tileSlot_.get(), args.visPlane = visPlane();
  args.tileMicro = tileMicro_.get(), args.microKey = microKey_.get(), args.microRecord = microRecord_.get();
  setKernelArgs(*kernel, args);
  const WorkShape shape = rasterShape(cl_.lanes, params_.tilesX, params_.tilesY, params_.samples);
  launch(*kernel, shape.global, shape.local, "raster");
  microDirty_ = false;  // raster clears the micro path's fragments (micro.h)
}

WorkShape rasterShape(int lanes, uint32_t tilesX, uint32_t tilesY, uint32_t samples)
{
  // One work-item per pixel sample (GPU shape) or per tile and sample index
  // (CPU shape, see raster.cl).
  if (lanes == 1)
    return {cl::NDRange(tilesX * CLR_TILE_SIZE, tilesY * CLR_TILE_SIZE, samples),
            cl::NDRange(CLR_TILE_SIZE, CLR_TILE_SIZE, 1)};
  return {cl::NDRange(tilesX, tilesY, samples), cl::NDRange(1, 1, 1)};
}

}  // namespace clr
