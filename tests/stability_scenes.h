// stability_scenes.h — scenes at the renderer's limits and the crack counter,
// shared by the stability tests (tests/test_stability_*.cpp) and the
// stability bench tool (bench/stability.cpp).
//
// A band mesh is a shared-edge mesh that reaches far beyond the viewport:
// `bands` parallel bands, tilted by `angleDeg`, each a quad between two long
// lines split along its diagonal, so every edge crossing the viewport is
// shared by two triangles and every vertex lies about `reach` pixels from
// the viewport's centre along the bands. Vertices lie on the 1/256-pixel
// grid; the band lines are jittered but never cross, so the triangles
// never overlap and a pixel centre inside the mesh belongs to exactly one
// triangle. Coverage is counted from the kernels, as in
// test_watertight.cpp: the triangles fall into 4 classes whose members
// never touch (band parity × lower/upper half), each class is rendered
// alone and the per-pixel hits are summed.
#pragma once

#include "pipeline/device.h"
#include "pipeline/pipeline.h"

#include <cstdint>
#include <vector>

namespace stab {

struct Scene {
  std::vector<float> positions;   // clip space with w = 1 (identity MVP), 3 per vertex
  std::vector<uint32_t> indices;  // 3 per triangle
  std::vector<uint8_t> cls;       // per triangle: its coverage class
  uint32_t numClasses = 0;
  double magnitude = 0.0;  // largest |x_s| or |y_s| of a vertex, in pixels
  size_t numTris() const { return indices.size() / 3; }
  clr::Mesh mesh() const;  // with smooth normals
};

// The clip-space position (w = 1) of screen point (sx, sy) of a width×height
// viewport; exact when the sizes are powers of 2 and the point lies on the
// 1/256 grid with at most 24 significant bits.
void addScreenVertex(Scene& scene, double sx, double sy, uint32_t width, uint32_t height);

// The band mesh described above, covering the whole viewport.
Scene bandMesh(uint32_t width, uint32_t height, double reach, uint32_t bands, double angleDeg, uint32_t seed);

// The largest reach whose band mesh keeps every vertex inside the guard
// band (fixed.h: x_s in [W − 2^16, 2^16], the same for y), so no triangle
// is clipped.
double guardBandReach(uint32_t width, uint32_t height, uint32_t bands, double angleDeg);

// Per pixel (bottom row first): how many triangles of the scene cover its
// centre, rendered class by class with these settings (ID shading, one
// sample).
std::vector<uint8_t> coverageCounts(clr::ClContext& cl, const Scene& scene, clr::FrameSettings settings);

struct Cracks {
  size_t holes = 0;    // pixels no triangle covers
  size_t doubles = 0;  // pixels covered more than once
  size_t total() const { return holes + doubles; }
};
Cracks countCracks(const std::vector<uint8_t>& counts);

}  // namespace stab
