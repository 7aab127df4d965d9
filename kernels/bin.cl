/* bin.cl — stage 4: binning screen triangles into CLR_TILE_SIZE² tiles.
 *
 * Two passes with a scan between them, so memory follows the actual counts
 * and no triangle is ever dropped. The passes ride on setup's (setup.cl):
 * setup_triangles' count pass adds one to every tile an unclipped
 * triangle's pixel bounds touch (bin_count_tiles) while it counts screen
 * triangles, and setup_clip does the same for the sub-triangles it writes;
 * the host scans the tile counts into offsets, sizes binEntries from the
 * total and gives each non-empty tile its block of the visibility buffer
 * (host bin.cpp, shared.h); then the emit pass writes each unclipped
 * triangle's record and its bin entries in one go (bin_fill_tiles), and
 * bin_fill_clipped fills the entries of the clipped triangles' records.
 * Fusing the passes this way saves reading every setup record twice more.
 * Both group their atomic adds where a mesh is coherent: the count pass
 * tallies one- and two-tile triangles for the two tiles it counted last
 * (bin_tally), the emit pass takes one add for a run of one-tile triangles
 * in one tile (bin_fill_run), and both take one add per tile for a run of
 * triangles on one range of several tiles (bin_count_range_run,
 * bin_fill_range_run). The order inside a tile is
 * not deterministic; the raster kernel breaks depth ties by setup index,
 * which is input order. With hierarchical traversal (FrameParams.traversal)
 * a tile of the bounds is skipped when all of it lies strictly outside one
 * edge: the edge function is linear, so its largest value over the tile's
 * rectangle is at a corner, and a negative maximum leaves every sample of
 * the tile outside, whatever the fill rule.
 */

/* Floor and ceiling of a / CLR_FIXED_ONE for signed a. */
CLR_INLINE int fixed_floor(int a)
{
  return a >> CLR_SUBPIXEL_BITS;
}
CLR_INLINE int fixed_ceil(int a)
{
  return (a + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS;
}

/* Inclusive pixel range that can hold a sample of the triangle, clamped to
 * the viewport: pixel i's samples lie at i·ONE + HALF + offset with the
 * offset in [sampleMin, sampleMax] (FrameParams), so with one sample at the
 * centre this is the range of pixel centres (i + 0.5) in the bounds. Empty
 * when x0 > x1 or y0 > y1. setup_make computes the same in lane types. */
CLR_INLINE int4 bin_pixel_bounds(const TriSetup* t, __constant FrameParams* params)
{
  const int4 b = CLR_RECORD_BOUNDS(*t);
  int4 r;
  r.x = max(0, fixed_ceil(b.x - CLR_FIXED_HALF - params->sampleMaxX));
  r.y = max(0, fixed_ceil(b.y - CLR_FIXED_HALF - params->sampleMaxY));
  r.z = min((int)params->width - 1, fixed_floor(b.z - CLR_FIXED_HALF - params->sampleMinX));
  r.w = min((int)params->height - 1, fixed_floor(b.w - CLR_FIXED_HALF - params->sampleMinY));
  return r;
}

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
    const long bias = CLR_EDGE_HOLDS_SAMPLES(t->x[a], t->y[a], t->x[b], t->y[b]) ? 1 : 0;  // the fill rule (fixed.h)
    inside = inside && min(min(c00, c10), min(c01, c11)) + bias > 0;
  }
  return inside ? 1 : 0;
}

/* Tiles touched by a triangle's pixel bounds. */
CLR_INLINE int4 bin_tile_range(const TriSetup* t, __constant FrameParams* params)
{
  return bin_pixel_bounds(t, params) / CLR_TILE_SIZE;
}

/* True when hierarchical traversal tests triangle tiles of range r. */
CLR_INLINE bool bin_hierarchical(__constant FrameParams* params, int4 r)
{
  return params->traversal == CLR_TRAVERSAL_HIERARCHICAL && (r.z > r.x || r.w > r.y);
}

#if !CLR_EXTRAS /* binning rides on setup (the frame program) */
/* Pass 1: adds one to the count of each tile of r (the triangle's tile
 * range) that hierarchical traversal does not reject; t is read only when
 * bin_hierarchical(params, r). */
CLR_CALLED void bin_count_tiles(const TriSetup* t, int4 r, __constant FrameParams* params, __global uint* tileCount)
{
  const bool hierarchical = bin_hierarchical(params, r);
  for (int ty = r.y; ty <= r.w; ++ty)
    for (int tx = r.x; tx <= r.z; ++tx)
      if (!hierarchical || bin_tile_class(t, params, tx, ty) >= 0) atomic_inc(&tileCount[ty * params->tilesX + tx]);
}

/* True when r (a tile range) is two tiles, side by side or one above the
 * other: a small triangle across a tile edge, which the passes bin without
 * a loop (and without traversal's tile test, which a frame of bbox
 * traversal skips anyway). */
CLR_INLINE bool bin_two_tiles(__constant FrameParams* params, int4 r)
{
  return params->traversal != CLR_TRAVERSAL_HIERARCHICAL && (r.z - r.x) + (r.w - r.y) == 1;
}

/* Pass 1's counts for the one- and two-tile triangles of one setup batch
 * (CLR_LANES, setup.cl), held for the two tiles most recently counted: a
 * tile's count takes one atomic add when it leaves the pair or the batch
 * ends. Meshes are coherent: consecutive small triangles fall in one tile,
 * or in the two on either side of a tile edge, where a run of one tile
 * would take an atomic add at every crossing and one per two-tile
 * triangle's tile. Slot `front` holds the more recent tile. */
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

/* Pass 1 for a run of `count` consecutive triangles on one range r of
 * several tiles under bbox traversal: one atomic add per tile for the whole
 * run. Large triangles come in such runs where a mesh is made of quads (the
 * two halves of a wall share their tiles). */
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

/* Pass 2's run of consecutive triangles (setup indices, at most one batch)
 * on one tile range: one tile (bin_fill_run), or several under bbox
 * traversal (bin_fill_range_run). bin_run_add writes the run out when the
 * next triangle's range differs; bin_run_end writes what is left. */
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

/* Pass 2 for clipped triangles: their records lie in CLR_MAX_SUBTRIS
 * reserved slots from clipList[i] (setup_clip put the first record's index
 * there); one work-item per slot. Each writes its record's source word,
 * its ClipBary slot, and bins it unless the slot is padding. */
__kernel void bin_fill_clipped(__constant FrameParams* params, __global const TriSetup* setup,
                               __global const ClipBary* clipBary,  // CLR_MAX_SUBTRIS · numClipped
                               __global uint* source,              // numSetup: the records' source words
                               __global const uint* clipList,      // numClipped: first records
                               uint numClipped,                    // clipList entries
                               __global const uint* tileOffset,    // tiles + 1, scanned
                               __global uint* tileCursor,          // tiles
                               __global uint* binEntries)          // tileOffset[tiles]
{
  const uint i = get_global_id(0);
  if (i >= numClipped * CLR_MAX_SUBTRIS) return;
  const uint s = clipList[i / CLR_MAX_SUBTRIS] + i % CLR_MAX_SUBTRIS;
  source[s] = CLR_SOURCE_CLIPPED | i;
  if (clipBary[i].flags & CLR_FLAG_DEAD) return;
  const TriSetup t = setup[s];
  bin_fill_tiles(&t, bin_tile_range(&t, params), s, params, tileOffset, tileCursor, binEntries);
}
#endif
