/* raster.cl — stage 5: coverage and the depth test of every binned triangle
 * at every sample of its tiles, written to the visibility buffer (shared.h).
 * Inputs: FrameParams, the setup records and the bin lists (tileOffset,
 * binEntries); tiles with no entry are skipped (resolve fills them).
 * Work shapes (-D CLR_LANES): GPU (1) one work-item per sample, one
 * work-group per tile, the bin read in local-memory batches; CPU (16) one
 * work-item per tile, testing each triangle on the rows its bounds span, 16
 * samples at a time in vector types. The third NDRange dimension is the
 * sample index k (FrameParams.sampleX/Y). Both shapes give identical bits.
 * Coverage, one kernel per method (FrameParams.edgeMode, .traversal): the
 * notes' edge functions in 64-bit fixed point (exact) or float; hierarchical
 * acceptance of tiles inside all edges; exact span tables; the classic float
 * edge walk. Fill rule: CLR_EDGE_HOLDS_SAMPLES (fixed.h). Depth: a LESS
 * compare of raster_depth_key; equal keys go to the triangle earlier in the
 * file (paintRank holds each input triangle's file index, host layout.h),
 * pieces of one clipped triangle by setup index; or the painter's ranks
 * (CLR_VISIBILITY_PAINTER, ranks from host raster.cpp).
 */
#pragma OPENCL FP_CONTRACT OFF
#include "bin.h"
#include "vis.h"
#include "micro.h"

#if CLR_TILE_SIZE % CLR_LANES != 0
#error "CLR_LANES must divide CLR_TILE_SIZE"
#endif

/* The GPU shape reads records from its batch in local memory. */
#if CLR_LANES == 1
#define CLR_RECORD_SPACE __local
#else
#define CLR_RECORD_SPACE __global
#endif

/* Lane 0 of a lane value. */
#if CLR_LANES == 1
#define CLR_LANE0(v) (v)
#else
#define CLR_LANE0(v) ((v).s0)
#endif

/* Twice the signed area of (a, b, p), positive when p is left of a→b;
 * exact in 64 bits (fixed.h). */
CLR_INLINE longL edge_function(int ax, int ay, int bx, int by, intL px, int py)
{
  return (long)(bx - ax) * (long)(py - ay) - (long)(by - ay) * convert_longL(px - ax);
}

CLR_INLINE long edge_bias(int ax, int ay, int bx, int by)
{
  return CLR_EDGE_HOLDS_SAMPLES(ax, ay, bx, by) ? 1 : 0;
}

/* The nearest fragment so far of a row segment. depth holds the compare key
 * (the paint rank's bits with the painter's algorithm). Under the z-buffer
 * index starts at 0: a fragment taken is nearer than the clear key, and
 * raster_write_row writes CLR_NONE where depth is still that key. */
typedef struct RowBest {
  uintL index;
  floatL depth, b1, b2;
} RowBest;

/* The depth test's key of window depth z: smaller is nearer. */
CLR_INLINE floatL raster_depth_key(floatL z, uint depthMode)
{
  if (depthMode == CLR_DEPTH_UNORM24) {
    const floatL lo = 0.0f, hi = 1.0f;
    return rint(clamp(z, lo, hi) * CLR_DEPTH_UNORM24_MAX);
  }
  return depthMode == CLR_DEPTH_REVERSED ? -z : z;
}

/* The cleared buffer's key: 1, 2^24 − 1, or −0 (reversed: −0 < −0 is false). */
CLR_INLINE float raster_clear_key(uint depthMode)
{
  return depthMode == CLR_DEPTH_UNORM24 ? CLR_DEPTH_UNORM24_MAX : depthMode == CLR_DEPTH_REVERSED ? -0.0f : 1.0f;
}

CLR_INLINE floatL raster_key_depth(floatL key, uint depthMode, uint visibility)
{
  if (visibility == CLR_VISIBILITY_PAINTER) return key;
  if (depthMode == CLR_DEPTH_UNORM24) return key / CLR_DEPTH_UNORM24_MAX;
  return depthMode == CLR_DEPTH_REVERSED ? -key : key;
}

CLR_INLINE void row_best_init(RowBest* b, float clearKey, uint visibility)
{
  b->index = visibility == CLR_VISIBILITY_PAINTER ? CLR_NONE : 0u;
  b->depth = clearKey;
  b->b1 = 0.0f;
  b->b2 = 0.0f;
}

/* How raster_depth_test decides, constant over a frame. */
typedef struct DepthRule {
  uint depthMode, visibility;
  float clearKey;
  bool barycentrics;  // keep b1, b2 (FrameParams.visAttributes)
  // An exact tie's order (raster_tie_wins): source words, clip slots, file ranks.
  __global const uint* source;
  __global const ClipBary* clipBary;
  __global const uint* fileRank;
  bool fileOrder;  // FrameParams.fileOrder: the rank is the triangle itself
} DepthRule;

CLR_INLINE DepthRule raster_depth_rule(__constant FrameParams* params, __global const uint* source,
                                       __global const ClipBary* clipBary, __global const uint* fileRank)
{
  DepthRule r;
  r.depthMode = params->depthMode;
  r.visibility = params->visibility;
  r.clearKey = raster_clear_key(r.depthMode);
  r.barycentrics = params->visAttributes != 0;
  r.source = source;
  r.clipBary = clipBary;
  r.fileRank = fileRank;
  r.fileOrder = params->fileOrder != 0;
  return r;
}

/* Which tied lanes setup record s wins against the records kept: the
 * triangle earlier in the file, then (pieces of one clipped triangle) the
 * lower setup index. A lane still at the clear key keeps it (nothing ties
 * the cleared state). Called only when some lane ties, which is rare. */
