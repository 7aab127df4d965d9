// diff.cpp — host side of kernels/diff.cl (see diff.h): uploads, one launch
// per call over every pixel of the batch, blocking reads of the gradients.
#include "pipeline/diff.h"

namespace clr {

namespace {

// Pixels per work-item of interpolate_grad (DIFF_SPAN, diff.cl).
constexpr uint64_t kInterpolateSpan = 16;

void checkCount(uint64_t n, const char* what)
{
  if (n > UINT32_MAX) throw Error(std::string(what) + ": " + std::to_string(n) + " is more than 2^32 - 1");
}

}  // namespace

DiffKernels::DiffKernels(ClContext& cl)
    : cl_(cl),
      memory_{cl.context, cl.queue, cl.maxAllocBytes, 0, cl.globalMemBytes, UINT64_MAX, cl.info.type == "CPU"},
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
    cl::Kernel& k = rasterizeGrad_;
    cl_uint a = 0;
    k.setArg(a++, in0_.get());
    k.setArg(a++, cl_uint(posImages > 1 ? numVertices * 4 : 0));
    k.setArg(a++, tri_.get());
    k.setArg(a++, cl_uint(numTriangles));
    k.setArg(a++, cl_uint(numVertices));
    k.setArg(a++, rastBuf);
    k.setArg(a++, gradRastBuf);
    k.setArg(a++, gradDbBuf);
    k.setArg(a++, cl_uint(gradDb ? 1 : 0));
    k.setArg(a++, cl_uint(batch.width));
    k.setArg(a++, cl_uint(batch.height));
    k.setArg(a++, cl_uint(n));
    k.setArg(a++, out0_.get());
    cl_.queue.enqueueNDRangeKernel(k, cl::NullRange, linear(n));
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
    cl::Kernel& k = interpolateGrad_;
    cl_uint a = 0;
    k.setArg(a++, in0_.get());
    k.setArg(a++, cl_uint(attrImages > 1 ? numVertices * numAttrs : 0));
    k.setArg(a++, cl_uint(numVertices));
    k.setArg(a++, cl_uint(numAttrs));
    k.setArg(a++, rastBuf);
    k.setArg(a++, tri_.get());
    k.setArg(a++, cl_uint(numTriangles));
    k.setArg(a++, gradOutBuf);
    k.setArg(a++, in3_.get());
    k.setArg(a++, in4_.get());
    k.setArg(a++, list_.get());
    k.setArg(a++, cl_uint(diff.size()));
    k.setArg(a++, cl_uint(uint64_t(batch.width) * batch.height));
    k.setArg(a++, cl_uint(n));
    k.setArg(a++, out0_.get());
    k.setArg(a++, gradRastBuf);
    k.setArg(a++, out2_.get());
    cl_.queue.enqueueNDRangeKernel(k, cl::NullRange, linear((n + kInterpolateSpan - 1) / kInterpolateSpan));
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
    mipBuild_.setArg(0, pyramid_.get());
    mipBuild_.setArg(1, levelInfo_.get());
    mipBuild_.setArg(2, cl_uint(k));
    mipBuild_.setArg(3, cl_uint(call.channels));
    mipBuild_.setArg(4, cl_uint(call.texImages));
    cl_.queue.enqueueNDRangeKernel(mipBuild_, cl::NullRange, linear(n));
  }
}

