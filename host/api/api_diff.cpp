// api_diff.cpp — the public backward passes (include/clraster/diff.hpp)
// over the pipeline's DiffKernels (host/pipeline/diff.h), which run on the
// Context's clip-input device context. Arguments are checked here (null
// arrays, index ranges) before anything reaches the device.
#include "api/api_impl.h"

#include "pipeline/diff.h"

#include <clraster/diff.hpp>

#include <algorithm>
#include <cmath>

namespace clraster {

clr::DiffKernels& Context::Impl::diffKernels()
{
  rasterPipeline();  // builds the clip-input context
  if (!diff) {
    diff = std::make_unique<clr::DiffKernels>(*clip);
    diff->memory().limitBytes = memoryLimit ? memoryLimit : UINT64_MAX;
  }
  return *diff;
}

namespace {

void checkBatch(const ImageBatch& b, const char* call)
{
  if (b.images && (b.width == 0 || b.height == 0 || b.width > CLR_MAX_VIEWPORT || b.height > CLR_MAX_VIEWPORT))
    throw Error(std::string(call) + ": resolution " + std::to_string(b.height) + "x" + std::to_string(b.width) +
                " outside 1.." + std::to_string(CLR_MAX_VIEWPORT));
}

void checkTri(const int32_t* tri, size_t numTriangles, size_t numVertices)
{
  if (numTriangles && !tri) throw Error("tri: null array");
  for (size_t k = 0; k < 3 * numTriangles; ++k)
    if (tri[k] < 0 || size_t(tri[k]) >= numVertices)
      throw Error("tri: vertex index " + std::to_string(tri[k]) + " outside 0.." +
                  std::to_string(int64_t(numVertices) - 1));
}

void need(const void* p, bool wanted, const char* name)
{
  if (wanted && !p) throw Error(std::string(name) + ": null array");
}

}  // namespace

void rasterizeGrad(Context& ctx, const float* pos, size_t numVertices, size_t posImages, const int32_t* tri,
                   size_t numTriangles, const ImageBatch& batch, const float* rast, const float* gradRast,
                   const float* gradDb, float* gradPos)
{
  guarded([&] {
    checkBatch(batch, "rasterize_grad");
    if (posImages != 1 && posImages != batch.images)
      throw Error("pos: " + std::to_string(posImages) + " images for a batch of " + std::to_string(batch.images));
    checkTri(tri, numTriangles, numVertices);
    const size_t pixels = batch.images * batch.width * batch.height;
    need(pos, numVertices, "pos");
    need(gradPos, numVertices, "grad_pos");
    need(rast, pixels, "rast");
    need(gradRast, pixels, "grad_rast");
    ctx.impl().diffKernels().rasterizeGrad(pos, numVertices, posImages, tri, numTriangles,
                                           {batch.images, batch.width, batch.height}, rast, gradRast, gradDb, gradPos);
  });
}

void interpolateGrad(Context& ctx, const float* attr, size_t numVertices, size_t numAttrs, size_t attrImages,
                     const float* rast, const ImageBatch& batch, const int32_t* tri, size_t numTriangles,
                     const float* gradOut, const float* db, const std::vector<int>& diffAttrs, const float* gradDa,
                     float* gradAttr, float* gradRast, float* gradDb)
{
  guarded([&] {
    checkBatch(batch, "interpolate_grad");
    if (attrImages != 1 && attrImages != batch.images)
      throw Error("attr: " + std::to_string(attrImages) + " images for a batch of " + std::to_string(batch.images));
    checkTri(tri, numTriangles, numVertices);
    std::vector<int> listed;
    for (int j : diffAttrs) {
      const int64_t k = j < 0 ? int64_t(j) + int64_t(numAttrs) : int64_t(j);
      if (k < 0 || k >= int64_t(numAttrs))
        throw Error("diff_attrs: attribute " + std::to_string(j) + " outside 0.." + std::to_string(numAttrs) + " - 1");
      listed.push_back(int(k));
    }
    const size_t pixels = batch.images * batch.width * batch.height;
    need(attr, numVertices != 0 && numAttrs != 0, "attr");
    need(gradAttr, numVertices != 0 && numAttrs != 0, "grad_attr");
    need(rast, pixels, "rast");
    need(gradOut, pixels != 0 && numAttrs != 0, "grad_out");
    need(gradRast, pixels, "grad_rast");
    need(db, pixels && !listed.empty(), "rast_db");
    need(gradDa, pixels && !listed.empty(), "grad_da");
    need(gradDb, pixels && !listed.empty(), "grad_db");
    ctx.impl().diffKernels().interpolateGrad(attr, numVertices, numAttrs, attrImages, rast,
                                             {batch.images, batch.width, batch.height}, tri, numTriangles, gradOut, db,
                                             listed, gradDa, gradAttr, gradRast, gradDb);
  });
}

namespace {

clr::TextureCall textureCall(const TextureSpec& spec)
{
  checkBatch(spec.batch, "texture");
  if (spec.texImages != 1 && spec.texImages != spec.batch.images)
    throw Error("tex: " + std::to_string(spec.texImages) + " textures for a batch of " +
                std::to_string(spec.batch.images));
  if (spec.texWidth == 0 || spec.texHeight == 0 || spec.texWidth > CLR_MAX_VIEWPORT ||
      spec.texHeight > CLR_MAX_VIEWPORT)
    throw Error("tex: size " + std::to_string(spec.texHeight) + "x" + std::to_string(spec.texWidth) + " outside 1.." +
                std::to_string(CLR_MAX_VIEWPORT));
  if (spec.channels == 0) throw Error("tex: no channels");
  const bool mipmapped =
      spec.filter == TextureFilter::LinearMipmapNearest || spec.filter == TextureFilter::LinearMipmapLinear;
  if (mipmapped && !spec.hasUvDa && !spec.hasBias)
    throw Error("filter_mode: mipmapped filtering needs uv_da or mip_level_bias");
  clr::TextureCall c;
  c.batch = {spec.batch.images, spec.batch.width, spec.batch.height};
  c.texImages = spec.texImages;
  c.texWidth = spec.texWidth;
  c.texHeight = spec.texHeight;
  c.channels = spec.channels;
  c.filter = uint32_t(spec.filter);
  c.boundary = uint32_t(spec.boundary);
  c.hasUvDa = spec.hasUvDa;
  c.hasBias = spec.hasBias;
  uint32_t w = spec.texWidth, h = spec.texHeight, level = 0;
  while ((w > 1 || h > 1) && (w == 1 || w % 2 == 0) && (h == 1 || h % 2 == 0) &&
         (spec.maxMipLevel < 0 || level < uint32_t(spec.maxMipLevel))) {
    w = std::max(1u, w / 2);
    h = std::max(1u, h / 2);
    ++level;
  }
  c.maxLevel = level;
  return c;
}

}  // namespace

uint32_t textureMaxLevel(const TextureSpec& spec)
{
  return guarded([&] {
    const clr::TextureCall c = textureCall(spec);
    return c.filter == uint32_t(TextureFilter::Nearest) || c.filter == uint32_t(TextureFilter::Linear) ? 0u
                                                                                                       : c.maxLevel;
  });
}

size_t textureMipFloats(const TextureSpec& spec)
{
  return guarded([&] {
    const clr::TextureCall c = textureCall(spec);
    return (c.pyramidTexels() - size_t(c.texWidth) * c.texHeight * c.texImages) * c.channels;
  });
}

void textureMips(Context& ctx, const TextureSpec& spec, const float* tex, float* mips)
{
  guarded([&] {
    const clr::TextureCall c = textureCall(spec);
    need(tex, true, "tex");
    need(mips, c.maxLevel > 0, "mip");
    ctx.impl().diffKernels().buildMips(c, tex, mips);
  });
}

namespace {

clr::TextureCall checkedTextureCall(const TextureSpec& spec, const float* tex, const float* uv, const float* uvDa,
                                    const float* bias)
{
  clr::TextureCall c = textureCall(spec);
  if (c.filter == uint32_t(TextureFilter::Nearest) || c.filter == uint32_t(TextureFilter::Linear)) {
    c.maxLevel = 0;
    c.hasUvDa = c.hasBias = false;
  }
  const bool pixels = c.batch.pixels() != 0;
  need(tex, true, "tex");
  need(uv, pixels, "uv");
  need(uvDa, pixels && c.hasUvDa, "uv_da");
  need(bias, pixels && c.hasBias, "mip_level_bias");
  return c;
}

}  // namespace

void texture(Context& ctx, const TextureSpec& spec, const float* tex, const float* mips, const float* uv,
             const float* uvDa, const float* bias, float* out)
{
  guarded([&] {
    const clr::TextureCall c = checkedTextureCall(spec, tex, uv, uvDa, bias);
    need(out, c.batch.pixels() != 0, "out");
    ctx.impl().diffKernels().textureForward(c, tex, c.maxLevel ? mips : nullptr, uv, uvDa, bias, out);
  });
}

void textureGrad(Context& ctx, const TextureSpec& spec, const float* tex, const float* mips, const float* uv,
                 const float* uvDa, const float* bias, const float* gradOut, float* gradTex, float* gradUv,
                 float* gradUvDa, float* gradBias)
{
  guarded([&] {
    const clr::TextureCall c = checkedTextureCall(spec, tex, uv, uvDa, bias);
    const bool pixels = c.batch.pixels() != 0;
    need(gradOut, pixels, "grad_out");
    need(gradTex, true, "grad_tex");
    need(gradUv, pixels, "grad_uv");
    ctx.impl().diffKernels().textureGrad(c, tex, c.maxLevel ? mips : nullptr, uv, uvDa, bias, gradOut, gradTex, gradUv,
                                         gradUvDa, gradBias);
  });
}

namespace {

void checkAntialias(const float* color, uint32_t channels, const float* rast, const ImageBatch& batch, const float* pos,
                    size_t numVertices, size_t posImages, const int32_t* tri, const int32_t* opp, size_t numTriangles)
{
  checkBatch(batch, "antialias");
  if (posImages != 1 && posImages != batch.images)
    throw Error("pos: " + std::to_string(posImages) + " images for a batch of " + std::to_string(batch.images));
  checkTri(tri, numTriangles, numVertices);
  need(opp, numTriangles != 0, "topology_hash");
  for (size_t k = 0; k < 3 * numTriangles; ++k)
    if (opp[k] < -1 || (opp[k] >= 0 && size_t(opp[k]) >= numVertices))
      throw Error("topology_hash: vertex " + std::to_string(opp[k]) + " outside -1.." +
                  std::to_string(int64_t(numVertices) - 1));
  const size_t pixels = batch.images * batch.width * batch.height;
  need(color, pixels != 0 && channels != 0, "color");
  need(rast, pixels != 0, "rast");
  need(pos, numVertices != 0, "pos");
}

}  // namespace

void antialias(Context& ctx, const float* color, uint32_t channels, const float* rast, const ImageBatch& batch,
               const float* pos, size_t numVertices, size_t posImages, const int32_t* tri, const int32_t* opp,
               size_t numTriangles, float* out)
{
  guarded([&] {
    checkAntialias(color, channels, rast, batch, pos, numVertices, posImages, tri, opp, numTriangles);
    need(out, batch.images * batch.width * batch.height * channels != 0, "out");
    ctx.impl().diffKernels().antialiasForward(color, channels, rast, {batch.images, batch.width, batch.height}, pos,
                                              numVertices, posImages, tri, opp, numTriangles, out);
  });
}

void antialiasGrad(Context& ctx, const float* color, uint32_t channels, const float* rast, const ImageBatch& batch,
                   const float* pos, size_t numVertices, size_t posImages, const int32_t* tri, const int32_t* opp,
                   size_t numTriangles, const float* gradOut, float posBoost, float* gradColor, float* gradPos)
{
  guarded([&] {
    checkAntialias(color, channels, rast, batch, pos, numVertices, posImages, tri, opp, numTriangles);
    const bool values = batch.images * batch.width * batch.height * channels != 0;
    need(gradOut, values, "grad_out");
    need(gradColor, values, "grad_color");
    need(gradPos, numVertices != 0, "grad_pos");
    ctx.impl().diffKernels().antialiasGrad(color, channels, rast, {batch.images, batch.width, batch.height}, pos,
                                           numVertices, posImages, tri, opp, numTriangles, gradOut, posBoost, gradColor,
                                           gradPos);
  });
}

std::vector<int32_t> antialiasTopology(const int32_t* tri, size_t numTriangles, size_t numVertices)
{
  return guarded([&] {
    checkTri(tri, numTriangles, numVertices);
    // Each edge (low, high vertex) with its triangle and the vertex opposite; sorted, runs of one edge.
    struct Side {
      uint64_t key;
      size_t slot;  // 3 · triangle + the opposite vertex's position
    };
    std::vector<Side> sides;
    sides.reserve(3 * numTriangles);
    for (size_t t = 0; t < numTriangles; ++t)
      for (size_t i = 0; i < 3; ++i) {
        const uint64_t a = uint32_t(tri[3 * t + (i + 1) % 3]), b = uint32_t(tri[3 * t + (i + 2) % 3]);
        if (a != b) sides.push_back({std::min(a, b) << 32 | std::max(a, b), 3 * t + i});
      }
    std::sort(sides.begin(), sides.end(),
              [](const Side& x, const Side& y) { return x.key != y.key ? x.key < y.key : x.slot < y.slot; });
    std::vector<int32_t> opp(3 * numTriangles, -1);
    for (size_t k = 0; k < sides.size();) {
      size_t end = k;
      while (end < sides.size() && sides[end].key == sides[k].key) ++end;
      if (end - k == 2) {
        opp[sides[k].slot] = tri[sides[k + 1].slot];
        opp[sides[k + 1].slot] = tri[sides[k].slot];
      }
      k = end;
    }
    return opp;
  });
}

namespace {

// A batch of images in instanced or range mode, as stacked frames (diff.hpp, rasterizeBatch).
struct Batch {
  const float* pos = nullptr;
  size_t numVertices = 0;
  const int32_t* tri = nullptr;
  size_t numTriangles = 0;
  const int32_t* ranges = nullptr;  // null: instanced
  size_t images = 0;
  size_t imageTris = 0;  // triangles per image (range images padded to the longest range)
  uint32_t width = 0, height = 0;
  uint32_t rows = 0;  // per image in a frame: height rounded up to the tile size
  size_t pixels() const { return size_t(width) * height; }
};

// The arguments checked (an Error naming the bad one) and the batch's layout.
Batch planBatch(const float* pos, size_t numVertices, size_t posImages, const int32_t* tri, size_t numTriangles,
                const int32_t* ranges, size_t numRanges, uint32_t width, uint32_t height)
{
  checkBatch({1, width, height}, "rasterize");
  checkTri(tri, numTriangles, numVertices);
  if (ranges && posImages != 1) throw Error("ranges: range mode takes one pos array");
  need(pos, numVertices != 0, "pos");
  Batch b{pos,
          numVertices,
          tri,
          numTriangles,
          ranges,
          ranges ? numRanges : posImages,
          ranges ? 0 : numTriangles,
          width,
          height,
          (height + CLR_TILE_SIZE - 1) / CLR_TILE_SIZE * CLR_TILE_SIZE};
  for (size_t k = 0; ranges && k < numRanges; ++k) {
    const int64_t start = ranges[2 * k], count = ranges[2 * k + 1];
    if (start < 0 || count < 0 || uint64_t(start + count) > numTriangles)
      throw Error("ranges: range " + std::to_string(k) + " (" + std::to_string(start) + ", " + std::to_string(count) +
                  ") outside the " + std::to_string(numTriangles) + " triangles");
    b.imageTris = std::max(b.imageTris, size_t(count));
  }
  return b;
}

// Pixels a batched frame holds at most (several images each when they are small): beyond this its per-pixel
// buffers outgrow a CPU core's caches between one stage and the next, which costs more per pixel than the
// launches of a further frame.
constexpr size_t kBatchFramePixels = size_t(1) << 19;

// Images per frame: the frame's rows within the viewport, its pixels within kBatchFramePixels, its indices and
// vertices in 32 bits (uploadClipScene), its device memory within the device and the Context's limit (halved
// until it fits; one image that does not is the Error).
size_t imagesPerFrame(Context& ctx, const Batch& b)
{
  size_t perFrame = std::min<size_t>(b.images, CLR_MAX_VIEWPORT / b.rows);
  perFrame = std::min(perFrame, std::max<size_t>(1, kBatchFramePixels / (size_t(b.width) * b.rows)));
  perFrame = std::min(perFrame, std::max<size_t>(1, UINT32_MAX / CLR_MAX_SUBTRIS / b.imageTris));
  if (!b.ranges) perFrame = std::min(perFrame, std::max<size_t>(1, UINT32_MAX / 4 / b.numVertices));
  for (perFrame = std::max<size_t>(perFrame, 1);; perFrame = (perFrame + 1) / 2) {
    try {
      checkRasterizeMemory(ctx, b.width, uint32_t(perFrame * b.rows), 0);
      return perFrame;
    } catch (const Error&) {
      if (perFrame == 1) throw;
    }
  }
}

// Each frame of the batch through setup and bin, then stage(pipeline, first image, images). Setup adds each
// image's row offset in fixed point and clamps its bounds to the image's rows (clr_image_row, shared.h).
template <typename Stage>
void runFrames(Context& ctx, const Batch& b, bool keepVisAttributes, Stage&& stage)
{
  const size_t perFrame = imagesPerFrame(ctx, b);
  clr::Pipeline& pipeline = ctx.impl().rasterPipeline();
  std::vector<int32_t> frameTri;
  for (size_t first = 0; first < b.images; first += perFrame) {
    const size_t count = std::min(perFrame, b.images - first);
    frameTri.assign(3 * count * b.imageTris, 0);
    for (size_t k = 0; k < count; ++k) {
      const int32_t* from = b.ranges ? b.tri + 3 * size_t(b.ranges[2 * (first + k)]) : b.tri;
      const size_t n = b.ranges ? size_t(b.ranges[2 * (first + k) + 1]) : b.numTriangles;
      int32_t* to = frameTri.data() + 3 * k * b.imageTris;
      const int32_t offset = b.ranges ? 0 : int32_t(k * b.numVertices);
      for (size_t i = 0; i < 3 * n; ++i) to[i] = from[i] + offset;
    }
    const float* framePos = b.ranges ? b.pos : b.pos + 4 * first * b.numVertices;
    pipeline.uploadClipScene(framePos, b.ranges ? b.numVertices : count * b.numVertices,
                             reinterpret_cast<const uint32_t*>(frameTri.data()), count * b.imageTris);
    clr::FrameSettings settings;  // as rasterizeInto's frame, images stacked
    settings.width = b.width;
    settings.height = uint32_t(count * b.rows);
    settings.shadeMode = CLR_SHADE_ID;
    settings.keepVisAttributes = keepVisAttributes;
    settings.imageTris = uint32_t(b.imageTris);
    settings.imageRows = b.rows;
    settings.imageHeight = b.height;
    pipeline.beginFrame(settings);
    pipeline.setup();
    pipeline.setupEmit();
    stage(pipeline, first, count);
  }
}

// Range mode's ids count from the start of tri (the frames write them per range).
void rangeIds(const Batch& b, float* rast)
{
  for (size_t k = 0; b.ranges && k < b.images; ++k) {
    const uint32_t start = uint32_t(b.ranges[2 * k]);
    float* id = rast + 4 * k * b.pixels() + 3;
    for (size_t p = 0; start && p < b.pixels(); ++p)
      if (id[4 * p] != 0.0f) id[4 * p] = encodeTriangleId(decodeTriangleId(id[4 * p]) + start);
  }
}

}  // namespace

void rasterizeBatch(Context& ctx, const float* pos, size_t numVertices, size_t posImages, const int32_t* tri,
                    size_t numTriangles, const int32_t* ranges, size_t numRanges, uint32_t width, uint32_t height,
                    float* rast, float* db)
{
  guarded([&] {
    const Batch b = planBatch(pos, numVertices, posImages, tri, numTriangles, ranges, numRanges, width, height);
    need(rast, b.images != 0, "rast");
    const size_t values = 4 * b.images * b.pixels();
    if (b.images && b.imageTris == 0) {  // nothing to draw: every output is background
      std::fill(rast, rast + values, 0.0f);
      if (db) std::fill(db, db + values, 0.0f);
    }
    if (b.images == 0 || b.imageTris == 0) return;
    runFrames(ctx, b, true, [&](clr::Pipeline& pipeline, size_t first, size_t) {
      pipeline.raster();
      pipeline.rastOutputs(false, db != nullptr);  // per-image ids and derivatives
      pipeline.readRastOutputs(rast + 4 * first * b.pixels(), nullptr, db ? db + 4 * first * b.pixels() : nullptr);
    });
    rangeIds(b, rast);
  });
}

void rasterizePeel(Context& ctx, const float* pos, size_t numVertices, size_t posImages, const int32_t* tri,
                   size_t numTriangles, const int32_t* ranges, size_t numRanges, uint32_t width, uint32_t height,
                   const float* floorDepth, float* rast, float* db, float* nextFloor)
{
  guarded([&] {
    const Batch b = planBatch(pos, numVertices, posImages, tri, numTriangles, ranges, numRanges, width, height);
    need(floorDepth, b.images != 0, "floor");
    need(rast, b.images != 0, "rast");
    need(nextFloor, b.images != 0, "next_floor");
    const size_t pixels = b.images * b.pixels();
    if (b.images && b.imageTris == 0) {
      std::fill(rast, rast + 4 * pixels, 0.0f);
      if (db) std::fill(db, db + 4 * pixels, 0.0f);
      std::fill(nextFloor, nextFloor + pixels, INFINITY);
    }
    if (b.images == 0 || b.imageTris == 0) return;
    runFrames(ctx, b, false, [&](clr::Pipeline& pipeline, size_t first, size_t) {
      const size_t at = first * b.pixels();
      pipeline.peelLayer(floorDepth + at, rast + 4 * at, db ? db + 4 * at : nullptr, nextFloor + at);
    });
    rangeIds(b, rast);
  });
}

}  // namespace clraster
