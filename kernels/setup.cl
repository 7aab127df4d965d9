/* setup.cl — stage 3: triangle setup: count, scan, emit.
 *
 * Per input triangle: transform (transform.cl), cull non-finite and trivially outside, clip near-plane and
 * guard-band crossers (clip.h), viewport (x_s = x_ndc·W/2 + W/2, y up), snap to CLR_SUBPIXEL_BITS, exact 64-bit
 * doubled area, cull zero-area, back-facing (if asked) and sample-free, orient counter-clockwise.
 * setup_triangles is one kernel run as two passes (one compile). Pass 1 (count) writes 0 or 1 screen triangles per
 * input, or reserves CLR_MAX_SUBTRIS and lists it for setup_clip. The scan lists each record's input triangle
 * (setupSource); setup_clip fills reserved records (unused ones CLR_FLAG_DEAD); pass 2 (emit) redoes the unclipped
 * survivors over the records, not the input, writing records and winding in input order whatever the scheduling.
 * CLR_LANES triangles per work-item (lanes.h); clipping is its own scalar kernel. Binning (bin.h) rides along.
 */
#pragma OPENCL FP_CONTRACT OFF
#include "transform.h"
#include "clip.h"
#include "bin.h"
#include "micro.h"
#if !CLR_EXTRAS /* the frame program (CLR_EXTRAS, shared.h) */

/* CLR_LANES triangles' clip-space vertices, one lane per triangle. */
typedef struct ClipBatch {
  floatL x[3], y[3], z[3], w[3];
} ClipBatch;

/* CLR_LANES screen triangles, one lane per triangle (TriSetup, transposed). */
typedef struct SetupBatch {
  intL x[3], y[3];
  floatL z[3];
  intL back;                            // mask: wound clockwise, vertices 1 and 2 swapped
  intL tileX0, tileY0, tileX1, tileY1;  // tiles of the pixel bounds (bin_tile_range)
  intL pixels;                          // pixel positions in the bounds, at most 64² (micro_lane)
} SetupBatch;

/* The same, unpacked to arrays so single lanes can be read. */
typedef struct SetupLanes {
  int x[3][CLR_LANES], y[3][CLR_LANES];
  float z[3][CLR_LANES];
  int back[CLR_LANES];
  int tileX0[CLR_LANES], tileY0[CLR_LANES], tileX1[CLR_LANES], tileY1[CLR_LANES];
  int pixels[CLR_LANES];
} SetupLanes;

/* How an input triangle is handled. */
#define CLR_SETUP_CULLED 0u
#define CLR_SETUP_SIMPLE 1u
#define CLR_SETUP_CLIP 2u

/* Loads and transforms (transform.cl) triangles tri[0 .. CLR_LANES − 1]; with 16 lanes swizzles transpose each
 * vertex's positions. All 48 loads come first: PoCL passes them through the stack, and a wide load of narrow stores
 * still in flight stalls the CPU. */
CLR_INLINE void setup_load_batch(const uint* tri, __constant FrameParams* params, __global const float* positions,
                                 __global const uint* indices, ClipBatch* c)
{
#if CLR_LANES > 1
  // One 16-byte load per vertex: x, y, z and the next x (unused; the host pads the buffer by one float).
  float4 loaded[3][CLR_LANES];
  for (int v = 0; v < 3; ++v)
    for (int lane = 0; lane < CLR_LANES; ++lane)
      loaded[v][lane] = vload4(0, positions + CLR_POSITION_STRIDE * indices[3 * tri[lane] + v]);
#endif
  for (int v = 0; v < 3; ++v) {
#if CLR_LANES == 1
    const float4 q = transform_vertex(params, positions, indices[3 * tri[0] + v]);
    c->x[v] = q.x;
    c->y[v] = q.y;
    c->z[v] = q.z;
    c->w[v] = q.w;
#else
    const float4* q = loaded[v];
    const float16 a = (float16)(q[0], q[1], q[2], q[3]), b = (float16)(q[4], q[5], q[6], q[7]);
    const float16 d = (float16)(q[8], q[9], q[10], q[11]), e = (float16)(q[12], q[13], q[14], q[15]);
    const float16 px = (float16)(a.s048c, b.s048c, d.s048c, e.s048c);
    const float16 py = (float16)(a.s159d, b.s159d, d.s159d, e.s159d);
    const float16 pz = (float16)(a.s26ae, b.s26ae, d.s26ae, e.s26ae);
#if CLR_CLIP_INPUT
    c->x[v] = px;
    c->y[v] = py;
    c->z[v] = pz;
    c->w[v] = (float16)(a.s37bf, b.s37bf, d.s37bf, e.s37bf);
#else
    c->x[v] = transform_lanes(params, 0, px, py, pz);
    c->y[v] = transform_lanes(params, 1, px, py, pz);
    c->z[v] = transform_lanes(params, 2, px, py, pz);
    c->w[v] = transform_lanes(params, 3, px, py, pz);
#endif
#endif
  }
}

