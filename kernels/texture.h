/* texture.h — base-colour sampling for resolve: per lane (tex_sample) or a row's lanes on one texture in lane
 * types (tex_sample_lanes), with the same floats. OpenCL only (after lanes.h).
 *
 * Texels: one buffer described by TextureDesc (shared.h), RGBA8, rows bottom first; (u, v) maps to (u·w, v·h) of a
 * w × h level, texel (i, j) centred at (i + 0.5, j + 0.5); indices wrap per axis: repeat, clamp, mirror (period 2n).
 *   nearest:   the level-0 texel containing (u·w, v·h)
 *   bilinear:  the four level-0 texels around (u·w − 0.5, v·h − 0.5), weighted by the fractional parts
 *   trilinear: bilinear in levels ⌊λ⌋, ⌊λ⌋ + 1 mixed by λ − ⌊λ⌋; λ = log2 ρ clamped to [0, levels − 1],
 *              ρ = max(|(∂u/∂x·w, ∂v/∂x·h)|, |(∂u/∂y·w, ∂v/∂y·h)|) from resolve's screen derivatives (level 0)
 * Values are t / 255 correctly rounded (no sRGB decoding), so an 8-bit texel round-trips exactly. Texel
 * coordinates are clamped to ±2^24 first, so NaN or huge (u, v) stay inside the texture.
 */
#ifndef CLR_TEXTURE_H
#define CLR_TEXTURE_H
#pragma OPENCL FP_CONTRACT OFF
#if !CLR_EXTRAS /* the frame program (CLR_EXTRAS, shared.h) */

CLR_INLINE int tex_wrap(int i, int n, uint mode)
{
  if (mode == CLR_WRAP_CLAMP) return clamp(i, 0, n - 1);
  if (mode == CLR_WRAP_MIRROR) {
    const int period = 2 * n;
    int m = i % period;
    m = m < 0 ? m + period : m;
    return m < n ? m : period - 1 - m;
  }
  const int m = i % n;
  return m < 0 ? m + n : m;
}

CLR_INLINE float4 tex_fetch(__global const uint* texels, uint offset, uint width, int x, int y)
{
  const uint t = texels[offset + (uint)y * width + (uint)x];
  return (float4)((float)(t & 0xFFu), (float)((t >> 8) & 0xFFu), (float)((t >> 16) & 0xFFu), (float)(t >> 24)) / 255.0f;
}

/* Texel-space coordinate, finite and bounded. */
CLR_INLINE float tex_coord(float t, uint size)
{
  return fmin(fmax(t * (float)size, -16777216.0f), 16777216.0f);
}

CLR_INLINE float4 tex_nearest(__global const TextureDesc* d, __global const uint* texels, float u, float v)
{
  const int w = (int)d->width, h = (int)d->height;
  const int x = tex_wrap((int)floor(tex_coord(u, d->width)), w, d->wrapS);
  const int y = tex_wrap((int)floor(tex_coord(v, d->height)), h, d->wrapT);
  return tex_fetch(texels, d->levelOffset[0], d->width, x, y);
}

CLR_INLINE float4 tex_bilinear(__global const TextureDesc* d, __global const uint* texels, uint level, float u, float v)
{
  // Step 1: the level's size and the four texels around the point.
  const uint w = max(1u, d->width >> level), h = max(1u, d->height >> level);
  const float fx = tex_coord(u, w) - 0.5f, fy = tex_coord(v, h) - 0.5f;
  const float x0f = floor(fx), y0f = floor(fy);
  const float ax = fx - x0f, ay = fy - y0f;
  const int x0 = tex_wrap((int)x0f, (int)w, d->wrapS), x1 = tex_wrap((int)x0f + 1, (int)w, d->wrapS);
  const int y0 = tex_wrap((int)y0f, (int)h, d->wrapT), y1 = tex_wrap((int)y0f + 1, (int)h, d->wrapT);
  const uint offset = d->levelOffset[level];
  // Step 2: weights from the fractional parts.
  const float4 bottom = tex_fetch(texels, offset, w, x0, y0) * (1.0f - ax) + tex_fetch(texels, offset, w, x1, y0) * ax;
  const float4 top = tex_fetch(texels, offset, w, x0, y1) * (1.0f - ax) + tex_fetch(texels, offset, w, x1, y1) * ax;
  return bottom * (1.0f - ay) + top * ay;
}

