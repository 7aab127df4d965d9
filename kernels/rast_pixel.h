/* rast_pixel.h — what rast_outputs.cl and diff_peel.cl write per pixel in
 * nvdiffrast's layout: rast's (u, v) from a fragment's screen barycentrics,
 * the triangle-id encoding of its fourth channel, and rast_db, the pixel
 * derivatives of u and v. With the clip vertices
 * p_i = (x_i, y_i, w_i) and s = (x_ndc, y_ndc, 1), k_i = (p_j × p_k)·s
 * (i, j, k cyclic) and λ_i = k_i / Σk, so dλ_i/dx_ndc = (r_i.x − λ_i Σ r.x) / Σk
 * with r_i = p_j × p_k, and dx_ndc/dX = 2/W, dy_ndc/dY = 2/H.
 */
#ifndef CLR_RAST_PIXEL_H
#define CLR_RAST_PIXEL_H

#include "transform.h"

/* (u, v): the perspective-correct weights of input vertices 0 and 1 at the
 * fragment of setup source word `from` with screen barycentrics (b1, b2),
 * mapped through ClipBary and the back-face swap as aov.cl does. */
CLR_INLINE float2 rast_pixel_uv(__constant FrameParams* params, __global const float* positions,
                                __global const uint* indices, __global const ClipBary* clipBary, uint from, float b1,
                                float b2)
{
  const uint clipSlot = clr_source_clip_slot(from), triId = clr_source_triangle(from, clipBary);
  const float b[3] = {1.0f - b1 - b2, b1, b2};
  const uint vertex[3] = {indices[3 * triId], indices[3 * triId + 1], indices[3 * triId + 2]};
  float w[3];
  record_clip_w(params, positions, clipBary, from, vertex, w);
  const float q[3] = {b[0] * (1.0f / w[0]), b[1] * (1.0f / w[1]), b[2] * (1.0f / w[2])};
  const float eyeDepth = 1.0f / (q[0] + q[1] + q[2]);
  const bool clipped = clipSlot != CLR_NOT_CLIPPED;
  const bool swapped = !clipped && clr_source_backfacing(from, clipBary);
  float mu[2] = {0.0f, 0.0f};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j) {
      const int identity = swapped && i != 0 ? 3 - i : i;
      const float wt = clipped ? clipBary[clipSlot].w[i][j] : (float)(identity == j);
      mu[j] += (q[i] * eyeDepth) * wt;
    }
  return (float2)(mu[0], mu[1]);
}

/* nvdiffrast's triangle-id encoding (triidx_to_float): exact up to 2^24,
 * above that the biased bit pattern 0x4a800000 + id, which decodes exactly. */
CLR_INLINE float rast_id_float(uint id)
{
  return id <= 0x01000000u ? (float)id : as_float(0x4a800000u + id);
}

/* (du/dX, du/dY, dv/dX, dv/dY) of triangle triId at pixel (px, py) of a
 * width × height image; positions are clip-space float4. */
CLR_INLINE float4 rast_pixel_db(__global const uint* indices, __global const float* positions, uint triId, uint px,
                                uint py, uint width, uint height)
{
  float4 c[3];
  for (int j = 0; j < 3; ++j) c[j] = vload4(indices[3 * triId + j], positions);
  const float3 p0 = (float3)(c[0].x, c[0].y, c[0].w), p1 = (float3)(c[1].x, c[1].y, c[1].w),
               p2 = (float3)(c[2].x, c[2].y, c[2].w);
  const float3 r0 = cross(p1, p2), r1 = cross(p2, p0), r2 = cross(p0, p1);
  const float3 s =
      (float3)(2.0f * ((float)px + 0.5f) / (float)width - 1.0f, 2.0f * ((float)py + 0.5f) / (float)height - 1.0f, 1.0f);
  const float k0 = dot(r0, s), k1 = dot(r1, s), k2 = dot(r2, s);
  const float sum = k0 + k1 + k2, l0 = k0 / sum, l1 = k1 / sum;
  const float sx = r0.x + r1.x + r2.x, sy = r0.y + r1.y + r2.y;
  const float dx = 2.0f / (float)width, dy = 2.0f / (float)height;
  return (float4)((r0.x - l0 * sx) / sum * dx, (r0.y - l0 * sy) / sum * dy, (r1.x - l1 * sx) / sum * dx,
                  (r1.y - l1 * sy) / sum * dy);
}

#endif
