// frame_request.cpp — a frame's settings from the arguments (see frame_request.h).
#include "render/frame_request.h"

#include "pipeline/aa.h"

#include <cstdio>

namespace clr {

FrameSettings makeFrameSettings(const RenderArgs& args, const Camera& camera, uint32_t width, uint32_t height,
                                const Bounds& sceneBounds, DepthChoice* depth)
{
  // Step 1: the depth format: --depth as given, or the auto rule, which
  // --quality auto applies too unless --depth names a format.
  DepthChoice chosen;
  if (args.depthAuto || (args.qualityAuto && !args.depthGiven)) {
    chosen = chooseDepthFormat(camera.zNear, camera.zFar);
  } else {
    chosen.mode = args.depthMode;
    chosen.reason = "--depth";
  }
  const double farNear = double(camera.zFar) / double(camera.zNear);
  if (chosen.mode != CLR_DEPTH_REVERSED && farNear > kFloat32MaxFarNear) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "far/near = %.3g is over %s depth's 1e4: surfaces may z-fight or vanish (--depth reversed or auto "
                  "keeps them)",
                  farNear, depthModeName(chosen.mode));
    chosen.warning = text;
  }
  if (depth) *depth = chosen;

  // Step 2: the camera and the viewport.
  FrameSettings s;
  s.width = width;
  s.height = height;
  s.depthMode = chosen.mode;
  s.mvp = camera.viewProjection(width, height, chosen.mode);
  s.lightDir = camera.lightDirection();
  s.eye = camera.eye;
  s.zNear = camera.zNear;
  s.zFar = camera.zFar;

  // Step 3: shading, lights and methods.
  s.shadeMode = args.shadeMode;
  s.cullBack = args.cullBack;
  s.texFilter = args.texFilter;
  s.pointLightOn = args.pointLightOn;
  s.pointLight = args.pointLight;
  const float radius = sceneBounds.empty ? 1.0f : 0.5f * glm::length(sceneBounds.max - sceneBounds.min);
  s.pointLightRange = args.pointLightRange.value_or(radius > 0.0f ? radius : 1.0f);
  if (args.aa != "auto") {
    const AaMode& mode = findAaMode(args.aa.empty() ? "none" : args.aa);
    s.samples = mode.samples;
    s.shadeEverySample = mode.shadeEverySample;
  }
  s.edgeMode = args.edgeMode;
  s.interpMode = args.interpMode;
  s.traversal = args.traversal;
  s.visibility = args.visibility;
  s.wireframe = args.wireframe;
  s.lineMethod = args.lineMethod;
  s.lineWidth = args.lineWidth;
  s.pointSize = args.pointSize;
  s.keepVisAttributes = !args.aovPath.empty();  // the AOVs read the depth and barycentric planes
  return s;
}

}  // namespace clr