CLR_INLINE intL raster_tie_wins(const DepthRule* rule, uint s, uintL kept, floatL keptKey, intL tie)
{
  const uint tri = clr_source_triangle(rule->source[s], rule->clipBary);
  const uint mine = rule->fileOrder ? tri : rule->fileRank[tri];
  uint keptLanes[CLR_LANES];
  int tieLanes[CLR_LANES], win[CLR_LANES];
  float keyLanes[CLR_LANES];
  CLR_STORE_LANES(kept, keptLanes);
  CLR_STORE_LANES(tie, tieLanes);
  CLR_STORE_LANES(keptKey, keyLanes);
  for (int lane = 0; lane < CLR_LANES; ++lane) {
    win[lane] = 0;
    if (tieLanes[lane] == 0 || keyLanes[lane] == rule->clearKey) continue;
    const uint other = keptLanes[lane];
    const uint otherTri = clr_source_triangle(rule->source[other], rule->clipBary);
    const uint theirs = rule->fileOrder ? otherTri : rule->fileRank[otherTri];
    win[lane] = mine < theirs || (mine == theirs && s < other) ? -1 : 0;
  }
  return CLR_LOAD_LANES(win);
}

/* The float edge function: the same formula on float pixel coordinates. */
CLR_INLINE floatL edge_function_float(int ax, int ay, int bx, int by, intL px, int py)
{
  const float k = 1.0f / CLR_FIXED_ONE;
  const float fax = (float)ax * k, fay = (float)ay * k, fbx = (float)bx * k, fby = (float)by * k;
  const floatL fpx = convert_floatL(px) * k;
  const float fpy = (float)py * k;
  return (fbx - fax) * (fpy - fay) - (fby - fay) * (fpx - fax);
}

/* Keeps the nearer of the samples' fragments of triangle s and *best. */
CLR_INLINE void raster_depth_test(CLR_RECORD_SPACE const TriSetup* t, uint s, intL inside, floatL b1, floatL b2,
                                  RowBest* best, const DepthRule* rule, uint rank)
{
  const floatL z = t->z[0] + b1 * (t->z[1] - t->z[0]) + b2 * (t->z[2] - t->z[0]);
  const floatL key = raster_depth_key(z, rule->depthMode);
  intL take;
  floatL kept = key;
  if (rule->visibility == CLR_VISIBILITY_PAINTER) {
    // In front of the far plane, and later in paint order.
    const intL later = (best->index == CLR_NONE) | ((uintL)rank > as_uintL(best->depth));
    take = inside & (key < rule->clearKey) & later;
    kept = as_floatL((uintL)rank);
  } else {
    // LESS on the key, ties to the earlier triangle.
    const intL nearer = key < best->depth;
    // (In the file's order the setup index orders ties; else the rare ties
    // look the file's order up.)
    intL tieWin = (key == best->depth) & (s < best->index);
    if (!rule->fileOrder) {
      const intL tie = inside & (key == best->depth);
      if (CLR_ANY(tie)) tieWin = raster_tie_wins(rule, s, best->index, best->depth, tie);
    }
    take = inside & (nearer | tieWin);
  }
  best->index = select(best->index, (uintL)s, take);
  best->depth = select(best->depth, kept, take);
  if (!rule->barycentrics) return;
  best->b1 = select(best->b1, b1, take);
  best->b2 = select(best->b2, b2, take);
}

/* Exact span tables. Edge i runs from vertex i + 1 to i + 2 (lanes x, y, z;
 * w holds every sample). It holds lane j of a row segment, at sample x
 * firstSx + j·ONE, when N − D·j > 0 with N = E(lane 0) + bias and D = dy·ONE:
 * a rising edge (dy > 0) ends the span at floor((N − 1) / D), a falling one
 * starts it at floor(−N / |D|) + 1, a level one holds the row or not
 * (N > 0, as u >= 0 with d = 1). The numerator u changes by ±dx·ONE per
 * row, so the quotient q = floor(u / d) and remainder r are stepped
 * exactly, as a DDA: q += floor(step / d), r += step mod d, and a carry
 * when r reaches d. */
typedef struct Spans {
  long4 q, r, d;          // d = |dy|·ONE, 1 for a level edge
  long4 dq, dr;           // the row step's quotient and remainder
  long4 rising, falling;  // masks
} Spans;

/* q = floor(a / d) and r = a − q·d for d > 0: a float estimate and one
 * exact correction where the quotient is below 2^20 (the estimate's error
 * is then below 1), else the integer division. */
CLR_INLINE void spans_divide(long4 a, long4 d, long4* q, long4* r)
{
  const float4 estimate = floor(convert_float4(a) / convert_float4(d));
  if (any(fabs(estimate) > (float4)0x1p20f)) {
    *q = a / d;  // truncated: one less below zero where inexact
    *q = select(*q, *q - 1, (*q * d != a) & (a < 0));
  } else {
    *q = convert_long4(estimate);
  }
  // (Selects, not arithmetic on masks, here and in spans_step: Oclgrind
  // gets the latter wrong for long vectors.)
  *r = a - *q * d;
  const long4 low = *r < 0, high = *r >= d;  // the estimate one too large, one too small
  *q = select(select(*q, *q + 1, high), *q - 1, low);
  *r = select(select(*r, *r - d, high), *r + d, low);
}

/* The spans of the rows from sample y firstSy (stepped: with the row step,
 * else for that row alone). */
