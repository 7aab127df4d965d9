// reference_raster.cpp — see reference_raster.h. Scalar, one triangle at a
// time, one pixel at a time; clarity over speed.
#include "reference_raster.h"

#include "fixed.h"
#include "shared.h"

#include <algorithm>
#include <cmath>

namespace ref {

namespace {

struct Vertex {
  glm::vec4 clip;
};

// Plane distances: 0 near, 1..4 guard band (left, right, bottom, top).
// nearSign: the near plane is z + w (GL, 1) or w − z (reversed, −1).
float distance(const glm::vec4& c, int plane, float gx, float gy, float nearSign)
{
  switch (plane) {
    case 0: return nearSign * c.z + c.w;
    case 1: return c.x + gx * c.w;
    case 2: return gx * c.w - c.x;
    case 3: return c.y + gy * c.w;
    default: return gy * c.w - c.y;
  }
}

glm::vec4 intersect(const glm::vec4& in, const glm::vec4& out, int plane, float gx, float gy, float nearSign)
{
  // As clip.h: halved values where a difference overflows, and the
  // result put exactly on the plane.
  const float dIn = distance(in, plane, gx, gy, nearSign), dOut = distance(out, plane, gx, gy, nearSign);
  const float denom = dIn - dOut;
  const float t = std::isfinite(denom) ? dIn / denom : (0.5f * dIn) / (0.5f * dIn - 0.5f * dOut);
  bool finite = true;
  for (int k = 0; k < 4; ++k) finite = finite && std::isfinite(out[k] - in[k]);
  glm::vec4 r;
  for (int k = 0; k < 4; ++k)
    r[k] = finite ? in[k] + t * (out[k] - in[k]) : 2.0f * (0.5f * in[k] + t * (0.5f * out[k] - 0.5f * in[k]));
  switch (plane) {
    case 0: r.z = -nearSign * r.w; break;
    case 1: r.x = -(gx * r.w); break;
    case 2: r.x = gx * r.w; break;
    case 3: r.y = -(gy * r.w); break;
    default: r.y = gy * r.w; break;
  }
  return r;
}

bool outsideViewport(const glm::vec4& c, int plane, float nearSign)
{
  switch (plane) {
    case 0: return nearSign * c.z + c.w < 0.0f;
    case 1: return c.x < -c.w;
    case 2: return c.x > c.w;
    case 3: return c.y < -c.w;
    case 4: return c.y > c.w;
    default: return nearSign < 0.0f ? c.z < 0.0f : c.z > c.w;
  }
}

// The compare key of window depth z (smaller is nearer), as raster.cl.
float depthKey(float z, uint32_t depthMode)
{
  if (depthMode == CLR_DEPTH_UNORM24) return std::nearbyint(std::clamp(z, 0.0f, 1.0f) * CLR_DEPTH_UNORM24_MAX);
  return depthMode == CLR_DEPTH_REVERSED ? -z : z;
}

int64_t edge(int ax, int ay, int bx, int by, int px, int py)
{
  return int64_t(bx - ax) * int64_t(py - ay) - int64_t(by - ay) * int64_t(px - ax);
}

bool topLeftInclusive(int ax, int ay, int bx, int by)
{
  const int dx = bx - ax, dy = by - ay;
  return dy < 0 || (dy == 0 && dx > 0);
}

int floorDiv(int a)
{
  return a >> CLR_SUBPIXEL_BITS;
}
int ceilDiv(int a)
{
  return (a + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS;
}

// Rasterizes one clip-space triangle into the z-buffer; returns whether it
// survived setup.
bool drawTriangle(const glm::vec4 c[3], uint32_t triId, const Options& o, Result& r)
{
  // Step 1: viewport transform of the notes and snapping.
  const float halfW = 0.5f * float(o.width), halfH = 0.5f * float(o.height);
  int X[3], Y[3];
  float Z[3];
  for (int i = 0; i < 3; ++i) {
    if (!(c[i].w > 0.0f)) return false;
    const float invW = 1.0f / c[i].w;
    const float xs = c[i].x * invW * halfW + halfW;
    const float ys = c[i].y * invW * halfH + halfH;
    Z[i] = o.depthMode == CLR_DEPTH_REVERSED ? c[i].z * invW : c[i].z * invW * 0.5f + 0.5f;
    X[i] = int(std::nearbyint(xs * float(CLR_FIXED_ONE)));
    Y[i] = int(std::nearbyint(ys * float(CLR_FIXED_ONE)));
  }
  // Step 2: orientation and culling.
  int64_t area2 = int64_t(X[1] - X[0]) * int64_t(Y[2] - Y[0]) - int64_t(X[2] - X[0]) * int64_t(Y[1] - Y[0]);
  if (area2 == 0) return false;
  if (area2 < 0) {
    if (o.cullBack) return false;
    std::swap(X[1], X[2]);
    std::swap(Y[1], Y[2]);
    std::swap(Z[1], Z[2]);
    area2 = -area2;
  }
  const int centreX = CLR_FIXED_HALF + o.sampleX, centreY = CLR_FIXED_HALF + o.sampleY;
  const int x0 = std::max(0, ceilDiv(std::min({X[0], X[1], X[2]}) - centreX));
  const int x1 = std::min(int(o.width) - 1, floorDiv(std::max({X[0], X[1], X[2]}) - centreX));
  const int y0 = std::max(0, ceilDiv(std::min({Y[0], Y[1], Y[2]}) - centreY));
  const int y1 = std::min(int(o.height) - 1, floorDiv(std::max({Y[0], Y[1], Y[2]}) - centreY));
  if (x0 > x1 || y0 > y1) return false;
  // Step 3: every sample of the bounding box, z-buffered.
  const float invArea2 = 1.0f / float(area2);
  bool coversSample = false;
  for (int py = y0; py <= y1; ++py)
    for (int px = x0; px <= x1; ++px) {
      const int sx = px * CLR_FIXED_ONE + centreX, sy = py * CLR_FIXED_ONE + centreY;
      const int64_t e[3] = {edge(X[1], Y[1], X[2], Y[2], sx, sy), edge(X[2], Y[2], X[0], Y[0], sx, sy),
                            edge(X[0], Y[0], X[1], Y[1], sx, sy)};
      bool inside = true;
      for (int i = 0; i < 3; ++i) {
        const int a = (i + 1) % 3, b = (i + 2) % 3;
        inside = inside && (e[i] > 0 || (e[i] == 0 && topLeftInclusive(X[a], Y[a], X[b], Y[b])));
      }
      if (!inside) continue;
      coversSample = true;
      const float b1 = float(e[1]) * invArea2, b2 = float(e[2]) * invArea2;
      const float z = Z[0] + b1 * (Z[1] - Z[0]) + b2 * (Z[2] - Z[0]);
      const size_t p = size_t(py) * o.width + px;
      if (!(depthKey(z, o.depthMode) < depthKey(r.depth[p], o.depthMode))) continue;
      r.depth[p] = z;
      r.triId[p] = triId;
      r.bary[p] = glm::dvec3(double(e[0]), double(e[1]), double(e[2])) / double(area2);
    }
  // Step 4: setup's rule (setup_covers_a_sample): a triangle of at most 2×2
  // centres, its vertices less than 4 pixels apart each way, that covers
  // none of them is culled, not set up.
  const bool small = x1 - x0 <= 1 && y1 - y0 <= 1 &&
                     std::max({X[0], X[1], X[2]}) - std::min({X[0], X[1], X[2]}) < 4 * CLR_FIXED_ONE &&
                     std::max({Y[0], Y[1], Y[2]}) - std::min({Y[0], Y[1], Y[2]}) < 4 * CLR_FIXED_ONE;
  return !(o.cullSampleFree && small && !coversSample);
}

}  // namespace

glm::vec4 transformVertex(const glm::mat4& m, const float* p)
{
  glm::vec4 c;
  for (int row = 0; row < 4; ++row) c[row] = m[0][row] * p[0] + m[1][row] * p[1] + m[2][row] * p[2] + m[3][row];
  return c;
}

Result rasterize(const std::vector<float>& positions, const std::vector<uint32_t>& indices, const glm::mat4& mvp,
                 const Options& o)
{
  std::vector<float> clip(4 * (positions.size() / 3));
  for (size_t v = 0; v < positions.size() / 3; ++v) {
    const glm::vec4 c = transformVertex(mvp, &positions[3 * v]);
    for (int k = 0; k < 4; ++k) clip[4 * v + k] = c[k];
  }
  return rasterizeClip(clip, indices, o);
}

Result rasterizeClip(const std::vector<float>& clip, const std::vector<uint32_t>& indices, const Options& o)
{
  Result r;
  r.width = o.width;
  r.height = o.height;
  r.triId.assign(size_t(o.width) * o.height, kNone);
  r.depth.assign(size_t(o.width) * o.height, o.depthMode == CLR_DEPTH_REVERSED ? 0.0f : 1.0f);
  const float ns = o.depthMode == CLR_DEPTH_REVERSED ? -1.0f : 1.0f;
  r.bary.assign(size_t(o.width) * o.height, glm::dvec3(0.0));
  const float gx = 2.0f * CLR_GUARD_BAND_PIXELS / float(o.width) - 1.0f;
  const float gy = 2.0f * CLR_GUARD_BAND_PIXELS / float(o.height) - 1.0f;

  for (size_t t = 0; t < indices.size() / 3; ++t) {
    // Step 1: transform; cull non-finite and trivially outside triangles.
    glm::vec4 c[3];
    bool finite = true;
    for (int i = 0; i < 3; ++i) {
      const float* p = &clip[4 * size_t(indices[3 * t + i])];
      c[i] = glm::vec4(p[0], p[1], p[2], p[3]);
      for (int k = 0; k < 4; ++k) finite = finite && std::isfinite(c[i][k]);
    }
    bool rejected = !finite;
    for (int plane = 0; plane < 6 && !rejected; ++plane)
      rejected =
          outsideViewport(c[0], plane, ns) && outsideViewport(c[1], plane, ns) && outsideViewport(c[2], plane, ns);
    if (rejected) {
      ++r.culledTriangles;
      continue;
    }
    // Step 2: Sutherland–Hodgman against the near plane and the guard band.
    std::vector<glm::vec4> poly(c, c + 3);
    bool clipped = false;
    // Planes are chosen from the input vertices, as the kernel does.
    for (int plane = 0; plane < 5; ++plane) {
      bool anyOut = false;
      for (int i = 0; i < 3; ++i) anyOut = anyOut || distance(c[i], plane, gx, gy, ns) < 0.0f;
      if (!anyOut) continue;
      clipped = true;
      std::vector<glm::vec4> next;
      for (size_t i = 0; i < poly.size(); ++i) {
        const glm::vec4 &a = poly[i], &b = poly[(i + 1) % poly.size()];
        const bool aIn = distance(a, plane, gx, gy, ns) >= 0.0f, bIn = distance(b, plane, gx, gy, ns) >= 0.0f;
        if (aIn) next.push_back(a);
        if (aIn != bIn) next.push_back(aIn ? intersect(a, b, plane, gx, gy, ns) : intersect(b, a, plane, gx, gy, ns));
      }
      poly.swap(next);
    }
    r.clippedTriangles += clipped;
    // Step 3: fan and draw.
    int drawn = 0;
    for (size_t k = 1; k + 1 < poly.size(); ++k) {
      const glm::vec4 sub[3] = {poly[0], poly[k], poly[k + 1]};
      drawn += drawTriangle(sub, uint32_t(t), o, r);
    }
    r.setupTriangles += drawn;
    r.culledTriangles += drawn == 0;
  }
  return r;
}

}  // namespace ref
