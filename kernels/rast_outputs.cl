/* rast_outputs.cl — the library's rasterize outputs (host/api/api.cpp), in
 * nvdiffrast's layout, from a frame built with -D CLR_CLIP_INPUT=1
 * (positions are the caller's clip-space float4, transform.cl).
 *
 * One work-item per pixel reads sample 0 of the visibility buffer (with its
 * depth and barycentric planes) and writes, bottom row first:
 *  rast float4 (u, v, z/w, id): u and v the perspective-correct weights of
 *    input vertices 0 and 1 (vertex 2 weighs 1 − u − v), mapped through
 *    ClipBary and the back-face swap as aov.cl does; z/w = 2d − 1 from the
 *    window depth d = z/w · 0.5 + 0.5 that raster interpolated in screen
 *    space and kept (float32 depth, setup.cl); id = triangle index + 1 as
 *    nvdiffrast encodes it (rast_pixel.h);
 *  ids uint: triangle index + 1, exact, when `outputs` has
 *    CLR_RAST_OUT_IDS;
 *  db float4 (du/dX, du/dY, dv/dX, dv/dY) per pixel, when `outputs` has
 *    CLR_RAST_OUT_DB (the only output that reads the positions; rast_pixel.h).
 * Background: all zero. A batched frame (FrameParams.imageTris) stacks its
 * images' rows; each pixel's id and db are those of its image alone.
 */
#pragma OPENCL FP_CONTRACT OFF
#include "vis.h"
#include "transform.h"
#include "rast_pixel.h"
#if CLR_EXTRAS /* the extras program (CLR_EXTRAS, shared.h) */

#define CLR_RAST_OUT_IDS 1u
#define CLR_RAST_OUT_DB 2u

__kernel void rast_outputs(__constant FrameParams* params,
                           __global const uint* visIndex,    // sample plane 0 (shared.h)
                           __global const float* visAttr,    // its depth, b1, b2 planes
                           __global const uint* tileOffset,  // tiles + 1
                           __global const uint* source, __global const ClipBary* clipBary,
                           __global const uint* indices,     // 3·numTris
                           __global const float* positions,  // 4·numVerts, clip space
                           __global const uint* tileSlot,    // tiles + 1
                           uint visPlane,
                           __global float4* rast,  // width · height
                           __global uint* ids,     // width · height, with CLR_RAST_OUT_IDS
                           __global float4* db,    // width · height, with CLR_RAST_OUT_DB
                           uint outputs)
{
  const uint px = get_global_id(0), py = get_global_id(1);
  if (px >= params->width || py >= params->height) return;
  const uint p = py * params->width + px;
  // Step 1: the visible triangle, or none.
  const uint tile = (py / CLR_TILE_SIZE) * params->tilesX + px / CLR_TILE_SIZE;
  const bool empty = tileOffset[tile] == tileOffset[tile + 1];
  const uint v = empty ? 0u : vis_address(tileSlot[tile], px, py);
  const uint index = empty ? CLR_NONE : vis_index_at(params, visIndex, v);
  if (index == CLR_NONE) {
    rast[p] = (float4)(0.0f);
    if (outputs & CLR_RAST_OUT_IDS) ids[p] = 0u;
    if (outputs & CLR_RAST_OUT_DB) db[p] = (float4)(0.0f);
    return;
  }
  const uint from = source[index], triId = clr_source_triangle(from, clipBary);
  // Step 2: perspective-correct weights of the input vertices (rast_pixel.h).
  const float2 uv =
      rast_pixel_uv(params, positions, indices, clipBary, from, visAttr[visPlane + v], visAttr[2 * visPlane + v]);
  // Step 3: the outputs; a batched frame's ids and pixel rows are its image's (clr_image_row).
  const uint row = (uint)clr_image_row(params, triId);
  const uint id = params->imageTris ? triId - row / params->imageRows * params->imageTris : triId;
  rast[p] = (float4)(uv.x, uv.y, 2.0f * visAttr[v] - 1.0f, rast_id_float(id + 1u));
  if (outputs & CLR_RAST_OUT_IDS) ids[p] = id + 1u;
  if (!(outputs & CLR_RAST_OUT_DB)) return;
  db[p] = rast_pixel_db(indices, positions, triId, px, py - row, params->width, params->imageHeight);
}
#endif
