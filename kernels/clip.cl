/* clip.cl — stage 2: homogeneous clipping (helpers used by setup.cl).
 *
 * Contract: a triangle with a non-finite clip coordinate, or with all three
 * vertices outside one viewport plane (or behind the near plane), is culled.
 * A triangle with a vertex behind the near plane or outside the
 * guard band (|x| > g_x·w, |y| > g_y·w, see fixed.h) is clipped in
 * homogeneous space by Sutherland–Hodgman, never divided by w <= 0. The near
 * plane follows the depth mode (shared.h): z >= −w is inside in the GL
 * convention (CLR_DEPTH_FLOAT32, CLR_DEPTH_UNORM24), z <= w with the
 * reversed projection of CLR_DEPTH_REVERSED. The far plane is not clipped:
 * fragments beyond it fail the depth test (GL LESS against a buffer cleared
 * to 1, or GREATER against 0 when reversed). Intersections are always computed from the
 * inside vertex towards the outside one, so an edge shared by two triangles
 * is cut at the same point from both sides (no seams); they are placed
 * exactly on the plane and stay finite for any finite vertices (provided
 * g·w does not overflow), so a triangle with vertices at 1e20 or 3e38 still
 * covers what it should (docs/limits.md).
 */
#pragma OPENCL FP_CONTRACT OFF

/* A polygon vertex during clipping: its clip position and its barycentric
 * weights with respect to the input triangle. */
typedef struct ClipVertex {
  float4 pos;
  float3 bary;
} ClipVertex;

/* The sign of z in the near plane's distance: z + w (GL), w − z (reversed). */
CLR_INLINE float clip_near_sign(uint depthMode)
{
  return depthMode == CLR_DEPTH_REVERSED ? -1.0f : 1.0f;
}

/* Signed distance to clip plane `plane` (>= 0 is inside). Planes: 0 near,
 * 1 left, 2 right, 3 bottom, 4 top (the last four are the guard band).
 * nearSign from clip_near_sign; multiplying by ±1 is exact. */
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

/* Outcode bits of one vertex: 0-4 as clip_distance planes < 0, 5-8 outside
 * the viewport planes x < −w, x > w, y < −w, y > w, 9 beyond far (z > w,
 * or z < 0 when reversed). */
CLR_INLINE uint clip_outcode(float4 c, float gx, float gy, float nearSign)
{
  // Written without branches or a loop (same expressions as clip_distance),
  // so setup's common path stays vectorisable.
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
  // Step 1: the crossing. Near FLT_MAX a difference overflows; then it is
  // taken of halved values (exact, so the same result where both work).
  const float dIn = clip_distance(inside->pos, plane, gx, gy, nearSign);
  const float dOut = clip_distance(outside->pos, plane, gx, gy, nearSign);
  const float denom = dIn - dOut;
  const float t = isfinite(denom) ? dIn / denom : (0.5f * dIn) / (0.5f * dIn - 0.5f * dOut);
  const float4 d = outside->pos - inside->pos;
  out->pos = all(isfinite(d)) ? inside->pos + t * d
                              : 2.0f * (0.5f * inside->pos + t * (0.5f * outside->pos - 0.5f * inside->pos));
  out->bary = inside->bary + t * (outside->bary - inside->bary);
  // Step 2: the point exactly on the plane. The interpolation rounds by up
  // to |coordinate|·2^-24, far more than the guard band when vertices lie
  // at 1e20: a triangle covering the band would lose half of it.
  switch (plane) {
    case 0: out->pos.z = -nearSign * out->pos.w; break;
    case 1: out->pos.x = -(gx * out->pos.w); break;
    case 2: out->pos.x = gx * out->pos.w; break;
    case 3: out->pos.y = -(gy * out->pos.w); break;
    default: out->pos.y = gy * out->pos.w; break;
  }
}

/* Clips the polygon poly[0..n) against the planes in `planeMask`, in place.
 * Returns the new vertex count (0 when nothing is left). */
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
