// camera.cpp — default framing and validation (see camera.h).
#include "render/camera.h"

#include "base/error.h"
#include "render/depth.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace clr {

glm::mat4 Camera::viewProjection(uint32_t width, uint32_t height, uint32_t depthMode) const
{
  const glm::mat4 projection = depthMode == CLR_DEPTH_REVERSED
                                   ? reversedPerspective(glm::radians(fovDegrees), width / (float)height, zNear, zFar)
                                   : glm::perspective(glm::radians(fovDegrees), width / (float)height, zNear, zFar);
  return projection * glm::lookAt(eye, target, up);
}

glm::vec3 Camera::lightDirection() const
{
  const glm::vec3 back = glm::normalize(eye - target);
  const glm::vec3 right = glm::normalize(glm::cross(up, back));
  const glm::vec3 trueUp = glm::cross(back, right);
  return glm::normalize(back + 0.6f * trueUp + 0.4f * right);
}

namespace {

const glm::vec3 kDefaultUp(0.0f, 1.0f, 0.0f);

void checkNear(float zNear, const std::string& prefix)
{
  if (!(zNear > 0.0f) || !std::isfinite(zNear)) throw Error(prefix + "near must be > 0");
}

void checkFar(float zNear, float zFar, const std::string& prefix)
{
  if (!(zFar > zNear) || !std::isfinite(zFar)) throw Error(prefix + "far must be greater than " + prefix + "near");
}

void checkViewDirection(glm::vec3 eye, glm::vec3 target, glm::vec3 up, const std::string& prefix)
{
  const glm::vec3 view = target - eye;
  if (!std::isfinite(glm::length(view)))
    throw Error(prefix + "eye and " + prefix + "target lie too far apart for float arithmetic");
  if (!(glm::length(view) > 0.0f)) throw Error(prefix + "eye and " + prefix + "target must differ");
  if (!(glm::length(glm::cross(view, up)) > 1e-6f * glm::length(view) * glm::length(up)))
    throw Error(prefix + "up must not be parallel to the view direction");
}

}  // namespace

void checkCameraArgs(const CameraArgs& args, const std::string& prefix)
{
  if (!(args.fovDegrees > 0.0f && args.fovDegrees < 180.0f)) throw Error(prefix + "fov must lie in (0, 180) degrees");
  if (args.zNear) checkNear(*args.zNear, prefix);
  if (args.zNear && args.zFar) checkFar(*args.zNear, *args.zFar, prefix);
  if (args.eye && args.target) checkViewDirection(*args.eye, *args.target, args.up.value_or(kDefaultUp), prefix);
}

Camera frameCamera(const CameraArgs& args, const Bounds& bounds, const std::string& prefix)
{
  // Step 1: what the arguments alone decide (the field of view first,
  // everything else may depend on it).
  checkCameraArgs(args, prefix);
  Camera cam;
  cam.fovDegrees = args.fovDegrees;
  const glm::vec3 centre = bounds.empty ? glm::vec3(0.0f) : 0.5f * (bounds.min + bounds.max);
  // A scene of one point (or one far smaller than its distance from the
  // origin) still gets a radius the eye can stand off by in float.
  const float centreScale = glm::max(glm::max(std::fabs(centre.x), std::fabs(centre.y)), std::fabs(centre.z));
  const float radius =
      bounds.empty ? 1.0f : std::max({0.5f * glm::length(bounds.max - bounds.min), 1e-6f, 1e-4f * centreScale});

  // Step 2: eye on a diagonal above the scene, far enough to see the sphere.
  cam.target = args.target.value_or(centre);
  cam.up = args.up.value_or(kDefaultUp);
  const float halfFov = glm::radians(cam.fovDegrees) * 0.5f;
  const float distance = radius / std::tan(std::min(halfFov, 1.2f)) * 1.1f;
  cam.eye = args.eye.value_or(cam.target + distance * glm::normalize(glm::vec3(0.55f, 0.45f, 1.0f)));

  // Step 3: near and far enclose the bounding sphere.
  const float eyeDistance = glm::length(centre - cam.eye);
  cam.zFar = args.zFar.value_or(eyeDistance + 1.5f * radius);
  cam.zNear = args.zNear.value_or(std::max(cam.zFar * 1e-4f, (eyeDistance - 1.5f * radius) * 0.9f));

  // Step 4: validate. Planes derived from an eye or fov beyond float range are not finite: say so, not "near".
  const float reach = glm::length(cam.target - cam.eye);
  if (!args.eye && !(std::isfinite(reach) && std::isfinite(eyeDistance)))
    throw Error(prefix + "fov: too narrow to frame the scene in float range (give " + prefix + "eye)");
  checkViewDirection(cam.eye, cam.target, cam.up, prefix);
  if (!std::isfinite(eyeDistance)) throw Error(prefix + "eye lies too far from the scene for float arithmetic");
  checkNear(cam.zNear, prefix);
  checkFar(cam.zNear, cam.zFar, prefix);
  return cam;
}

}  // namespace clr
