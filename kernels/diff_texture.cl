/* diff_texture.cl — nvdiffrast's texture operation, forward and backward
 * (host/pipeline/diff.cpp; python/clraster/torch.py).
 *
 * A texture is a mip pyramid in one buffer: level k of every texture image
 * (texImages of them) at levelOffset[k], sizes levelW[k] × levelH[k] ×
 * channels, row 0 at v = 0. Texel (i, j) of a level has its centre at
 * u = (i + 0.5) / w. One work-item per output pixel (B · H · W, image-major;
 * texture image b, or 0 when texImages is 1).
 *  - Filters (TexFilter): nearest (level 0), linear (bilinear on level 0),
 *    linear-mipmap-nearest and linear-mipmap-linear: the level is
 *    0.5 · log2 of the major axis² of the footprint from uv_da (nvdiffrast:
 *    (A + B) / 2 + sqrt((A − B)² / 4 + C²) in texels of level 0) plus
 *    mip_level_bias, clamped to 0..maxLevel; -nearest takes its floor,
 *    -linear blends floor and floor + 1 by the fraction.
 *  - Boundaries (TexBoundary): wrap (u − floor(u)), clamp (to the edge
 *    texels' centres, with zero gradient there), zero (texels outside read
 *    0).
 * texture_grad adds, with float atomics, d L / d texel to every level it
 * read and writes d L / d uv, d uv_da and d bias per pixel; mip_grad_down
 * then pushes one level's texel gradients to the level below (each parent
 * texel is the mean of its 2×2, or 2, children: mip_build).
 */
#pragma OPENCL FP_CONTRACT OFF
#if CLR_EXTRAS /* the extras program (CLR_EXTRAS, shared.h) */

#define TEX_NEAREST 0u
#define TEX_LINEAR 1u
#define TEX_LINEAR_MIPMAP_NEAREST 2u
#define TEX_LINEAR_MIPMAP_LINEAR 3u
#define TEX_WRAP 0u
#define TEX_CLAMP 1u
#define TEX_ZERO 2u

typedef struct TexParams {
  uint filter, boundary, channels, texImages;
  uint width, height, numPixels, maxLevel;  // output image size, B·H·W, deepest level used
  uint hasUvDa, hasBias, pad0, pad1;
} TexParams;

/* The four texel addresses (−1: reads zero) and bilinear fractions of uv on one level. */
CLR_INLINE float2 tex_quad(const TexParams* p, float2 uv, uint image, __global const int* levelInfo, uint level,
                           int4* tc)
{
  const int w = levelInfo[3 * level + 1], h = levelInfo[3 * level + 2];
  if (!isfinite(uv.x) || !isfinite(uv.y)) {  // reads nothing (zero), with zero gradients
    *tc = (int4)(-1);
    return (float2)(0.0f);
  }
  // Far outside the texture every mode reads what it reads at 2^20 texels out; the integer conversions stay defined.
  float u = clamp(uv.x, -1048576.0f, 1048576.0f), v = clamp(uv.y, -1048576.0f, 1048576.0f);
  if (p->boundary == TEX_WRAP) {
    u -= floor(u);
    v -= floor(v);
  }
  u = u * (float)w - 0.5f;
  v = v * (float)h - 0.5f;
  bool clampU = false, clampV = false;
  if (p->boundary == TEX_CLAMP) {
    u = fmin(fmax(u, 0.0f), (float)w - 1.0f);
    v = fmin(fmax(v, 0.0f), (float)h - 1.0f);
    clampU = u == 0.0f || u == (float)w - 1.0f;
    clampV = v == 0.0f || v == (float)h - 1.0f;
  }
  int iu0 = (int)floor(u), iv0 = (int)floor(v);
  int iu1 = iu0 + (clampU ? 0 : 1), iv1 = iv0 + (clampV ? 0 : 1);
  const float2 f = (float2)(u - (float)iu0, v - (float)iv0);
  if (p->boundary == TEX_WRAP) {
    iu0 = iu0 < 0 ? iu0 + w : iu0;
    iv0 = iv0 < 0 ? iv0 + h : iv0;
    iu1 = iu1 >= w ? iu1 - w : iu1;
    iv1 = iv1 >= h ? iv1 - h : iv1;
  }
  const bool out0 = iu0 < 0 || iu0 >= w, out1 = iu1 < 0 || iu1 >= w;
  const bool outV0 = iv0 < 0 || iv0 >= h, outV1 = iv1 < 0 || iv1 >= h;
  const int base = levelInfo[3 * level] + (int)(image * (uint)(w * h));
  // Beyond the texture only in zero mode (wrap and clamp stay inside), where such texels read 0.
  (*tc).x = out0 || outV0 ? -1 : base + iv0 * w + iu0;
  (*tc).y = out1 || outV0 ? -1 : base + iv0 * w + iu1;
  (*tc).z = out0 || outV1 ? -1 : base + iv1 * w + iu0;
  (*tc).w = out1 || outV1 ? -1 : base + iv1 * w + iu1;
  return f;
}

