/* bin.h — the binning helpers setup's passes (setup.cl) and bin_fill_clipped (bin.cl) share, and the tile test
 * raster's hierarchical traversal reuses (bin_tile_class, raster.cl): a triangle's pixel bounds and tile range,
 * the tile classes against its edges, and the grouped atomic adds that fill its bins.
 *
 * Count, scan, fill, so memory follows the counts and no triangle is dropped: setup's count pass (and setup_clip
 * for sub-triangles) adds one per tile of a triangle's pixel bounds; the host scans counts into offsets, sizes
 * binEntries and gives each non-empty tile a visibility-buffer slot (host bin.cpp); the emit pass writes records and
 * bin entries together (bin_fill_tiles) and bin_fill_clipped bins clipped records. Atomic adds are grouped where a
 * mesh is coherent (bin_tally, bin_fill_run, bin_*_range_run). Order within a tile is not deterministic: raster
 * breaks depth ties by setup index (input order). Hierarchical traversal skips a tile strictly outside one edge:
 * the edge function is linear, so its maximum over the tile is at a corner.
 */
#ifndef CLR_BIN_H
#define CLR_BIN_H

/* Floor and ceiling of a / CLR_FIXED_ONE for signed a. */
CLR_INLINE int fixed_floor(int a)
{
  return a >> CLR_SUBPIXEL_BITS;
}
CLR_INLINE int fixed_ceil(int a)
{
  return (a + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS;
}

/* Inclusive pixel range, clamped to the viewport (the image from `row`, clr_image_row), that can hold a sample (at
 * i·ONE + HALF + offset, offset in [sampleMin, sampleMax]); empty when x0 > x1 or y0 > y1. setup_make computes the
 * same in lane types. */
CLR_INLINE int4 bin_pixel_bounds(const TriSetup* t, __constant FrameParams* params, int row)
{
  const int4 b = CLR_RECORD_BOUNDS(*t);
  int4 r;
  r.x = max(0, fixed_ceil(b.x - CLR_FIXED_HALF - params->sampleMaxX));
  r.y = max(row, fixed_ceil(b.y - CLR_FIXED_HALF - params->sampleMaxY));
  r.z = min((int)params->width - 1, fixed_floor(b.z - CLR_FIXED_HALF - params->sampleMinX));
  r.w = min(row + (int)params->imageHeight - 1, fixed_floor(b.w - CLR_FIXED_HALF - params->sampleMinY));
  return r;
}

/* Edge function of a→b at one point, exact in 64 bits (fixed.h). */
CLR_INLINE long bin_edge_at(int ax, int ay, int bx, int by, int px, int py)
{
  return (long)(bx - ax) * (long)(py - ay) - (long)(by - ay) * (long)(px - ax);
}

/* Tile (tx, ty)'s samples against the triangle: −1 strictly outside one edge, 1 all inside by the fill rule, else 0. */
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
    const long bias = CLR_EDGE_HOLDS_SAMPLES(t->x[a], t->y[a], t->x[b], t->y[b]) ? 1 : 0;  // the fill rule (fixed.h)
    inside = inside && min(min(c00, c10), min(c01, c11)) + bias > 0;
  }
  return inside ? 1 : 0;
}

/* Tiles touched by a triangle's pixel bounds. */
CLR_INLINE int4 bin_tile_range(const TriSetup* t, __constant FrameParams* params, int row)
{
  return bin_pixel_bounds(t, params, row) / CLR_TILE_SIZE;
}

/* True when hierarchical traversal tests triangle tiles of range r. */
CLR_INLINE bool bin_hierarchical(__constant FrameParams* params, int4 r)
{
  return params->traversal == CLR_TRAVERSAL_HIERARCHICAL && (r.z > r.x || r.w > r.y);
}

#if !CLR_EXTRAS /* binning rides on setup (the frame program) */
/* Pass 1: +1 to each tile of range r that hierarchical traversal keeps (t read only if bin_hierarchical). */
CLR_CALLED void bin_count_tiles(const TriSetup* t, int4 r, __constant FrameParams* params, __global uint* tileCount)
{
  const bool hierarchical = bin_hierarchical(params, r);
  for (int ty = r.y; ty <= r.w; ++ty)
    for (int tx = r.x; tx <= r.z; ++tx)
      if (!hierarchical || bin_tile_class(t, params, tx, ty) >= 0) atomic_inc(&tileCount[ty * params->tilesX + tx]);
}

/* True when range r is two adjacent tiles (a small triangle across a tile edge), binned without a loop. */
CLR_INLINE bool bin_two_tiles(__constant FrameParams* params, int4 r)
{
  return params->traversal != CLR_TRAVERSAL_HIERARCHICAL && (r.z - r.x) + (r.w - r.y) == 1;
}

/* Pass 1's counts for a batch's one- and two-tile triangles, held for the two most recent tiles (`front` the
 * newer): one atomic add when a tile leaves the pair or the batch ends. Two tiles, not one, because coherent small
 * triangles straddle tile edges. */
typedef struct BinTally {
  uint tile[2], count[2], front;
} BinTally;

CLR_INLINE void bin_tally_init(BinTally* t)
{
  t->tile[0] = t->tile[1] = CLR_NONE;
  t->count[0] = t->count[1] = 0;
  t->front = 0;
}

