/* raster.cl — stage 5: the per-pixel kernel.
 *
 * One work-item per pixel sample, one work-group per tile. Each work-item
 * walks its tile's bin and, for every triangle, evaluates the three integer
 * edge functions of the notes at the pixel centre (i + 0.5, j + 0.5) in
 * 64-bit fixed point. Fill rule (GL as in llvmpipe, y up): a centre exactly
 * on an edge is inside for a left edge (dy < 0 on a counter-clockwise
 * triangle) or a horizontal bottom edge (dy = 0, dx > 0), outside otherwise.
 * Inside samples get barycentrics b_i = E_i / (2·area) and window depth
 * z = z0 + b1·(z1 − z0) + b2·(z2 − z0); the nearest is kept (GL LESS against
 * the far value 1, ties to the lower setup index, i.e. the earlier input
 * triangle) and written to the visibility buffer.
 */
#pragma OPENCL FP_CONTRACT OFF

/* Edge function of the directed edge (ax, ay)→(bx, by) at (px, py): twice
 * the signed area of (a, b, p), positive when p is left of the edge. */
inline long edge_function(int ax, int ay, int bx, int by, int px, int py)
{
  return (long)(bx - ax) * (long)(py - ay) - (long)(by - ay) * (long)(px - ax);
}

/* 1 when a centre exactly on the edge a→b belongs to the triangle. */
inline long edge_bias(int ax, int ay, int bx, int by)
{
  const int dx = bx - ax, dy = by - ay;
  return (dy < 0 || (dy == 0 && dx > 0)) ? 1 : 0;
}

__kernel __attribute__((reqd_work_group_size(CLR_TILE_SIZE, CLR_TILE_SIZE, 1))) void raster(
    __constant FrameParams* params, __global const TriSetup* setup,
    __global const uint* tileOffset,  // tiles + 1
    __global const uint* binEntries,
    __global VisSample* vis)  // width · height
{
  const uint px = get_global_id(0), py = get_global_id(1);
  const uint tile = get_group_id(1) * params->tilesX + get_group_id(0);
  const int sx = (int)px * CLR_FIXED_ONE + CLR_FIXED_HALF;
  const int sy = (int)py * CLR_FIXED_ONE + CLR_FIXED_HALF;

  VisSample best;
  best.setupIndex = CLR_NONE;
  best.depth = 1.0f;
  best.b1 = 0.0f;
  best.b2 = 0.0f;
  const uint end = tileOffset[tile + 1];
  for (uint k = tileOffset[tile]; k < end; ++k) {
    const uint s = binEntries[k];
    __global const TriSetup* t = &setup[s];
    // Step 1: coverage by the three edge functions and the fill rule.
    const long e0 = edge_function(t->x[1], t->y[1], t->x[2], t->y[2], sx, sy);
    const long e1 = edge_function(t->x[2], t->y[2], t->x[0], t->y[0], sx, sy);
    const long e2 = edge_function(t->x[0], t->y[0], t->x[1], t->y[1], sx, sy);
    if (e0 + edge_bias(t->x[1], t->y[1], t->x[2], t->y[2]) <= 0) continue;
    if (e1 + edge_bias(t->x[2], t->y[2], t->x[0], t->y[0]) <= 0) continue;
    if (e2 + edge_bias(t->x[0], t->y[0], t->x[1], t->y[1]) <= 0) continue;
    // Step 2: barycentrics and depth.
    const float b1 = convert_float(e1) * t->invArea2;
    const float b2 = convert_float(e2) * t->invArea2;
    const float z = t->z[0] + b1 * (t->z[1] - t->z[0]) + b2 * (t->z[2] - t->z[0]);
    // Step 3: depth test, LESS, ties to the earlier triangle.
    const bool nearer = z < best.depth;
    const bool tieWin = z == best.depth && best.setupIndex != CLR_NONE && s < best.setupIndex;
    if (nearer || tieWin) {
      best.setupIndex = s;
      best.depth = z;
      best.b1 = b1;
      best.b2 = b2;
    }
  }
  if (px < params->width && py < params->height) vis[py * params->width + px] = best;
}
