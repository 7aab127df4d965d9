// camera.h — the camera of the CLI, exactly as the brief states it:
//   mvp = glm::perspective(glm::radians(fov), W / (float)H, near, far)
//       * glm::lookAt(eye, target, up),
// vertical fov, GL clip conventions, model matrix the identity (with the
// reversed depth format the projection is depth.h's reversedPerspective,
// the same x and y rows). Missing
// values are chosen to frame the scene's bounds. An impossible camera is a
// clr::Error: from the arguments alone (checkCameraArgs) before any device
// work, or once framed (frameCamera).
#pragma once

#include "kernels/shared.h"
#include "io/scene.h"

#include <glm/glm.hpp>

#include <optional>
#include <string>

namespace clr {

struct CameraArgs {
  std::optional<glm::vec3> eye, target, up;
  float fovDegrees = 45.0f;
  std::optional<float> zNear, zFar;
};

struct Camera {
  glm::vec3 eye, target, up;
  float fovDegrees, zNear, zFar;
  glm::mat4 viewProjection(uint32_t width, uint32_t height, uint32_t depthMode = CLR_DEPTH_FLOAT32) const;
  // Towards the light: above, right of and behind the eye.
  glm::vec3 lightDirection() const;
};

// Fills unset fields so the scene's bounding sphere is in view, then
// validates the result. Error messages name each field with `prefix` before
// it: "--fov" for the command line, "fov" for a views file (views.h).
Camera frameCamera(const CameraArgs& args, const Bounds& bounds, const std::string& prefix = "--");

// frameCamera's checks that need no scene: the field of view, and those of
// near, far, eye, target and up that the arguments give. The commands run
// it before any device work, so that such a camera fails at once.
void checkCameraArgs(const CameraArgs& args, const std::string& prefix = "--");

}  // namespace clr
