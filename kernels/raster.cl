/* raster.cl — stage 5: the per-pixel kernel.
 *
 * One work-group per tile. Each work-item owns CLR_ROW_PIXELS pixel samples
 * of one row (1 on a GPU: one work-item per pixel; 16 on a CPU, where PoCL
 * vectorises the explicit vector types to AVX-512 but not a data-dependent
 * loop across work-items). Every work-item walks its tile's bin and, for
 * every triangle, evaluates the three integer edge functions of the notes at
 * its pixel centres (i + 0.5, j + 0.5) in 64-bit fixed point. Fill rule (GL
 * as in llvmpipe, y up): a centre exactly on an edge is inside for a left
 * edge (dy < 0 on a counter-clockwise triangle) or a horizontal bottom edge
 * (dy = 0, dx > 0), outside otherwise. Inside samples get barycentrics
 * b_i = E_i / (2·area) and window depth z = z0 + b1·(z1 − z0) + b2·(z2 − z0);
 * the nearest is kept (GL LESS against the far value 1, ties to the lower
 * setup index, i.e. the earlier input triangle) and written to the
 * visibility buffer. Both row widths compute bit-identical results.
 */
#pragma OPENCL FP_CONTRACT OFF

#ifndef CLR_ROW_PIXELS
#define CLR_ROW_PIXELS 1
#endif

/* The per-row vector types: scalars for one pixel, 16-wide vectors for 16. */
#if CLR_ROW_PIXELS == 1
typedef long longR;
typedef int intR;
typedef uint uintR;
typedef float floatR;
#define CLR_LANE_INDEX 0
#define CLR_ANY(mask) (mask)
#define convert_longR convert_long
#define convert_intR convert_int
#define convert_floatR convert_float
#define CLR_STORE_LANES(value, array) ((array)[0] = (value))
#elif CLR_ROW_PIXELS == 16
typedef long16 longR;
typedef int16 intR;
typedef uint16 uintR;
typedef float16 floatR;
#define CLR_LANE_INDEX ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
#define CLR_ANY(mask) any(mask)
#define convert_longR convert_long16
#define convert_intR convert_int16
#define convert_floatR convert_float16
#define CLR_STORE_LANES(value, array) vstore16((value), 0, (array))
#else
#error "CLR_ROW_PIXELS must be 1 or 16"
#endif

#if CLR_TILE_SIZE % CLR_ROW_PIXELS != 0
#error "CLR_ROW_PIXELS must divide CLR_TILE_SIZE"
#endif

/* Edge function of the directed edge (ax, ay)→(bx, by) at the samples
 * (px, py): twice the signed area of (a, b, p), positive when p is left of
 * the edge. Exact in 64 bits (fixed.h). */
CLR_INLINE longR edge_function(int ax, int ay, int bx, int by, intR px, int py)
{
  return (long)(bx - ax) * (long)(py - ay) - (long)(by - ay) * convert_longR(px - ax);
}

/* 1 when a centre exactly on the edge a→b belongs to the triangle. */
CLR_INLINE long edge_bias(int ax, int ay, int bx, int by)
{
  const int dx = bx - ax, dy = by - ay;
  return (dy < 0 || (dy == 0 && dx > 0)) ? 1 : 0;
}

__kernel __attribute__((reqd_work_group_size(CLR_TILE_SIZE / CLR_ROW_PIXELS, CLR_TILE_SIZE, 1))) void raster(
    __constant FrameParams* params, __global const TriSetup* setup,
    __global const uint* tileOffset,  // tiles + 1
    __global const uint* binEntries,
    __global VisSample* vis)  // width · height
{
  const uint firstX = get_global_id(0) * CLR_ROW_PIXELS, py = get_global_id(1);
  const uint tile = get_group_id(1) * params->tilesX + get_group_id(0);
  const intR sx = (int)firstX * CLR_FIXED_ONE + CLR_FIXED_HALF + CLR_LANE_INDEX * CLR_FIXED_ONE;
  const int sy = (int)py * CLR_FIXED_ONE + CLR_FIXED_HALF;
  const int firstSx = (int)firstX * CLR_FIXED_ONE + CLR_FIXED_HALF;
  const int lastSx = firstSx + (CLR_ROW_PIXELS - 1) * CLR_FIXED_ONE;

  uintR bestIndex = CLR_NONE;
  floatR bestDepth = 1.0f, bestB1 = 0.0f, bestB2 = 0.0f;
  const uint end = tileOffset[tile + 1];
  for (uint k = tileOffset[tile]; k < end; ++k) {
    const uint s = binEntries[k];
    __global const TriSetup* t = &setup[s];
    // Step 1: skip triangles whose bounds miss this row segment.
    const int minY = min(t->y[0], min(t->y[1], t->y[2])), maxY = max(t->y[0], max(t->y[1], t->y[2]));
    const int minX = min(t->x[0], min(t->x[1], t->x[2])), maxX = max(t->x[0], max(t->x[1], t->x[2]));
    if (sy < minY || sy > maxY || firstSx > maxX || lastSx < minX) continue;
    // Step 2: coverage by the three edge functions and the fill rule.
    const longR e0 = edge_function(t->x[1], t->y[1], t->x[2], t->y[2], sx, sy);
    const longR e1 = edge_function(t->x[2], t->y[2], t->x[0], t->y[0], sx, sy);
    const longR e2 = edge_function(t->x[0], t->y[0], t->x[1], t->y[1], sx, sy);
    const intR inside = convert_intR((e0 + edge_bias(t->x[1], t->y[1], t->x[2], t->y[2]) > 0) &
                                     (e1 + edge_bias(t->x[2], t->y[2], t->x[0], t->y[0]) > 0) &
                                     (e2 + edge_bias(t->x[0], t->y[0], t->x[1], t->y[1]) > 0));
    if (!CLR_ANY(inside)) continue;
    // Step 3: barycentrics and depth.
    const floatR b1 = convert_floatR(e1) * t->invArea2;
    const floatR b2 = convert_floatR(e2) * t->invArea2;
    const floatR z = t->z[0] + b1 * (t->z[1] - t->z[0]) + b2 * (t->z[2] - t->z[0]);
    // Step 4: depth test, LESS, ties to the earlier triangle.
    const intR nearer = z < bestDepth;
    const intR tieWin = (z == bestDepth) & (bestIndex != CLR_NONE) & (s < bestIndex);
    const intR take = inside & (nearer | tieWin);
    bestIndex = select(bestIndex, (uintR)s, take);
    bestDepth = select(bestDepth, z, take);
    bestB1 = select(bestB1, b1, take);
    bestB2 = select(bestB2, b2, take);
  }
  // Step 5: write the samples that lie inside the viewport.
  if (py >= params->height) return;
  uint index[CLR_ROW_PIXELS];
  float depth[CLR_ROW_PIXELS], b1[CLR_ROW_PIXELS], b2[CLR_ROW_PIXELS];
  CLR_STORE_LANES(bestIndex, index);
  CLR_STORE_LANES(bestDepth, depth);
  CLR_STORE_LANES(bestB1, b1);
  CLR_STORE_LANES(bestB2, b2);
  for (int lane = 0; lane < CLR_ROW_PIXELS; ++lane) {
    if (firstX + lane >= params->width) break;
    VisSample v;
    v.setupIndex = index[lane];
    v.depth = depth[lane];
    v.b1 = b1[lane];
    v.b2 = b2[lane];
    vis[py * params->width + firstX + lane] = v;
  }
}