CLR_INLINE Spans spans_begin(CLR_RECORD_SPACE const TriSetup* t, int firstSx, int firstSy, const bool stepped)
{
  const int4 ax = (int4)(t->x[1], t->x[2], t->x[0], 0), ay = (int4)(t->y[1], t->y[2], t->y[0], 0);
  const int4 bx = (int4)(t->x[2], t->x[0], t->x[1], 0), by = (int4)(t->y[2], t->y[0], t->y[1], 0);
  const int4 dx = bx - ax, dy = by - ay;
  const long4 e = convert_long4(dx) * convert_long4(firstSy - ay) - convert_long4(dy) * convert_long4(firstSx - ax);
  long4 n = e - convert_long4(CLR_EDGE_HOLDS_SAMPLES(ax, ay, bx, by));  // the mask is −1 where it holds
  long4 step = convert_long4(dx) * CLR_FIXED_ONE;
  n.w = 1;  // lane w: a level edge that holds every row
  step.w = 0;
  Spans sp;
  sp.rising = convert_long4(dy > 0);
  sp.falling = convert_long4(dy < 0);
  sp.d = select((long4)1, convert_long4(abs(dy)) * CLR_FIXED_ONE, sp.rising | sp.falling);
  const long4 u = select(n - 1, -n, sp.falling), du = select(step, -step, sp.falling);
  spans_divide(u, sp.d, &sp.q, &sp.r);
  sp.dq = sp.dr = (long4)0;
  if (stepped) spans_divide(du, sp.d, &sp.dq, &sp.dr);
  return sp;
}

/* The span of the current row, (first lane, last lane); empty when
 * first > last. */
CLR_INLINE int2 spans_row(const Spans* sp)
{
  const long4 q = clamp(sp->q, (long4)(-1), (long4)CLR_LANES);
  const long4 first = select((long4)0, q + 1, sp->falling);
  const long4 last = select((long4)(CLR_LANES - 1), q, sp->rising);
  const long4 none = CLR_NOT(sp->rising | sp->falling) & (sp->q < 0);
  const int lo = (int)max(first.x, max(first.y, first.z)), hi = (int)min(last.x, min(last.y, last.z));
  return (int2)(lo, (none.x | none.y | none.z) != 0 ? -1 : hi);
}

CLR_INLINE void spans_step(Spans* sp)
{
  sp->r += sp->dr;
  const long4 carry = sp->r >= sp->d;
  sp->q += select(sp->dq, sp->dq + 1, carry);
  sp->r = select(sp->r, sp->r - sp->d, carry);
}

/* The classic edge walk of the notes (spans-float), in float pixel units:
 * the vertices sorted top to bottom, the triangle split at the middle
 * vertex by v4 = (yMid − yTop)/(yBottom − yTop)·(xBottom − xTop) + xTop on the
 * long edge. Each half's two edges start at its top (the top vertex; the
 * middle vertex and v4), are prestepped to the tile's first row by
 * x0 + (y − y0)·dx/dy and stepped a row at a time by dx/dy. A sample of row
 * y is inside when left <= x < right and yMid <= y < yTop (upper half) or
 * yBottom <= y < yMid (lower half), the fill rule in exact arithmetic. A
 * flat top or bottom leaves its half empty (no dx/dy of a level edge). */
typedef struct Walk {
  float yTop, yMid, yBottom;
  float4 x, step;  // upper left, upper right, lower left, lower right
} Walk;

CLR_INLINE Walk walk_begin(CLR_RECORD_SPACE const TriSetup* t, float y0)
{
  const float k = 1.0f / CLR_FIXED_ONE;
  float2 top = (float2)((float)t->x[0] * k, (float)t->y[0] * k);
  float2 mid = (float2)((float)t->x[1] * k, (float)t->y[1] * k);
  float2 bottom = (float2)((float)t->x[2] * k, (float)t->y[2] * k), swap;
  if (mid.y > top.y) swap = top, top = mid, mid = swap;
  if (bottom.y > top.y) swap = top, top = bottom, bottom = swap;
  if (bottom.y > mid.y) swap = mid, mid = bottom, bottom = swap;
  const bool flatTop = top.y == mid.y, flatBottom = mid.y == bottom.y, level = top.y == bottom.y;
  const float longStep = level ? 0.0f : (bottom.x - top.x) / (bottom.y - top.y);
  const float upperStep = flatTop ? 0.0f : (mid.x - top.x) / (mid.y - top.y);
  const float lowerStep = flatBottom ? 0.0f : (bottom.x - mid.x) / (bottom.y - mid.y);
  const float v4 = level ? top.x : (mid.y - top.y) / (bottom.y - top.y) * (bottom.x - top.x) + top.x;
  const float4 x = (float4)(top.x + (y0 - top.y) * upperStep, top.x + (y0 - top.y) * longStep,
                            mid.x + (y0 - mid.y) * lowerStep, v4 + (y0 - mid.y) * longStep);
  const float4 step = (float4)(upperStep, longStep, lowerStep, longStep);
  Walk w;
  w.yTop = top.y;
  w.yMid = mid.y;
  w.yBottom = bottom.y;
  w.x = mid.x < v4 ? x : x.s1032;  // the middle vertex on the left or on the right
  w.step = mid.x < v4 ? step : step.s1032;
  return w;
}

/* Row y's (left, right), or false where no half holds the row. */
CLR_INLINE bool walk_row(const Walk* w, float y, float2* span)
{
  if (y >= w->yMid && y < w->yTop) {
    *span = w->x.s01;
    return true;
  }
  *span = w->x.s23;
  return y >= w->yBottom && y < w->yMid;
}

/* The samples of row y inside the walk's span. */
CLR_INLINE intL walk_inside(const Walk* w, intL sx, int sy)
{
  const float k = 1.0f / CLR_FIXED_ONE;
  float2 span;
  if (!walk_row(w, (float)sy * k, &span)) return (intL)0;
  const floatL x = convert_floatL(sx) * k;
  return (x >= span.x) & (x < span.y);
}

/* Tests setup triangle s at the samples (sx, sy), row tileRow of its tile,
 * and keeps the nearest fragment in *best. edgeMode and traversal are
 * constant at every call site. Used by the GPU shape for every method and
 * by the CPU shape for float edges. */
