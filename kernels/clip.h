/* clip.h — stage 2: homogeneous clipping (helpers included by setup.cl).
 *
 * Culled: a non-finite clip coordinate, or all three vertices outside one viewport plane or the near plane.
 * Clipped (Sutherland–Hodgman in homogeneous space, never dividing by w <= 0): a vertex behind the near plane or
 * outside the guard band (|x| > g_x·w, |y| > g_y·w, fixed.h). Near is z >= −w (GL), z <= w with CLR_DEPTH_REVERSED;
 * far is not clipped (the depth test drops it). Crossings go from the inside vertex outwards, so a shared edge is cut
 * at the same point from both sides (no seams), and land exactly on the plane, finite for any finite vertices
 * (docs/limits.md).
 */
#ifndef CLR_CLIP_H
#define CLR_CLIP_H
#include "transform.h"
#pragma OPENCL FP_CONTRACT OFF

/* A polygon vertex during clipping: clip position and barycentrics in the input triangle. */
typedef struct ClipVertex {
  float4 pos;
  float3 bary;
} ClipVertex;

/* The sign of z in the near plane's distance: z + w (GL), w − z (reversed). */
CLR_INLINE float clip_near_sign(uint depthMode)
{
  return depthMode == CLR_DEPTH_REVERSED ? -1.0f : 1.0f;
}

/* Signed distance to `plane` (>= 0 inside): 0 near, 1-4 guard band left, right, bottom, top. ×nearSign is exact. */
CLR_INLINE float clip_distance(float4 c, int plane, float gx, float gy, float nearSign)
{
  switch (plane) {
    case 0: return nearSign * c.z + c.w;
    case 1: return c.x + gx * c.w;
    case 2: return gx * c.w - c.x;
    case 3: return c.y + gy * c.w;
    default: return gy * c.w - c.y;
  }
}

/* Outcode bits: 0-4 clip_distance < 0; 5-8 x < −w, x > w, y < −w, y > w; 9 beyond far (z > w, reversed z < 0). */
CLR_INLINE uint clip_outcode(float4 c, float gx, float gy, float nearSign)
{
  // Branch- and loop-free (clip_distance's expressions), so setup's common path stays vectorisable.
  const bool beyondFar = nearSign < 0.0f ? c.z < 0.0f : c.z > c.w;
  return (nearSign * c.z + c.w < 0.0f ? 1u : 0u) | (c.x + gx * c.w < 0.0f ? 2u : 0u) |
         (gx * c.w - c.x < 0.0f ? 4u : 0u) | (c.y + gy * c.w < 0.0f ? 8u : 0u) | (gy * c.w - c.y < 0.0f ? 16u : 0u) |
         (c.x < -c.w ? 32u : 0u) | (c.x > c.w ? 64u : 0u) | (c.y < -c.w ? 128u : 0u) | (c.y > c.w ? 256u : 0u) |
         (beyondFar ? 512u : 0u);
}

/* The point where edge a→b crosses `plane`, computed from the inside end. */
CLR_INLINE void clip_intersect(const ClipVertex* inside, const ClipVertex* outside, int plane, float gx, float gy,
                               float nearSign, ClipVertex* out)
{
  // Step 1: the crossing; near FLT_MAX a difference overflows, so halve (exact: same result where both work).
  const float dIn = clip_distance(inside->pos, plane, gx, gy, nearSign);
  const float dOut = clip_distance(outside->pos, plane, gx, gy, nearSign);
  const float denom = dIn - dOut;
  const float t = isfinite(denom) ? dIn / denom : (0.5f * dIn) / (0.5f * dIn - 0.5f * dOut);
  const float4 d = outside->pos - inside->pos;
  out->pos = all(isfinite(d)) ? inside->pos + t * d
                              : 2.0f * (0.5f * inside->pos + t * (0.5f * outside->pos - 0.5f * inside->pos));
  out->bary = inside->bary + t * (outside->bary - inside->bary);
  // Step 2: exactly on the plane: interpolation rounds by |coordinate|·2^-24, more than the band for huge vertices.
  switch (plane) {
    case 0: out->pos.z = -nearSign * out->pos.w; break;
    case 1: out->pos.x = -(gx * out->pos.w); break;
    case 2: out->pos.x = gx * out->pos.w; break;
    case 3: out->pos.y = -(gy * out->pos.w); break;
    default: out->pos.y = gy * out->pos.w; break;
  }
}

/* Clips poly[0..n) against the planes in `planeMask` in place; returns the new vertex count (0: nothing left). */
CLR_INLINE int clip_polygon(ClipVertex* poly, int n, uint planeMask, float gx, float gy, float nearSign)
{
  ClipVertex scratch[CLR_MAX_CLIP_VERTS];
  for (int plane = 0; plane < 5; ++plane) {
    if (!(planeMask & (1u << plane)) || n == 0) continue;
    // Step 1: walk the edges, keeping inside vertices and crossings.
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const ClipVertex a = poly[i];
      const ClipVertex b = poly[(i + 1) % n];
      const bool aIn = clip_distance(a.pos, plane, gx, gy, nearSign) >= 0.0f;
      const bool bIn = clip_distance(b.pos, plane, gx, gy, nearSign) >= 0.0f;
      if (aIn) scratch[m++] = a;
      if (aIn != bIn) {
        if (aIn)
          clip_intersect(&a, &b, plane, gx, gy, nearSign, &scratch[m]);
        else
          clip_intersect(&b, &a, plane, gx, gy, nearSign, &scratch[m]);
        ++m;
      }
    }
    // Step 2: copy back for the next plane.
    for (int i = 0; i < m; ++i) poly[i] = scratch[i];
    n = m;
  }
  return n;
}

#endif /* CLR_CLIP_H */
