// depth.h — the depth formats (kernels/shared.h, CLR_DEPTH_*): names, the
// reversed-Z projection and the `--depth auto` rule.
//
// float32 is GL's convention: window z = z_ndc/2 + 1/2, LESS, clear 1.
// unorm24 quantises that z to rint(z·(2^24 − 1)) before the compare, as a GL
// depth24 buffer does. reversed is a float buffer whose window depth comes
// straight from a reversed projection (near → 1, far → 0, GREATER, clear 0):
// z_clip = n/(f − n)·z_eye + n·f/(f − n), w_clip = −z_eye, so z/w = n(f − d)/
// (d(f − n)) for eye distance d. Float's relative precision is then spent
// where depth shrinks, far away, instead of being cancelled against 1 as
// 1 − z would be. The auto rule picks from the measured z-fighting table
// (docs/bench/zfight.csv, bench/zfight.cpp; docs/limits.md).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>

namespace clr {

const char* depthModeName(uint32_t depthMode);  // "float32", "unorm24", "reversed"

// glm::perspective with the depth rows replaced by the reversed mapping above.
glm::mat4 reversedPerspective(float fovyRadians, float aspect, float zNear, float zFar);

// The largest far/near ratio (of 10^1, 10^1.5, ..., 10^6) at which float32
// kept every pixel of the z-fighting bench correctly ordered for planes
// 10^-3 of their distance apart: 0 of 131,072 pixels wrong at 10^4, 16,816
// (12.8%) at 10^4.5 (docs/bench/zfight_summary.csv; docs/limits.md, "Depth
// precision"). reversed had 0 wrong pixels at every ratio up to 10^6 for
// separations down to 10^-6 of the distance.
constexpr double kFloat32MaxFarNear = 1e4;

struct DepthChoice {
  uint32_t mode = 0;  // CLR_DEPTH_*
  std::string reason;
  std::string warning;       // a float or 24-bit depth beyond kFloat32MaxFarNear: surfaces may z-fight or vanish
  std::string json() const;  // for --stats
};

// `--depth auto`: float32 while far/near <= kFloat32MaxFarNear, reversed beyond.
DepthChoice chooseDepthFormat(float zNear, float zFar);

}  // namespace clr
