// diff.cpp — host side of kernels/diff.cl (see diff.h): uploads, one launch
// per call over every pixel of the batch, blocking reads of the gradients.
#include "pipeline/diff.h"

namespace clr {

namespace {

void checkCount(uint64_t n, const char* what)
{
  if (n > UINT32_MAX) throw Error(std::string(what) + ": " + std::to_string(n) + " is more than 2^32 - 1");
}

}  // namespace

DiffKernels::DiffKernels(ClContext& cl)
    : cl_(cl),
      memory_{cl.context, cl.queue, cl.maxAllocBytes, 0},
      in0_(memory_, "gradient input 0"),
      in1_(memory_, "gradient input 1"),
      in2_(memory_, "gradient input 2"),
      in3_(memory_, "gradient input 3"),
      in4_(memory_, "gradient input 4"),
      out0_(memory_, "gradient output 0"),
      out1_(memory_, "gradient output 1"),
      out2_(memory_, "gradient output 2"),
      tri_(memory_, "triangles"),
      list_(memory_, "attribute list")
{
}

template <typename T>
void DiffKernels::upload(DeviceBuffer<T>& buffer, const T* data, uint64_t n)
{
  buffer.reserve(n);
  if (n) cl_.queue.enqueueWriteBuffer(buffer.get(), CL_FALSE, 0, n * sizeof(T), data);
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
  upload(in1_, rast, 4 * n);
  upload(in2_, gradRast, 4 * n);
  upload(in3_, gradDb, gradDb ? 4 * n : 0);
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
    k.setArg(a++, in1_.get());
    k.setArg(a++, in2_.get());
    k.setArg(a++, in3_.get());
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
  upload(in1_, rast, 4 * n);
  upload(in2_, gradOut, n * numAttrs);
  upload(in3_, db, diff.empty() ? 0 : 4 * n);
  upload(in4_, gradDa, n * 2 * diff.size());
  upload(list_, diff.data(), diff.size());
  out0_.zero(attrFloats);
  out1_.reserve(4 * n);
  out2_.reserve(diff.empty() ? 0 : 4 * n);
  if (n) {
    if (!interpolateGrad_()) interpolateGrad_ = cl::Kernel(cl_.extras(), "interpolate_grad");
    cl::Kernel& k = interpolateGrad_;
    cl_uint a = 0;
    k.setArg(a++, in0_.get());
    k.setArg(a++, cl_uint(attrImages > 1 ? numVertices * numAttrs : 0));
    k.setArg(a++, cl_uint(numVertices));
    k.setArg(a++, cl_uint(numAttrs));
    k.setArg(a++, in1_.get());
    k.setArg(a++, tri_.get());
    k.setArg(a++, cl_uint(numTriangles));
    k.setArg(a++, in2_.get());
    k.setArg(a++, in3_.get());
    k.setArg(a++, in4_.get());
    k.setArg(a++, list_.get());
    k.setArg(a++, cl_uint(diff.size()));
    k.setArg(a++, cl_uint(uint64_t(batch.width) * batch.height));
    k.setArg(a++, cl_uint(n));
    k.setArg(a++, out0_.get());
    k.setArg(a++, out1_.get());
    k.setArg(a++, out2_.get());
    cl_.queue.enqueueNDRangeKernel(k, cl::NullRange, linear(n));
  }
  if (attrFloats) cl_.queue.enqueueReadBuffer(out0_.get(), CL_FALSE, 0, attrFloats * sizeof(float), gradAttr);
  if (n) cl_.queue.enqueueReadBuffer(out1_.get(), CL_FALSE, 0, 4 * n * sizeof(float), gradRast);
  if (n && !diff.empty()) cl_.queue.enqueueReadBuffer(out2_.get(), CL_FALSE, 0, 4 * n * sizeof(float), gradDb);
  cl_.queue.finish();
}

}  // namespace clr
