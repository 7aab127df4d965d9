/* texture.cl — base-colour texture sampling for resolve (one lane at a time).
 *
 * Textures live in one texel buffer described by TextureDesc records
 * (shared.h, filled by host/texture.cpp): RGBA8, rows bottom first, so a
 * texture coordinate (u, v) maps to texel space (u·w, v·h) of a level of
 * w × h texels, texel (i, j) centred at (i + 0.5, j + 0.5). Integer texel
 * indices wrap per axis as the file says: repeat (i mod n), clamp to
 * [0, n − 1], or mirror (period 2n, the second half reversed).
 *   nearest:   the texel containing (u·w, v·h) of level 0
 *   bilinear:  the four texels around (u·w − 0.5, v·h − 0.5) of level 0,
 *              weighted by the fractional parts
 *   trilinear: bilinear in levels ⌊λ⌋ and ⌊λ⌋ + 1, mixed by λ − ⌊λ⌋, with
 *              λ = log2 ρ clamped to [0, levels − 1] and
 *              ρ = max(|(∂u/∂x·w, ∂v/∂x·h)|, |(∂u/∂y·w, ∂v/∂y·h)|)
 *              from the screen-space derivatives resolve computes (w, h of
 *              level 0). Level l is max(1, w >> l) × max(1, h >> l).
 * Texel values are returned in [0, 1] as stored (no sRGB decoding), t / 255
 * correctly rounded, so an 8-bit texel written back unchanged is exact.
 * Texel coordinates are clamped to ±2^24 first, so NaN or huge (u, v) stay
 * inside the texture. OpenCL only (follows lanes.h).
 */
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
#endif
