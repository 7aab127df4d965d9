// api.cpp — the public C++ API (include/clraster/clraster.hpp) over the
// pipeline: Context, rasterize and interpolate.
//
// rasterize runs the frame pipeline's own stages (setup, bin, raster) on a
// context whose programs take clip-space positions (ClContext clipInput,
// transform.cl), so coverage and ids are the CLI's for the same clip
// coordinates; rast_outputs.cl turns the visibility buffer into nvdiffrast's
// arrays. interpolate is host arithmetic in nvdiffrast's order of
// operations. Every entry point turns OpenCL and allocation failures into
// clraster::Error (guarded(), api_impl.h). The scene-level calls are api_render.cpp.
#include "api/api_impl.h"

#include "base/memory.h"
#include "pipeline/pipeline.h"

#include <clraster/clraster.hpp>

#include <cstdio>
#include <cstring>

namespace clraster {

std::vector<DeviceInfo> listDevices()
{
  return guarded([] {
    std::vector<DeviceInfo> out;
    for (const clr::DeviceInfo& d : clr::listDevices()) out.push_back({d.index, d.name, d.platformName, d.type});
    return out;
  });
}

Context::Context(const std::string& device)
{
  guarded([&] {
    impl_ = std::make_unique<Impl>();
    impl_->selector = device;
    const clr::DeviceInfo d = clr::selectDevice(device);
    impl_->info = {d.index, d.name, d.platformName, d.type};
  });
}
Context::~Context() = default;
Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;
const DeviceInfo& Context::device() const
{
  return Error::live(impl_.get(), "clraster::Context")->info;
}

void Context::setMemoryLimit(uint64_t bytes)
{
  Impl& i = impl();
  i.memoryLimit = bytes;
  if (i.clipPipeline) i.clipPipeline->memory().limitBytes = bytes ? bytes : UINT64_MAX;
  if (i.diff) i.diff->memory().limitBytes = bytes ? bytes : UINT64_MAX;
}
uint64_t Context::memoryLimit() const
{
  return Error::live(impl_.get(), "clraster::Context")->memoryLimit;
}
void Context::release()
{
  impl().diff.reset();
  impl().clipPipeline.reset();
}

clr::Pipeline& Context::Impl::rasterPipeline()
{
  if (!clip) clip = std::make_unique<clr::ClContext>(selector, 0, true);
  if (!clipPipeline) {
    clipPipeline = std::make_unique<clr::Pipeline>(*clip);
    clipPipeline->memory().limitBytes = memoryLimit ? memoryLimit : UINT64_MAX;
  }
  return *clipPipeline;
}

clr::ClContext& Context::Impl::frameContext()
{
  if (!frames) frames = std::make_unique<clr::ClContext>(selector);
  return *frames;
}

float encodeTriangleId(uint32_t id)
{
  if (id <= 0x01000000u) return float(id);
  const uint32_t bits = 0x4a800000u + id;
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

uint32_t decodeTriangleId(float f)
{
  if (!(f > 0.0f)) return 0;  // background, and anything not an id
  if (f <= 16777216.0f) return uint32_t(f);
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  return bits - 0x4a800000u;
}

namespace {

void checkTriangles(const int32_t* tri, size_t numTriangles, size_t numVertices)
{
  if (numTriangles && !tri) throw Error("tri: null array");
  for (size_t k = 0; k < 3 * numTriangles; ++k)
    if (tri[k] < 0 || size_t(tri[k]) >= numVertices)
      throw Error("tri: vertex index " + std::to_string(tri[k]) + " of triangle " + std::to_string(k / 3) +
                  " outside 0.." + std::to_string(int64_t(numVertices) - 1));
}

// Every pixel's channel 3 is 0 (background) or the encoding of an id in 1..numTriangles.
void checkRastIds(const float* rast, size_t pixels, size_t numTriangles)
{
  for (size_t p = 0; p < pixels; ++p) {
    const float f = rast[4 * p + 3];
    const uint32_t id = decodeTriangleId(f);
    if (f != 0.0f && (id == 0 || id > numTriangles || encodeTriangleId(id) != f)) {
      char value[32];
      std::snprintf(value, sizeof value, "%.9g", double(f));
      throw Error("rast: pixel " + std::to_string(p) + " holds triangle id channel " + value + ", not an id in 0.." +
                  std::to_string(numTriangles) + " (0: background)");
    }
  }
}

// Device bytes per pixel a rasterize takes at least: the visibility buffer
// and the outputs' device copies (measured 35 retained, more at the peak);
// the buffers themselves are checked again as they are allocated.
constexpr uint64_t kRasterizeDeviceBytesPerPixel = 40;

void checkResolution(uint32_t width, uint32_t height)
{
  if (width == 0 || height == 0 || width > CLR_MAX_VIEWPORT || height > CLR_MAX_VIEWPORT)
    throw Error("resolution " + std::to_string(height) + "x" + std::to_string(width) + " (height x width) outside 1.." +
                std::to_string(CLR_MAX_VIEWPORT));
}

}  // namespace

void checkRasterizeMemory(Context& ctx, uint32_t width, uint32_t height, uint64_t outputBytes)
{
  guarded([&] {
    checkResolution(width, height);
    const uint64_t device = kRasterizeDeviceBytesPerPixel * width * height;
    ctx.impl().rasterPipeline();  // the device's context, built on first use
    const clr::ClContext& cl = *ctx.impl().clip;
    const std::string what = "rasterize at " + std::to_string(height) + "x" + std::to_string(width);
    if (device > cl.globalMemBytes)
      throw Error(what + " needs " + clr::byteCount(device) + " of device memory, more than the device's " +
                  clr::byteCount(cl.globalMemBytes));
    const bool hostBacked = cl.info.type == "CPU";
    const uint64_t limit = ctx.memoryLimit() ? ctx.memoryLimit() : UINT64_MAX;
    const uint64_t onHost = hostBacked ? device : 0;
    clr::checkHostMemory(what, outputBytes > UINT64_MAX - onHost ? UINT64_MAX : outputBytes + onHost, limit);
    if (!hostBacked && device > limit)
      throw Error(what + " needs " + clr::byteCount(device) + " of device memory, more than the limit of " +
                  clr::byteCount(limit));
  });
}

void rasterizeInto(Context& ctx, const float* pos, size_t numVertices, const int32_t* tri, size_t numTriangles,
                   uint32_t width, uint32_t height, float* rast, uint32_t* ids, float* db)
{
  guarded([&] {
    // Step 1: the arguments, and the memory they need.
    checkResolution(width, height);
    if (numVertices && !pos) throw Error("pos: null array");
    checkTriangles(tri, numTriangles, numVertices);
    const size_t pixels = size_t(width) * height;
    if (numTriangles == 0) {  // nothing to draw: every output is background
      if (rast) std::memset(rast, 0, 4 * pixels * sizeof(float));
      if (ids) std::memset(ids, 0, pixels * sizeof(uint32_t));
      if (db) std::memset(db, 0, 4 * pixels * sizeof(float));
      return;
    }
    checkRasterizeMemory(ctx, width, height, 0);
    // Step 2: the frame pipeline's stages on the clip positions, identity
    // mvp (unused), one sample, no culling, the float32 depth test.
    clr::Pipeline& pipeline = ctx.impl().rasterPipeline();
    pipeline.uploadClipScene(pos, numVertices, reinterpret_cast<const uint32_t*>(tri), numTriangles);
    clr::FrameSettings settings;
    settings.width = width;
    settings.height = height;
    settings.shadeMode = CLR_SHADE_ID;
    settings.keepVisAttributes = true;  // rast_outputs reads the barycentric planes
    pipeline.beginFrame(settings);
    pipeline.setup();
    pipeline.setupEmit();
    pipeline.raster();
    pipeline.rastOutputs(ids != nullptr, db != nullptr);
    pipeline.readRastOutputs(rast, ids, db);
  });
}

Raster rasterize(Context& ctx, const float* pos, size_t numVertices, const int32_t* tri, size_t numTriangles,
                 uint32_t width, uint32_t height, bool derivatives)
{
  return guarded([&] {
    Raster r;
    r.width = width;
    r.height = height;
    r.numTriangles = numTriangles;
    const size_t pixels = size_t(width) * height;
    if (width && height && width <= CLR_MAX_VIEWPORT && height <= CLR_MAX_VIEWPORT) {
      checkRasterizeMemory(ctx, width, height, pixels * (derivatives ? 36 : 20));  // rast, ids (and db)
      r.rast.resize(4 * pixels);
      r.ids.resize(pixels);
      if (derivatives) r.db.resize(4 * pixels);
    }
    rasterizeInto(ctx, pos, numVertices, tri, numTriangles, width, height, r.rast.data(), r.ids.data(),
                  derivatives ? r.db.data() : nullptr);
    return r;
  });
}

void interpolateInto(const float* attr, size_t numVertices, size_t numAttrs, const float* rast, size_t pixels,
                     const int32_t* tri, size_t numTriangles, float* out, const float* db,
                     const std::vector<int>& diffAttrs, float* outDa)
{
  guarded([&] {
    // Step 1: the arguments: every triangle's indices, the listed attributes.
    checkTriangles(tri, numTriangles, numVertices);
    if (numVertices && numAttrs && !attr) throw Error("attr: null array");
    if (pixels && !rast) throw Error("rast: null array");
    if (pixels && numAttrs && !out) throw Error("out: null array");
    std::vector<size_t> listed;
    for (int j : diffAttrs) {
      const int64_t k = j < 0 ? int64_t(j) + int64_t(numAttrs) : int64_t(j);
      if (k < 0 || k >= int64_t(numAttrs))
        throw Error("diff_attrs: attribute " + std::to_string(j) + " outside 0.." + std::to_string(numAttrs) + " - 1");
      listed.push_back(size_t(k));
    }
    if (!listed.empty() && (!db || !outDa)) throw Error("diff_attrs: needs rast_db");
    checkRastIds(rast, pixels, numTriangles);
    // Step 2: per pixel, nvdiffrast's formula (interpolate.cu) in its order.
    for (size_t p = 0; p < pixels; ++p) {
      const uint32_t id = decodeTriangleId(rast[4 * p + 3]);
      float* o = out + p * numAttrs;
      float* da = outDa ? outDa + p * 2 * listed.size() : nullptr;
      if (id == 0) {
        std::fill(o, o + numAttrs, 0.0f);
        if (da) std::fill(da, da + 2 * listed.size(), 0.0f);
        continue;
      }
      const int32_t* t = tri + 3 * size_t(id - 1);
      const float* a0 = attr + size_t(t[0]) * numAttrs;
      const float* a1 = attr + size_t(t[1]) * numAttrs;
      const float* a2 = attr + size_t(t[2]) * numAttrs;
      const float b0 = rast[4 * p], b1 = rast[4 * p + 1], b2 = 1.0f - rast[4 * p] - rast[4 * p + 1];
      for (size_t c = 0; c < numAttrs; ++c) o[c] = b0 * a0[c] + b1 * a1[c] + b2 * a2[c];
      for (size_t k = 0; k < listed.size(); ++k) {
        const size_t c = listed[k];
        const float dsdu = a0[c] - a2[c], dsdv = a1[c] - a2[c];
        da[2 * k] = db[4 * p] * dsdu + db[4 * p + 2] * dsdv;
        da[2 * k + 1] = db[4 * p + 1] * dsdu + db[4 * p + 3] * dsdv;
      }
    }
  });
}

std::vector<float> interpolate(Context&, const float* attr, size_t numVertices, size_t numAttrs, const Raster& r,
                               const int32_t* tri)
{
  return guarded([&] {
    const size_t pixels = size_t(r.width) * r.height;
    if (r.rast.size() != 4 * pixels)
      throw Error("raster: rast holds " + std::to_string(r.rast.size()) + " floats, not 4 per pixel of its " +
                  std::to_string(pixels));
    std::vector<float> out(pixels * numAttrs);
    interpolateInto(attr, numVertices, numAttrs, r.rast.data(), pixels, tri, r.numTriangles, out.data());
    return out;
  });
}

}  // namespace clraster
