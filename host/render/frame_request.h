// frame_request.h — the one place a frame's FrameSettings are built from a request.
//
// makeFrameSettings turns the render command's arguments (RenderArgs, flags.h),
// a framed camera (camera.h), a viewport and the scene's bounds into the
// settings Pipeline::render takes: the camera's matrix (reversed for the
// reversed depth format), light direction, eye and depth range; shading and
// culling; the methods the arguments name (--aa auto and --quality auto are
// left at their defaults: quality.h chooses them from a probe frame); the
// depth format (--depth, or the auto rule of depth.h); the point light, its
// range half the bounds' diagonal unless given; lines; and the visibility
// planes the AOVs read. The single-view and --views renders (api_command.cpp) and
// the bench tools call it; nothing else assembles a frame from arguments.
#pragma once

#include "render/camera.h"
#include "render/flags.h"
#include "render/depth.h"
#include "pipeline/frame_settings.h"
#include "io/scene.h"

namespace clr {

// depth, when given, receives the depth format's choice and its reason (--stats).
FrameSettings makeFrameSettings(const RenderArgs& args, const Camera& camera, uint32_t width, uint32_t height,
                                const Bounds& sceneBounds, DepthChoice* depth = nullptr);

}  // namespace clr