/* The level of detail λ from the screen-space derivatives of (u, v). */
CLR_INLINE float tex_lod(__global const TextureDesc* d, float dudx, float dvdx, float dudy, float dvdy)
{
  const float w = (float)d->width, h = (float)d->height;
  const float ax = dudx * w, bx = dvdx * h, ay = dudy * w, by = dvdy * h;
  const float rho2 = fmax(ax * ax + bx * bx, ay * ay + by * by);
  const float lambda = 0.5f * log2(rho2);  // log2 ρ; −inf for ρ = 0, NaN for NaN
  return fmin(fmax(lambda, 0.0f), (float)(d->levels - 1));
}

CLR_CALLED float4 tex_sample(__global const TextureDesc* d, __global const uint* texels, uint filter, float u, float v,
                             float dudx, float dvdx, float dudy, float dvdy)
{
  if (filter == CLR_FILTER_NEAREST) return tex_nearest(d, texels, u, v);
  if (filter == CLR_FILTER_BILINEAR) return tex_bilinear(d, texels, 0, u, v);
  const float lambda = tex_lod(d, dudx, dvdx, dudy, dvdy);
  const uint l0 = (uint)lambda, l1 = min(l0 + 1, d->levels - 1);
  const float t = lambda - (float)l0;
  const float4 a = tex_bilinear(d, texels, l0, u, v);
  return t > 0.0f ? a * (1.0f - t) + tex_bilinear(d, texels, l1, u, v) * t : a;
}

/* tex_wrap in lane types without integer division (no vector unit has it): i mod p from a float quotient, off by
 * at most one period (rounding; i above 2^24), then corrected. The clamped corner i = 2^24 + 1 needs it: weight 0,
 * but its load must stay in the level. */
CLR_INLINE intL tex_wrap_lanes(intL i, intL n, uint mode)
{
  if (mode == CLR_WRAP_CLAMP) return clamp(i, (intL)0, n - 1);
  const intL period = mode == CLR_WRAP_MIRROR ? 2 * n : n;
  intL m = i - convert_intL(floor(convert_floatL(i) / convert_floatL(period))) * period;
  m = select(m, m + period, m < 0);
  m = select(m, m - period, m >= period);
  return mode == CLR_WRAP_MIRROR ? select(m, period - 1 - m, m >= n) : m;
}

/* The lanes' texels (x, y) of the level at `offset` of `width` (per lane), RGB in [0, 1] as tex_fetch converts.
 * Lane functions return through arrays: an inlined struct return leaves an intrinsic Oclgrind cannot run. */
CLR_INLINE void tex_fetch_lanes(__global const uint* texels, uintL offset, uintL width, intL x, intL y, floatL rgb[3])
{
  uint at[CLR_LANES], value[CLR_LANES];
  CLR_STORE_LANES(offset + as_uintL(y) * width + as_uintL(x), at);
  for (uint lane = 0; lane < CLR_LANES; ++lane) value[lane] = texels[at[lane]];
  const uintL t = CLR_LOAD_LANES(value);
  for (int k = 0; k < 3; ++k) rgb[k] = convert_floatL((t >> (8 * k)) & 0xFFu) / 255.0f;
}

/* tex_coord in lane types. */
CLR_INLINE floatL tex_coord_lanes(floatL t, uintL size)
{
  return fmin(fmax(t * convert_floatL(size), -16777216.0f), 16777216.0f);
}

/* a · (1 − t) + b · t per channel into out, as tex_bilinear and tex_sample weigh (out may be a). */
CLR_INLINE void tex_mix_lanes(const floatL a[3], const floatL b[3], floatL t, floatL out[3])
{
  for (int k = 0; k < 3; ++k) out[k] = a[k] * (1.0f - t) + b[k] * t;
}

