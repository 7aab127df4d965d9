// aa.h — the anti-aliasing modes and their sample positions, in one place.
//
// A mode is a sample count and a shading frequency: MSAA tests coverage and
// depth per sample and shades once per pixel and covering triangle, SSAA
// shades every sample. Sample k of a pixel lies at the pixel centre plus
// the standard Direct3D / Vulkan position of its count (the same positions
// Mesa llvmpipe uses, read in clraster's y-up screen space), given in
// 1/16 pixel and stored in fixed-point units (×16 at 8 subpixel bits). The
// resolve is the box filter of the notes (004): equal weights.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace clr {

struct AaMode {
  const char* name;  // as the --aa flag spells it
  uint32_t samples;
  bool shadeEverySample;  // SSAA
};

// none, msaa2, msaa4, msaa8, msaa16, ssaa4, ssaa16 (cheapest first).
const std::vector<AaMode>& aaModes();

// The mode named `name`; throws clr::Error listing the names otherwise.
const AaMode& findAaMode(const std::string& name);

// The name of the mode with these settings.
std::string aaModeName(uint32_t samples, bool shadeEverySample);

// Sample k's offset from the pixel centre, in 1/16 pixel (x right, y up).
struct SampleOffset {
  int x, y;
};
const std::vector<SampleOffset>& samplePositions(uint32_t samples);  // samples ∈ {1, 2, 4, 8, 16}

}  // namespace clr
