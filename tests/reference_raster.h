// reference_raster.h — the scalar CPU oracle the kernel tests compare with.
//
// A deliberately plain implementation of the notes' z-buffer algorithm with
// clraster's conventions: transform, homogeneous clipping (near plane and
// guard band, intersections from the inside vertex), the viewport matrix,
// 8-bit subpixel snapping, 64-bit integer edge functions with the GL/llvmpipe
// fill rule (left and bottom edges inclusive, y up), window depth
// interpolated from screen barycentrics, LESS against far = 1, triangles in
// input order (so an earlier triangle keeps a tie). Options.depthMode picks
// the other depth formats of kernels/shared.h: unorm24 compares
// rint(z·(2^24 − 1)), reversed uses window z = z_ndc, the near plane
// z <= w, GREATER against 0. Its float operations are
// written in the same order as the kernels', so on a device that rounds
// IEEE-correctly the triangle-ID images agree bit for bit.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace ref {

constexpr uint32_t kNone = 0xFFFFFFFFu;

struct Options {
  uint32_t width = 64, height = 64;
  bool cullBack = false;
  // The sample position of every pixel: its centre plus this offset, in
  // fixed-point units (one sample plane of an anti-aliased frame).
  int sampleX = 0, sampleY = 0;
  uint32_t depthMode = 0;  // CLR_DEPTH_*
  // Setup's cull of a small triangle that covers no sample (FrameParams.cullSampleFree):
  // only the count of setup triangles depends on it, never a pixel.
  bool cullSampleFree = true;
};

struct Result {
  uint32_t width = 0, height = 0;
  std::vector<uint32_t> triId;   // per pixel, bottom row first; kNone = empty
  std::vector<float> depth;      // window depth of the visible fragment (1 = far; 0 when reversed)
  std::vector<glm::dvec3> bary;  // screen barycentrics of the visible (sub-)triangle, exact (double)
  uint64_t setupTriangles = 0;   // screen triangles after clipping and culling
  uint64_t clippedTriangles = 0;
  uint64_t culledTriangles = 0;
};

// positions: 3 floats per vertex; indices: 3 per triangle; mvp column-major.
Result rasterize(const std::vector<float>& positions, const std::vector<uint32_t>& indices, const glm::mat4& mvp,
                 const Options& options);

// The same from clip-space positions, 4 floats per vertex (the library's
// rasterize, whose kernels read them untransformed).
Result rasterizeClip(const std::vector<float>& clip, const std::vector<uint32_t>& indices, const Options& options);

// clip = mvp · (p, 1), with the kernels' order of operations.
glm::vec4 transformVertex(const glm::mat4& mvp, const float* p);

}  // namespace ref