/* Every lane set to one triangle's clip positions. */
CLR_INLINE void setup_broadcast(const float4* c, ClipBatch* b)
{
  for (int v = 0; v < 3; ++v) {
    b->x[v] = (floatL)(c[v].x);
    b->y[v] = (floatL)(c[v].y);
    b->z[v] = (floatL)(c[v].z);
    b->w[v] = (floatL)(c[v].w);
  }
}

/* clip_outcode (clip.h) of one vertex per lane, the same expressions. */
CLR_INLINE uintL setup_outcode(floatL x, floatL y, floatL z, floatL w, float gx, float gy, float nearSign)
{
  const uintL zero = 0;
  const intL beyondFar = nearSign < 0.0f ? (intL)(z < 0.0f) : (intL)(z > w);
  return select(zero, (uintL)1u, nearSign * z + w < 0.0f) | select(zero, (uintL)2u, x + gx * w < 0.0f) |
         select(zero, (uintL)4u, gx * w - x < 0.0f) | select(zero, (uintL)8u, y + gy * w < 0.0f) |
         select(zero, (uintL)16u, gy * w - y < 0.0f) | select(zero, (uintL)32u, x < -w) |
         select(zero, (uintL)64u, x > w) | select(zero, (uintL)128u, y < -w) | select(zero, (uintL)256u, y > w) |
         select(zero, (uintL)512u, beyondFar);
}

/* Where cluster bounds lie against setup_classify's planes (setup_cluster_place). */
#define CLR_CLUSTER_MIXED 0u
#define CLR_CLUSTER_OUTSIDE 1u /* wholly outside one plane it culls by: every triangle culled */
#define CLR_CLUSTER_INSIDE 2u  /* wholly inside every plane it tests: every finite triangle CLR_SETUP_SIMPLE */

#if CLR_LANES > 1 && !CLR_CLIP_INPUT
/* Where cluster bounds b (CLR_CLUSTER_TRIS) lie: the count pass skips an outside cluster unloaded, and takes every
 * triangle of an inside one as simple without classifying it (the host's bounds are NaN where a vertex is not
 * finite, device_scene.cpp). Clip coordinates are affine, so the box's extremes are at its 8 corners (lanes 0-7,
 * again 8-15). Margin m = clusterMargin = 2^-16 M, M the largest sum of term magnitudes of a vertex's clip
 * coordinates: transform rounding is below 2^-21 M and a plane's sum adds less, so a corner outside (inside) by m
 * puts every vertex's computed outcode bit at 1 (0); the guard planes scale w by g, so their margin is (1 + g)·m.
 * A NaN bound is mixed. */
CLR_INLINE uint setup_cluster_place(__constant FrameParams* params, __global const float* b)
{
  // Step 1: the corners' clip coordinates.
  const intL lane = CLR_LANE_INDEX;
  const floatL px = select((floatL)b[0], (floatL)b[3], (lane & 1) != 0);
  const floatL py = select((floatL)b[1], (floatL)b[4], (lane & 2) != 0);
  const floatL pz = select((floatL)b[2], (floatL)b[5], (lane & 4) != 0);
  const floatL x = transform_lanes(params, 0, px, py, pz), y = transform_lanes(params, 1, px, py, pz);
  const floatL z = transform_lanes(params, 2, px, py, pz), w = transform_lanes(params, 3, px, py, pz);
  // Step 2: each corner's outside-by-margin planes as bits (NaN sets none); a bit in every lane culls.
  const float m = params->clusterMargin, nearSign = clip_near_sign(params->depthMode);
  const uintL zero = 0;
  const floatL nearSum = nearSign * z + w, farSum = nearSign < 0.0f ? z : w - z;
  const uintL code = select(zero, (uintL)1u, nearSum < -m) | select(zero, (uintL)2u, x + w < -m) |
                     select(zero, (uintL)4u, x - w > m) | select(zero, (uintL)8u, y + w < -m) |
                     select(zero, (uintL)16u, y - w > m) | select(zero, (uintL)32u, farSum < -m);
  if (clr_and_lanes(code) != 0) return CLR_CLUSTER_OUTSIDE;
  // Step 3: inside when every corner is inside every plane by its margin (NaN fails).
  const float gx = params->guardX, gy = params->guardY, mx = (1.0f + gx) * m, my = (1.0f + gy) * m;
  const intL in = (nearSum > m) & (farSum > m) & (x + w > m) & (w - x > m) & (y + w > m) & (w - y > m) &
                  (x + gx * w > mx) & (gx * w - x > mx) & (y + gy * w > my) & (gy * w - y > my);
  return CLR_ANY(in == 0) ? CLR_CLUSTER_MIXED : CLR_CLUSTER_INSIDE;
}
#endif