CLR_INLINE void bin_tally_flush(BinTally* t, uint k, __global uint* tileCount)
{
  if (t->count[k]) atomic_add(&tileCount[t->tile[k]], t->count[k]);
  t->count[k] = 0;
}

CLR_INLINE void bin_tally_add(BinTally* t, uint tile, __global uint* tileCount)
{
  uint k = t->front;
  if (tile != t->tile[k]) {
    k ^= 1u;
    if (tile != t->tile[k]) {
      bin_tally_flush(t, k, tileCount);
      t->tile[k] = tile;
    }
    t->front = k;
  }
  ++t->count[k];
}

CLR_INLINE void bin_tally_end(BinTally* t, __global uint* tileCount)
{
  bin_tally_flush(t, 0, tileCount);
  bin_tally_flush(t, 1, tileCount);
}

/* Pass 2: writes setup index s into the same tiles, at the scanned offset
 * plus a per-tile cursor. */
CLR_CALLED void bin_fill_tiles(const TriSetup* t, int4 r, uint s, __constant FrameParams* params,
                               __global const uint* tileOffset, __global uint* tileCursor, __global uint* binEntries)
{
  const bool hierarchical = bin_hierarchical(params, r);
  for (int ty = r.y; ty <= r.w; ++ty)
    for (int tx = r.x; tx <= r.z; ++tx) {
      if (hierarchical && bin_tile_class(t, params, tx, ty) < 0) continue;
      const uint tile = ty * params->tilesX + tx;
      binEntries[tileOffset[tile] + atomic_inc(&tileCursor[tile])] = s;
    }
}

/* Pass 2 for a two-tile triangle (bin_two_tiles): s into both tiles. */
CLR_INLINE void bin_fill_two_tiles(int4 r, uint s, __constant FrameParams* params, __global const uint* tileOffset,
                                   __global uint* tileCursor, __global uint* binEntries)
{
  const uint a = r.y * params->tilesX + r.x, b = r.w * params->tilesX + r.z;
  binEntries[tileOffset[a] + atomic_inc(&tileCursor[a])] = s;
  binEntries[tileOffset[b] + atomic_inc(&tileCursor[b])] = s;
}

/* Pass 2 for a run of triangles binned to one tile: one atomic add takes
 * their entries. */
CLR_INLINE void bin_fill_run(uint tile, const uint* setupIndex, uint count, __global const uint* tileOffset,
                             __global uint* tileCursor, __global uint* binEntries)
{
  const uint at = tileOffset[tile] + atomic_add(&tileCursor[tile], count);
  for (uint i = 0; i < count; ++i) binEntries[at + i] = setupIndex[i];
}

/* True when tile ranges a and b are the same. */
CLR_INLINE bool bin_same_range(int4 a, int4 b)
{
  return a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w;
}

/* Pass 1 for `count` consecutive triangles on one multi-tile range r (bbox traversal): one add per tile for the run
 * (the two halves of a quad share their tiles). */
CLR_CALLED void bin_count_range_run(int4 r, uint count, __constant FrameParams* params, __global uint* tileCount)
{
  for (int ty = r.y; ty <= r.w; ++ty)
    for (int tx = r.x; tx <= r.z; ++tx) atomic_add(&tileCount[ty * params->tilesX + tx], count);
}

/* Pass 2 for the same runs: one atomic add per tile takes the run's
 * entries there (bin_fill_run). */
CLR_CALLED void bin_fill_range_run(int4 r, const uint* setupIndex, uint count, __constant FrameParams* params,
                                   __global const uint* tileOffset, __global uint* tileCursor,
                                   __global uint* binEntries)
{
  for (int ty = r.y; ty <= r.w; ++ty)
    for (int tx = r.x; tx <= r.z; ++tx)
      bin_fill_run(ty * params->tilesX + tx, setupIndex, count, tileOffset, tileCursor, binEntries);
}

/* Pass 2's run of consecutive setup indices (<= one batch) on one tile range; bin_run_add flushes it when the next
 * range differs, bin_run_end flushes the rest. */
typedef struct BinRun {
  int4 range;
  uint length, setupIndex[CLR_LANES];
} BinRun;

CLR_INLINE void bin_run_end(BinRun* run, __constant FrameParams* params, __global const uint* tileOffset,
                            __global uint* tileCursor, __global uint* binEntries)
{
  const int4 r = run->range;
  if (run->length == 0) return;
  if (r.x == r.z && r.y == r.w)
    bin_fill_run(r.y * params->tilesX + r.x, run->setupIndex, run->length, tileOffset, tileCursor, binEntries);
  else
    bin_fill_range_run(r, run->setupIndex, run->length, params, tileOffset, tileCursor, binEntries);
  run->length = 0;
}

CLR_INLINE void bin_run_add(BinRun* run, int4 r, uint s, __constant FrameParams* params,
                            __global const uint* tileOffset, __global uint* tileCursor, __global uint* binEntries)
{
  if (run->length > 0 && !bin_same_range(r, run->range)) bin_run_end(run, params, tileOffset, tileCursor, binEntries);
  run->range = r;
  run->setupIndex[run->length++] = s;
}

#endif /* !CLR_EXTRAS */

#endif /* CLR_BIN_H */
