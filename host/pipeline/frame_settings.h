// frame_settings.h — FrameSettings, what one frame renders, as a plain
// struct: the viewport, shading, culling, the coverage, depth and line
// methods and the lights. Pipeline::render takes it (pipeline.h); the
// render room builds it from flags (render/frame_request.h), the library
// from its arguments. Only kernels/shared.h's constants and glm.
#pragma once

#include "kernels/shared.h"

#include <glm/glm.hpp>

#include <cstdint>

namespace clr {

// What one frame renders: viewport, shading, culling and the methods.
struct FrameSettings {
  uint32_t width = 0, height = 0;
  uint32_t shadeMode = CLR_SHADE_LAMBERT;
  bool cullBack = false;
  uint32_t samples = 1;           // per pixel: 1, 2, 4, 8, 16 (aa.h)
  bool shadeEverySample = false;  // SSAA rather than MSAA
  uint32_t edgeMode = CLR_EDGES_FIXED;
  uint32_t interpMode = CLR_INTERP_PERSPECTIVE;
  uint32_t traversal = CLR_TRAVERSAL_BBOX;
  // Depth format (CLR_DEPTH_*); CLR_DEPTH_REVERSED needs a reversed
  // projection in mvp (Camera::viewProjection builds one, depth.h).
  uint32_t depthMode = CLR_DEPTH_FLOAT32;
  uint32_t visibility = CLR_VISIBILITY_ZBUFFER;  // CLR_VISIBILITY_*
  glm::mat4 mvp{1.0f};
  glm::vec3 lightDir{0.0f, 0.0f, 1.0f};  // world space, towards the light
  glm::vec3 eye{0.0f, 0.0f, 0.0f};       // world space, for specular highlights
  bool pointLightOn = false;             // a point light besides the directional one
  glm::vec3 pointLight{0.0f};            // its position, world space
  float pointLightRange = 1.0f;          // r of the attenuation 1 / (1 + (d / r)²), > 0
  uint32_t texFilter = CLR_FILTER_TRILINEAR;
  float zNear = 0.1f, zFar = 100.0f;  // for depth shading only
  // Lines (lines.cpp): wireframe mode, method and anti-aliased width in pixels.
  uint32_t wireframe = CLR_WIREFRAME_OFF;
  uint32_t lineMethod = CLR_LINE_AA;
  float lineWidth = 1.0f;
  // A file's points (Mesh::points): squares of this many pixels a side (file_primitives.cpp).
  uint32_t pointSize = 1;
  // Raster also writes the depth and barycentric planes of the visibility
  // buffer (12 more bytes per sample), for aov() and for the depth and
  // barycentrics of readVis(). Frames with lines or float edges have them
  // anyway; otherwise resolve recomputes the barycentrics (shared.h).
  bool keepVisAttributes = false;
  // Lets resolve use its lean lambert kernel when the frame qualifies
  // (Pipeline::resolve); tests turn it off to compare the two kernels.
  bool leanResolve = true;
  // The fewest bits of a visibility index (16, 24 or 32; more when the
  // frame's setup records need them, shared.h): tests compare the widths.
  uint32_t minVisIndexBits = 16;
  // Lets setup cull a small triangle that covers no pixel centre (shared.h,
  // FrameParams.cullSampleFree); tests turn it off to show that the pixels
  // do not change.
  bool cullSampleFree = true;
  // A batch of clip-input images in one frame (the library's batched
  // rasterize, api_diff.cpp): image k is triangles k·imageTris onwards,
  // viewport imageHeight rows from row k·imageRows (a tile multiple), and
  // height = images·imageRows. 0: one image of height rows.
  uint32_t imageTris = 0, imageRows = 0, imageHeight = 0;
  // The micro path's size limit in pixel positions (kernels/micro.h): -1
  // the device's default (Pipeline::microMaxFor), 0 off; tests compare the two.
  int32_t microMax = -1;
};

}  // namespace clr
