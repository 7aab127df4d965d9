/* bin.cl — stage 4: binning screen triangles into CLR_TILE_SIZE² tiles.
 *
 * Two passes with a scan between them, so memory follows the actual counts
 * and no triangle is ever dropped: bin_count adds one to every tile that a
 * triangle's pixel bounds touch; the host scans the counts into offsets,
 * sizes binEntries from the total, and bin_fill writes each triangle's setup
 * index into its tiles. The order inside a tile is not deterministic; the
 * raster kernel breaks depth ties by setup index, which is input order.
 * With hierarchical traversal (FrameParams.traversal) a tile of the bounds
 * is skipped when all of it lies strictly outside one edge: the edge
 * function is linear, so its largest value over the tile's rectangle is at
 * a corner, and a negative maximum leaves every sample of the tile outside,
 * whatever the fill rule.
 */

/* Edge function of a→b at one point, exact in 64 bits (fixed.h). */
CLR_INLINE long bin_edge_at(int ax, int ay, int bx, int by, int px, int py)
{
  return (long)(bx - ax) * (long)(py - ay) - (long)(by - ay) * (long)(px - ax);
}

/* Where tile (tx, ty)'s rectangle of sample positions lies against the
 * triangle: −1 strictly outside one edge (no sample can be covered), 1
 * inside all three edges by the fill rule (every sample is covered), 0
 * otherwise. */
CLR_INLINE int bin_tile_class(const TriSetup* t, __constant FrameParams* params, int tx, int ty)
{
  const int x0 = tx * CLR_TILE_SIZE * CLR_FIXED_ONE + CLR_FIXED_HALF + params->sampleMinX;
  const int y0 = ty * CLR_TILE_SIZE * CLR_FIXED_ONE + CLR_FIXED_HALF + params->sampleMinY;
  const int x1 = x0 + (CLR_TILE_SIZE - 1) * CLR_FIXED_ONE + params->sampleMaxX - params->sampleMinX;
  const int y1 = y0 + (CLR_TILE_SIZE - 1) * CLR_FIXED_ONE + params->sampleMaxY - params->sampleMinY;
  bool inside = true;
  for (int e = 0; e < 3; ++e) {
    const int a = (e + 1) % 3, b = (e + 2) % 3;
    const long c00 = bin_edge_at(t->x[a], t->y[a], t->x[b], t->y[b], x0, y0);
    const long c10 = bin_edge_at(t->x[a], t->y[a], t->x[b], t->y[b], x1, y0);
    const long c01 = bin_edge_at(t->x[a], t->y[a], t->x[b], t->y[b], x0, y1);
    const long c11 = bin_edge_at(t->x[a], t->y[a], t->x[b], t->y[b], x1, y1);
    if (max(max(c00, c10), max(c01, c11)) < 0) return -1;
    const int dx = t->x[b] - t->x[a], dy = t->y[b] - t->y[a];
    const long bias = (dy < 0 || (dy == 0 && dx > 0)) ? 1 : 0;  // the fill rule, as raster.cl's edge_bias
    inside = inside && min(min(c00, c10), min(c01, c11)) + bias > 0;
  }
  return inside ? 1 : 0;
}

/* Tiles touched by a triangle's pixel bounds; empty for padding records. */
CLR_INLINE int4 bin_tile_range(const TriSetup* t, __constant FrameParams* params)
{
  if (t->flags & CLR_FLAG_DEAD) return (int4)(0, 0, -1, -1);
  const int4 px = setup_pixel_bounds(t, params);
  return px / CLR_TILE_SIZE;
}

__kernel void bin_count(__constant FrameParams* params, __global const TriSetup* setup, uint numSetup,
                        __global uint* tileCount)  // tiles + 1
{
  const uint s = get_global_id(0);
  if (s >= numSetup) return;
  const TriSetup t = setup[s];
  const int4 r = bin_tile_range(&t, params);
  const bool hierarchical = params->traversal == CLR_TRAVERSAL_HIERARCHICAL && (r.z > r.x || r.w > r.y);
  for (int ty = r.y; ty <= r.w; ++ty)
    for (int tx = r.x; tx <= r.z; ++tx)
      if (!hierarchical || bin_tile_class(&t, params, tx, ty) >= 0) atomic_inc(&tileCount[ty * params->tilesX + tx]);
}

__kernel void bin_fill(__constant FrameParams* params, __global const TriSetup* setup, uint numSetup,
                       __global const uint* tileOffset,  // tiles + 1, scanned
                       __global uint* tileCursor,        // tiles, zeroed
                       __global uint* binEntries)        // tileOffset[tiles]
{
  const uint s = get_global_id(0);
  if (s >= numSetup) return;
  const TriSetup t = setup[s];
  const int4 r = bin_tile_range(&t, params);
  const bool hierarchical = params->traversal == CLR_TRAVERSAL_HIERARCHICAL && (r.z > r.x || r.w > r.y);
  for (int ty = r.y; ty <= r.w; ++ty)
    for (int tx = r.x; tx <= r.z; ++tx) {
      if (hierarchical && bin_tile_class(&t, params, tx, ty) < 0) continue;
      const uint tile = ty * params->tilesX + tx;
      binEntries[tileOffset[tile] + atomic_inc(&tileCursor[tile])] = s;
    }
}

/* One per tile: 1 when its bin holds a triangle. The host scans these into
 * each tile's slot in the visibility buffer (shared.h) and sizes the buffer
 * from the total. */
__kernel void bin_slots(__global const uint* tileOffset,         // tiles + 1, scanned
                        uint numTiles, __global uint* tileSlot)  // tiles + 1
{
  const uint t = get_global_id(0);
  if (t < numTiles) tileSlot[t] = tileOffset[t + 1] != tileOffset[t] ? 1u : 0u;
}