/* Each lane: CLR_SETUP_CULLED (non-finite, outside one viewport plane or the near plane), _CLIP or _SIMPLE. */
CLR_INLINE uintL setup_classify(const ClipBatch* c, __constant FrameParams* params)
{
  intL finite = isfinite(c->w[0]);
  uintL all = ~(uintL)0, any = 0;
  for (int v = 0; v < 3; ++v) {
    finite = finite & isfinite(c->x[v]) & isfinite(c->y[v]) & isfinite(c->z[v]) & isfinite(c->w[v]);
    const uintL code = setup_outcode(c->x[v], c->y[v], c->z[v], c->w[v], params->guardX, params->guardY,
                                     clip_near_sign(params->depthMode));
    all &= code;
    any |= code;
  }
  const intL culled = CLR_NOT(finite) | ((all & (1u | (0x1Fu << 5))) != 0);
  const uintL kind = select((uintL)CLR_SETUP_SIMPLE, (uintL)CLR_SETUP_CLIP, (any & 0x1Fu) != 0);
  return select(kind, (uintL)CLR_SETUP_CULLED, culled);
}

/* Whether each lane's oriented triangle covers a pixel centre; tested only for small ones (<= 2×2 centres in
 * x0..xEnd, y0..yEnd, vertices < 4 px apart), larger ones count as covering. Raster's test (integer edge functions,
 * fill rule, one sample: cullSampleFree), so a culled triangle is one raster would find in no sample. 32 bits are
 * exact here: tested centres lie in the vertex bounds, factors < 4·CLR_FIXED_ONE = 2^10, |E| < 2^21 (other lanes may
 * wrap, unsigned, and are discarded). Tiny triangles between centres are much of a distant dense mesh; culling
 * saves their records, bins and raster work. Called, not inlined, to keep setup's compile short. */
CLR_CALLED intL setup_covers_a_sample(const SetupBatch* t, intL minX, intL maxX, intL minY, intL maxY, intL x0, intL y0,
                                      intL xEnd, intL yEnd, __constant FrameParams* params)
{
  // Both masks are comparisons: Oclgrind reads a negated mask of this shape as 1, not −1, which select() rejects.
  const intL small =
      (xEnd - x0 <= 1) & (yEnd - y0 <= 1) & (maxX - minX < 4 * CLR_FIXED_ONE) & (maxY - minY < 4 * CLR_FIXED_ONE);
  const intL large =
      (xEnd - x0 > 1) | (yEnd - y0 > 1) | (maxX - minX >= 4 * CLR_FIXED_ONE) | (maxY - minY >= 4 * CLR_FIXED_ONE);
  if (!CLR_ANY(small)) return large;
  // Step 1: which of the up to four centres (x0 + col, y0 + row) lie in the bounds.
  intL in00 = (x0 <= xEnd) & (y0 <= yEnd), in10 = in00 & (x0 + 1 <= xEnd);
  intL in01 = in00 & (y0 + 1 <= yEnd), in11 = in10 & in01;
  // Step 2: edge i (vertex i + 1 to i + 2, as raster) E = dx·(py − ay) − dy·(px − ax) at the first centre, then
  // stepped by −dy·ONE a column, dx·ONE a row (same ints mod 2^32); inside where E > low (−1 if the fill rule holds).
  const intL px = x0 * CLR_FIXED_ONE + (CLR_FIXED_HALF + params->sampleX[0]);
  const intL py = y0 * CLR_FIXED_ONE + (CLR_FIXED_HALF + params->sampleY[0]);
  for (int i = 0; i < 3; ++i) {
    const int a = (i + 1) % 3, b = (i + 2) % 3;
    const uintL dx = as_uintL(t->x[b] - t->x[a]), dy = as_uintL(t->y[b] - t->y[a]);
    const intL low = select((intL)0, (intL)(-1), CLR_EDGE_HOLDS_SAMPLES(t->x[a], t->y[a], t->x[b], t->y[b]));
    const uintL e00 = dx * as_uintL(py - t->y[a]) - dy * as_uintL(px - t->x[a]);
    const uintL e01 = e00 + dx * CLR_FIXED_ONE, column = dy * CLR_FIXED_ONE;
    in00 = in00 & (as_intL(e00) > low);
    in10 = in10 & (as_intL(e00 - column) > low);
    in01 = in01 & (as_intL(e01) > low);
    in11 = in11 & (as_intL(e01 - column) > low);
  }
  return large | in00 | in10 | in01 | in11;
}

/* Each lane's screen triangle: viewport, snap, exact doubled area, orientation, pixel bounds. Returns the survivors
 * (w > 0, non-zero area, not back-face culled, a centre in the bounds, with testCoverage setup_covers_a_sample). */