CLR_INLINE void raster_row(CLR_RECORD_SPACE const TriSetup* t, uint s, intL sx, int sy, int tileRow, RowBest* best,
                           const DepthRule* rule, uint rank, const uint edgeMode, const uint traversal)
{
  if (edgeMode == CLR_EDGES_FLOAT) {
    const floatL e0 = edge_function_float(t->x[1], t->y[1], t->x[2], t->y[2], sx, sy);
    const floatL e1 = edge_function_float(t->x[2], t->y[2], t->x[0], t->y[0], sx, sy);
    const floatL e2 = edge_function_float(t->x[0], t->y[0], t->x[1], t->y[1], sx, sy);
    const intL on0 = edge_bias(t->x[1], t->y[1], t->x[2], t->y[2]) ? (intL)(-1) : (intL)0;
    const intL on1 = edge_bias(t->x[2], t->y[2], t->x[0], t->y[0]) ? (intL)(-1) : (intL)0;
    const intL on2 = edge_bias(t->x[0], t->y[0], t->x[1], t->y[1]) ? (intL)(-1) : (intL)0;
    const intL inside = ((e0 > 0.0f) | ((e0 == 0.0f) & on0)) & ((e1 > 0.0f) | ((e1 == 0.0f) & on1)) &
                        ((e2 > 0.0f) | ((e2 == 0.0f) & on2));
    if (!CLR_ANY(inside)) return;
    const float invArea2 = CLR_RECORD_INV_AREA2(*t) * (float)(CLR_FIXED_ONE * CLR_FIXED_ONE);  // per pixel²
    raster_depth_test(t, s, inside, e1 * invArea2, e2 * invArea2, best, rule, rank);
    return;
  }
  const longL e1 = edge_function(t->x[2], t->y[2], t->x[0], t->y[0], sx, sy);
  const longL e2 = edge_function(t->x[0], t->y[0], t->x[1], t->y[1], sx, sy);
  intL inside;
  if (traversal == CLR_TRAVERSAL_SPANS) {
    const Spans sp = spans_begin(t, CLR_LANE0(sx), sy, false);
    const int2 span = spans_row(&sp);
    inside = (CLR_LANE_INDEX >= (intL)span.x) & (CLR_LANE_INDEX <= (intL)span.y);
  } else if (traversal == CLR_TRAVERSAL_SPANS_FLOAT) {
    Walk w = walk_begin(t, (float)(sy - tileRow * CLR_FIXED_ONE) * (1.0f / CLR_FIXED_ONE));
    for (int row = 0; row < tileRow; ++row) w.x += w.step;
    inside = walk_inside(&w, sx, sy);
  } else {
    const longL e0 = edge_function(t->x[1], t->y[1], t->x[2], t->y[2], sx, sy);
    inside = convert_intL((e0 + edge_bias(t->x[1], t->y[1], t->x[2], t->y[2]) > 0) &
                          (e1 + edge_bias(t->x[2], t->y[2], t->x[0], t->y[0]) > 0) &
                          (e2 + edge_bias(t->x[0], t->y[0], t->x[1], t->y[1]) > 0));
  }
  if (!CLR_ANY(inside)) return;
  const float invArea2 = CLR_RECORD_INV_AREA2(*t);
  raster_depth_test(t, s, inside, convert_floatL(e1) * invArea2, convert_floatL(e2) * invArea2, best, rule, rank);
}

/* The edge function in 32 bits, modulo 2^32 (unsigned, defined wrapping):
 * read as an int it is E wherever E fits an int. */
CLR_INLINE uintL edge_function32(int ax, int ay, int bx, int by, intL px, int py)
{
  return (uint)(bx - ax) * (uint)(py - ay) - (uint)(by - ay) * as_uintL(px - ax);
}

/* The widest and tallest triangle bounds (fixed units, 64 pixels) whose
 * edge functions raster_rows_fixed32 evaluates in 32 bits. With width W and
 * height H of the bounds, |bx − ax| <= W, |by − ay| <= H, the rows tested
 * lie inside the bounds (one step past the last: |py − ay| <= H + ONE) and
 * the 16-lane column overlaps them (|px − ax| <= W + 16·ONE < W + 2^13), so
 * |E| <= W·(H + 2^8) + H·(W + 2^13) < 2^29 + 2^27 + 2^23 for W, H <= 2^14. */
#define CLR_EDGE32_SPAN (1 << 14)

/* raster_rows_fixed (64-bit lanes) and raster_rows_fixed32 (32-bit lanes, modulo 2^32): one row loop, raster_rows.h,
 * specialised by the macros defined before each include. */
#define CLR_ROWS_NAME raster_rows_fixed
#define CLR_ROWS_EDGE_L longL
#define CLR_ROWS_EDGE long
#define CLR_ROWS_SIGNED_L(v) (v)
#define CLR_ROWS_SIGNED_EDGE long
#define CLR_ROWS_EDGE_FUNCTION edge_function
#define CLR_ROWS_TO_INT_L(m) convert_intL(m)
#define CLR_ROWS_SKIP_EMPTY true
#include "raster_rows.h"
#define CLR_ROWS_NAME raster_rows_fixed32
#define CLR_ROWS_EDGE_L uintL
#define CLR_ROWS_EDGE uint
#define CLR_ROWS_SIGNED_L(v) as_intL(v)
#define CLR_ROWS_SIGNED_EDGE int
#define CLR_ROWS_EDGE_FUNCTION edge_function32
#define CLR_ROWS_TO_INT_L(m) (m)
#define CLR_ROWS_SKIP_EMPTY false
#include "raster_rows.h"

