// exact_coverage.cpp — see exact_coverage.h. Scalar, one triangle at a time,
// one pixel of its bounding box at a time; clarity over speed, with one fast
// path for pixels wholly inside the triangle.
#include "exact_coverage.h"

#include <algorithm>
#include <cmath>

namespace oracle {

namespace {

// A convex polygon of at most 3 + 4 vertices (one more per clipping plane).
struct Polygon {
  glm::dvec2 v[8];
  int n = 0;
};

// Keeps the part of p with p[axis] <= bound (keepBelow) or >= bound: one side
// of the unit square in pixel-local coordinates. Intersection points get the
// bound itself as their clipped coordinate.
Polygon clipHalfPlane(const Polygon& p, int axis, double bound, bool keepBelow)
{
  Polygon out;
  const auto inside = [&](const glm::dvec2& q) { return keepBelow ? q[axis] <= bound : q[axis] >= bound; };
  for (int i = 0; i < p.n; ++i) {
    const glm::dvec2 &a = p.v[i], &b = p.v[(i + 1) % p.n];
    const bool aIn = inside(a), bIn = inside(b);
    if (aIn) out.v[out.n++] = a;
    if (aIn == bIn) continue;
    // Step: the crossing, interpolated from a towards b; the other axis only.
    const int other = 1 - axis;
    const double t = (bound - a[axis]) / (b[axis] - a[axis]);
    glm::dvec2 q;
    q[axis] = bound;
    q[other] = a[other] + t * (b[other] - a[other]);
    out.v[out.n++] = q;
  }
  return out;
}

double polygonArea(const Polygon& p)
{
  double twice = 0.0;
  for (int i = 0; i < p.n; ++i) {
    const glm::dvec2 &a = p.v[i], &b = p.v[(i + 1) % p.n];
    twice += a.x * b.y - b.x * a.y;
  }
  return 0.5 * std::fabs(twice);
}

// Twice the signed area of abc (positive counter-clockwise, y up).
double cross(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c)
{
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Area of triangle t (pixel-local, counter-clockwise) inside the unit square.
double pixelArea(const glm::dvec2 t[3])
{
  // Step 1: fast path, all four corners inside the triangle.
  bool whole = true;
  for (int c = 0; c < 4 && whole; ++c) {
    const glm::dvec2 corner(double(c & 1), double(c >> 1));
    for (int e = 0; e < 3 && whole; ++e) whole = cross(t[e], t[(e + 1) % 3], corner) >= 0.0;
  }
  if (whole) return 1.0;
  // Step 2: Sutherland–Hodgman against the four sides, then the shoelace sum.
  Polygon p;
  for (int i = 0; i < 3; ++i) p.v[p.n++] = t[i];
  p = clipHalfPlane(p, 0, 0.0, false);
  if (p.n) p = clipHalfPlane(p, 0, 1.0, true);
  if (p.n) p = clipHalfPlane(p, 1, 0.0, false);
  if (p.n) p = clipHalfPlane(p, 1, 1.0, true);
  return p.n >= 3 ? polygonArea(p) : 0.0;
}

}  // namespace

double triangleArea(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c)
{
  return 0.5 * std::fabs(cross(a, b, c));
}

std::vector<double> exactCoverage(const std::vector<glm::dvec2>& screenVerts, uint32_t width, uint32_t height)
{
  std::vector<double> coverage(size_t(width) * height, 0.0);
  for (size_t t = 0; t + 2 < screenVerts.size(); t += 3) {
    // Step 1: skip non-finite and degenerate triangles; orient counter-clockwise.
    glm::dvec2 v[3] = {screenVerts[t], screenVerts[t + 1], screenVerts[t + 2]};
    bool finite = true;
    for (const glm::dvec2& q : v) finite = finite && std::isfinite(q.x) && std::isfinite(q.y);
    if (!finite) continue;
    const double area2 = cross(v[0], v[1], v[2]);
    if (area2 == 0.0) continue;
    if (area2 < 0.0) std::swap(v[1], v[2]);
    // Step 2: the bounding box in whole pixels, clamped to the viewport.
    const double minX = std::min({v[0].x, v[1].x, v[2].x}), maxX = std::max({v[0].x, v[1].x, v[2].x});
    const double minY = std::min({v[0].y, v[1].y, v[2].y}), maxY = std::max({v[0].y, v[1].y, v[2].y});
    const double x0 = std::max(0.0, std::floor(minX)), x1 = std::min(double(width), std::ceil(maxX));
    const double y0 = std::max(0.0, std::floor(minY)), y1 = std::min(double(height), std::ceil(maxY));
    if (x0 >= x1 || y0 >= y1) continue;
    // Step 3: each pixel's share, from vertices translated to its corner.
    for (uint32_t j = uint32_t(y0); double(j) < y1; ++j)
      for (uint32_t i = uint32_t(x0); double(i) < x1; ++i) {
        const glm::dvec2 corner(i, j);
        const glm::dvec2 local[3] = {v[0] - corner, v[1] - corner, v[2] - corner};
        coverage[size_t(j) * width + i] += pixelArea(local);
      }
  }
  // Step 4: clamp the sums (rounding may push a fully covered pixel past 1).
  for (double& c : coverage) c = std::min(1.0, std::max(0.0, c));
  return coverage;
}

}  // namespace oracle