CLR_INLINE intL setup_make(const ClipBatch* c, __constant FrameParams* params, SetupBatch* out, bool testCoverage,
                           intL row)
{
  // Step 1: viewport and snapping. Window depth z_ndc/2 + 1/2 (GL), or z_ndc when reversed (clip z spans [0, w]).
  intL valid = (c->w[0] > 0.0f) & (c->w[1] > 0.0f) & (c->w[2] > 0.0f);
  const bool reversed = params->depthMode == CLR_DEPTH_REVERSED;
  for (int v = 0; v < 3; ++v) {
    const floatL invW = 1.0f / c->w[v];
    const floatL xs = c->x[v] * invW * params->halfWidth + params->halfWidth;
    const floatL ys = c->y[v] * invW * params->halfHeight + params->halfHeight;
    out->z[v] = reversed ? c->z[v] * invW : c->z[v] * invW * 0.5f + 0.5f;
    out->x[v] = convert_intL(clr_rint(xs * (float)CLR_FIXED_ONE));  // = convert_intL_rte, cheaper (lanes.h)
    out->y[v] = convert_intL(clr_rint(ys * (float)CLR_FIXED_ONE)) + row * CLR_FIXED_ONE;  // row: clr_image_row
  }
  // Step 2: exact doubled signed area; cull zero and (optionally) back faces.
  const longL area2 = clr_area2L(out->x[0], out->y[0], out->x[1], out->y[1], out->x[2], out->y[2]);
  const intL back = convert_intL(area2 < 0);
  valid = valid & convert_intL(area2 != 0) & CLR_NOT(params->cullBack ? back : (intL)0);
  // Step 3: orient counter-clockwise by swapping vertices 1 and 2.
  const intL x1 = out->x[1], y1 = out->y[1];
  const floatL z1 = out->z[1];
  out->x[1] = select(x1, out->x[2], back);
  out->x[2] = select(out->x[2], x1, back);
  out->y[1] = select(y1, out->y[2], back);
  out->y[2] = select(out->y[2], y1, back);
  out->z[1] = select(z1, out->z[2], back);
  out->z[2] = select(out->z[2], z1, back);
  out->back = back;
  // Step 4: cull bounds holding no sample (as bin_pixel_bounds); keep the bounds' tiles for binning.
  const intL minX = min(out->x[0], min(out->x[1], out->x[2])), maxX = max(out->x[0], max(out->x[1], out->x[2]));
  const intL minY = min(out->y[0], min(out->y[1], out->y[2])), maxY = max(out->y[0], max(out->y[1], out->y[2]));
  const intL x0 = max((minX - (CLR_FIXED_HALF + params->sampleMaxX) + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS, (intL)0);
  const intL y0 = max((minY - (CLR_FIXED_HALF + params->sampleMaxY) + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS, row);
  const intL xEnd =
      min((maxX - (CLR_FIXED_HALF + params->sampleMinX)) >> CLR_SUBPIXEL_BITS, (intL)((int)params->width - 1));
  const intL yEnd =
      min((maxY - (CLR_FIXED_HALF + params->sampleMinY)) >> CLR_SUBPIXEL_BITS, row + (int)params->imageHeight - 1);
  valid = valid & (x0 <= xEnd) & (y0 <= yEnd);
  out->tileX0 = x0 / CLR_TILE_SIZE;
  out->tileY0 = y0 / CLR_TILE_SIZE;
  out->tileX1 = xEnd / CLR_TILE_SIZE;
  out->tileY1 = yEnd / CLR_TILE_SIZE;
  out->pixels = clamp(xEnd - x0 + 1, (intL)0, (intL)64) * clamp(yEnd - y0 + 1, (intL)0, (intL)64);
  // Step 5: a small triangle that covers none of its pixel centres.
  if (testCoverage && params->cullSampleFree)
    valid = valid & setup_covers_a_sample(out, minX, maxX, minY, maxY, x0, y0, xEnd, yEnd, params);
  return valid;
}

CLR_INLINE void setup_unpack(const SetupBatch* b, SetupLanes* l)
{
  for (int v = 0; v < 3; ++v) {
    CLR_STORE_LANES(b->x[v], l->x[v]);
    CLR_STORE_LANES(b->y[v], l->y[v]);
    CLR_STORE_LANES(b->z[v], l->z[v]);
  }
  CLR_STORE_LANES(b->back, l->back);
  CLR_STORE_LANES(b->tileX0, l->tileX0);
  CLR_STORE_LANES(b->tileY0, l->tileY0);
  CLR_STORE_LANES(b->tileX1, l->tileX1);
  CLR_STORE_LANES(b->tileY1, l->tileY1);
  CLR_STORE_LANES(b->pixels, l->pixels);
}

/* One lane as a TriSetup, field by field into *t: a returned struct leaves a marker Oclgrind cannot run, and a
 * private record copied whole stalls the CPU (wide load after narrow stores). */
#define CLR_SETUP_LANE(l, lane, t) \
  do {                             \
    for (int v = 0; v < 3; ++v) {  \
      (t)->x[v] = (l)->x[v][lane]; \
      (t)->y[v] = (l)->y[v][lane]; \
      (t)->z[v] = (l)->z[v][lane]; \
    }                              \
  } while (0)
CLR_INLINE void setup_lane(const SetupLanes* l, int lane, TriSetup* t)
{
  CLR_SETUP_LANE(l, lane, t);
}
CLR_INLINE void setup_lane_store(const SetupLanes* l, int lane, __global TriSetup* t)
{
  CLR_SETUP_LANE(l, lane, t);
}

/* One lane's tile range (bin_tile_range). */
CLR_INLINE int4 setup_lane_tiles(const SetupLanes* l, int lane)
{
  return (int4)(l->tileX0[lane], l->tileY0[lane], l->tileX1[lane], l->tileY1[lane]);
}

/* The micro path's arguments (micro.h): microMax 0 is off. */
typedef struct SetupMicro {
  uint microMax;
  uint microCap;                   // count: the micro slots microKey holds
  __global uint* tileMicro;        // tiles, zeroed: count claims slots, emit reads them
  __global ulong* microKey;        // emit: all CLR_MICRO_CLEAR
  __global uint* microRecord;      // emit: the setup index of each paint rank (not in the file's order)
  __global const uint* paintRank;  // emit: each triangle's rank in the file (not in the file's order)
  uint lastTile;                   // count: the work-item's last claimed tile and its outcome (micro_claim_tile)
  bool lastSlotted;
} SetupMicro;

/* Pass 1 for CLR_LANES triangles from `first`: screen triangles each yields (triCount) and the unclipped ones'
 * tiles (one- and two-tile ones tallied by bin_tally). Returns clipped lanes as bits of *clipMask. Culls are not
 * counted here: the host derives them from the scan total, sparing a shared atomic counter. */
CLR_INLINE void setup_count_lanes(__constant FrameParams* params, uint first, const uint* counts, const SetupLanes* l,
                                  __global uchar* triCount, __global uint* tileCount, uint* clipMask, SetupMicro* micro,
                                  __global uint* counters)
{
  // Step 1: the counts, branch-free, and the mask of unclipped survivors.
  uint survivors = 0;
  for (uint lane = 0; lane < CLR_LANES && first + lane < params->numTris; ++lane) {
    triCount[first + lane] = (uchar)counts[lane];
    *clipMask |= (counts[lane] == CLR_MAX_SUBTRIS ? 1u : 0u) << lane;
    survivors |= (counts[lane] == 1 ? 1u : 0u) << lane;
  }
  // Step 2: the survivors' tiles, visited by their bits: culls are unpredictable, so a branch per lane costs more.
  BinTally tally;
  bin_tally_init(&tally);
  int4 rangeRun = (int4)(0);
  uint rangeRunLength = 0;
  while (survivors) {
    const uint lane = 31 - clz(survivors & (0u - survivors));  // the lowest set bit
    survivors &= survivors - 1;
    const int4 r = setup_lane_tiles(l, lane);
    if (micro_lane(micro->microMax, r, l->pixels[lane]) &&
        micro_claim_tile(r.y * params->tilesX + r.x, &micro->lastTile, &micro->lastSlotted, micro->microCap,
                         micro->tileMicro, tileCount, counters))
      continue;
    const bool one = r.x == r.z && r.y == r.w;
    if (one || bin_two_tiles(params, r)) {
      bin_tally_add(&tally, r.y * params->tilesX + r.x, tileCount);
      if (!one) bin_tally_add(&tally, r.w * params->tilesX + r.z, tileCount);
      continue;
    }
    if (bin_hierarchical(params, r)) {
      TriSetup t;  // for traversal's tile test
      setup_lane(l, lane, &t);
      bin_count_tiles(&t, r, params, tileCount);
      continue;
    }
    // Several tiles, bbox traversal: runs on one range (bin_count_range_run).
    if (rangeRunLength > 0 && !bin_same_range(r, rangeRun)) {
      bin_count_range_run(rangeRun, rangeRunLength, params, tileCount);
      rangeRunLength = 0;
    }
    rangeRun = r;
    ++rangeRunLength;
  }
  if (rangeRunLength > 0) bin_count_range_run(rangeRun, rangeRunLength, params, tileCount);
  bin_tally_end(&tally, tileCount);
}

/* Pass 1 for CLR_LANES triangles from `first` none of which yields a screen triangle: zero counts, no tiles. */
CLR_INLINE void setup_count_none(__constant FrameParams* params, uint first, __global uchar* triCount)
{
  for (uint lane = 0; lane < CLR_LANES && first + lane < params->numTris; ++lane) triCount[first + lane] = 0;
}

/* Pass 2 for the same lanes: writes the `write` lanes' records, their winding into the source words, and their bin
 * entries; runs on one tile range take one atomic add per tile (BinRun, bin.h), two-tile triangles one per tile. */
CLR_INLINE void setup_emit_lanes(__constant FrameParams* params, uint first, const uint* tri, const int* write,
                                 const SetupLanes* l, __global TriSetup* setup, __global uint* source,
                                 __global const uint* tileOffset, __global uint* tileCursor, __global uint* binEntries,
                                 const SetupMicro* micro)
{
  BinRun oneTile, range;  // runs of one-tile triangles; of triangles on one range of several tiles
  oneTile.length = range.length = 0;
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    if (!write[lane]) continue;
    const uint s = first + lane;
    setup_lane_store(l, lane, &setup[s]);
    source[s] = tri[lane] | (l->back[lane] ? CLR_SOURCE_BACKFACING : 0u);
    const int4 r = setup_lane_tiles(l, lane);
#if CLR_MICRO_ATOMICS
    const bool microLane = micro_lane(micro->microMax, r, l->pixels[lane]);
    const uint microWord = microLane ? micro->tileMicro[r.y * params->tilesX + r.x] : 0u;
    if (micro_slotted(microWord)) {
      TriSetup t;
      setup_lane(l, lane, &t);
      const uint order = params->fileOrder ? s : micro->paintRank[tri[lane]];
      if (!params->fileOrder) micro->microRecord[order] = s;
      micro_emit(params, &t, order, bin_pixel_bounds(&t, params, clr_image_row(params, tri[lane])), microWord,
                 micro->microKey);
      continue;
    }
#endif
    if (bin_two_tiles(params, r)) {
      bin_fill_two_tiles(r, s, params, tileOffset, tileCursor, binEntries);
    } else if (bin_hierarchical(params, r)) {
      TriSetup t;  // for traversal's tile test
      setup_lane(l, lane, &t);
      bin_fill_tiles(&t, r, s, params, tileOffset, tileCursor, binEntries);
    } else if (r.x == r.z && r.y == r.w) {
      bin_run_add(&oneTile, r, s, params, tileOffset, tileCursor, binEntries);
    } else {
      bin_run_add(&range, r, s, params, tileOffset, tileCursor, binEntries);
    }
  }
  bin_run_end(&oneTile, params, tileOffset, tileCursor, binEntries);
  bin_run_end(&range, params, tileOffset, tileCursor, binEntries);
}

/* Body of setup_triangles for work-item `item`'s CLR_LANES triangles, `pass` CLR_SETUP_PASS_COUNT then (after the
 * scans) CLR_SETUP_PASS_EMIT. Pass 1 writes triCount and tileCount; pass 2 reads them scanned. */
CLR_KERNEL_BODY void setup_triangles_body(__constant FrameParams* params, __global const float* positions,
                                          __global const uint* indices, __global uchar* triCount,
                                          __global uint* counters, __global uint* clipList, uint clipListCapacity,
                                          __global uint* tileCount, __global TriSetup* setup, __global uint* tileCursor,
                                          __global uint* binEntries, __global uint* source, uint numSetup, uint pass,
                                          SetupMicro* micro, uint item, bool inside)
{
  // Step 1: pass 1 input triangles from `first`; pass 2 the sources of records from `first` (lanes of clipped
  // records and past the end are not written).
  const uint first = item * CLR_LANES;
  const bool emit = pass == CLR_SETUP_PASS_EMIT;
  // A speculative frame launches emit over its capacity: the records end at the scan's total, and a frame that does
  // not fit emits nothing (scan.cl, scan_frame_fits).
  if (emit && counters[CLR_COUNTER_OVERFLOW]) return;
  if (emit) numSetup = min(numSetup, counters[CLR_COUNTER_SETUP_TOTAL]);
  if (first >= (emit ? numSetup : params->numTris)) return;
  uint tri[CLR_LANES], from[CLR_LANES];
  if (emit) {
    for (uint lane = 0; lane < CLR_LANES; ++lane)
      from[lane] = first + lane < numSetup ? source[first + lane] : CLR_NONE;
    // (a clipped triangle's records, CLR_SOURCE_CLIPPED, are setup_clip's)
    for (uint lane = 0; lane < CLR_LANES; ++lane) tri[lane] = from[lane] < CLR_SOURCE_CLIPPED ? from[lane] : 0;
  } else {
    for (uint lane = 0; lane < CLR_LANES; ++lane) tri[lane] = min(first + lane, params->numTris - 1);
  }
  ClipBatch c;
  setup_load_batch(tri, params, positions, indices, &c);
  // Pass 2 does not classify again: its sources are pass 1's simple survivors, or clipped records it skips. Nor
  // does pass 1 in a cluster inside the view (setup_cluster_place).
  const uintL kind = emit || inside ? (uintL)CLR_SETUP_SIMPLE : setup_classify(&c, params);
  // Pass 1 stops early, before setup_make, when every lane is culled (a batch beside the view).
  if (!emit && !CLR_ANY(kind != CLR_SETUP_CULLED)) {
    setup_count_none(params, first, triCount);
    return;
  }
  SetupBatch b;
  int rows[CLR_LANES] = {0};  // each lane's image row (clr_image_row), all 0 unless batched
  for (uint lane = 0; params->imageTris && lane < CLR_LANES; ++lane) rows[lane] = clr_image_row(params, tri[lane]);
  const intL made = setup_make(&c, params, &b, !emit, CLR_LOAD_LANES(rows));  // emit's sources passed pass 1's test
  const intL simple = made & (kind == CLR_SETUP_SIMPLE);
  if (!emit && !CLR_ANY(simple | (kind == CLR_SETUP_CLIP))) {
    setup_count_none(params, first, triCount);
    return;
  }
#if CLR_LANES > 1
  // Step 2 (pass 1) for a whole batch, none clipped, whose survivors lie in one or two tiles each and two in all, as
  // a dense mesh's small triangles often do: their counts and an add to each tile's count, without walking the lanes
  // (as setup_count_lanes: a survivor counts in its one tile, or in both of bin_two_tiles's).
  if (!emit && micro->microMax == 0 && first + CLR_LANES <= params->numTris && !CLR_ANY(kind == CLR_SETUP_CLIP)) {
    const intL tileA = b.tileY0 * (int)params->tilesX + b.tileX0, tileB = b.tileY1 * (int)params->tilesX + b.tileX1;
    const intL one = tileA == tileB;
    const intL two = ((b.tileX1 - b.tileX0) + (b.tileY1 - b.tileY0) == 1) &
                     (intL)(params->traversal != CLR_TRAVERSAL_HIERARCHICAL ? -1 : 0);
    // (tileA <= tileB: the range's first and last tile)
    const int lo = clr_min_lanes_int(select((intL)INT_MAX, tileA, simple));
    const int hi = clr_max_lanes_int(select((intL)INT_MIN, tileB, simple));
    const intL inPair = ((tileA == lo) | (tileA == hi)) & ((tileB == lo) | (tileB == hi));
    if (!CLR_ANY(simple & ((one | two) == 0)) && !CLR_ANY(simple & (inPair == 0))) {
      vstore16(convert_uchar16(simple & 1), 0, triCount + first);
      // (a two-tile survivor's tiles are then lo and hi)
      atomic_add(&tileCount[lo], popcount(clr_lane_mask(simple & (tileA == lo))));
      if (hi != lo) atomic_add(&tileCount[hi], popcount(clr_lane_mask(simple & (tileB == hi))));
      return;
    }
  }
#endif
  SetupLanes l;
  setup_unpack(&b, &l);
  // Step 2 (pass 2): emit; the same arithmetic as pass 1, so every valid lane is a simple survivor.
  if (emit) {
    int write[CLR_LANES];
    CLR_STORE_LANES(simple, write);
    for (uint lane = 0; lane < CLR_LANES; ++lane) write[lane] = write[lane] && from[lane] < CLR_SOURCE_CLIPPED;
    setup_emit_lanes(params, first, tri, write, &l, setup, source, tileCount, tileCursor, binEntries, micro);
    return;
  }
  // Step 2 (pass 1): count; then the counters and the clip list (scheduling order; its output places are not).
  const uintL count = select(select((uintL)0u, (uintL)1u, simple), (uintL)CLR_MAX_SUBTRIS, kind == CLR_SETUP_CLIP);
  uint counts[CLR_LANES], clipMask = 0;
  CLR_STORE_LANES(count, counts);
  setup_count_lanes(params, first, counts, &l, triCount, tileCount, &clipMask, micro, counters);
  if (!clipMask) return;
  uint slot = atomic_add(&counters[CLR_COUNTER_CLIPPED_TRIS], popcount(clipMask));
  for (uint lane = 0; lane < CLR_LANES; ++lane)
    if (clipMask & (1u << lane)) {
      if (slot < clipListCapacity) clipList[slot] = first + lane;
      ++slot;
    }
}

__kernel __attribute__((reqd_work_group_size(CLR_SETUP_GROUP(CLR_LANES), 1, 1))) void setup_triangles(
    __constant FrameParams* params,
    __global const float* positions,  // 3·numVerts
    __global const uint* indices,     // 3·numTris
    __global uchar* triCount,         // numTris
    __global uint* counters,          // CLR_NUM_COUNTERS
    __global uint* clipList,          // clipListCapacity
    uint clipListCapacity,
    __global uint* tileCount,   // tiles + 1
    __global TriSetup* setup,   // pass 2: numSetup
    __global uint* tileCursor,  // pass 2: tiles, zeroed
    __global uint* binEntries,  // pass 2: tileOffset[tiles]
    __global uint* source,      // pass 2: numSetup (the scan lists them; winding added)
    uint numSetup, uint pass,
    __global const float* clusterBounds,  // pass 1, CPU work shape (a work-item per cluster): 6 · clusters
    __global uint* clusterCount,          // pass 1, CPU work shape: clusters (the listing scans them, scan.cl)
    uint microMax, uint microCap, __global uint* tileMicro, __global ulong* microKey, __global uint* microRecord,
    __global const uint* paintRank)  // SetupMicro
{
  SetupMicro micro = {microMax, microCap, tileMicro, microKey, microRecord, paintRank, CLR_NONE, false};
#if CLR_LANES > 1 && !CLR_CLIP_INPUT
  // Pass 1 in the CPU shape: a work-item per cluster, which it places once; one beside the view is skipped unloaded,
  // its total 0 and its bytes unwritten. The cluster's total is its bytes' sum.
  if (pass == CLR_SETUP_PASS_COUNT) {
    const uint cluster = get_global_id(0), first = cluster * CLR_CLUSTER_TRIS;
    if (first >= params->numTris) return;
    const uint place =
        params->clusterMargin > 0.0f ? setup_cluster_place(params, clusterBounds + 6 * cluster) : CLR_CLUSTER_MIXED;
    if (place == CLR_CLUSTER_OUTSIDE) {
      clusterCount[cluster] = 0;
      return;
    }
    CLR_NO_UNROLL
    for (uint k = 0; k < CLR_CLUSTER_TRIS / CLR_LANES; ++k)
      setup_triangles_body(params, positions, indices, triCount, counters, clipList, clipListCapacity, tileCount, setup,
                           tileCursor, binEntries, source, numSetup, pass, &micro,
                           cluster * (CLR_CLUSTER_TRIS / CLR_LANES) + k, place == CLR_CLUSTER_INSIDE);
    const uint end = min(first + CLR_CLUSTER_TRIS, params->numTris);
    uint sum = 0;
    for (uint t = first; t < end; ++t) sum += triCount[t];
    clusterCount[cluster] = sum;
    return;
  }
#endif
  setup_triangles_body(params, positions, indices, triCount, counters, clipList, clipListCapacity, tileCount, setup,
                       tileCursor, binEntries, source, numSetup, pass, &micro, get_global_id(0), false);
}

/* The lowest s with source[s] == CLR_SOURCE_CLIPPED | tri: binary search, the listing being sorted by triangle. */
CLR_INLINE uint clip_first_record(__global const uint* source, uint numSetup, uint tri)
{
  uint lo = 0, hi = numSetup;
  while (lo < hi) {
    const uint mid = lo + (hi - lo) / 2;
    if ((source[mid] & ~CLR_SOURCE_CLIPPED) < tri)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

/* Pass 3 (before the tile scan): clips the listed triangles into their reserved records and ClipBary slots (entry i
 * owns slots i·CLR_MAX_SUBTRIS + k), counts their tiles and puts the first record's index in clipList. Source words
 * are bin_fill_clipped's, after the scan: this kernel's work-items are still searching the listing. */
__kernel void setup_clip(__constant FrameParams* params,
                         __global const float* positions,  // 3·numVerts
                         __global const uint* indices,     // 3·numTris
                         __global const uint* source,      // numSetup, listed by the scan
                         uint numSetup,
                         __global uint* clipList,      // CLIPPED_TRIS counter
                         __global TriSetup* setup,     // numSetup
                         __global ClipBary* clipBary,  // CLR_MAX_SUBTRIS · CLIPPED_TRIS
                         __global uint* counters,
                         __global uint* tileCount)  // tiles + 1
{
  const uint i = get_global_id(0);
  if (i >= counters[CLR_COUNTER_CLIPPED_TRIS]) return;
  const uint tri = clipList[i];
  const uint base = clip_first_record(source, numSetup, tri);
  clipList[i] = base;
  // Step 1: clip in homogeneous space against the planes a vertex is outside.
  ClipVertex poly[CLR_MAX_CLIP_VERTS];
  uint planes = 0;
  const float nearSign = clip_near_sign(params->depthMode);
  for (int v = 0; v < 3; ++v) {
    poly[v].pos = transform_vertex(params, positions, indices[3 * tri + v]);
    poly[v].bary = (float3)((float)(v == 0), (float)(v == 1), (float)(v == 2));
    planes |= clip_outcode(poly[v].pos, params->guardX, params->guardY, nearSign) & 0x1Fu;
  }
  const int n = clip_polygon(poly, 3, planes, params->guardX, params->guardY, nearSign);
  // Step 2: fan the polygon; set up and write each surviving triangle.
  uint count = 0;
  for (int k = 1; k + 1 < n; ++k) {
    const float4 sc[3] = {poly[0].pos, poly[k].pos, poly[k + 1].pos};
    ClipBatch batch;
    setup_broadcast(sc, &batch);
    SetupBatch b;
    int made[CLR_LANES];
    CLR_STORE_LANES(setup_make(&batch, params, &b, true, (intL)clr_image_row(params, tri)), made);
    if (!made[0]) continue;
    SetupLanes l;
    setup_unpack(&b, &l);
    const int order[3] = {0, l.back[0] ? k + 1 : k, l.back[0] ? k : k + 1};  // setup_make's vertex order
    __global ClipBary* bary = &clipBary[i * CLR_MAX_SUBTRIS + count];
    for (int v = 0; v < 3; ++v) {
      bary->w[v][0] = poly[order[v]].bary.x;
      bary->w[v][1] = poly[order[v]].bary.y;
      bary->w[v][2] = poly[order[v]].bary.z;
      bary->clipW[v] = poly[order[v]].pos.w;  // setup_make's divisor
    }
    bary->triId = tri;
    bary->flags = l.back[0] ? CLR_FLAG_BACKFACING : 0u;
    TriSetup t;
    setup_lane(&l, 0, &t);
    setup[base + count++] = t;
    bin_count_tiles(&t, bin_tile_range(&t, params, clr_image_row(params, tri)), params, tileCount);
  }
  // Step 3: flag the reservation's unused slots, whose records binning skips.
  for (uint k = count; k < CLR_MAX_SUBTRIS; ++k) {
    const TriSetup deadRecord = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    const ClipBary deadSlot = {{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, {0, 0, 0}, tri, CLR_FLAG_DEAD};
    setup[base + k] = deadRecord;
    clipBary[i * CLR_MAX_SUBTRIS + k] = deadSlot;
  }
  atomic_add(&counters[CLR_COUNTER_DEAD_RECORDS], CLR_MAX_SUBTRIS - count);
  if (count == 0) atomic_inc(&counters[CLR_COUNTER_CULLED_TRIS]);
}
#endif