/* For a large triangle's row segment of CLR_LANES samples from sample x
 * firstSx (row r at sample y (firstY + r)·ONE + centreY): narrows rows
 * *rowBegin .. *rowEnd to those where every edge can pass the fill rule at
 * some lane, and returns whether all three edge functions fit an int over
 * the rows kept (raster_rows_fixed32 steps them modulo 2^32, so a row step
 * beyond an int, or the step past the last row, wraps harmlessly).
 * - Rows: over a row's lanes an edge function is largest at the first or the
 *   last lane, and that value changes by the row step from row to row; each
 *   edge holds the rows on one side of the boundary k (eMax + k·step = low).
 *   k is computed in float and clamped to ±(CLR_TILE_SIZE + 2); inside
 *   that range |k' − k| < 1, and truncating k' never drops a row with a
 *   sample inside (a rising edge's first such row is floor(k) + 1 >=
 *   trunc(k'); a falling edge's last, ceil(k) − 1 <= trunc(k')).
 * - Fit: a linear function's extremes over the rectangle lie at its
 *   corners, computed in 64 bits (|E| < 2^51, fixed.h). */
CLR_INLINE bool raster_segment_rows(CLR_RECORD_SPACE const TriSetup* t, int firstSx, int firstY, int centreY,
                                    int* rowBegin, int* rowEnd)
{
  // The three edges in lanes x, y, z (as raster_rows_fixed); w unused.
  const int first = *rowBegin, firstSy = (firstY + first) * CLR_FIXED_ONE + centreY;
  const int4 ax = (int4)(t->x[1], t->x[2], t->x[0], 0), ay = (int4)(t->y[1], t->y[2], t->y[0], 0);
  const int4 bx = (int4)(t->x[2], t->x[0], t->x[1], 0), by = (int4)(t->y[2], t->y[0], t->y[1], 0);
  const int4 dx = bx - ax, dy = by - ay;
  const int4 px = select((int4)(firstSx + (CLR_LANES - 1) * CLR_FIXED_ONE), (int4)firstSx, dy > 0);
  const long4 eMax = convert_long4(dx) * convert_long4(firstSy - ay) - convert_long4(dy) * convert_long4(px - ax);
  const long4 across = convert_long4(abs(dy)) * ((CLR_LANES - 1) * CLR_FIXED_ONE);
  const long4 step = convert_long4(dx) * CLR_FIXED_ONE;
  const long4 low = convert_long4(CLR_EDGE_HOLDS_SAMPLES(ax, ay, bx, by));  // −1 or 0
  // The rows k from the first where eMax + k·step > low.
  const float bound = CLR_TILE_SIZE + 2;
  const int4 level = convert_int4(step == 0), rising = convert_int4(step >= 0);
  const float4 quotient = convert_float4(low - eMax) / convert_float4(select(step, (long4)1, step == 0));
  const float4 k =
      select(clamp(quotient, -bound, bound), select((float4)bound, (float4)(-bound), convert_int4(eMax > low)), level);
  const int4 boundary = first + convert_int4(k);  // truncated
  const int4 fromRow = select((int4)(*rowBegin), boundary, rising);
  const int4 toRow = select(boundary, (int4)(*rowEnd), rising);
  const int begin = max(fromRow.x, max(fromRow.y, fromRow.z)), end = min(toRow.x, min(toRow.y, toRow.z));
  *rowBegin = begin;
  *rowEnd = end;
  const long4 top0 = eMax + (long)(begin - first) * step, top1 = eMax + (long)(end - first) * step;
  const int4 fits = convert_int4((min(top0, top1) - across >= INT_MIN) & (max(top0, top1) <= INT_MAX));
  return (fits.x & fits.y & fits.z) != 0;
}

/* Writes a row segment into sample plane k at address a: the index plane,
 * and the depth and barycentric planes when the frame has them. Lanes past
 * the viewport's edge are stored too (the tile's block has room) and never
 * read. */
CLR_INLINE void raster_write_row(__constant FrameParams* params, uint visPlane, uint k, uint a, const RowBest* best,
                                 __global uint* visIndex, __global float* visAttr)
{
  const bool zbuffer = params->visibility != CLR_VISIBILITY_PAINTER;
  const uintL index =
      zbuffer ? select((uintL)CLR_NONE, best->index, best->depth < raster_clear_key(params->depthMode)) : best->index;
  vis_store_index_lanes(params, index, visIndex, k * visPlane + a);
  if (!params->visAttributes) return;
  const floatL windowDepth = raster_key_depth(best->depth, params->depthMode, params->visibility);
  CLR_STORE_LANES(windowDepth, &visAttr[3 * k * visPlane + a]);
  CLR_STORE_LANES(best->b1, &visAttr[(3 * k + 1) * visPlane + a]);
  CLR_STORE_LANES(best->b2, &visAttr[(3 * k + 2) * visPlane + a]);
}

/* Merges the micro path's fragments (micro.h) of one row segment, lanes from entry a of microKey, samples (sx, sy),
 * into *best, and clears those entries. A micro fragment's key is exact but for −0 (micro_key_bits), so a kept
 * depth plane takes the key recomputed from its record. */
CLR_INLINE void raster_merge_micro(__global ulong* microKey, uint a, intL sx, int sy, RowBest* best,
                                   const DepthRule* rule, __global const TriSetup* setup,
                                   __global const uint* microRecord)
{
  ulong m[CLR_LANES];
  bool any = false;
  for (int lane = 0; lane < CLR_LANES; ++lane) {
    m[lane] = microKey[a + lane];
    any |= m[lane] != CLR_MICRO_CLEAR;
  }
  if (!any) return;
  uint index[CLR_LANES];
  int sxs[CLR_LANES];
  float depth[CLR_LANES], b1[CLR_LANES], b2[CLR_LANES];
  CLR_STORE_LANES(best->index, index);
  CLR_STORE_LANES(best->depth, depth);
  CLR_STORE_LANES(best->b1, b1);
  CLR_STORE_LANES(best->b2, b2);
  CLR_STORE_LANES(sx, sxs);
  for (int lane = 0; lane < CLR_LANES; ++lane) {
    if (m[lane] == CLR_MICRO_CLEAR) continue;
    microKey[a + lane] = CLR_MICRO_CLEAR;
    uint s;
    if (!micro_take(m[lane], index[lane], depth[lane], rule->fileOrder, microRecord, rule->source, rule->clipBary,
                    rule->fileRank, &s))
      continue;
    index[lane] = s;
    depth[lane] = micro_bits_key((uint)(m[lane] >> 32));
    if (rule->barycentrics) {
      const TriSetup t = setup[s];
      micro_sample(&t, sxs[lane], sy, rule->depthMode, &depth[lane], &b1[lane], &b2[lane]);
    }
  }
  best->index = CLR_LOAD_LANES(index);
  best->depth = CLR_LOAD_LANES(depth);
  best->b1 = CLR_LOAD_LANES(b1);
  best->b2 = CLR_LOAD_LANES(b2);
}