CLR_INLINE float tex_fetch(__global const float* tex, int t, uint channels, uint c)
{
  return t < 0 ? 0.0f : tex[(size_t)t * channels + c];
}

/* The bilinear value of quad t (fractions f) in channel c. */
CLR_INLINE float tex_quad_value(__global const float* tex, int4 t, float2 f, uint nc, uint c)
{
  return mix(mix(tex_fetch(tex, t.x, nc, c), tex_fetch(tex, t.y, nc, c), f.x),
             mix(tex_fetch(tex, t.z, nc, c), tex_fetch(tex, t.w, nc, c), f.x), f.y);
}

/* The pixel's level (before its floor) and d level / d uv_da, d level / d bias (0 where clamped). */
CLR_INLINE float tex_level(const TexParams* p, __global const int* levelInfo, __global const float4* uvDa,
                           __global const float* bias, uint pixel, float4* dLevelDa, float* dLevelBias)
{
  float level = 0.0f;
  *dLevelDa = (float4)(0.0f);
  if (p->hasUvDa) {
    const float us = (float)levelInfo[1], vs = (float)levelInfo[2];
    const float4 d = uvDa[pixel];
    const float dsdx = d.x * us, dsdy = d.y * us, dtdx = d.z * vs, dtdy = d.w * vs;
    const float A = dsdx * dsdx + dtdx * dtdx, B = dsdy * dsdy + dtdy * dtdy, C = dsdx * dsdy + dtdx * dtdy;
    const float l2b = 0.5f * (A + B), l2n = 0.25f * (A - B) * (A - B) + C * C, l2a = sqrt(l2n);
    level = 0.5f * log2(l2b + l2a);
    // d level / d (ds/dX, ds/dY, dt/dX, dt/dY) = (0.5 / ln 2) · d(l2b + l2a) / (l2b + l2a), times the texel scale.
    const float k = 0.72134752f / (l2n + l2a * l2b), ab = 0.5f * (A - B);
    const float4 g = k * (float4)(us * (dsdx * (l2a + ab) + dsdy * C), us * (dsdy * (l2a - ab) + dsdx * C),
                                  vs * (dtdx * (l2a + ab) + dtdy * C), vs * (dtdy * (l2a - ab) + dtdx * C));
    *dLevelDa = all(isfinite(g)) ? g : (float4)(0.0f);
  }
  if (p->hasBias) level += bias[pixel];
  const bool inside = level > 0.0f && level < (float)p->maxLevel;
  *dLevelBias = inside ? 1.0f : 0.0f;
  if (!inside) *dLevelDa = (float4)(0.0f);
  return fmin(fmax(level, 0.0f), (float)p->maxLevel);  // NaN → 0 (fmax)
}

