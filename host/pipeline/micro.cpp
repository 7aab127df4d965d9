// micro.cpp — host side of the micro-triangle path (kernels/micro.h): which
// frames take it, and microKey_, the buffer of its fragments, which raster
// leaves all ones (CLR_MICRO_CLEAR) after each frame. Setup's count pass
// flags tiles in tileMicro_ (zeroed with the tile counts, setup.cpp), emit
// writes fragments (setupEmit), raster merges them (raster.cpp).
#include "pipeline/pipeline.h"

#include <algorithm>
#include <cstdlib>
#include <string>

namespace clr {

// Pixel positions a triangle's bounds may hold to take the micro path by
// default: 0 (off), as measured on PoCL's CPU device, where the path's emit
// costs more than the binning and raster it saves at every limit tried
// (docs/methods.md, "Micro triangles"); CLRASTER_MICRO_MAX or
// FrameSettings.microMax turn it on.
constexpr uint32_t kMicroMaxDefault = 0;
// A micro triangle lies in one tile, so no limit above its pixels means more.
constexpr uint32_t kMicroMaxMost = CLR_TILE_SIZE * CLR_TILE_SIZE;

void Pipeline::initMicro()
{
  const std::string extensions = cl_.queue.getInfo<CL_QUEUE_DEVICE>().getInfo<CL_DEVICE_EXTENSIONS>();
  microAtomics_ = extensions.find("cl_khr_int64_extended_atomics") != std::string::npos;
  if (const char* env = std::getenv("CLRASTER_MICRO_MAX")) {
    char* end = nullptr;
    const long value = std::strtol(env, &end, 10);
    if (*env == '\0' || *end != '\0' || value < 0)
      throw Error("CLRASTER_MICRO_MAX " + userText(env) + ": expected a count of pixels, 0 for off");
    microEnv_ = int32_t(std::min<long>(value, kMicroMaxMost));
  }
}

uint32_t Pipeline::microMaxFor(const FrameSettings& settings) const
{
  // The path writes depth-tested fragments with raster's exact integers: the
  // z-buffer, fixed edges and an exact traversal. Depth peeling and the
  // library's rasterize read every triangle's bins (clip-space contexts).
  if (!microAtomics_ || cl_.clipInput || settings.visibility != CLR_VISIBILITY_ZBUFFER ||
      settings.edgeMode != CLR_EDGES_FIXED || settings.traversal == CLR_TRAVERSAL_SPANS_FLOAT)
    return 0;
  if (settings.microMax >= 0) return std::min<uint32_t>(uint32_t(settings.microMax), kMicroMaxMost);
  return microEnv_ >= 0 ? uint32_t(microEnv_) : kMicroMaxDefault;
}

void Pipeline::reserveMicroKeys(uint32_t slots)
{
  if (microMax_ == 0) {
    microCap_ = 0;
    return;
  }
  microRecord_.reserve(fileOrder_ ? 1 : params_.numTris);
  const uint64_t perSlot = uint64_t(CLR_TILE_SIZE) * CLR_TILE_SIZE * params_.samples;
  const uint64_t before = microKey_.capacity();
  microKey_.reserve(std::max<uint64_t>(slots, 1) * perSlot);
  microCap_ = uint32_t(std::min<uint64_t>(microKey_.capacity() / perSlot, UINT32_MAX));
  if (microDirty_ || microKey_.capacity() != before)
    cl_.queue.enqueueFillBuffer(microKey_.get(), cl_ulong(~0ull), 0, microKey_.capacity() * sizeof(cl_ulong));
  // Raster clears what emit writes; until it runs, the buffer holds fragments.
  microDirty_ = true;
}

}  // namespace clr
