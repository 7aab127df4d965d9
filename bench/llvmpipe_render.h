// llvmpipe_render.h — Mesa llvmpipe (OSMesa) as the benchmark's reference renderer, and the triangle-ID comparison of
// two images.
//
// renderLlvmpipeLambert draws the mesh (its positions, normals and indices) from GL buffer objects with glDrawElements
// and the lighting of clraster's lambert shade: one directional light, ambient 0.12 + diffuse 0.88 times the built-in
// albedo (0.80, 0.78, 0.74), two-sided, no specular. perPixel does it as clraster does, in a GLSL program: the normal
// interpolated (with the 1/w rule, as GL's smooth varyings are), made unit and lit at each pixel, so the two images
// differ only by rounding. perVertex uses fixed-function lighting: no global ambient, vertex normals renormalised
// (GL_NORMALIZE: some files' normals are not unit), lit at the vertices and the colours interpolated (GL_SMOOTH), a
// different image. Both: 24-bit depth, LESS, and clraster's background colour. A frame is timed from glClear through
// glDrawElements and glFinish, when the RGBA8 image lies in OSMesa's host buffer; the image is read back once, after
// the timed frames. renderLlvmpipeIds draws the ID image of clraster_vs_llvmpipe (flat colour = triangle index + 1,
// un-shared vertices). Images come back top row first, R in the low byte. llvmpipe's thread count is LP_NUM_THREADS,
// read when the first context is created. Failures are clr::Error.
#pragma once

#include "io/scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace clr::bench {

constexpr uint32_t kIdMask = 0xFFFFFFu;  // ID images: low 24 bits = triangle + 1

// Fixes glibc's heap trim threshold at 256 MB, before any rendering, so that
// llvmpipe's frames are timed at its faster mode in every process. glibc
// returns the free top of the heap to the system once it exceeds a threshold
// that it raises as large blocks are freed; llvmpipe frees its per-frame
// memory at the heap's top, so with the initial threshold every frame gives its
// pages back and faults them in again, and a bench process would land in either
// mode depending on what clraster freed first. Fixed, every frame runs in the
// faster mode.
void fixHeapTrimThreshold();

struct LlvmpipeFrames {
  std::vector<double> frameMs;  // the timed frames only
  std::vector<uint32_t> image;  // the last frame
  std::string renderer;         // GL_RENDERER
  std::string version;          // GL_VERSION, which names the Mesa release ("... Mesa 22.3.6")
};

enum class LambertShading {
  perVertex,  // fixed-function lighting at the vertices, colours interpolated (GL_SMOOTH)
  perPixel,   // a GLSL program: clraster's lambert, normal interpolated and lit per pixel
};

LlvmpipeFrames renderLlvmpipeLambert(const Mesh& mesh, uint32_t width, uint32_t height, const glm::mat4& mvp,
                                     const glm::vec3& lightDir, LambertShading shading, uint32_t warmupFrames,
                                     uint32_t timedFrames);

// frames ID frames, each timed from glClear to glFinish; image is the last.
LlvmpipeFrames renderLlvmpipeIds(const Mesh& mesh, uint32_t width, uint32_t height, const glm::mat4& mvp,
                                 uint32_t frames = 1);

// Pixel-by-pixel comparison of two ID images, as clraster_vs_llvmpipe does:
// the differing fraction is over the pixels either image covers; a differing
// pixel is "near an edge" unless its 3x3 neighbourhood holds one id in both.
struct IdComparison {
  uint64_t coveredOurs = 0, coveredTheirs = 0, coveredUnion = 0, differing = 0, differingNotNearEdge = 0;
  std::string firstNotNearEdge;     // "(x, y): clraster id A, llvmpipe id B", top row 0
  std::vector<uint32_t> diffImage;  // RGBA8: black equal, red differing
  double differingFraction() const { return coveredUnion ? double(differing) / double(coveredUnion) : 0.0; }
};

IdComparison compareIds(const std::vector<uint32_t>& ours, const std::vector<uint32_t>& theirs, uint32_t width,
                        uint32_t height);

// Mean absolute difference of the RGB channels (0..255) over the pixels
// that differ from `background` in either image; a sanity check that both
// renderers shade alike (per pixel, they differ only by rounding).
double meanShadeDifference(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b, uint32_t background);

}  // namespace clr::bench
