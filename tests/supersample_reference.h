// supersample_reference.h — a very-high-sample reference renderer: the ground truth for anti-aliased images
// (coverage and shaded colour per pixel) where triangles overlap and exact_coverage.h does not apply.
//
// Input is screen space after clipping: per vertex (x, y) in pixels (y up, pixel (i, j) = [i, i+1] × [j, j+1]),
// window depth z and 1/w (w > 0), triangles in input order. Each pixel has S×S samples at sub-cell centres
// (i + (sx+0.5)/S, j + (sy+0.5)/S) or, jittered, one hashed random point per sub-cell (independent of threads).
// Per sample, in double: clraster's fill rule on counter-clockwise triangles (left and horizontal bottom edges
// inclusive), depth interpolated from screen barycentrics, LESS against a clear of 1.0 (a tie keeps the earlier
// triangle). An edge is evaluated from the same endpoint whichever triangle owns it, so a shared-edge sample
// belongs to exactly one; on a dyadic grid with S a power of two the edge functions are exact. The visible
// triangle's perspective-correct λ_i = (b_i/w_i) / Σ_j (b_j/w_j) goes to the caller's shading function;
// uncovered samples take the background. A pixel's colour is its samples' mean, its coverage the covered fraction.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace oracle {

struct ScreenVertex {
  glm::dvec2 xy;      // pixels
  double z = 0.0;     // window depth; a sample with z >= 1 is never drawn
  double invW = 1.0;  // 1 / clip w, > 0
};

struct SupersampleOptions {
  uint32_t width = 64, height = 64;
  uint32_t samplesPerAxis = 64;  // S: S×S samples per pixel
  bool jitter = false;           // one random point per sub-cell instead of its centre
  uint64_t seed = 1;             // jitter seed
  glm::dvec3 background = glm::dvec3(0.0);
  unsigned threads = 1;  // rows are shared out among this many threads (0: hardware concurrency)
};

struct SupersampleResult {
  uint32_t width = 0, height = 0;
  std::vector<glm::dvec3> color;  // per pixel, bottom row first: mean over samples
  std::vector<double> coverage;   // per pixel: fraction of samples covered by some triangle
};

// shade(triangle, λ): the colour of a sample of input triangle `triangle`
// (index into the vertex list / 3) with perspective-correct barycentrics λ of
// its three vertices in input order (λ sums to 1). With threads > 1 it is
// called concurrently and must be thread-safe.
using ShadeFn = std::function<glm::dvec3(uint32_t triangle, glm::dvec3 lambda)>;

// Accuracy against the exact area (exact_coverage.h): with S×S stratified
// samples, plain or jittered, a straight edge crosses at most 2S − 1 of a
// pixel's S² sub-cells, and only a sample of a crossed cell can disagree with
// its cell's covered area, so one edge through a pixel changes its coverage
// error by at most (2S − 1)/S² < 2/S (0.031 at S = 64); k edges through a
// pixel, at most 2k/S. Edges shared by two triangles of a mesh cancel.
//
// Cost: triangles are binned into cache-sized tiles (a run of pixels in one
// row), and each sample row of a triangle is restricted to the triangle's
// horizontal extent, so the work is proportional to the covered samples,
// plus one shading call per sample; `threads` splits the rows.
//
// Renders the triangles (3 vertices each). Degenerate and non-finite
// triangles are skipped. Throws std::invalid_argument on samplesPerAxis = 0.
SupersampleResult supersampleRender(const std::vector<ScreenVertex>& verts, const ShadeFn& shade,
                                    const SupersampleOptions& options);

// The position of sample (sx, sy) of pixel (x, y), as supersampleRender uses it.
glm::dvec2 samplePosition(const SupersampleOptions& options, uint32_t x, uint32_t y, uint32_t sx, uint32_t sy);

}  // namespace oracle
