/* diff_peel.cl — one layer of depth peeling (nvdiffrast's DepthPeeler) over a
 * clip-input frame that ran setup and bin (host/pipeline/peel.cpp).
 *
 * One work-item per pixel tests every setup record binned into its tile at
 * the pixel's sample as raster.cl does with fixed edges (exact 64-bit edge
 * functions, CLR_EDGE_HOLDS_SAMPLES, b = E · 1/(2·area), window depth
 * z0 + b1 (z1 − z0) + b2 (z2 − z0), LESS against the clear depth 1, ties to
 * the lower record) but takes only fragments strictly behind floorDepth,
 * the window depth of the pixel's previous layer (−inf for the first, which
 * is then raster's own choice). It writes rast and rast_db as
 * rast_outputs.cl does (per image in a batched frame), and the layer's
 * depth into nextFloor (+inf where nothing is left, so later layers stay
 * empty).
 */
#pragma OPENCL FP_CONTRACT OFF
#include "rast_pixel.h"
#if CLR_EXTRAS /* the extras program (CLR_EXTRAS, shared.h) */

CLR_INLINE long peel_edge(int ax, int ay, int bx, int by, int px, int py)
{
  return (long)(bx - ax) * (long)(py - ay) - (long)(by - ay) * (long)(px - ax) +
         (CLR_EDGE_HOLDS_SAMPLES(ax, ay, bx, by) ? 1 : 0);
}

__kernel void peel_layer(__constant FrameParams* params, __global const TriSetup* setup,
                         __global const uint* tileOffset,  // tiles + 1
                         __global const uint* binEntries, __global const uint* source,
                         __global const ClipBary* clipBary,
                         __global const uint* indices,      // 3·numTris
                         __global const float* positions,   // 4·numVerts, clip space
                         __global const float* floorDepth,  // width · height
                         __global float4* rast, __global float4* db, uint withDb, __global float* nextFloor)
{
  const uint px = get_global_id(0), py = get_global_id(1);
  if (px >= params->width || py >= params->height) return;
  const uint p = py * params->width + px;
  // Step 1: the nearest fragment behind the floor.
  const int sx = (int)px * CLR_FIXED_ONE + CLR_FIXED_HALF + params->sampleX[0];
  const int sy = (int)py * CLR_FIXED_ONE + CLR_FIXED_HALF + params->sampleY[0];
  const uint tile = (py / CLR_TILE_SIZE) * params->tilesX + px / CLR_TILE_SIZE;
  const float floor = floorDepth[p];
  float best = 1.0f, b1 = 0.0f, b2 = 0.0f;
  uint bestS = CLR_NONE;
  for (uint n = tileOffset[tile]; n < tileOffset[tile + 1]; ++n) {
    const uint s = binEntries[n];
    const TriSetup t = setup[s];
    const long e0 = peel_edge(t.x[1], t.y[1], t.x[2], t.y[2], sx, sy);
    const long e1 = peel_edge(t.x[2], t.y[2], t.x[0], t.y[0], sx, sy);
    const long e2 = peel_edge(t.x[0], t.y[0], t.x[1], t.y[1], sx, sy);
    if (e0 <= 0 || e1 <= 0 || e2 <= 0) continue;
    const float inv = CLR_RECORD_INV_AREA2(t);
    // raster's b: the edge function without the fill rule's bias.
    const float c1 = (float)(e1 - (CLR_EDGE_HOLDS_SAMPLES(t.x[2], t.y[2], t.x[0], t.y[0]) ? 1 : 0)) * inv;
    const float c2 = (float)(e2 - (CLR_EDGE_HOLDS_SAMPLES(t.x[0], t.y[0], t.x[1], t.y[1]) ? 1 : 0)) * inv;
    const float z = t.z[0] + c1 * (t.z[1] - t.z[0]) + c2 * (t.z[2] - t.z[0]);
    if (!(z > floor) || !(z < best || (z == best && s < bestS))) continue;
    best = z;
    bestS = s;
    b1 = c1;
    b2 = c2;
  }
  if (bestS == CLR_NONE) {
    rast[p] = (float4)(0.0f);
    if (withDb) db[p] = (float4)(0.0f);
    nextFloor[p] = INFINITY;
    return;
  }
  nextFloor[p] = best;
  // Step 2: rast_outputs.cl's outputs for that fragment.
  const uint from = source[bestS], triId = clr_source_triangle(from, clipBary);
  const float2 uv = rast_pixel_uv(params, positions, indices, clipBary, from, b1, b2);
  const uint row = (uint)clr_image_row(params, triId);  // a batched frame's ids and rows are its image's
  const uint id = params->imageTris ? triId - row / params->imageRows * params->imageTris : triId;
  rast[p] = (float4)(uv.x, uv.y, 2.0f * best - 1.0f, rast_id_float(id + 1u));
  if (withDb) db[p] = rast_pixel_db(indices, positions, triId, px, py - row, params->width, params->imageHeight);
}
#endif
