// diff.hpp — the backward passes of clraster::rasterize and interpolate
// (clraster.hpp), for gradient-based optimisation (the Python module
// clraster.torch wraps them as torch.autograd Functions). Both run as one
// OpenCL launch over every pixel of a batch of images on the Context's
// device; gradients are those of the forward formulas at the pixel centres
// with coverage held fixed (a pixel keeps its triangle), as in nvdiffrast.
// Arrays are row-major, images one after another, row 0 at the bottom.
#pragma once

#include "clraster.hpp"

namespace clraster {

// images × height × width pixels.
struct ImageBatch {
  size_t images = 0;
  uint32_t width = 0, height = 0;
};

// d L / d pos from d L / d rast (gradRast, 4 floats per pixel: u, v, z/w,
// id; the id's gradient is ignored) and, when not null, d L / d rast_db
// (gradDb, 4 floats per pixel). pos: posImages × numVertices × 4 floats
// (posImages 1: every image shares pos; else batch.images, instanced);
// rast: rasterize's output for the batch (ids index tri); gradPos: pos's
// shape, overwritten.
CLRASTER_API void rasterizeGrad(Context& ctx, const float* pos, size_t numVertices, size_t posImages,
                                const int32_t* tri, size_t numTriangles, const ImageBatch& batch, const float* rast,
                                const float* gradRast, const float* gradDb, float* gradPos);

// d L / d attr (gradAttr, attr's shape: attrImages × numVertices ×
// numAttrs, attrImages 1 or batch.images), d L / d rast (gradRast, 4 floats
// per pixel; channels z/w and id get 0) and, with diffAttrs (indices, as
// interpolateInto takes them), d L / d rast_db (gradDb, 4 per pixel) from
// d L / d out (gradOut, numAttrs per pixel) and d L / d out_da (gradDa,
// 2 · diffAttrs.size() per pixel).
CLRASTER_API void interpolateGrad(Context& ctx, const float* attr, size_t numVertices, size_t numAttrs,
                                  size_t attrImages, const float* rast, const ImageBatch& batch, const int32_t* tri,
                                  size_t numTriangles, const float* gradOut, const float* db,
                                  const std::vector<int>& diffAttrs, const float* gradDa, float* gradAttr,
                                  float* gradRast, float* gradDb);

// nvdiffrast's texture sampling (texture(), texture_construct_mip()).
enum class TextureFilter { Nearest, Linear, LinearMipmapNearest, LinearMipmapLinear };
enum class TextureBoundary { Wrap, Clamp, Zero };

// A texture call: batch output pixels (uv 2 floats, uvDa 4 floats and bias
// 1 float per pixel, the last two when hasUvDa, hasBias) sampling texImages
// (1 or batch.images) textures of texHeight × texWidth × channels floats,
// row 0 at v = 0. Mip level k is max(1, size >> k) on each side, each texel
// the mean of its 2×2 children (2 where a side is 1); the pyramid stops
// before a level whose parent has an odd side above 1, at level 1 ×
// 1, or at maxMipLevel (-1: no bound). The level of a pixel is nvdiffrast's
// (the footprint's major axis from uvDa, plus bias).
struct TextureSpec {
  ImageBatch batch;
  size_t texImages = 1;
  uint32_t texWidth = 0, texHeight = 0, channels = 0;
  TextureFilter filter = TextureFilter::Linear;
  TextureBoundary boundary = TextureBoundary::Wrap;
  int maxMipLevel = -1;
  bool hasUvDa = false, hasBias = false;
};

// The deepest mip level a call uses (0 for nearest and linear).
CLRASTER_API uint32_t textureMaxLevel(const TextureSpec& spec);
// Floats of mip levels 1..textureMaxLevel (all texture images), as
// textureMips writes them, level after level.
CLRASTER_API size_t textureMipFloats(const TextureSpec& spec);
CLRASTER_API void textureMips(Context& ctx, const TextureSpec& spec, const float* tex, float* mips);
// out: channels floats per pixel. mips: levels from textureMips (or null:
// built from tex on the device).
CLRASTER_API void texture(Context& ctx, const TextureSpec& spec, const float* tex, const float* mips, const float* uv,
                          const float* uvDa, const float* bias, float* out);
// Gradients of texture(): gradTex has tex's shape (every level's share
// pushed down to tex unless mips came from the caller: then only level 0's
// share); gradUvDa, gradBias only with hasUvDa, hasBias.
CLRASTER_API void textureGrad(Context& ctx, const TextureSpec& spec, const float* tex, const float* mips,
                              const float* uv, const float* uvDa, const float* bias, const float* gradOut,
                              float* gradTex, float* gradUv, float* gradUvDa, float* gradBias);

// nvdiffrast's analytic antialias (Laine et al. 2020): colour (channels
// floats per pixel of batch) blended across the silhouette edges of the
// mesh rasterized into rast, into out. pos: posImages × numVertices × 4
// (posImages 1 or batch.images); opp: per triangle, for each vertex i the
// vertex across the edge opposite it, or −1 on a boundary
// (antialiasTopology).
CLRASTER_API void antialias(Context& ctx, const float* color, uint32_t channels, const float* rast,
                            const ImageBatch& batch, const float* pos, size_t numVertices, size_t posImages,
                            const int32_t* tri, const int32_t* opp, size_t numTriangles, float* out);
// Its gradients to colour and (times posBoost) to pos.
CLRASTER_API void antialiasGrad(Context& ctx, const float* color, uint32_t channels, const float* rast,
                                const ImageBatch& batch, const float* pos, size_t numVertices, size_t posImages,
                                const int32_t* tri, const int32_t* opp, size_t numTriangles, const float* gradOut,
                                float posBoost, float* gradColor, float* gradPos);
// opp (3 · numTriangles) for tri: the vertex across each edge when exactly
// one other triangle shares it (else −1: a boundary, or a non-manifold
// edge, counted as a silhouette).
CLRASTER_API std::vector<int32_t> antialiasTopology(const int32_t* tri, size_t numTriangles, size_t numVertices);

// nvdiffrast's instanced and range mode: a batch of images rasterized in
// one frame (images stacked, each a tile multiple of rows apart; batches
// beyond CLR_MAX_VIEWPORT rows or 2^19 pixels, or the memory check, split
// into several frames), each image bit for bit as rasterizeInto writes it
// alone.
// Instanced (ranges null): pos posImages × numVertices × 4, every image
// draws all of tri, ids 1..numTriangles. Range mode (posImages 1): ranges
// numRanges (start, count) pairs, image k draws tri[start, start + count),
// ids absolute (start + index + 1). rast, db: images × height × width × 4
// floats (db may be null).
CLRASTER_API void rasterizeBatch(Context& ctx, const float* pos, size_t numVertices, size_t posImages,
                                 const int32_t* tri, size_t numTriangles, const int32_t* ranges, size_t numRanges,
                                 uint32_t width, uint32_t height, float* rast, float* db);

// One layer of depth peeling (nvdiffrast's DepthPeeler) of a batch, with
// rasterizeBatch's arguments and frames: each image as rasterizeInto writes
// it (the same coverage, ids and outputs), but each pixel takes the nearest
// fragment strictly behind floorDepth (images × height × width window
// depths, z/w · 0.5 + 0.5; −inf for the first layer, which equals
// rasterize's). nextFloor receives this layer's window depths (+inf where
// nothing is left): the floor of the next layer. db may be null.
CLRASTER_API void rasterizePeel(Context& ctx, const float* pos, size_t numVertices, size_t posImages,
                                const int32_t* tri, size_t numTriangles, const int32_t* ranges, size_t numRanges,
                                uint32_t width, uint32_t height, const float* floorDepth, float* rast, float* db,
                                float* nextFloor);

}  // namespace clraster
