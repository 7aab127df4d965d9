/* raster.cl — stage 5: the per-pixel kernel.
 *
 * Two work shapes, chosen per device with -D CLR_LANES. On a GPU (1)
 * one work-item per pixel sample and one work-group per tile; each
 * work-item walks its tile's bin. On a CPU (16) one work-item per tile, which
 * walks the bin once and tests each triangle only on the rows its bounds
 * span, 16 pixels at a time in explicit vector types (PoCL turns these into
 * AVX-512, but does not vectorise a data-dependent loop across work-items).
 * Either way, for every triangle the three integer edge functions of the
 * notes are evaluated at pixel centres (i + 0.5, j + 0.5) in 64-bit fixed
 * point. Fill rule (GL as in llvmpipe, y up): a centre exactly on an edge is
 * inside for a left edge (dy < 0 on a counter-clockwise triangle) or a
 * horizontal bottom edge (dy = 0, dx > 0), outside otherwise. Inside samples get barycentrics
 * b_i = E_i / (2·area) and window depth z = z0 + b1·(z1 − z0) + b2·(z2 − z0);
 * the nearest is kept (GL LESS against the far value 1, ties to the lower
 * setup index, i.e. the earlier input triangle) and written to the
 * visibility buffer. Both shapes compute bit-identical results. Tiles with
 * no binned triangle are skipped; resolve fills them.
 */
#pragma OPENCL FP_CONTRACT OFF

#if CLR_TILE_SIZE % CLR_LANES != 0
#error "CLR_LANES must divide CLR_TILE_SIZE"
#endif

/* Edge function of the directed edge (ax, ay)→(bx, by) at the samples
 * (px, py): twice the signed area of (a, b, p), positive when p is left of
 * the edge. Exact in 64 bits (fixed.h). */
CLR_INLINE longL edge_function(int ax, int ay, int bx, int by, intL px, int py)
{
  return (long)(bx - ax) * (long)(py - ay) - (long)(by - ay) * convert_longL(px - ax);
}

/* 1 when a centre exactly on the edge a→b belongs to the triangle. */
CLR_INLINE long edge_bias(int ax, int ay, int bx, int by)
{
  const int dx = bx - ax, dy = by - ay;
  return (dy < 0 || (dy == 0 && dx > 0)) ? 1 : 0;
}

/* The nearest fragment so far of one row segment. */
typedef struct RowBest {
  uintL index;
  floatL depth, b1, b2;
} RowBest;

CLR_INLINE void row_best_init(RowBest* b)
{
  b->index = CLR_NONE;
  b->depth = 1.0f;
  b->b1 = 0.0f;
  b->b2 = 0.0f;
}

/* Tests setup triangle s against the row segment (sx, sy) and keeps the
 * nearest fragment in *best. */
CLR_INLINE void raster_row(__global const TriSetup* t, uint s, intL sx, int sy, RowBest* best)
{
  // Step 1: coverage by the three edge functions and the fill rule.
  const longL e0 = edge_function(t->x[1], t->y[1], t->x[2], t->y[2], sx, sy);
  const longL e1 = edge_function(t->x[2], t->y[2], t->x[0], t->y[0], sx, sy);
  const longL e2 = edge_function(t->x[0], t->y[0], t->x[1], t->y[1], sx, sy);
  const intL inside = convert_intL((e0 + edge_bias(t->x[1], t->y[1], t->x[2], t->y[2]) > 0) &
                                   (e1 + edge_bias(t->x[2], t->y[2], t->x[0], t->y[0]) > 0) &
                                   (e2 + edge_bias(t->x[0], t->y[0], t->x[1], t->y[1]) > 0));
  if (!CLR_ANY(inside)) return;
  // Step 2: barycentrics and depth.
  const floatL b1 = convert_floatL(e1) * t->invArea2;
  const floatL b2 = convert_floatL(e2) * t->invArea2;
  const floatL z = t->z[0] + b1 * (t->z[1] - t->z[0]) + b2 * (t->z[2] - t->z[0]);
  // Step 3: depth test, LESS, ties to the earlier triangle.
  const intL nearer = z < best->depth;
  const intL tieWin = (z == best->depth) & (best->index != CLR_NONE) & (s < best->index);
  const intL take = inside & (nearer | tieWin);
  best->index = select(best->index, (uintL)s, take);
  best->depth = select(best->depth, z, take);
  best->b1 = select(best->b1, b1, take);
  best->b2 = select(best->b2, b2, take);
}

/* Writes the samples of a row segment that lie inside the viewport into
 * the visibility planes (shared.h): a whole row segment in one vector store
 * per plane, a segment cut by the viewport's right edge lane by lane. */