/* The nearest key a triangle's fragments can have, for the skip of hidden
 * triangles (z-buffer, exact coverage): the CPU shape skips an entry beyond
 * the farthest key its tile keeps (raster_tile_far, refreshed every
 * CLR_FAR_REFRESH entries when one reached the rows: it only falls, so a
 * stale one skips less), the GPU shape one beyond its sample's key.
 * Margin: a fragment's z = z0 + b1·(z1 − z0) + b2·(z2 − z0) has b1, b2 >= 0
 * and b1 + b2 <= 1 + 4u (u = 2^-24, four roundings), so with M = max |z_i|
 * its exact value lies within 8u·M of [min z_i, max z_i], and the
 * evaluation rounds by at most 10u·M more: 18u·M. The range is widened by
 * 2^-18·M = 64u·M (and 2^-120 for tiny depths) and mapped by the format's
 * monotonic key. A depth that is not finite skips nothing under unorm24,
 * which clamps NaN to a key. A test in tests/ finds triangles rounded in
 * front of their vertices, which the skip without its margin drops. */
CLR_INLINE float raster_nearest_key(float z0, float z1, float z2, uint depthMode)
{
  const float margin = max(fabs(z0), max(fabs(z1), fabs(z2))) * 0x1p-18f + 0x1p-120f;
  if (depthMode == CLR_DEPTH_REVERSED) return -(max(z0, max(z1, z2)) + margin);
  const float zLow = min(z0, min(z1, z2)) - margin;
  if (depthMode != CLR_DEPTH_UNORM24) return zLow;
  if (!(isfinite(z0) && isfinite(z1) && isfinite(z2))) return -INFINITY;
  return rint(clamp(zLow, 0.0f, 1.0f) * CLR_DEPTH_UNORM24_MAX);
}

/* The kernels' parameters, the same for every variant:
 *   params, setup, source, clipBary, tileOffset (tiles + 1), binEntries,
 *   visIndex (samples · visPlane), visAttr (3 · samples · visPlane),
 *   paintRank (numTris: each input triangle's paint rank with the
 *   painter's algorithm, else its index in the file), tileSlot
 *   (tiles + 1: each non-empty tile's slot), visPlane (slots · tile²), and the micro path's tileMicro (tiles: a
 *   slotted tile's last bin entry is a hole), microKey and microRecord (micro.h). */
#define CLR_RASTER_PARAMS                                                                                              \
  __constant FrameParams *params, __global const TriSetup *setup, __global const uint *source,                         \
      __global const ClipBary *clipBary, __global const uint *tileOffset, __global const uint *binEntries,             \
      __global uint *visIndex, __global float *visAttr, __global const uint *paintRank, __global const uint *tileSlot, \
      uint visPlane, __global const uint *tileMicro, __global ulong *microKey, __global const uint *microRecord
#define CLR_RASTER_ARGS                                                                                      \
  params, setup, source, clipBary, tileOffset, binEntries, visIndex, visAttr, paintRank, tileSlot, visPlane, \
      tileMicro, microKey, microRecord

/* The methods are separate kernels, each with its method a compile-time
 * constant, so a device compiles only the variant a frame launches: the
 * default, raster, in the frame program, the others (raster_hierarchical,
 * raster_float, raster_spans, raster_spans_float) in the extras program
 * (CLR_EXTRAS, shared.h). The skip of hidden triangles and the narrowed
 * rows of large triangles rely on the exact coverage. */
#define CLR_EXACT_COVERAGE(edgeMode, traversal) \
  ((edgeMode) == CLR_EDGES_FIXED && (traversal) != CLR_TRAVERSAL_SPANS_FLOAT)
#if CLR_LANES == 1
/* GPU shape: one work-item per sample, one work-group per tile and sample
 * index. The group walks its tile's bin in batches of one entry per
 * work-item: each copies one record, its bounds, nearest key, index and
 * paint rank into local memory, then every work-item tests its sample
 * against the batch, skipping records whose bounds miss it or whose nearest
 * key lies beyond its own (docs/architecture.md has the measurements). */
