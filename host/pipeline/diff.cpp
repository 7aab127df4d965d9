// diff.cpp — host side of kernels/diff*.cl (see diff.h): uploads, one launch
// per call over every pixel of the batch (arguments set from their
// kernel_args.h structs), blocking reads of the gradients.
#include "pipeline/diff.h"

namespace clr {

namespace {

// Pixels per work-item of rasterize_grad and interpolate_grad (DIFF_SPAN, diff.cl).
constexpr uint64_t kPixelSpan = 16;

void checkCount(uint64_t n, const char* what)
{
  if (n > UINT32_MAX) throw Error(std::string(what) + ": " + std::to_string(n) + " is more than 2^32 - 1");
}

}  // namespace

DiffKernels::DiffKernels(ClContext& cl)
    : cl_(cl),
      memory_(deviceMemoryOf(cl)),
      in0_(memory_, "gradient input 0"),
      in1_(memory_, "gradient input 1"),
      in2_(memory_, "gradient input 2"),
      in3_(memory_, "gradient input 3"),
      in4_(memory_, "gradient input 4"),
      out0_(memory_, "gradient output 0"),
      out1_(memory_, "gradient output 1"),
      out2_(memory_, "gradient output 2"),
      pyramid_(memory_, "texture mip pyramid"),
      gradPyramid_(memory_, "texture gradient pyramid"),
      tri_(memory_, "triangles"),
      list_(memory_, "attribute list"),
      levelInfo_(memory_, "mip level table"),
      opp_(memory_, "triangle neighbours")
{
}

template <typename T>
void DiffKernels::upload(DeviceBuffer<T>& buffer, const T* data, uint64_t n)
{
  buffer.reserve(n);
  if (n) cl_.queue.enqueueWriteBuffer(buffer.get(), CL_FALSE, 0, n * sizeof(T), data);
}

cl::Buffer DiffKernels::callerBuffer(const float* data, uint64_t n, bool written)
{
  if (n * sizeof(float) > cl_.maxAllocBytes)
    throw Error("a gradient array of " + std::to_string(n * sizeof(float)) +
                " bytes is more than the device's largest allocation (" + std::to_string(cl_.maxAllocBytes) +
                " bytes)");
  if (n == 0) {  // any buffer: the kernel reads none of it
    in4_.reserve(1);
    return in4_.get();
  }
  return cl::Buffer(cl_.context, CL_MEM_USE_HOST_PTR | (written ? CL_MEM_WRITE_ONLY : CL_MEM_READ_ONLY),
                    n * sizeof(float), const_cast<float*>(data));
}

cl::NDRange DiffKernels::linear(uint64_t n) const
{
  const uint64_t group = 64;
  return cl::NDRange(size_t((n + group - 1) / group * group));
}

void DiffKernels::rasterizeGrad(const float* pos, size_t numVertices, size_t posImages, const int32_t* tri,
                                size_t numTriangles, const DiffImages& batch, const float* rast, const float* gradRast,
                                const float* gradDb, float* gradPos)
{
  const uint64_t n = batch.pixels(), posFloats = uint64_t(posImages) * numVertices * 4;
  checkCount(n, "pixels");
  checkCount(posFloats, "pos floats");
  checkCount(3 * uint64_t(numTriangles), "triangle indices");
  upload(in0_, pos, posFloats);
  upload(tri_, tri, 3 * uint64_t(numTriangles));
  const cl::Buffer rastBuf = callerBuffer(rast, 4 * n, false), gradRastBuf = callerBuffer(gradRast, 4 * n, false);
  const cl::Buffer gradDbBuf = callerBuffer(gradDb, gradDb ? 4 * n : 0, false);
  out0_.zero(posFloats);
  if (n && numTriangles) {
    if (!rasterizeGrad_()) rasterizeGrad_ = cl::Kernel(cl_.extras(), "rasterize_grad");
    RasterizeGradArgs args;
    args.pos = in0_.get(), args.posStride = cl_uint(posImages > 1 ? numVertices * 4 : 0), args.tri = tri_.get();
    args.numTriangles = cl_uint(numTriangles), args.numVertices = cl_uint(numVertices);
    args.rast = rastBuf, args.gradRast = gradRastBuf, args.gradDb = gradDbBuf, args.withDb = gradDb ? 1 : 0;
    args.width = batch.width, args.height = batch.height, args.numPixels = cl_uint(n), args.gradPos = out0_.get();
    setKernelArgs(rasterizeGrad_, args);
    cl_.queue.enqueueNDRangeKernel(rasterizeGrad_, cl::NullRange, linear((n + kPixelSpan - 1) / kPixelSpan));
  }
  if (posFloats) cl_.queue.enqueueReadBuffer(out0_.get(), CL_TRUE, 0, posFloats * sizeof(float), gradPos);
  cl_.queue.finish();
}

void DiffKernels::interpolateGrad(const float* attr, size_t numVertices, size_t numAttrs, size_t attrImages,
                                  const float* rast, const DiffImages& batch, const int32_t* tri, size_t numTriangles,
                                  const float* gradOut, const float* db, const std::vector<int>& diff,
                                  const float* gradDa, float* gradAttr, float* gradRast, float* gradDb)
{
  const uint64_t n = batch.pixels(), attrFloats = uint64_t(attrImages) * numVertices * numAttrs;
  checkCount(n * std::max<uint64_t>(numAttrs, 4 + 2 * diff.size()), "pixel values");
  checkCount(attrFloats, "attr floats");
  checkCount(3 * uint64_t(numTriangles), "triangle indices");
  for (int c : diff)
    if (c < 0 || size_t(c) >= numAttrs) throw Error("diff_attrs: attribute " + std::to_string(c) + " out of range");
  upload(in0_, attr, attrFloats);
  upload(tri_, tri, 3 * uint64_t(numTriangles));
  // The per-pixel arrays in the caller's memory where the device can read it there (a CPU: no copies).
  const cl::Buffer rastBuf = callerBuffer(rast, 4 * n, false), gradOutBuf = callerBuffer(gradOut, n * numAttrs, false);
  const cl::Buffer gradRastBuf = callerBuffer(gradRast, 4 * n, true);
  upload(in3_, db, diff.empty() ? 0 : 4 * n);
  upload(in4_, gradDa, n * 2 * diff.size());
  upload(list_, diff.data(), diff.size());
  out0_.zero(attrFloats);
  out2_.reserve(diff.empty() ? 0 : 4 * n);
  if (n) {
    if (!interpolateGrad_()) interpolateGrad_ = cl::Kernel(cl_.extras(), "interpolate_grad");
    InterpolateGradArgs args;
    args.attr = in0_.get(), args.attrStride = cl_uint(attrImages > 1 ? numVertices * numAttrs : 0);
    args.numVertices = cl_uint(numVertices), args.numAttrs = cl_uint(numAttrs), args.rast = rastBuf;
    args.tri = tri_.get(), args.numTriangles = cl_uint(numTriangles), args.gradOut = gradOutBuf, args.db = in3_.get();
    args.gradDa = in4_.get(), args.diff = list_.get(), args.numDiff = cl_uint(diff.size());
    args.pixelsPerImage = cl_uint(uint64_t(batch.width) * batch.height), args.numPixels = cl_uint(n);
    args.gradAttr = out0_.get(), args.gradRast = gradRastBuf, args.gradDb = out2_.get();
    setKernelArgs(interpolateGrad_, args);
    cl_.queue.enqueueNDRangeKernel(interpolateGrad_, cl::NullRange, linear((n + kPixelSpan - 1) / kPixelSpan));
    // Mapping a caller-memory buffer makes the caller's array hold what the kernel wrote.
    void* mapped = cl_.queue.enqueueMapBuffer(gradRastBuf, CL_TRUE, CL_MAP_READ, 0, 4 * n * sizeof(float));
    cl_.queue.enqueueUnmapMemObject(gradRastBuf, mapped);
  }
  if (attrFloats) cl_.queue.enqueueReadBuffer(out0_.get(), CL_FALSE, 0, attrFloats * sizeof(float), gradAttr);
  if (n && !diff.empty()) cl_.queue.enqueueReadBuffer(out2_.get(), CL_FALSE, 0, 4 * n * sizeof(float), gradDb);
  cl_.queue.finish();
}

std::vector<uint32_t> TextureCall::levelSizes() const
{
  std::vector<uint32_t> sizes;
  for (uint32_t k = 0; k <= maxLevel; ++k) {
    sizes.push_back(std::max(1u, texWidth >> k));
    sizes.push_back(std::max(1u, texHeight >> k));
  }
  return sizes;
}

size_t TextureCall::pyramidTexels() const
{
  const std::vector<uint32_t> sizes = levelSizes();
  size_t n = 0;
  for (size_t k = 0; k < sizes.size(); k += 2) n += size_t(sizes[k]) * sizes[k + 1] * texImages;
  return n;
}

void DiffKernels::uploadPyramid(const TextureCall& call, const float* tex, const float* mips)
{
  const std::vector<uint32_t> sizes = call.levelSizes();
  std::vector<int32_t> info;
  uint64_t offset = 0;
  for (size_t k = 0; k < sizes.size(); k += 2) {
    checkCount(offset, "texture texels");
    info.insert(info.end(), {int32_t(offset), int32_t(sizes[k]), int32_t(sizes[k + 1])});
    offset += uint64_t(sizes[k]) * sizes[k + 1] * call.texImages;
  }
  checkCount(offset * call.channels, "texture floats");
  levelInfo_.upload(info);  // blocking: info is local
  pyramid_.reserve(offset * call.channels);
  const uint64_t base = uint64_t(call.texWidth) * call.texHeight * call.texImages * call.channels;
  if (base) cl_.queue.enqueueWriteBuffer(pyramid_.get(), CL_FALSE, 0, base * sizeof(float), tex);
  if (mips && offset * call.channels > base)
    cl_.queue.enqueueWriteBuffer(pyramid_.get(), CL_FALSE, base * sizeof(float),
                                 (offset * call.channels - base) * sizeof(float), mips);
  if (mips) return;
  if (!mipBuild_()) mipBuild_ = cl::Kernel(cl_.extras(), "mip_build");
  for (uint32_t k = 1; k <= call.maxLevel; ++k) {
    const uint64_t n = uint64_t(sizes[2 * k]) * sizes[2 * k + 1] * call.texImages;
    MipBuildArgs args;
    args.tex = pyramid_.get(), args.levelInfo = levelInfo_.get(), args.level = k, args.channels = call.channels;
    args.texImages = cl_uint(call.texImages);
    setKernelArgs(mipBuild_, args);
    cl_.queue.enqueueNDRangeKernel(mipBuild_, cl::NullRange, linear(n));
  }
}

TexParams DiffKernels::texParams(const TextureCall& call) const
{
  const uint64_t n = call.batch.pixels();
  checkCount(n * std::max<uint64_t>(call.channels, 4), "pixel values");
  TexParams p;
  p.filter = call.filter, p.boundary = call.boundary, p.channels = call.channels;
  p.texImages = cl_uint(call.texImages), p.width = call.batch.width, p.height = call.batch.height;
  p.numPixels = cl_uint(n), p.maxLevel = call.maxLevel, p.hasUvDa = call.hasUvDa, p.hasBias = call.hasBias;
  return p;
}

void DiffKernels::buildMips(const TextureCall& call, const float* tex, float* mips)
{
  uploadPyramid(call, tex, nullptr);
  const uint64_t base = uint64_t(call.texWidth) * call.texHeight * call.texImages * call.channels;
  const uint64_t rest = call.pyramidTexels() * call.channels - base;
  if (rest) cl_.queue.enqueueReadBuffer(pyramid_.get(), CL_FALSE, base * sizeof(float), rest * sizeof(float), mips);
  cl_.queue.finish();
}

void DiffKernels::textureForward(const TextureCall& call, const float* tex, const float* mips, const float* uv,
                                 const float* uvDa, const float* bias, float* out)
{
  const uint64_t n = call.batch.pixels();
  uploadPyramid(call, tex, mips);
  upload(in0_, uv, 2 * n);
  upload(in1_, uvDa, call.hasUvDa ? 4 * n : 0);
  upload(in2_, bias, call.hasBias ? n : 0);
  out0_.reserve(n * call.channels);
  if (n && call.channels) {
    if (!textureFwd_()) textureFwd_ = cl::Kernel(cl_.extras(), "texture_fwd");
    TextureFwdArgs args;
    args.params = texParams(call), args.tex = pyramid_.get(), args.levelInfo = levelInfo_.get();
    args.uv = in0_.get(), args.uvDa = in1_.get(), args.bias = in2_.get(), args.out = out0_.get();
    setKernelArgs(textureFwd_, args);
    cl_.queue.enqueueNDRangeKernel(textureFwd_, cl::NullRange, linear(n));
    cl_.queue.enqueueReadBuffer(out0_.get(), CL_FALSE, 0, n * call.channels * sizeof(float), out);
  }
  cl_.queue.finish();
}

void DiffKernels::textureGrad(const TextureCall& call, const float* tex, const float* mips, const float* uv,
                              const float* uvDa, const float* bias, const float* gradOut, float* gradTex, float* gradUv,
                              float* gradUvDa, float* gradBias)
{
  const uint64_t n = call.batch.pixels();
  const uint64_t texels = call.pyramidTexels();
  uploadPyramid(call, tex, mips);
  upload(in0_, uv, 2 * n);
  upload(in1_, uvDa, call.hasUvDa ? 4 * n : 0);
  upload(in2_, bias, call.hasBias ? n : 0);
  upload(in3_, gradOut, n * call.channels);
  gradPyramid_.zero(texels * call.channels);
  out0_.reserve(2 * n);
  out1_.reserve(call.hasUvDa ? 4 * n : 0);
  out2_.reserve(call.hasBias ? n : 0);
  if (n && call.channels) {
    if (!textureGrad_()) textureGrad_ = cl::Kernel(cl_.extras(), "texture_grad");
    TextureGradArgs args;
    args.params = texParams(call), args.tex = pyramid_.get(), args.levelInfo = levelInfo_.get();
    args.uv = in0_.get(), args.uvDa = in1_.get(), args.bias = in2_.get(), args.gradOut = in3_.get();
    args.gradTex = gradPyramid_.get(), args.gradUv = out0_.get(), args.gradUvDa = out1_.get();
    args.gradBias = out2_.get();
    setKernelArgs(textureGrad_, args);
    cl_.queue.enqueueNDRangeKernel(textureGrad_, cl::NullRange, linear(n));
  }
  // Every level's gradient down to level 0, deepest first (not through a caller's levels).
  const std::vector<uint32_t> sizes = call.levelSizes();
  if (!mips && call.maxLevel) {
    if (!mipGradDown_()) mipGradDown_ = cl::Kernel(cl_.extras(), "mip_grad_down");
    for (uint32_t k = call.maxLevel; k >= 1; --k) {
      const uint64_t m = uint64_t(sizes[2 * k - 2]) * sizes[2 * k - 1] * call.texImages;
      MipGradDownArgs args;
      args.grad = gradPyramid_.get(), args.levelInfo = levelInfo_.get(), args.level = k;
      args.channels = call.channels, args.texImages = cl_uint(call.texImages);
      setKernelArgs(mipGradDown_, args);
      cl_.queue.enqueueNDRangeKernel(mipGradDown_, cl::NullRange, linear(m));
    }
  }
  const uint64_t base = uint64_t(call.texWidth) * call.texHeight * call.texImages * call.channels;
  if (base) cl_.queue.enqueueReadBuffer(gradPyramid_.get(), CL_FALSE, 0, base * sizeof(float), gradTex);
  if (n) cl_.queue.enqueueReadBuffer(out0_.get(), CL_FALSE, 0, 2 * n * sizeof(float), gradUv);
  if (n && call.hasUvDa && gradUvDa)
    cl_.queue.enqueueReadBuffer(out1_.get(), CL_FALSE, 0, 4 * n * sizeof(float), gradUvDa);
  if (n && call.hasBias && gradBias) cl_.queue.enqueueReadBuffer(out2_.get(), CL_FALSE, 0, n * sizeof(float), gradBias);
  cl_.queue.finish();
}

AntialiasArgs DiffKernels::antialiasSetup(cl::Kernel& kernel, const char* name, const float* color, uint32_t channels,
                                          const float* rast, const DiffImages& batch, const float* pos,
                                          size_t numVertices, size_t posImages, const int32_t* tri, const int32_t* opp,
                                          size_t numTriangles)
{
  const uint64_t n = batch.pixels(), posFloats = uint64_t(posImages) * numVertices * 4;
  checkCount(n * std::max<uint32_t>(channels, 4), "pixel values");
  checkCount(posFloats, "pos floats");
  checkCount(3 * uint64_t(numTriangles), "triangle indices");
  upload(in0_, color, n * channels);
  upload(in1_, rast, 4 * n);
  upload(in2_, pos, posFloats);
  upload(tri_, tri, 3 * uint64_t(numTriangles));
  upload(opp_, opp, 3 * uint64_t(numTriangles));
  if (!kernel()) kernel = cl::Kernel(cl_.extras(), name);
  AntialiasArgs a;
  a.color = in0_.get(), a.rast = in1_.get(), a.pos = in2_.get();
  a.posStride = cl_uint(posImages > 1 ? numVertices * 4 : 0), a.tri = tri_.get(), a.opp = opp_.get();
  a.numTriangles = cl_uint(numTriangles), a.width = batch.width, a.height = batch.height, a.numPixels = cl_uint(n);
  a.channels = channels;
  return a;
}

void DiffKernels::antialiasForward(const float* color, uint32_t channels, const float* rast, const DiffImages& batch,
                                   const float* pos, size_t numVertices, size_t posImages, const int32_t* tri,
                                   const int32_t* opp, size_t numTriangles, float* out)
{
  const uint64_t n = batch.pixels();
  AntialiasFwdArgs args;
  args.head = antialiasSetup(aaFwd_, "antialias_fwd", color, channels, rast, batch, pos, numVertices, posImages, tri,
                             opp, numTriangles);
  upload(out0_, color, n * channels);
  if (n && channels) {
    args.out = out0_.get();
    setKernelArgs(aaFwd_, args);
    cl_.queue.enqueueNDRangeKernel(aaFwd_, cl::NullRange, linear(n));
    cl_.queue.enqueueReadBuffer(out0_.get(), CL_FALSE, 0, n * channels * sizeof(float), out);
  }
  cl_.queue.finish();
}

void DiffKernels::antialiasGrad(const float* color, uint32_t channels, const float* rast, const DiffImages& batch,
                                const float* pos, size_t numVertices, size_t posImages, const int32_t* tri,
                                const int32_t* opp, size_t numTriangles, const float* gradOut, float posBoost,
                                float* gradColor, float* gradPos)
{
  const uint64_t n = batch.pixels(), posFloats = uint64_t(posImages) * numVertices * 4;
  AntialiasGradArgs args;
  args.head = antialiasSetup(aaGrad_, "antialias_grad", color, channels, rast, batch, pos, numVertices, posImages, tri,
                             opp, numTriangles);
  upload(in3_, gradOut, n * channels);
  upload(out0_, gradOut, n * channels);
  out1_.zero(posFloats);
  if (n && channels) {
    args.gradOut = in3_.get(), args.posBoost = posBoost, args.gradColor = out0_.get(), args.gradPos = out1_.get();
    setKernelArgs(aaGrad_, args);
    cl_.queue.enqueueNDRangeKernel(aaGrad_, cl::NullRange, linear(n));
    cl_.queue.enqueueReadBuffer(out0_.get(), CL_FALSE, 0, n * channels * sizeof(float), gradColor);
  }
  if (posFloats) cl_.queue.enqueueReadBuffer(out1_.get(), CL_FALSE, 0, posFloats * sizeof(float), gradPos);
  cl_.queue.finish();
}

}  // namespace clr
