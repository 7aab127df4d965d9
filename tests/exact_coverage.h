// exact_coverage.h — analytic ground truth for per-pixel coverage (area
// fractions), the reference that anti-aliasing accuracy is measured against.
//
// Each triangle is clipped against every pixel square of its bounding box
// (Sutherland–Hodgman against the four half-planes x >= i, x <= i + 1,
// y >= j, y <= j + 1) and the clipped polygon's area is taken with the
// shoelace formula. Screen conventions are clraster's: origin bottom-left,
// y up, pixel (i, j) is the square [i, i+1] × [j, j+1] (centre (i+0.5,
// j+0.5)), results bottom row first at index j·width + i. Orientation does
// not matter (clockwise and counter-clockwise give the same areas), and there
// is no fill rule: an edge on a pixel boundary splits nothing.
//
// Overlap is not resolved: the per-pixel areas of all triangles are summed
// and the sum is clamped to [0, 1], so the result is exact only when the
// caller's triangles do not overlap (a mesh, or disjoint triangles). For
// scenes with occlusion use supersample_reference.h.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace oracle {

// Unsigned area of the triangle abc, in square pixels.
double triangleArea(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c);

// Precision: everything is in double. Vertices are first translated to the
// pixel's corner, so the clipping and the shoelace sum work on coordinates of
// magnitude <= max(1, triangle extent); the error of one pixel's area is a
// few ulps of that magnitude, about 1e-15 for triangles of a few pixels and
// below 1e-12 relative for triangles up to ~1000 pixels across. Intersections
// with a pixel boundary land exactly on it (the clipped coordinate is set,
// not computed), and a triangle whose vertices lie on pixel corners or on a
// dyadic grid (1/256 pixel) is clipped and measured exactly.
//
// Per pixel (bottom row first, index y·width + x), the covered fraction of the
// pixel's area, summed over the triangles (3 screen-space vertices each, in
// pixels) and clamped to [0, 1]. The triangles must not overlap. Triangles and
// parts of triangles outside the viewport contribute nothing; degenerate and
// non-finite triangles are skipped.
std::vector<double> exactCoverage(const std::vector<glm::dvec2>& screenVerts, uint32_t width, uint32_t height);

}  // namespace oracle