#define CLR_RASTER_BATCH (CLR_TILE_SIZE * CLR_TILE_SIZE)
CLR_INLINE void raster_pixel(CLR_RASTER_PARAMS, const uint edgeMode, const uint traversal, __local TriSetup* records,
                             __local int4* bounds, __local float* nearestKeys, __local uint* indices,
                             __local uint* ranks)
{
  const uint px = get_global_id(0), py = get_global_id(1), k = get_global_id(2);
  const uint tile = get_group_id(1) * params->tilesX + get_group_id(0);
  const uint item = get_local_id(1) * CLR_TILE_SIZE + get_local_id(0);
  const int sx = (int)px * CLR_FIXED_ONE + CLR_FIXED_HALF + params->sampleX[k];
  const int sy = (int)py * CLR_FIXED_ONE + CLR_FIXED_HALF + params->sampleY[k];
  const uint begin = tileOffset[tile];
  uint end = tileOffset[tile + 1];
  if (begin == end) return;  // the whole group
  const uint microWord = micro_tile_slot(tileMicro, tile, &end);
  const DepthRule rule = raster_depth_rule(params, source, clipBary, paintRank);
  const bool painter = rule.visibility == CLR_VISIBILITY_PAINTER;
  const bool skipHidden = !painter && CLR_EXACT_COVERAGE(edgeMode, traversal);
  RowBest best;
  row_best_init(&best, rule.clearKey, rule.visibility);
  for (uint first = begin; first < end; first += CLR_RASTER_BATCH) {
    const uint count = min(end - first, (uint)CLR_RASTER_BATCH);
    barrier(CLK_LOCAL_MEM_FENCE);  // the previous batch is tested
    if (item < count) {
      const uint s = binEntries[first + item];
      const TriSetup t = setup[s];
      records[item] = t;
      bounds[item] = CLR_RECORD_BOUNDS(t);
      nearestKeys[item] = skipHidden ? raster_nearest_key(t.z[0], t.z[1], t.z[2], rule.depthMode) : -INFINITY;
      indices[item] = s;
      ranks[item] = painter ? paintRank[clr_source_triangle(source[s], clipBary)] : 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    for (uint n = 0; n < count; ++n) {
      const int4 b = bounds[n];
      if (sx < b.x || sy < b.y || sx > b.z || sy > b.w || nearestKeys[n] > best.depth) continue;
      raster_row(&records[n], indices[n], sx, sy, (int)get_local_id(1), &best, &rule, ranks[n], edgeMode, traversal);
    }
  }
  const uint a = vis_address(tileSlot[tile], px, py);
  if (microWord)
    raster_merge_micro(microKey, micro_address(microWord, params->samples, k, px, py), sx, sy, &best, &rule, setup,
                       microRecord);
  raster_write_row(params, visPlane, k, a, &best, visIndex, visAttr);
}

/* Local memory is declared at kernel scope (OpenCL 1.2): 256 records of 36
 * bytes, their bounds, nearest keys and two words each, 16 KB (host
 * deviceNeeds, device.h, checks the device has it). */
#define CLR_RASTER_KERNEL(name, edgeMode, traversal)                                                           \
  __kernel __attribute__((reqd_work_group_size(CLR_TILE_SIZE, CLR_TILE_SIZE, 1))) void name(CLR_RASTER_PARAMS) \
  {                                                                                                            \
    __local TriSetup records[CLR_RASTER_BATCH];                                                                \
    __local int4 bounds[CLR_RASTER_BATCH];                                                                     \
    __local float nearestKeys[CLR_RASTER_BATCH];                                                               \
    __local uint indices[CLR_RASTER_BATCH], ranks[CLR_RASTER_BATCH];                                           \
    raster_pixel(CLR_RASTER_ARGS, edgeMode, traversal, records, bounds, nearestKeys, indices, ranks);          \
  }
#else
#define CLR_FAR_REFRESH 8
CLR_INLINE float raster_tile_far(const RowBest best[CLR_TILE_SIZE / CLR_LANES][CLR_TILE_SIZE])
{
  floatL far = best[0][0].depth;
  for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col)
    for (int row = 0; row < CLR_TILE_SIZE; ++row) far = max(far, best[col][row].depth);
  return clr_max_lanes(far);
}

/* One triangle's rows rowFirst .. rowLast of one tile column, by method:
 * float edges row by row, fixed edges in 32- or 64-bit lanes (rows32).
 * Called with the default depth rule as a constant where it applies, so
 * that those row loops have no branch on the rule. */
CLR_HOT void raster_segment(__global const TriSetup* t, uint s, intL sx, int firstSy, int rowFirst, int rowLast,
                            RowBest* best, const DepthRule* rule, uint rank, bool acceptAll, bool rows32,
                            const uint edgeMode, const uint traversal)
{
  if (edgeMode == CLR_EDGES_FLOAT) {
    for (int row = rowFirst; row <= rowLast; ++row)
      raster_row(t, s, sx, firstSy + (row - rowFirst) * CLR_FIXED_ONE, row, &best[row], rule, rank, edgeMode,
                 CLR_TRAVERSAL_BBOX);
  } else if (rows32) {
    raster_rows_fixed32(t, s, sx, firstSy, rowFirst, rowLast, best, rule, rank, acceptAll, traversal);
  } else {
    raster_rows_fixed(t, s, sx, firstSy, rowFirst, rowLast, best, rule, rank, acceptAll, traversal);
  }
}

/* CPU shape: one work-item per tile and sample index, as llvmpipe's
 * per-tile threads; the tile's nearest fragments stay in private memory. */