CLR_INLINE void raster_write_row(__constant FrameParams* params, uint firstX, uint py, const RowBest* best,
                                 __global uint* visIndex, __global float* visAttr)
{
  if (py >= params->height) return;
  const uint plane = params->width * params->height, p = py * params->width + firstX;
  if (firstX + CLR_LANES <= params->width) {
    CLR_STORE_LANES(best->index, &visIndex[p]);
    CLR_STORE_LANES(best->depth, &visAttr[p]);
    CLR_STORE_LANES(best->b1, &visAttr[plane + p]);
    CLR_STORE_LANES(best->b2, &visAttr[2 * plane + p]);
    return;
  }
  uint index[CLR_LANES];
  float depth[CLR_LANES], b1[CLR_LANES], b2[CLR_LANES];
  CLR_STORE_LANES(best->index, index);
  CLR_STORE_LANES(best->depth, depth);
  CLR_STORE_LANES(best->b1, b1);
  CLR_STORE_LANES(best->b2, b2);
  for (uint lane = 0; firstX + lane < params->width; ++lane) {
    visIndex[p + lane] = index[lane];
    visAttr[p + lane] = depth[lane];
    visAttr[plane + p + lane] = b1[lane];
    visAttr[2 * plane + p + lane] = b2[lane];
  }
}

#if CLR_LANES == 1
/* GPU shape: one work-item per pixel, one work-group per tile. */
__kernel __attribute__((reqd_work_group_size(CLR_TILE_SIZE, CLR_TILE_SIZE, 1))) void raster(
    __constant FrameParams* params, __global const TriSetup* setup,
    __global const uint* tileOffset,  // tiles + 1
    __global const uint* binEntries,
    __global uint* visIndex,  // width · height
    __global float* visAttr)  // 3 planes of width · height: depth, b1, b2
{
  const uint px = get_global_id(0), py = get_global_id(1);
  const uint tile = get_group_id(1) * params->tilesX + get_group_id(0);
  const int sx = (int)px * CLR_FIXED_ONE + CLR_FIXED_HALF;
  const int sy = (int)py * CLR_FIXED_ONE + CLR_FIXED_HALF;
  const uint begin = tileOffset[tile], end = tileOffset[tile + 1];
  if (begin == end) return;  // resolve fills empty tiles without reading the visibility buffer
  RowBest best;
  row_best_init(&best);
  for (uint k = begin; k < end; ++k) {
    const uint s = binEntries[k];
    raster_row(&setup[s], s, sx, sy, &best);
  }
  raster_write_row(params, px, py, &best, visIndex, visAttr);
}
#else
/* CPU shape: one work-item per tile, as llvmpipe's per-tile threads. Each
 * triangle is tested only on the rows its bounds span, a 16-pixel vector row
 * at a time; the tile's nearest fragments stay in private memory. */
__kernel __attribute__((reqd_work_group_size(1, 1, 1))) void raster(__constant FrameParams* params,
                                                                    __global const TriSetup* setup,
                                                                    __global const uint* tileOffset,  // tiles + 1
                                                                    __global const uint* binEntries,
                                                                    __global uint* visIndex,  // width · height
                                                                    __global float* visAttr)  // 3 planes
{
  const uint tileX = get_global_id(0), tileY = get_global_id(1);
  const uint tile = tileY * params->tilesX + tileX;
  const int firstY = (int)tileY * CLR_TILE_SIZE;
  const uint begin = tileOffset[tile], end = tileOffset[tile + 1];
  if (begin == end) return;  // resolve fills empty tiles without reading the visibility buffer
  // Step 1: the tile's sample positions and its nearest fragments so far.
  RowBest best[CLR_TILE_SIZE / CLR_LANES][CLR_TILE_SIZE];
  intL sx[CLR_TILE_SIZE / CLR_LANES];
  for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col) {
    const int firstX = (int)tileX * CLR_TILE_SIZE + col * CLR_LANES;
    sx[col] = firstX * CLR_FIXED_ONE + CLR_FIXED_HALF + CLR_LANE_INDEX * CLR_FIXED_ONE;
    for (int row = 0; row < CLR_TILE_SIZE; ++row) row_best_init(&best[col][row]);
  }
  // Step 2: each binned triangle, on the rows and row segments it spans.
  for (uint k = begin; k < end; ++k) {
    const uint s = binEntries[k];
    __global const TriSetup* t = &setup[s];
    const int minY = min(t->y[0], min(t->y[1], t->y[2])), maxY = max(t->y[0], max(t->y[1], t->y[2]));
    const int minX = min(t->x[0], min(t->x[1], t->x[2])), maxX = max(t->x[0], max(t->x[1], t->x[2]));
    const int rowBegin = max(0, ((minY - CLR_FIXED_HALF + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS) - firstY);
    const int rowEnd = min(CLR_TILE_SIZE - 1, ((maxY - CLR_FIXED_HALF) >> CLR_SUBPIXEL_BITS) - firstY);
    for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col) {
      const int firstSx = (int)(tileX * CLR_TILE_SIZE + col * CLR_LANES) * CLR_FIXED_ONE + CLR_FIXED_HALF;
      if (firstSx > maxX || firstSx + (CLR_LANES - 1) * CLR_FIXED_ONE < minX) continue;
      for (int row = rowBegin; row <= rowEnd; ++row)
        raster_row(t, s, sx[col], (firstY + row) * CLR_FIXED_ONE + CLR_FIXED_HALF, &best[col][row]);
    }
  }
  // Step 3: write the tile.
  for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col)
    for (int row = 0; row < CLR_TILE_SIZE; ++row)
      raster_write_row(params, tileX * CLR_TILE_SIZE + col * CLR_LANES, firstY + row, &best[col][row], visIndex,
                       visAttr);
}
#endif
