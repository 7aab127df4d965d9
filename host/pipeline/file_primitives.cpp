// file_primitives.cpp — a scene file's own lines and points (Mesh::lines,
// Mesh::points: glTF's line and point modes, OBJ's l and p), drawn by the
// lines stage (lines.cpp, kernels/lines.cl) after resolve and any wireframe,
// depth-tested against the triangles like the wireframe.
//
// Projection runs here on the host: each vertex through FrameSettings.mvp,
// each segment clipped in clip space to the view frustum (Liang-Barsky on
// the six planes; near and far as the depth format places them), then the
// viewport transform and window depth of setup.cl. Lines use the frame's
// --line method and --line-width; a point is an axis-aligned square of
// --point-size pixels snapped to the pixel grid (the pixel holding the point,
// and for larger sizes the (size - 1) / 2 pixels left and below of it),
// drawn as an anti-aliased segment of that width and length, which covers
// exactly those pixels. Both are white (kColour). --shade id draws neither:
// its image holds triangle ids only.
#include "pipeline/pipeline.h"

#include <algorithm>
#include <cmath>

namespace clr {

namespace {

constexpr uint32_t kColour = 0xFFFFFFFFu;  // RGBA8 white

}  // namespace

void Pipeline::filePrimitives()
{
  const FrameSettings& s = settings_;
  if (s.shadeMode == CLR_SHADE_ID) return;
  if (s.pointSize < 1 || s.pointSize > 16) throw Error("point size must lie in 1..16 pixels");
  const bool reversed = s.depthMode == CLR_DEPTH_REVERSED;
  const float halfW = 0.5f * float(s.width), halfH = 0.5f * float(s.height);
  auto clip = [&](uint32_t v) {
    const float* p = &scene_.positions[3 * size_t(v)];
    return s.mvp * glm::vec4(p[0], p[1], p[2], 1.0f);
  };
  // Signed distances to the six frustum planes, inside when >= 0.
  auto planes = [&](const glm::vec4& c, float d[6]) {
    d[0] = c.w + c.x;
    d[1] = c.w - c.x;
    d[2] = c.w + c.y;
    d[3] = c.w - c.y;
    d[4] = reversed ? c.w - c.z : c.w + c.z;  // near
    d[5] = reversed ? c.z : c.w - c.z;        // far
  };
  auto window = [&](const glm::vec4& c, float& xs, float& ys, float& z) {
    const float invW = 1.0f / c.w;
    xs = c.x * invW * halfW + halfW;
    ys = c.y * invW * halfH + halfH;
    z = reversed ? c.z * invW : c.z * invW * 0.5f + 0.5f;
  };
  auto fixed = [](float v) { return int(std::lrint(v * float(CLR_FIXED_ONE))); };

  // Step 1: line segments, clipped.
  std::vector<LineSeg> segs;
  for (size_t l = 0; l + 1 < scene_.lines.size(); l += 2) {
    const glm::vec4 a = clip(scene_.lines[l]), b = clip(scene_.lines[l + 1]);
    float da[6], db[6], t0 = 0.0f, t1 = 1.0f;
    planes(a, da);
    planes(b, db);
    bool visible = std::isfinite(a.x + a.y + a.z + a.w + b.x + b.y + b.z + b.w);
    for (int k = 0; k < 6 && visible; ++k) {
      if (da[k] < 0.0f && db[k] < 0.0f)
        visible = false;
      else if (da[k] < 0.0f)
        t0 = std::max(t0, da[k] / (da[k] - db[k]));
      else if (db[k] < 0.0f)
        t1 = std::min(t1, da[k] / (da[k] - db[k]));
    }
    if (!visible || t0 > t1) continue;
    const glm::vec4 ca = a + t0 * (b - a), cb = a + t1 * (b - a);
    if (!(ca.w > 0.0f && cb.w > 0.0f)) continue;
    LineSeg seg{};
    float xs, ys;
    window(ca, xs, ys, seg.z[0]);
    seg.x[0] = fixed(xs);
    seg.y[0] = fixed(ys);
    window(cb, xs, ys, seg.z[1]);
    seg.x[1] = fixed(xs);
    seg.y[1] = fixed(ys);
    seg.triId = uint32_t(l / 2);
    segs.push_back(seg);
  }
  if (!segs.empty()) {
    lineSegs_.upload(segs);
    drawLineSegments(uint32_t(segs.size()), {CLR_WIREFRAME_OVERLAY, s.lineMethod, s.lineWidth, kColour});
  }

  // Step 2: points inside the frustum, as squares: the segment from the
  // left edge to the right edge of the square along its middle row, as
  // wide as it is long.
  segs.clear();
  const int size = int(s.pointSize), half = (size - 1) / 2;
  for (size_t i = 0; i < scene_.points.size(); ++i) {
    const glm::vec4 c = clip(scene_.points[i]);
    float d[6];
    planes(c, d);
    if (!std::isfinite(c.x + c.y + c.z + c.w) || !(c.w > 0.0f) || d[4] < 0.0f || d[5] < 0.0f) continue;
    LineSeg seg{};
    float xs, ys;
    window(c, xs, ys, seg.z[0]);
    if (!(xs >= -float(size) && xs <= float(s.width) + size && ys >= -float(size) && ys <= float(s.height) + size))
      continue;
    seg.z[1] = seg.z[0];
    const int left = int(std::floor(xs)) - half, bottom = int(std::floor(ys)) - half;
    seg.x[0] = left * CLR_FIXED_ONE;
    seg.x[1] = (left + size) * CLR_FIXED_ONE;
    seg.y[0] = seg.y[1] = bottom * CLR_FIXED_ONE + size * (CLR_FIXED_ONE / 2);
    seg.triId = uint32_t(i);
    segs.push_back(seg);
  }
  if (!segs.empty()) {
    lineSegs_.upload(segs);
    drawLineSegments(uint32_t(segs.size()), {CLR_WIREFRAME_OVERLAY, CLR_LINE_AA, float(size), kColour});
  }
}

}  // namespace clr