CLR_INLINE void raster_tile(CLR_RASTER_PARAMS, uint tileX, uint tileY, uint k, const uint edgeMode,
                            const uint traversal)
{
  const uint tile = tileY * params->tilesX + tileX;
  const int firstY = (int)tileY * CLR_TILE_SIZE;
  const uint begin = tileOffset[tile];
  uint end = tileOffset[tile + 1];
  if (begin == end) return;
  const uint microWord = micro_tile_slot(tileMicro, tile, &end);
  const int offsetX = params->sampleX[k], offsetY = params->sampleY[k];
  const DepthRule rule = raster_depth_rule(params, source, clipBary, paintRank);
  const bool painter = rule.visibility == CLR_VISIBILITY_PAINTER;
  // The default rule (float32, z-buffer) as a constant (raster_segment).
  const DepthRule zbufferFloat32 = {CLR_DEPTH_FLOAT32, CLR_VISIBILITY_ZBUFFER, 1.0f, false, source, clipBary,
                                    paintRank,         rule.fileOrder};
  const bool defaultRule = rule.depthMode == CLR_DEPTH_FLOAT32 && !painter && !rule.barycentrics;
  RowBest best[CLR_TILE_SIZE / CLR_LANES][CLR_TILE_SIZE];
  intL sx[CLR_TILE_SIZE / CLR_LANES];
  for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col) {
    const int firstX = (int)tileX * CLR_TILE_SIZE + col * CLR_LANES;
    sx[col] = firstX * CLR_FIXED_ONE + CLR_FIXED_HALF + offsetX + CLR_LANE_INDEX * CLR_FIXED_ONE;
    for (int row = 0; row < CLR_TILE_SIZE; ++row) row_best_init(&best[col][row], rule.clearKey, rule.visibility);
  }
  const bool skipHidden = !painter && CLR_EXACT_COVERAGE(edgeMode, traversal);
  float tileFar = rule.clearKey;
  bool stale = false;  // an entry since the last refresh reached the rows
  for (uint n = begin; n < end; ++n) {
    const uint s = binEntries[n];
    __global const TriSetup* t = &setup[s];
#ifdef CLR_PREFETCH
    if (n + CLR_PREFETCH < end) __builtin_prefetch(&setup[binEntries[n + CLR_PREFETCH]]);
#endif
    if (skipHidden) {
      if ((n - begin) % CLR_FAR_REFRESH == CLR_FAR_REFRESH - 1 && stale) {
        tileFar = raster_tile_far(best);
        stale = false;
      }
      const float nearest = defaultRule ? raster_nearest_key(t->z[0], t->z[1], t->z[2], CLR_DEPTH_FLOAT32)
                                        : raster_nearest_key(t->z[0], t->z[1], t->z[2], rule.depthMode);
      if (nearest > tileFar) continue;
      stale = true;
    }
    const uint rank = painter ? paintRank[clr_source_triangle(source[s], clipBary)] : 0u;
    const int4 bounds = CLR_RECORD_BOUNDS(*t);
    const bool small = bounds.z - bounds.x <= CLR_EDGE32_SPAN && bounds.w - bounds.y <= CLR_EDGE32_SPAN;
    const int centreY = CLR_FIXED_HALF + offsetY;
    const int rowBegin = max(0, ((bounds.y - centreY + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS) - firstY);
    const int rowEnd = min(CLR_TILE_SIZE - 1, ((bounds.w - centreY) >> CLR_SUBPIXEL_BITS) - firstY);
    bool acceptAll = false;  // hierarchical: a tile inside all three edges
    if (traversal == CLR_TRAVERSAL_HIERARCHICAL) {
      const TriSetup tri = *t;
      acceptAll = bin_tile_class(&tri, params, (int)tileX, (int)tileY) > 0;
    }
    for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col) {
      const int firstSx = (int)(tileX * CLR_TILE_SIZE + col * CLR_LANES) * CLR_FIXED_ONE + CLR_FIXED_HALF + offsetX;
      if (firstSx > bounds.z || firstSx + (CLR_LANES - 1) * CLR_FIXED_ONE < bounds.x) continue;
      // A large triangle: the rows that can hold a sample, in 32-bit lanes
      // where its edge functions fit (near its edges). The float walk is
      // not narrowed by the exact test.
      int rowFirst = rowBegin, rowLast = rowEnd;
      bool rows32 = small;
      if (CLR_EXACT_COVERAGE(edgeMode, traversal) && !small && !acceptAll) {
        rows32 = raster_segment_rows(t, firstSx, firstY, centreY, &rowFirst, &rowLast);
        if (rowFirst > rowLast) continue;
      }
      const int firstSy = (firstY + rowFirst) * CLR_FIXED_ONE + centreY;
      if (defaultRule)
        raster_segment(t, s, sx[col], firstSy, rowFirst, rowLast, best[col], &zbufferFloat32, rank, acceptAll, rows32,
                       edgeMode, traversal);
      else
        raster_segment(t, s, sx[col], firstSy, rowFirst, rowLast, best[col], &rule, rank, acceptAll, rows32, edgeMode,
                       traversal);
    }
  }
  const uint slot = tileSlot[tile];
  if (microWord)
    for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col)
      for (int row = 0; row < CLR_TILE_SIZE; ++row)
        raster_merge_micro(microKey, micro_address(microWord, params->samples, k, col * CLR_LANES, row), sx[col],
                           (firstY + row) * CLR_FIXED_ONE + CLR_FIXED_HALF + offsetY, &best[col][row], &rule, setup,
                           microRecord);
  for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col)
    for (int row = 0; row < CLR_TILE_SIZE; ++row)
      raster_write_row(params, visPlane, k, vis_address(slot, col * CLR_LANES, row), &best[col][row], visIndex,
                       visAttr);
}

/* A CPU-shape kernel: its body one called function (CLR_KERNEL_BODY). */
#define CLR_RASTER_KERNEL(name, edgeMode, traversal)                                    \
  CLR_KERNEL_BODY void name##_body(CLR_RASTER_PARAMS, uint tileX, uint tileY, uint k)   \
  {                                                                                     \
    raster_tile(CLR_RASTER_ARGS, tileX, tileY, k, edgeMode, traversal);                 \
  }                                                                                     \
  __kernel __attribute__((reqd_work_group_size(1, 1, 1))) void name(CLR_RASTER_PARAMS)  \
  {                                                                                     \
    name##_body(CLR_RASTER_ARGS, get_global_id(0), get_global_id(1), get_global_id(2)); \
  }
#endif
#if !CLR_EXTRAS
CLR_RASTER_KERNEL(raster, CLR_EDGES_FIXED, CLR_TRAVERSAL_BBOX)
#else
CLR_RASTER_KERNEL(raster_hierarchical, CLR_EDGES_FIXED, CLR_TRAVERSAL_HIERARCHICAL)
CLR_RASTER_KERNEL(raster_float, CLR_EDGES_FLOAT, CLR_TRAVERSAL_BBOX)
CLR_RASTER_KERNEL(raster_spans, CLR_EDGES_FIXED, CLR_TRAVERSAL_SPANS)
CLR_RASTER_KERNEL(raster_spans_float, CLR_EDGES_FIXED, CLR_TRAVERSAL_SPANS_FLOAT)
#endif
