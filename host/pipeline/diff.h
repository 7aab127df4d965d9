// diff.h — host side of kernels/diff.cl: the backward passes of the
// library's rasterize and interpolate (include/clraster/diff.hpp), on host
// arrays. Each call uploads its inputs, runs one kernel over every pixel of
// the batch and reads the gradients back; buffers are kept between calls
// and grow as needed (buffer.h: a request beyond the device's largest
// allocation is a clr::Error naming the buffer).
#pragma once

#include "pipeline/buffer.h"
#include "pipeline/device.h"
#include "pipeline/kernel_args.h"

#include <cstdint>
#include <vector>

namespace clr {

// A batch of `images` images of width × height pixels, image-major.
struct DiffImages {
  size_t images = 0;
  uint32_t width = 0, height = 0;
  size_t pixels() const { return images * width * height; }
};

// A texture call (diff_texture.cl): output images × height × width
// pixels sampling texImages (1 or images) textures of texWidth × texHeight
// × channels through mip levels 0..maxLevel.
struct TextureCall {
  DiffImages batch;
  size_t texImages = 0;
  uint32_t texWidth = 0, texHeight = 0, channels = 0;
  uint32_t filter = 0, boundary = 0;  // TEX_* of diff_texture.cl
  uint32_t maxLevel = 0;
  bool hasUvDa = false, hasBias = false;
  // The sizes of levels 0..maxLevel (level k: max(1, size >> k)).
  std::vector<uint32_t> levelSizes() const;
  size_t pyramidTexels() const;  // over all levels and texture images
};

class DiffKernels {
 public:
  DeviceMemory& memory() { return memory_; }  // its limits (buffer.h)
  explicit DiffKernels(ClContext& cl);

  // gradPos (posImages · numVertices · 4 floats, posImages 1 or
  // batch.images) = d L / d pos from gradRast (4 floats per pixel) and,
  // when not null, gradDb (4 floats per pixel); rast: rasterize's output.
  void rasterizeGrad(const float* pos, size_t numVertices, size_t posImages, const int32_t* tri, size_t numTriangles,
                     const DiffImages& batch, const float* rast, const float* gradRast, const float* gradDb,
                     float* gradPos);

  // gradAttr (attrImages · numVertices · numAttrs), gradRast (4 per pixel)
  // and, with diff (attribute indices in 0..numAttrs-1), gradDb (4 per
  // pixel) from gradOut (numAttrs per pixel) and gradDa (2 · diff.size()
  // per pixel); db is rasterize's rast_db (needed with diff).
  void interpolateGrad(const float* attr, size_t numVertices, size_t numAttrs, size_t attrImages, const float* rast,
                       const DiffImages& batch, const int32_t* tri, size_t numTriangles, const float* gradOut,
                       const float* db, const std::vector<int>& diff, const float* gradDa, float* gradAttr,
                       float* gradRast, float* gradDb);

  // The mip levels 1..maxLevel of tex (level 0), built on the device
  // (mip_build), written after each other into mips.
  void buildMips(const TextureCall& call, const float* tex, float* mips);
  // out (channels per pixel) sampled from tex, with its levels 1.. from
  // mips when not null (else built here). uv: 2 floats per pixel; uvDa: 4
  // (with hasUvDa); bias: 1 (with hasBias).
  void textureForward(const TextureCall& call, const float* tex, const float* mips, const float* uv, const float* uvDa,
                      const float* bias, float* out);
  // Gradients of textureForward: gradTex (tex's shape: every level's
  // gradient pushed down to level 0 unless mips came from the caller, whose
  // levels then get none), gradUv, gradUvDa, gradBias (those given).
  void textureGrad(const TextureCall& call, const float* tex, const float* mips, const float* uv, const float* uvDa,
                   const float* bias, const float* gradOut, float* gradTex, float* gradUv, float* gradUvDa,
                   float* gradBias);

  // nvdiffrast's antialias of colour (channels per pixel of the batch)
  // into out, from rasterize's rast of pos (posImages × numVertices × 4)
  // and tri, with opp (per triangle, the vertex across each edge, or −1).
  void antialiasForward(const float* color, uint32_t channels, const float* rast, const DiffImages& batch,
                        const float* pos, size_t numVertices, size_t posImages, const int32_t* tri, const int32_t* opp,
                        size_t numTriangles, float* out);
  // Its gradients: gradColor (colour's shape), gradPos (pos's shape, the
  // silhouette terms times posBoost).
  void antialiasGrad(const float* color, uint32_t channels, const float* rast, const DiffImages& batch,
                     const float* pos, size_t numVertices, size_t posImages, const int32_t* tri, const int32_t* opp,
                     size_t numTriangles, const float* gradOut, float posBoost, float* gradColor, float* gradPos);

 private:
  // Uploads colour, rast, pos, tri and opp, builds the kernel if needed,
  // and returns the antialias kernels' common arguments.
  AntialiasArgs antialiasSetup(cl::Kernel& kernel, const char* name, const float* color, uint32_t channels,
                               const float* rast, const DiffImages& batch, const float* pos, size_t numVertices,
                               size_t posImages, const int32_t* tri, const int32_t* opp, size_t numTriangles);
  // Uploads tex and its levels into pyramid_ (building those not given).
  void uploadPyramid(const TextureCall& call, const float* tex, const float* mips);
  TexParams texParams(const TextureCall& call) const;
  // Non-blocking: data must live until the call's closing finish().
  template <typename T>
  void upload(DeviceBuffer<T>& buffer, const T* data, uint64_t n);
  cl::NDRange linear(uint64_t n) const;
  // A buffer over the caller's n floats (CL_MEM_USE_HOST_PTR), which the
  // device may use in place; `written`: the kernel writes it (map it after).
  cl::Buffer callerBuffer(const float* data, uint64_t n, bool written);

  ClContext& cl_;
  DeviceMemory memory_;
  DeviceBuffer<float> in0_, in1_, in2_, in3_, in4_, out0_, out1_, out2_;
  DeviceBuffer<float> pyramid_, gradPyramid_;
  DeviceBuffer<int32_t> tri_, list_, levelInfo_, opp_;
  cl::Kernel rasterizeGrad_, interpolateGrad_, textureFwd_, textureGrad_, mipBuild_, mipGradDown_, aaFwd_, aaGrad_;
};

}  // namespace clr
