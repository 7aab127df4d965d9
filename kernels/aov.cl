/* aov.cl — visibility-buffer outputs (AOVs), as nvdiffrast's rasterize output or PyTorch3D's fragments.
 *
 * One work-item per pixel reads sample 0 of the visibility buffer (empty tiles are "none" unread) and writes the
 * CLR_AOV_CHANNELS float planes of shared.h. Weights are of the input triangle's vertices 1 and 2, mapped through
 * ClipBary (clipped) or the 1↔2 swap (back-facing) as resolve.cl does: bary by the 1/w rule
 * λ_i = (b_i / w_i) / Σ_j (b_j / w_j), bary_screen the screen b_i (--interp affine). Triangle id is exact below 2^24;
 * eye depth is w_clip = 1 / Σ b_i / w_i; normals are never flipped, 0 when they cancel.
 * Background: id −1, barycentrics 0, z/w 1, eye depth +inf, normal 0.
 */
#pragma OPENCL FP_CONTRACT OFF
#include "vis.h"
#include "transform.h"
#if CLR_EXTRAS /* the extras program (CLR_EXTRAS, shared.h) */

__kernel void aov(__constant FrameParams* params,
                  __global const uint* visIndex,    // sample plane 0 (shared.h)
                  __global const float* visAttr,    // its depth, b1, b2 planes
                  __global const uint* tileOffset,  // tiles + 1
                  __global const uint* source,      // setup's source words
                  __global const ClipBary* clipBary,
                  __global const uint* indices,     // 3·numTris
                  __global const float* positions,  // 3·numVerts, for 1/w (record_clip_w)
                  __global const float* normals,    // 3·numVerts
                  __global float* out,              // CLR_AOV_CHANNELS · width · height
                  __global const uint* tileSlot,    // tiles + 1: visibility-buffer slots (shared.h)
                  uint visPlane,
                  __global const uint* fileTri)  // numTris: each input triangle's index in the file
{
  const uint px = get_global_id(0), py = get_global_id(1);
  if (px >= params->width || py >= params->height) return;
  const uint plane = params->width * params->height, p = py * params->width + px;
  // Step 1: the visible triangle, or none.
  const uint tile = (py / CLR_TILE_SIZE) * params->tilesX + px / CLR_TILE_SIZE;
  const bool empty = tileOffset[tile] == tileOffset[tile + 1];
  const uint v = empty ? 0u : vis_address(tileSlot[tile], px, py);  // in plane 0 of the visibility buffer
  const uint index = empty ? CLR_NONE : vis_index_at(params, visIndex, v);
  if (index == CLR_NONE) {
    for (int c = 0; c < CLR_AOV_CHANNELS; ++c) out[c * plane + p] = 0.0f;
    out[CLR_AOV_TRIANGLE_ID * plane + p] = -1.0f;
    out[CLR_AOV_Z_W * plane + p] = 1.0f;
    out[CLR_AOV_EYE_DEPTH * plane + p] = INFINITY;
    return;
  }
  const uint from = source[index], clipSlot = clr_source_clip_slot(from), triId = clr_source_triangle(from, clipBary);
  // Step 2: screen and perspective-correct barycentrics of the setup vertices.
  const float b[3] = {1.0f - visAttr[visPlane + v] - visAttr[2 * visPlane + v], visAttr[visPlane + v],
                      visAttr[2 * visPlane + v]};
  const uint vertex[3] = {indices[3 * triId], indices[3 * triId + 1], indices[3 * triId + 2]};
  float w[3];
  record_clip_w(params, positions, clipBary, from, vertex, w);
  const float q[3] = {b[0] * (1.0f / w[0]), b[1] * (1.0f / w[1]), b[2] * (1.0f / w[2])};
  const float eyeDepth = 1.0f / (q[0] + q[1] + q[2]);
  // Step 3: weights of the input vertices in each setup vertex (resolve.cl).
  const bool clipped = clipSlot != CLR_NOT_CLIPPED;
  const bool swapped = !clipped && clr_source_backfacing(from, clipBary);
  float mu[3] = {0.0f, 0.0f, 0.0f}, muScreen[3] = {0.0f, 0.0f, 0.0f};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int identity = swapped && i != 0 ? 3 - i : i;
      const float w = clipped ? clipBary[clipSlot].w[i][j] : (float)(identity == j);
      mu[j] += (q[i] * eyeDepth) * w;
      muScreen[j] += b[i] * w;
    }
  // Step 4: the interpolated normal.
  float3 n = (float3)(0.0f);
  for (int j = 0; j < 3; ++j) n += mu[j] * vload3(vertex[j], normals);
  // Not length(): its rounding is the driver's; each operation here is IEEE, so every device agrees.
  const float len = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  n = len > 0.0f ? n / len : (float3)(0.0f);
  // Step 5: write.
  out[CLR_AOV_TRIANGLE_ID * plane + p] = (float)(params->fileOrder ? triId : fileTri[triId]);
  out[CLR_AOV_BARY_U * plane + p] = mu[1];
  out[CLR_AOV_BARY_V * plane + p] = mu[2];
  out[CLR_AOV_SCREEN_U * plane + p] = muScreen[1];
  out[CLR_AOV_SCREEN_V * plane + p] = muScreen[2];
  out[CLR_AOV_Z_W * plane + p] = visAttr[v];
  out[CLR_AOV_EYE_DEPTH * plane + p] = eyeDepth;
  out[CLR_AOV_NORMAL_X * plane + p] = n.x;
  out[CLR_AOV_NORMAL_Y * plane + p] = n.y;
  out[CLR_AOV_NORMAL_Z * plane + p] = n.z;
}
#endif
