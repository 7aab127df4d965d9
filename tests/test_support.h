// test_support.h — shared fixtures for the kernel tests: one OpenCL context
// per test process, meshes built from screen-space or clip-space vertices,
// and per-pixel triangle IDs read from the visibility buffer.
#pragma once

#include "pipeline/pipeline.h"
#include "reference_raster.h"
#include "render/camera.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace test {

// The device selector of the tests: CLRASTER_TEST_DEVICE, else "" (default).
std::string deviceSelector();

// The context every test shares (on deviceSelector()'s device).
clr::ClContext& context();

// Three cameras on a model's bounds: the render command's framing, an eye
// inside the model (near-plane clipping) and one grazing its side.
std::vector<clr::Camera> modelViews(const clr::Bounds& bounds);

// Whether that device is Oclgrind's simulator (tests/oclgrind_check.sh), which
// interprets every work-item: the few large cases there take the smallest
// sizes that still reach the paths they exist for (docs/testing.md, "Oclgrind").
bool underOclgrind();

// A grid vertex (x, y) in pixels moved by up to `jitter` subpixels on each axis, then, in three cases of four, its
// x, its y or both put on a pixel centre (where only the fill rule decides shared edges). Draws from rng: x's
// jitter, y's, then the case.
glm::vec2 jitterVertex(float x, float y, int jitter, std::mt19937& rng);

// A mesh builder. With an identity MVP, a position (x, y, z) is already in
// clip space with w = 1; screen() maps a screen-space point of a W×H
// viewport back to that NDC position, exactly when W and H are powers of 2
// and the point lies on the subpixel grid.
struct Geometry {
  std::vector<float> positions;
  std::vector<uint32_t> indices;
  uint32_t addVertex(glm::vec3 p);
  void addTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c);
  clr::Mesh mesh() const;  // with smooth normals
  size_t numTris() const { return indices.size() / 3; }
};
glm::vec3 screen(float sx, float sy, float z, uint32_t width, uint32_t height);
// `count` random triangles for an identity MVP, from seed: corners uniform in
// [−1.2, 1.2]² (some cross the viewport's edges), depths in [−0.9, 0.9].
Geometry randomTriangles(uint32_t seed, int count);

// The settings with FrameSettings.keepVisAttributes on: for tests that read
// the depth and barycentrics raster writes (Pipeline::readVis, aov()).
inline clr::FrameSettings keepingVis(clr::FrameSettings s)
{
  s.keepVisAttributes = true;
  return s;
}

// The settings with the micro-triangle path off (FrameSettings.microMax): for
// tests of the bins themselves, which that path leaves out.
inline clr::FrameSettings allBinned(clr::FrameSettings s)
{
  s.microMax = 0;
  return s;
}

// Settings for an ID render of a width×height viewport.
clr::FrameSettings idSettings(uint32_t width, uint32_t height, const glm::mat4& mvp = glm::mat4(1.0f),
                              bool cullBack = false);

// Runs the whole pipeline and returns, per pixel (bottom row first), the
// input triangle index of the visible fragment or ref::kNone.
std::vector<uint32_t> renderTriIds(clr::Pipeline& pipeline, const clr::FrameSettings& settings);

// The input triangle index per pixel of one sample plane of the last frame.
std::vector<uint32_t> readTriIds(const clr::Pipeline& pipeline, uint32_t sample = 0);

// Same, for a fresh pipeline on the shared context.
std::vector<uint32_t> renderTriIds(const Geometry& geometry, const clr::FrameSettings& settings);

// The tests' scratch directory (created on first use).
// Two vectors' bytes equal (sizes too; empty vectors compare without memcmp).
template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// The first array or fact of two meshes that differs, byte for byte ("" when equal): the direct readers' oracle.
std::string meshDifference(const clr::Mesh& a, const clr::Mesh& b);

std::string tempDir();

// Number of pixels where two ID images differ.
size_t countDifferences(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b);

// Index of pixel (x, y) in a row-major image `width` pixels wide.
inline size_t pixel(uint32_t width, uint32_t x, uint32_t y)
{
  return size_t(y) * width + x;
}

}  // namespace test
