// api_diff.cpp — the public backward passes (include/clraster/diff.hpp)
// over the pipeline's DiffKernels (host/pipeline/diff.h), which run on the
// Context's clip-input device context. Arguments are checked here (null
// arrays, index ranges) before anything reaches the device.
#include "api/api_impl.h"

#include "pipeline/diff.h"

#include <clraster/diff.hpp>

namespace clraster {

clr::DiffKernels& Context::Impl::diffKernels()
{
  rasterPipeline();  // builds the clip-input context
  if (!diff) diff = std::make_unique<clr::DiffKernels>(*clip);
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

}  // namespace clraster