__kernel void texture_fwd(TexParams params, __global const float* tex, __global const int* levelInfo,
                          __global const float2* uv, __global const float4* uvDa, __global const float* bias,
                          __global float* out)
{
  const uint p = get_global_id(0);
  if (p >= params.numPixels) return;
  const uint image = params.texImages == 1u ? 0u : p / (params.width * params.height);
  const uint nc = params.channels;
  __global float* o = out + (size_t)p * nc;
  if (params.filter == TEX_NEAREST) {
    int4 tc;
    tex_quad(&params, uv[p] + (float2)(0.5f / (float)levelInfo[1], 0.5f / (float)levelInfo[2]), image, levelInfo, 0u,
             &tc);
    for (uint c = 0; c < nc; ++c) o[c] = tex_fetch(tex, tc.x, nc, c);
    return;
  }
  float4 dDa;
  float dBias, level = 0.0f;
  if (params.filter != TEX_LINEAR) level = tex_level(&params, levelInfo, uvDa, bias, p, &dDa, &dBias);
  const uint l0 = (uint)floor(level);
  const float frac = params.filter == TEX_LINEAR_MIPMAP_LINEAR ? level - (float)l0 : 0.0f;
  const uint l1 = min(l0 + 1u, params.maxLevel);
  int4 t0, t1 = (int4)(-1);
  const float2 f0 = tex_quad(&params, uv[p], image, levelInfo, l0, &t0);
  const float2 f1 = frac > 0.0f ? tex_quad(&params, uv[p], image, levelInfo, l1, &t1) : (float2)(0.0f);
  for (uint c = 0; c < nc; ++c) {
    const float a = tex_quad_value(tex, t0, f0, nc, c);
    o[c] = frac > 0.0f ? mix(a, tex_quad_value(tex, t1, f1, nc, c), frac) : a;
  }
}

/* *p += v (diff.cl's compare-and-swap add; the two files share the extras program). */
CLR_INLINE void tex_add(__global float* grad, int t, uint channels, uint c, float v)
{
  if (t >= 0) diff_atomic_add(grad + (size_t)t * channels + c, v);
}

/* One level's bilinear quad t (fractions f) in the backward pass for channel c with weight w (the channel's
 * gradient times the level's share): its texels' gradients, and the uv gradient scaled by the level's size.
 * Returns the quad's value (tex_quad_value, from the texels fetched here). */
CLR_INLINE float tex_quad_grad(__global float* gradTex, __global const float* tex, __global const int* levelInfo,
                               uint level, int4 t, float2 f, uint nc, uint c, float w, float2* guv)
{
  const float a00 = tex_fetch(tex, t.x, nc, c), a10 = tex_fetch(tex, t.y, nc, c);
  const float a01 = tex_fetch(tex, t.z, nc, c), a11 = tex_fetch(tex, t.w, nc, c);
  tex_add(gradTex, t.x, nc, c, w * (1.0f - f.x) * (1.0f - f.y));
  tex_add(gradTex, t.y, nc, c, w * f.x * (1.0f - f.y));
  tex_add(gradTex, t.z, nc, c, w * (1.0f - f.x) * f.y);
  tex_add(gradTex, t.w, nc, c, w * f.x * f.y);
  guv->x += w * ((a10 - a00) * (1.0f - f.y) + (a11 - a01) * f.y) * (float)levelInfo[3 * level + 1];
  guv->y += w * ((a01 - a00) * (1.0f - f.x) + (a11 - a10) * f.x) * (float)levelInfo[3 * level + 2];
  return mix(mix(a00, a10, f.x), mix(a01, a11, f.x), f.y);
}

__kernel void texture_grad(TexParams params, __global const float* tex, __global const int* levelInfo,
                           __global const float2* uv, __global const float4* uvDa, __global const float* bias,
                           __global const float* gradOut,  // numPixels · channels
                           __global float* gradTex,        // tex's layout, zeroed
                           __global float2* gradUv, __global float4* gradUvDa, __global float* gradBias)
{
  const uint p = get_global_id(0);
  if (p >= params.numPixels) return;
  const uint image = params.texImages == 1u ? 0u : p / (params.width * params.height);
  const uint nc = params.channels;
  __global const float* g = gradOut + (size_t)p * nc;
  gradUv[p] = (float2)(0.0f);
  if (params.hasUvDa) gradUvDa[p] = (float4)(0.0f);
  if (params.hasBias) gradBias[p] = 0.0f;
  if (params.filter == TEX_NEAREST) {
    int4 tc;
    tex_quad(&params, uv[p] + (float2)(0.5f / (float)levelInfo[1], 0.5f / (float)levelInfo[2]), image, levelInfo, 0u,
             &tc);
    for (uint c = 0; c < nc; ++c) tex_add(gradTex, tc.x, nc, c, g[c]);
    return;
  }
  float4 dDa = (float4)(0.0f);
  float dBias = 0.0f, level = 0.0f;
  if (params.filter != TEX_LINEAR) level = tex_level(&params, levelInfo, uvDa, bias, p, &dDa, &dBias);
  const uint l0 = (uint)floor(level);
  const float frac = params.filter == TEX_LINEAR_MIPMAP_LINEAR ? level - (float)l0 : 0.0f;
  const uint l1 = min(l0 + 1u, params.maxLevel);
  int4 t0, t1;
  float2 guv = (float2)(0.0f);
  const float2 f0 = tex_quad(&params, uv[p], image, levelInfo, l0, &t0);
  // Level l0 with weight 1 − frac, level l1 with frac; the channels are strided by nc in the texture.
  for (uint c = 0; c < nc; ++c) tex_quad_grad(gradTex, tex, levelInfo, l0, t0, f0, nc, c, g[c] * (1.0f - frac), &guv);
  float gLevel = 0.0f;
  if (frac > 0.0f) {
    const float2 f1 = tex_quad(&params, uv[p], image, levelInfo, l1, &t1);
    for (uint c = 0; c < nc; ++c) {
      const float b = tex_quad_grad(gradTex, tex, levelInfo, l1, t1, f1, nc, c, g[c] * frac, &guv);
      gLevel += g[c] * (b - tex_quad_value(tex, t0, f0, nc, c));
    }
  }
  // Clamped boundaries give the clamped axis zero gradient (the quad collapsed onto one texel column or row).
  gradUv[p] = guv;
  if (params.hasUvDa) gradUvDa[p] = gLevel * dDa;
  if (params.hasBias) gradBias[p] = gLevel * dBias;
}