/* tex_bilinear in lane types, each lane at its own level. */
CLR_INLINE void tex_bilinear_lanes(__global const TextureDesc* d, __global const uint* texels, uintL level, floatL u,
                                   floatL v, floatL rgb[3])
{
  // Step 1: the levels' sizes and offsets, and the four texels around the point.
  const uintL w = max((uintL)1u, (uintL)d->width >> level), h = max((uintL)1u, (uintL)d->height >> level);
  uint lanesLevel[CLR_LANES], offsets[CLR_LANES];
  CLR_STORE_LANES(level, lanesLevel);
  for (uint lane = 0; lane < CLR_LANES; ++lane) offsets[lane] = d->levelOffset[lanesLevel[lane]];
  const uintL offset = CLR_LOAD_LANES(offsets);
  const floatL fx = tex_coord_lanes(u, w) - 0.5f, fy = tex_coord_lanes(v, h) - 0.5f;
  const floatL x0f = floor(fx), y0f = floor(fy);
  const floatL ax = fx - x0f, ay = fy - y0f;
  const intL xi = convert_intL(x0f), yi = convert_intL(y0f);
  const intL x0 = tex_wrap_lanes(xi, as_intL(w), d->wrapS), x1 = tex_wrap_lanes(xi + 1, as_intL(w), d->wrapS);
  const intL y0 = tex_wrap_lanes(yi, as_intL(h), d->wrapT), y1 = tex_wrap_lanes(yi + 1, as_intL(h), d->wrapT);
  // Step 2: weights from the fractional parts.
  floatL bottom[3], top[3], corner[3];
  tex_fetch_lanes(texels, offset, w, x0, y0, bottom);
  tex_fetch_lanes(texels, offset, w, x1, y0, corner);
  tex_mix_lanes(bottom, corner, ax, bottom);
  tex_fetch_lanes(texels, offset, w, x0, y1, top);
  tex_fetch_lanes(texels, offset, w, x1, y1, corner);
  tex_mix_lanes(top, corner, ax, top);
  tex_mix_lanes(bottom, top, ay, rgb);
}

/* tex_sample for a row's lanes on one texture, in lane types: the same floats (tested). The LOD's log2 stays
 * scalar, as tex_lod: a vector log2 need not round as the scalar one does. */
CLR_CALLED void tex_sample_lanes(__global const TextureDesc* d, __global const uint* texels, uint filter, floatL u,
                                 floatL v, floatL dudx, floatL dvdx, floatL dudy, floatL dvdy, floatL rgb[3])
{
  if (filter == CLR_FILTER_NEAREST) {
    const intL x =
        tex_wrap_lanes(convert_intL(floor(tex_coord_lanes(u, (uintL)d->width))), (intL)(int)d->width, d->wrapS);
    const intL y =
        tex_wrap_lanes(convert_intL(floor(tex_coord_lanes(v, (uintL)d->height))), (intL)(int)d->height, d->wrapT);
    tex_fetch_lanes(texels, (uintL)d->levelOffset[0], (uintL)d->width, x, y, rgb);
    return;
  }
  if (filter == CLR_FILTER_BILINEAR) {
    tex_bilinear_lanes(d, texels, (uintL)0u, u, v, rgb);
    return;
  }
  float x[4][CLR_LANES], lambda[CLR_LANES];
  CLR_STORE_LANES(dudx, x[0]);
  CLR_STORE_LANES(dvdx, x[1]);
  CLR_STORE_LANES(dudy, x[2]);
  CLR_STORE_LANES(dvdy, x[3]);
  for (uint lane = 0; lane < CLR_LANES; ++lane)
    lambda[lane] = tex_lod(d, x[0][lane], x[1][lane], x[2][lane], x[3][lane]);
  const floatL lod = CLR_LOAD_LANES(lambda);
  const uintL l0 = convert_uintL(lod), l1 = min(l0 + 1u, (uintL)(d->levels - 1));
  const floatL t = lod - convert_floatL(l0);
  tex_bilinear_lanes(d, texels, l0, u, v, rgb);
  if (!CLR_ANY(t > 0.0f)) return;
  floatL next[3], mixed[3];
  tex_bilinear_lanes(d, texels, l1, u, v, next);
  tex_mix_lanes(rgb, next, t, mixed);
  for (int k = 0; k < 3; ++k) rgb[k] = select(rgb[k], mixed[k], t > 0.0f);
}
#endif

#endif /* CLR_TEXTURE_H */
