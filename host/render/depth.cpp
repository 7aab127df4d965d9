// depth.cpp — depth format names, the reversed projection and the auto rule
// (see depth.h).
#include "render/depth.h"

#include "kernels/shared.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>

namespace clr {

const char* depthModeName(uint32_t depthMode)
{
  switch (depthMode) {
    case CLR_DEPTH_UNORM24: return "unorm24";
    case CLR_DEPTH_REVERSED: return "reversed";
    default: return "float32";
  }
}

glm::mat4 reversedPerspective(float fovyRadians, float aspect, float zNear, float zFar)
{
  glm::mat4 p = glm::perspective(fovyRadians, aspect, zNear, zFar);
  // Step 1: z_clip = A·z_eye + B with A = n/(f − n), B = n·f/(f − n), in double.
  const double n = zNear, f = zFar;
  p[2][2] = float(n / (f - n));
  p[3][2] = float(n * f / (f - n));
  return p;
}

std::string DepthChoice::json() const
{
  return std::string("{\"depth\":\"") + depthModeName(mode) + "\",\"reason\":\"" + reason + "\"}";
}

DepthChoice chooseDepthFormat(float zNear, float zFar)
{
  DepthChoice c;
  const double ratio = double(zFar) / double(zNear);
  char text[200];
  if (ratio <= kFloat32MaxFarNear) {
    c.mode = CLR_DEPTH_FLOAT32;
    std::snprintf(text, sizeof text, "far/near %.4g <= %.4g: float32 resolves planes 1e-3 of their distance apart",
                  ratio, kFloat32MaxFarNear);
  } else {
    c.mode = CLR_DEPTH_REVERSED;
    std::snprintf(text, sizeof text, "far/near %.4g > %.4g: float32 misorders planes 1e-3 of their distance apart",
                  ratio, kFloat32MaxFarNear);
  }
  c.reason = text;
  return c;
}

}  // namespace clr