/* Level `level` (≥ 1) from level − 1: each texel the mean of its 2×2 children (2 when a side is 1). */
__kernel void mip_build(__global float* tex, __global const int* levelInfo, uint level, uint channels, uint texImages)
{
  const uint t = get_global_id(0);
  const int w = levelInfo[3 * level + 1], h = levelInfo[3 * level + 2];
  const int pw = levelInfo[3 * level - 2], ph = levelInfo[3 * level - 1];
  if (t >= (uint)(w * h) * texImages) return;
  const int image = (int)t / (w * h), x = (int)t % (w * h) % w, y = (int)t % (w * h) / w;
  const int base = levelInfo[3 * level - 3] + image * pw * ph;
  const int x0 = pw == 1 ? 0 : 2 * x, x1 = pw == 1 ? 0 : 2 * x + 1;
  const int y0 = ph == 1 ? 0 : 2 * y, y1 = ph == 1 ? 0 : 2 * y + 1;
  const float k = (pw == 1 || ph == 1) ? 0.5f : 0.25f;
  const int c00 = base + y0 * pw + x0, c10 = base + y0 * pw + x1, c01 = base + y1 * pw + x0, c11 = base + y1 * pw + x1;
  __global float* o = tex + ((size_t)levelInfo[3 * level] + t) * channels;
  for (uint c = 0; c < channels; ++c) {
    const float s = pw == 1 || ph == 1 ? tex[(size_t)c00 * channels + c] + tex[(size_t)c11 * channels + c]
                                       : tex[(size_t)c00 * channels + c] + tex[(size_t)c10 * channels + c] +
                                             tex[(size_t)c01 * channels + c] + tex[(size_t)c11 * channels + c];
    o[c] = k * s;
  }
}

/* The transpose of mip_build: level − 1's texels gain their parent's gradient × 1/4 (1/2). */
__kernel void mip_grad_down(__global float* grad, __global const int* levelInfo, uint level, uint channels,
                            uint texImages)
{
  const uint t = get_global_id(0);
  const int w = levelInfo[3 * level + 1], h = levelInfo[3 * level + 2];
  const int pw = levelInfo[3 * level - 2], ph = levelInfo[3 * level - 1];
  if (t >= (uint)(pw * ph) * texImages) return;
  const int image = (int)t / (pw * ph), x = (int)t % (pw * ph) % pw, y = (int)t % (pw * ph) / pw;
  const int px = pw == 1 ? 0 : x / 2, py = ph == 1 ? 0 : y / 2;
  const float k = (pw == 1 || ph == 1) ? 0.5f : 0.25f;
  const size_t parent = (size_t)levelInfo[3 * level] + (size_t)image * w * h + (size_t)py * w + px;
  __global float* o = grad + ((size_t)levelInfo[3 * level - 3] + t) * channels;
  for (uint c = 0; c < channels; ++c) o[c] += k * grad[parent * channels + c];
}
#endif