void DiffKernels::setTextureArgs(cl::Kernel& kernel, const TextureCall& call)
{
  const uint64_t n = call.batch.pixels();
  checkCount(n * std::max<uint64_t>(call.channels, 4), "pixel values");
  const cl_uint params[12] = {call.filter,
                              call.boundary,
                              call.channels,
                              cl_uint(call.texImages),
                              call.batch.width,
                              call.batch.height,
                              cl_uint(n),
                              call.maxLevel,
                              call.hasUvDa,
                              call.hasBias,
                              0,
                              0};
  cl_uint a = 0;
  kernel.setArg(a++, sizeof params, params);
  kernel.setArg(a++, pyramid_.get());
  kernel.setArg(a++, levelInfo_.get());
  kernel.setArg(a++, in0_.get());
  kernel.setArg(a++, in1_.get());
  kernel.setArg(a++, in2_.get());
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
    setTextureArgs(textureFwd_, call);
    textureFwd_.setArg(6, out0_.get());
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
    setTextureArgs(textureGrad_, call);
    cl_uint a = 6;
    textureGrad_.setArg(a++, in3_.get());
    textureGrad_.setArg(a++, gradPyramid_.get());
    textureGrad_.setArg(a++, out0_.get());
    textureGrad_.setArg(a++, out1_.get());
    textureGrad_.setArg(a++, out2_.get());
    cl_.queue.enqueueNDRangeKernel(textureGrad_, cl::NullRange, linear(n));
  }
  // Every level's gradient down to level 0, deepest first (not through a caller's levels).
  const std::vector<uint32_t> sizes = call.levelSizes();
  if (!mips && call.maxLevel) {
    if (!mipGradDown_()) mipGradDown_ = cl::Kernel(cl_.extras(), "mip_grad_down");
    for (uint32_t k = call.maxLevel; k >= 1; --k) {
      const uint64_t m = uint64_t(sizes[2 * k - 2]) * sizes[2 * k - 1] * call.texImages;
      mipGradDown_.setArg(0, gradPyramid_.get());
      mipGradDown_.setArg(1, levelInfo_.get());
      mipGradDown_.setArg(2, cl_uint(k));
      mipGradDown_.setArg(3, cl_uint(call.channels));
      mipGradDown_.setArg(4, cl_uint(call.texImages));
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

void DiffKernels::antialiasSetup(cl::Kernel& kernel, const char* name, const float* color, uint32_t channels,
                                 const float* rast, const DiffImages& batch, const float* pos, size_t numVertices,
                                 size_t posImages, const int32_t* tri, const int32_t* opp, size_t numTriangles)
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
  cl_uint a = 0;
  kernel.setArg(a++, in0_.get());
  kernel.setArg(a++, in1_.get());
  kernel.setArg(a++, in2_.get());
  kernel.setArg(a++, cl_uint(posImages > 1 ? numVertices * 4 : 0));
  kernel.setArg(a++, tri_.get());
  kernel.setArg(a++, opp_.get());
  kernel.setArg(a++, cl_uint(numTriangles));
  kernel.setArg(a++, cl_uint(batch.width));
  kernel.setArg(a++, cl_uint(batch.height));
  kernel.setArg(a++, cl_uint(n));
  kernel.setArg(a++, cl_uint(channels));
}

void DiffKernels::antialiasForward(const float* color, uint32_t channels, const float* rast, const DiffImages& batch,
                                   const float* pos, size_t numVertices, size_t posImages, const int32_t* tri,
                                   const int32_t* opp, size_t numTriangles, float* out)
{
  const uint64_t n = batch.pixels();
  antialiasSetup(aaFwd_, "antialias_fwd", color, channels, rast, batch, pos, numVertices, posImages, tri, opp,
                 numTriangles);
  upload(out0_, color, n * channels);
  if (n && channels) {
    aaFwd_.setArg(11, out0_.get());
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
  antialiasSetup(aaGrad_, "antialias_grad", color, channels, rast, batch, pos, numVertices, posImages, tri, opp,
                 numTriangles);
  upload(in3_, gradOut, n * channels);
  upload(out0_, gradOut, n * channels);
  out1_.zero(posFloats);
  if (n && channels) {
    aaGrad_.setArg(11, in3_.get());
    aaGrad_.setArg(12, posBoost);
    aaGrad_.setArg(13, out0_.get());
    aaGrad_.setArg(14, out1_.get());
    cl_.queue.enqueueNDRangeKernel(aaGrad_, cl::NullRange, linear(n));
    cl_.queue.enqueueReadBuffer(out0_.get(), CL_FALSE, 0, n * channels * sizeof(float), gradColor);
  }
  if (posFloats) cl_.queue.enqueueReadBuffer(out1_.get(), CL_FALSE, 0, posFloats * sizeof(float), gradPos);
  cl_.queue.finish();
}

}  // namespace clr
