/* raster.cl — stage 5: the per-pixel kernel.
 *
 * Two work shapes, chosen per device with -D CLR_LANES. On a GPU (1)
 * one work-item per pixel sample and one work-group per tile; each
 * work-item walks its tile's bin. On a CPU (16) one work-item per tile, which
 * walks the bin once and tests each triangle only on the rows its bounds
 * span, 16 pixels at a time in explicit vector types (PoCL turns these into
 * AVX-512, but does not vectorise a data-dependent loop across work-items).
 * A third NDRange dimension runs over the FrameParams.samples sample
 * positions: sample k of pixel (i, j) lies at its centre (i + 0.5, j + 0.5)
 * plus (sampleX[k], sampleY[k]) and has its own plane of the visibility
 * buffer (shared.h), so work and memory follow the sample count.
 * Either way, for every triangle the three integer edge functions of the
 * notes are evaluated at the sample positions in 64-bit fixed point
 * (CLR_EDGES_FIXED) or, as the weaker method to compare, in 32-bit floats
 * in pixel units (CLR_EDGES_FLOAT). Fill rule (GL as in llvmpipe, y up): a centre exactly on an edge is
 * inside for a left edge (dy < 0 on a counter-clockwise triangle) or a
 * horizontal bottom edge (dy = 0, dx > 0), outside otherwise. Inside samples get barycentrics
 * b_i = E_i / (2·area) and window depth z = z0 + b1·(z1 − z0) + b2·(z2 − z0);
 * the nearest is kept and written to the visibility buffer (its setup index;
 * its depth and barycentrics too when FrameParams.visAttributes asks for
 * them, shared.h; vis_barycentrics recomputes them). The depth test
 * follows FrameParams.depthMode (shared.h), as a LESS compare of a key:
 * float32 key z (GL LESS against the clear value 1), unorm24 key
 * rint(clamp(z, 0, 1)·(2^24 − 1)) in float (LESS against 2^24 − 1), reversed
 * key −z (so GREATER against the clear value 0); equal keys go to the
 * triangle earlier in the file (paintRank holds each input triangle's index
 * in the file, host layout.h; a clipped triangle's pieces by setup index).
 * With
 * CLR_VISIBILITY_PAINTER there is no test between triangles: a fragment
 * that passes the test against the clear value replaces the kept one when
 * its triangle comes later in the host's far-to-near order (paintRank, by
 * input triangle). Both shapes compute bit-identical results. Tiles with
 * no binned triangle are skipped; resolve fills them. With hierarchical
 * traversal the CPU shape accepts a tile that lies inside all three edges
 * without testing its samples (bin.cl rejects the tiles outside one).
 * Under the z-buffer a triangle wholly behind the depths kept is skipped:
 * by a CPU tile behind all it keeps, before the rows; by a GPU sample
 * behind its own, before the edge tests (raster_nearest_key).
 */
#pragma OPENCL FP_CONTRACT OFF

#if CLR_TILE_SIZE % CLR_LANES != 0
#error "CLR_LANES must divide CLR_TILE_SIZE"
#endif

/* Where the raster helpers read a setup record: in global memory in the CPU
 * shape, which reads each record where setup wrote it; in local memory in
 * the GPU shape, whose work-group copies a batch of its tile's records there
 * first (raster_pixel). */
#if CLR_LANES == 1
#define CLR_RECORD_SPACE __local
#else
#define CLR_RECORD_SPACE __global
#endif

/* Edge function of the directed edge (ax, ay)→(bx, by) at the samples
 * (px, py): twice the signed area of (a, b, p), positive when p is left of
 * the edge. Exact in 64 bits (fixed.h). */
CLR_INLINE longL edge_function(int ax, int ay, int bx, int by, intL px, int py)
{
  return (long)(bx - ax) * (long)(py - ay) - (long)(by - ay) * convert_longL(px - ax);
}

/* 1 when a centre exactly on the edge a→b belongs to the triangle (fixed.h). */
CLR_INLINE long edge_bias(int ax, int ay, int bx, int by)
{
  return CLR_EDGE_HOLDS_SAMPLES(ax, ay, bx, by) ? 1 : 0;
}

/* The nearest fragment so far of one row segment. depth holds the compare
 * key of raster_depth_key (the paint rank's bits with the painter's
 * algorithm) until raster_write_row turns it back into window depth. With
 * the z-buffer, index starts at 0, not CLR_NONE: a fragment taken is
 * always nearer than the clear key (a tie with the cleared state would need
 * s < 0), so the depth test needs no test for "none yet", and
 * raster_write_row writes CLR_NONE where depth is still the clear key
 * (raster on yxa_1 filling 1080p 4% faster). */
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

/* The key of the cleared depth buffer: 1 (float32), 2^24 − 1 (unorm24),
 * −0 (reversed; −0 < −0 is false, as 0 > 0 is). */
CLR_INLINE float raster_clear_key(uint depthMode)
{
  return depthMode == CLR_DEPTH_UNORM24 ? CLR_DEPTH_UNORM24_MAX : depthMode == CLR_DEPTH_REVERSED ? -0.0f : 1.0f;
}

/* A kept key back as the depth format stores it (shared.h, visAttr). */
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
  bool barycentrics;  // keep the nearest fragment's b1, b2 (FrameParams.visAttributes)
  // An exact tie's order (raster_tie_wins): source words, clip slots, and
  // each input triangle's index in the file (the paintRank argument).
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

/* The float edge function, the weaker method: the same formula on float
 * pixel coordinates, rounded at every operation. */
CLR_INLINE floatL edge_function_float(int ax, int ay, int bx, int by, intL px, int py)
{
  const float k = 1.0f / CLR_FIXED_ONE;
  const float fax = (float)ax * k, fay = (float)ay * k, fbx = (float)bx * k, fby = (float)by * k;
  const floatL fpx = convert_floatL(px) * k;
  const float fpy = (float)py * k;
  return (fbx - fax) * (fpy - fay) - (fby - fay) * (fpx - fax);
}

/* Keeps the nearer of the samples' fragments of triangle s and *best
 * (rank: the triangle's paint rank, read only by the painter's algorithm). */
CLR_INLINE void raster_depth_test(CLR_RECORD_SPACE const TriSetup* t, uint s, intL inside, floatL b1, floatL b2,
                                  RowBest* best, const DepthRule* rule, uint rank)
{
  const floatL z = t->z[0] + b1 * (t->z[1] - t->z[0]) + b2 * (t->z[2] - t->z[0]);
  const floatL key = raster_depth_key(z, rule->depthMode);
  intL take;
  floatL kept = key;
  if (rule->visibility == CLR_VISIBILITY_PAINTER) {
    // Step 1 (painter): in front of the far plane, and later in paint order.
    const intL later = (best->index == CLR_NONE) | ((uintL)rank > as_uintL(best->depth));
    take = inside & (key < rule->clearKey) & later;
    kept = as_floatL((uintL)rank);
  } else {
    // Step 1 (z-buffer): LESS on the key, ties to the earlier triangle.
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
  // Step 2: keep the fragment.
  best->index = select(best->index, (uintL)s, take);
  best->depth = select(best->depth, kept, take);
  if (!rule->barycentrics) return;  // no plane will hold them
  best->b1 = select(best->b1, b1, take);
  best->b2 = select(best->b2, b2, take);
}

/* Tests setup triangle s against the row segment of samples (sx, sy) and
 * keeps the nearest fragment in *best. edgeMode is constant at every call
 * site, so each method compiles to its own loop body. (The CPU shape's
 * fixed-edge rows, with hierarchical acceptance, are raster_rows_fixed.) */
CLR_INLINE void raster_row(CLR_RECORD_SPACE const TriSetup* t, uint s, intL sx, int sy, RowBest* best,
                           const DepthRule* rule, uint rank, const uint edgeMode)
{
  if (edgeMode == CLR_EDGES_FLOAT) {
    // Coverage and barycentrics from float edge functions; a sample on an
    // edge (E == 0 after rounding) follows the same fill rule.
    const floatL e0 = edge_function_float(t->x[1], t->y[1], t->x[2], t->y[2], sx, sy);
    const floatL e1 = edge_function_float(t->x[2], t->y[2], t->x[0], t->y[0], sx, sy);
    const floatL e2 = edge_function_float(t->x[0], t->y[0], t->x[1], t->y[1], sx, sy);
    // Masks are −1 (all bits) for true, as vector comparisons give.
    const intL on0 = edge_bias(t->x[1], t->y[1], t->x[2], t->y[2]) ? (intL)(-1) : (intL)0;
    const intL on1 = edge_bias(t->x[2], t->y[2], t->x[0], t->y[0]) ? (intL)(-1) : (intL)0;
    const intL on2 = edge_bias(t->x[0], t->y[0], t->x[1], t->y[1]) ? (intL)(-1) : (intL)0;
    const intL inside = ((e0 > 0.0f) | ((e0 == 0.0f) & on0)) & ((e1 > 0.0f) | ((e1 == 0.0f) & on1)) &
                        ((e2 > 0.0f) | ((e2 == 0.0f) & on2));
    if (!CLR_ANY(inside)) return;
    const float invArea2 =
        CLR_RECORD_INV_AREA2(*t) * (float)(CLR_FIXED_ONE * CLR_FIXED_ONE);  // per pixel², not subpixel²
    raster_depth_test(t, s, inside, e1 * invArea2, e2 * invArea2, best, rule, rank);
    return;
  }
  // Step 1: coverage by the three edge functions and the fill rule.
  const longL e0 = edge_function(t->x[1], t->y[1], t->x[2], t->y[2], sx, sy);
  const longL e1 = edge_function(t->x[2], t->y[2], t->x[0], t->y[0], sx, sy);
  const longL e2 = edge_function(t->x[0], t->y[0], t->x[1], t->y[1], sx, sy);
  const intL inside = convert_intL((e0 + edge_bias(t->x[1], t->y[1], t->x[2], t->y[2]) > 0) &
                                   (e1 + edge_bias(t->x[2], t->y[2], t->x[0], t->y[0]) > 0) &
                                   (e2 + edge_bias(t->x[0], t->y[0], t->x[1], t->y[1]) > 0));
  if (!CLR_ANY(inside)) return;
  // Step 2: barycentrics, then the depth test.
  const float invArea2 = CLR_RECORD_INV_AREA2(*t);
  raster_depth_test(t, s, inside, convert_floatL(e1) * invArea2, convert_floatL(e2) * invArea2, best, rule, rank);
}

/* The edge function of a→b at the samples in 32 bits, modulo 2^32
 * (unsigned arithmetic, whose wrapping is defined): read as an int it is E
 * wherever E fits an int, whatever its terms do. That holds at every sample
 * raster tests of a triangle whose bounds span at most CLR_EDGE32_SPAN
 * fixed units each way (below), and over a row segment that
 * raster_segment_rows admits. (The deltas and offsets fit an int: fixed.h.) */
CLR_INLINE uintL edge_function32(int ax, int ay, int bx, int by, intL px, int py)
{
  return (uint)(bx - ax) * (uint)(py - ay) - (uint)(by - ay) * as_uintL(px - ax);
}

/* The widest and tallest triangle bounds (fixed units, 64 pixels) whose
 * edge functions raster_rows_fixed32 evaluates in 32 bits. Derivation: with
 * width W and height H of the bounds, |bx − ax| <= W, |by − ay| <= H, and
 * the samples tested lie in rows inside the bounds (one step past the last
 * row included: |py − ay| <= H + ONE) and in a 16-lane column that
 * overlaps them (|px − ax| <= W + 15·ONE + ONE, sample offsets included,
 * < W + 2^13), so |E| <= W·(H + 2^8) + H·(W + 2^13) < 2^29 + 2^27 + 2^23
 * for W, H <= 2^14: well inside int32. */
#define CLR_EDGE32_SPAN (1 << 14)

/* raster_row with fixed edges over rows rowBegin .. rowEnd of one column of
 * a tile, the first at sample y firstSy: the edge functions are evaluated
 * once, then stepped by their exact y increment (bx − ax)·CLR_FIXED_ONE per
 * row, so each row costs additions instead of multiplies and gives the same
 * integers. Defined twice by the macro below, with the same body:
 * raster_rows_fixed in 64-bit lanes for any triangle, and
 * raster_rows_fixed32 in 32-bit lanes (half the vector work) for one within
 * CLR_EDGE32_SPAN or a segment that raster_segment_rows admits, stepped
 * modulo 2^32 and read as ints (signedL); the barycentrics convert the
 * same integers to float, so both give bit-identical results.
 * skipEmptyRows: a row no sample of which is inside skips the depth test.
 * That pays on large triangles, whose empty rows come in long runs; a small
 * triangle's empty rows are few and unpredictable, and the branch's
 * mispredictions cost more than testing them with an all-false mask
 * (measured on 252k- and 121k-triangle meshes at 1080p: raster 37% and 18%
 * faster with the 32-bit rows branch-free). */
#define CLR_DEFINE_RASTER_ROWS(name, edgeL, edge, signedL, signedEdge, edgeFunction, toIntL, skipEmptyRows)     \
  CLR_HOT void name(CLR_RECORD_SPACE const TriSetup* t, uint s, intL sx, int firstSy, int rowBegin, int rowEnd, \
                    RowBest* best, const DepthRule* rule, uint rank, const bool acceptAll)                      \
  {                                                                                                             \
    /* Step 1: the edge functions at the first row, their row steps, and the */                                 \
    /* fill rule's thresholds (inside when e > −bias). */                                                     \
    edgeL e0 = edgeFunction(t->x[1], t->y[1], t->x[2], t->y[2], sx, firstSy);                                   \
    edgeL e1 = edgeFunction(t->x[2], t->y[2], t->x[0], t->y[0], sx, firstSy);                                   \
    edgeL e2 = edgeFunction(t->x[0], t->y[0], t->x[1], t->y[1], sx, firstSy);                                   \
    const edge step0 = (edge)(t->x[2] - t->x[1]) * CLR_FIXED_ONE;                                               \
    const edge step1 = (edge)(t->x[0] - t->x[2]) * CLR_FIXED_ONE;                                               \
    const edge step2 = (edge)(t->x[1] - t->x[0]) * CLR_FIXED_ONE;                                               \
    const signedEdge low0 = -(signedEdge)edge_bias(t->x[1], t->y[1], t->x[2], t->y[2]);                         \
    const signedEdge low1 = -(signedEdge)edge_bias(t->x[2], t->y[2], t->x[0], t->y[0]);                         \
    const signedEdge low2 = -(signedEdge)edge_bias(t->x[0], t->y[0], t->x[1], t->y[1]);                         \
    const float invArea2 = CLR_RECORD_INV_AREA2(*t);                                                            \
    /* Step 2: each row: coverage, barycentrics, depth test; then step. */                                      \
    for (int row = rowBegin; row <= rowEnd; ++row) {                                                            \
      intL inside = (intL)(-1);                                                                                 \
      if (!acceptAll) inside = toIntL((signedL(e0) > low0) & (signedL(e1) > low1) & (signedL(e2) > low2));      \
      if (acceptAll || !(skipEmptyRows) || CLR_ANY(inside))                                                     \
        raster_depth_test(t, s, inside, convert_floatL(signedL(e1)) * invArea2,                                 \
                          convert_floatL(signedL(e2)) * invArea2, &best[row], rule, rank);                      \
      e0 += step0;                                                                                              \
      e1 += step1;                                                                                              \
      e2 += step2;                                                                                              \
    }                                                                                                           \
  }
CLR_DEFINE_RASTER_ROWS(raster_rows_fixed, longL, long, , long, edge_function, convert_intL, true)
CLR_DEFINE_RASTER_ROWS(raster_rows_fixed32, uintL, uint, as_intL, int, edge_function32, , false)
#undef CLR_DEFINE_RASTER_ROWS

/* For a large triangle's row segment of CLR_LANES samples from sample x
 * firstSx (row r at sample y (firstY + r)·CLR_FIXED_ONE + centreY):
 * narrows rows *rowBegin .. *rowEnd to those where every edge function can
 * pass the fill rule at some lane, and returns whether the three edge
 * functions fit an int over the rows kept, so that raster_rows_fixed32
 * gives the integers of the 64-bit loop (it steps them in unsigned
 * arithmetic, modulo 2^32, so that a row step beyond an int, up to 2^33,
 * or the step past its last row, wraps harmlessly: a signed overflow there
 * let the compiler change the pixels of a frame of the Haus model).
 * - The rows: an edge function is linear, so over a row's lanes it is
 *   largest at the first lane or the last, and that largest value changes
 *   by the row step (bx − ax)·CLR_FIXED_ONE from row to row. Each edge
 *   holds the rows on one side of a boundary k (rows from the first,
 *   eMax + k·step = low), and the range kept is the intersection. k is
 *   computed in float as k' and clamped to ±(CLR_TILE_SIZE + 2), beyond
 *   which the boundary leaves every row of the tile on one side; inside
 *   that range |k' − k| < 1 (a quotient of two roundings: relative error
 *   below 2^-22). Truncating k' then never drops a row with a sample
 *   inside: a rising edge's first such row is floor(k) + 1, and trunc(k')
 *   is at most that (floor(k') for k' >= 0; for k' < 0 all rows are kept);
 *   a falling edge's last is ceil(k) − 1, and trunc(k') >= ceil(k') >=
 *   ceil(k − 1) for k' < 0, floor(k') >= ceil(k) − 1 for k' >= 0. Rows
 *   kept may still be empty; the row loops skip or mask those.
 * - The fit: the extremes of a linear function over the rectangle lie at
 *   its corners, computed in 64 bits (fixed.h: |E| < 2^51). A large
 *   triangle fits near its edges (E grows with the distance from an edge
 *   times its length: a 1000-pixel edge fits within about 8 pixels of it)
 *   and not deep inside.
 * Branch-free, the three edges in the lanes of vectors. */
CLR_INLINE bool raster_segment_rows(CLR_RECORD_SPACE const TriSetup* t, int firstSx, int firstY, int centreY,
                                    int* rowBegin, int* rowEnd)
{
  // The three edges side by side in the lanes x, y, z of 4-vectors (edge i
  // runs from vertex i + 1 to vertex i + 2, as in raster_rows_fixed); w is
  // unused.
  const int first = *rowBegin, firstSy = (firstY + first) * CLR_FIXED_ONE + centreY;
  const int4 ax = (int4)(t->x[1], t->x[2], t->x[0], 0), ay = (int4)(t->y[1], t->y[2], t->y[0], 0);
  const int4 bx = (int4)(t->x[2], t->x[0], t->x[1], 0), by = (int4)(t->y[2], t->y[0], t->y[1], 0);
  // Step 1: each edge's largest value over the lanes of the first row
  // (E = dx·(py − ay) − dy·(px − ax)), its spread over the lanes, its row
  // step and its threshold (inside when E > low, the fill rule's bias).
  const int4 dx = bx - ax, dy = by - ay;
  const int4 px = select((int4)(firstSx + (CLR_LANES - 1) * CLR_FIXED_ONE), (int4)firstSx, dy > 0);
  const long4 eMax = convert_long4(dx) * convert_long4(firstSy - ay) - convert_long4(dy) * convert_long4(px - ax);
  const long4 across = convert_long4(abs(dy)) * ((CLR_LANES - 1) * CLR_FIXED_ONE);
  const long4 step = convert_long4(dx) * CLR_FIXED_ONE;
  const long4 low = convert_long4(CLR_EDGE_HOLDS_SAMPLES(ax, ay, bx, by));  // −1 or 0
  // Step 2: the rows k from the first where eMax + k·step > low: from the
  // boundary on when the edge rises (a level edge: all rows or none), up
  // to it when it falls.
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
  // Step 3: the fit, over rows begin .. end.
  const long4 top0 = eMax + (long)(begin - first) * step, top1 = eMax + (long)(end - first) * step;
  const int4 fits = convert_int4((min(top0, top1) - across >= INT_MIN) & (max(top0, top1) <= INT_MAX));
  return (fits.x & fits.y & fits.z) != 0;
}

/* The visibility buffer's index planes (shared.h): 16-bit entries, 0xFFFF
 * for none, when FrameParams.visIndex16, else 32-bit ones; i counts
 * entries either way. vis_index_at reads one entry, vis_load_index_lanes
 * CLR_LANES from i (CLR_NONE past `count`) into `lanes` and returns them
 * as a vector too (use that, not a load of `lanes`: the compiler splits the
 * store, and a wide load right after it waits for all the pieces; that
 * took a fifth of resolve's time on a screen of large triangles),
 * vis_store_index_lanes writes them (a setup index is below 0xFFFF when the
 * entries are 16-bit). */
CLR_INLINE uint vis_index_at(__constant FrameParams* params, __global const uint* visIndex, uint i)
{
  if (!params->visIndex16) return visIndex[i];
  const uint v = ((__global const ushort*)visIndex)[i];
  return v == 0xFFFFu ? CLR_NONE : v;
}
CLR_INLINE uintL vis_load_index_lanes(__constant FrameParams* params, __global const uint* visIndex, uint i, uint count,
                                      uint* lanes)
{
  if (count < CLR_LANES) {
    for (uint lane = 0; lane < CLR_LANES; ++lane)
      lanes[lane] = lane < count ? vis_index_at(params, visIndex, i + lane) : CLR_NONE;
    return CLR_LOAD_LANES(lanes);  // the viewport's edge: rare
  }
  uintL v;
  if (params->visIndex16) {
    const uintL wide = convert_uintL(CLR_LOAD_LANES((__global const ushort*)visIndex + i));
    v = select(wide, (uintL)CLR_NONE, wide == 0xFFFFu);
  } else {
    v = CLR_LOAD_LANES(visIndex + i);
  }
  CLR_STORE_LANES(v, lanes);
  return v;
}
CLR_INLINE void vis_store_index_lanes(__constant FrameParams* params, uintL index, __global uint* visIndex, uint i)
{
  if (!params->visIndex16) {
    CLR_STORE_LANES(index, visIndex + i);
    return;
  }
  // (CLR_NONE keeps its low 16 bits, 0xFFFF.)
#if CLR_LANES == 16
  // One aligned vector store: i is a multiple of 16 (a row segment of a
  // tile's block, vis_address, in a plane of whole blocks). vstore16 of
  // ushorts compiles to 16 two-byte stores on PoCL (raster on the close 10k
  // sphere 1.88 -> 1.64 ms); of uints, to three vector stores, which
  // measured no slower than one.
  *(__global ushort16*)((__global ushort*)visIndex + i) = convert_ushort16(index);
#else
  CLR_STORE_LANES(convert_ushortL(index), (__global ushort*)visIndex + i);
#endif
}

/* Writes a row segment of samples into sample plane k of the visibility
 * buffer (shared.h) at address a of the plane: one vector store per plane,
 * the depth and barycentric planes only when the frame has them; with the
 * z-buffer, a sample whose depth is still the clear key gets CLR_NONE
 * (RowBest). The tile's block has room for its whole rows, so lanes past
 * the viewport's edge are stored too (and never read). */
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

/* The edge function of a→b at the samples, with a and b per lane: the
 * integers of edge_function, exact in 64 bits. */
CLR_INLINE longL edge_function_lanes(intL ax, intL ay, intL bx, intL by, intL px, int py)
{
  return convert_longL(bx - ax) * convert_longL(py - ay) - convert_longL(by - ay) * convert_longL(px - ax);
}

/* The screen barycentrics b1, b2 that raster kept for the samples
 * (sx + lane·CLR_FIXED_ONE, sy) with fixed edges, of the lanes' triangles
 * with snapped vertices (x_i, y_i) and 1 / (2·area) `scale`: the same integer
 * edge functions E1, E2, converted to float and scaled as in raster_row and
 * raster_rows_fixed, so the floats are bit-identical. Resolve calls this
 * when the frame has no barycentric planes (shared.h). Lanes outside
 * `covered` give values the caller discards. */
CLR_INLINE void vis_barycentrics(intL x0, intL y0, intL x1, intL y1, intL x2, intL y2, floatL scale, intL covered,
                                 intL sx, int sy, floatL* b1, floatL* b2)
{
  // E1 of edge 2→0 and E2 of edge 0→1, as raster_row has them. In 32 bits
  // when every covered lane's scale is at least 2^-30: unsigned arithmetic
  // is exact modulo 2^32, and a covered sample's E lies in [0, 2·area],
  // where scale = RN(1 / RN(2·area)) >= 2^-30 bounds RN(2·area) by 2^30 and
  // so 2·area below 2^30 + 64 < 2^31: the low 32 bits read as int are E
  // (uncovered lanes may wrap; they are discarded). That holds for every
  // triangle within CLR_EDGE32_SPAN (2·area <= 2^28) and for larger ones
  // up to about 8000 square pixels. Else in 64 bits. Either way the same
  // integers, so the same floats.
  const float minScale = 1.0f / 1073741824.0f;  // 2^-30
  if (!CLR_ANY(covered & (scale < minScale))) {
    const uintL py = (uintL)(uint)sy, px = as_uintL(sx);
    const uintL ax0 = as_uintL(x0), ax1 = as_uintL(x1), ax2 = as_uintL(x2);
    const uintL ay0 = as_uintL(y0), ay1 = as_uintL(y1), ay2 = as_uintL(y2);
    *b1 = convert_floatL(as_intL((ax0 - ax2) * (py - ay2) - (ay0 - ay2) * (px - ax2))) * scale;
    *b2 = convert_floatL(as_intL((ax1 - ax0) * (py - ay0) - (ay1 - ay0) * (px - ax0))) * scale;
    return;
  }
  *b1 = convert_floatL(edge_function_lanes(x2, y2, x0, y0, sx, sy)) * scale;
  *b2 = convert_floatL(edge_function_lanes(x0, y0, x1, y1, sx, sy)) * scale;
}

/* The skip of hidden triangles, under the z-buffer with fixed edges, in
 * every depth format and both shapes: a bin entry whose every fragment's
 * key lies beyond a kept key can take none of those samples. The CPU shape
 * compares with the farthest key its tile keeps (tileFar, raster_tile_far,
 * refreshed every CLR_FAR_REFRESH entries, unless every entry since the
 * last refresh was skipped and so changed nothing; it only falls, so a
 * stale one skips less, never wrongly) and skips the entry before its rows
 * (the refresh's condition took raster 2-3% off the engine filling 1080p,
 * 1-3% elsewhere, in bench/ab.sh turns); the GPU
 * shape's work-item compares with its own sample's kept key and skips the
 * entry's edge tests (raster_pixel). raster_nearest_key gives the nearest
 * key a triangle's fragments can have. The margin: a fragment's depth is
 * z = z0 + b1·(z1 − z0) + b2·(z2 − z0) in floats (raster_depth_test) with
 * b1, b2 >= 0 (an inside sample has E1, E2 >= 0, and 1/(2 area) > 0) and
 * b1 + b2 <= (E1 + E2)/(2 area)·(1 + 4u) <= 1 + 4u, u = 2^-24 (four
 * roundings: two conversions, the reciprocal, the product). With
 * M = max |z_i|, the exact value with those b lies within 8u·M of
 * [min z_i, max z_i] (z0's weight is at least −4u), and the two
 * differences, two products and two sums round by at most 10u·M more: z
 * lies within 18u·M of the vertices' range. The skip widens the range by
 * 2^-18·M (64u·M, 3.5 times the bound; 2^-120 more for depths so small that
 * roundings are absolute) and takes the nearest key of the widened range
 * (every format's key is monotonic in z: raster_depth_key); when that key
 * is beyond the kept key, no fragment would have passed the test or tied
 * (a fragment with a NaN depth never passes, but under unorm24, so there a
 * vertex depth that is not finite skips nothing: −∞). A test
 * (test_kernels.cpp) finds, in each format, a triangle rounded in front of
 * its nearest vertices, which the skip without its margin drops (float32,
 * reversed; unorm24's steps hide it). CPU shape, raster at 1080p on the
 * 2-core machine, medians of alternated pairs: yxa_1 filling the screen
 * 2.55 -> 2.19 ms (float32, ten pairs), 3.17 -> 2.88 (reversed, four),
 * 5.11 -> 4.79 (unorm24, three); the 1M-triangle sphere near
 * 10.3 -> 9.0 ms and far 6.5 -> 6.3 ms (six), the engine filling the
 * screen 9.4 -> 6.0 ms (four). */
CLR_INLINE float raster_nearest_key(float z0, float z1, float z2, uint depthMode)
{
  const float margin = max(fabs(z0), max(fabs(z1), fabs(z2))) * 0x1p-18f + 0x1p-120f;
  // The nearest key of the widened range (raster_depth_key's, scalar).
  if (depthMode == CLR_DEPTH_REVERSED) return -(max(z0, max(z1, z2)) + margin);
  const float zLow = min(z0, min(z1, z2)) - margin;
  if (depthMode != CLR_DEPTH_UNORM24) return zLow;
  // (A NaN vertex depth makes every fragment's key NaN, never taken, but
  // for unorm24, which clamps it to the nearest key.)
  if (!(isfinite(z0) && isfinite(z1) && isfinite(z2))) return -INFINITY;
  return rint(clamp(zLow, 0.0f, 1.0f) * CLR_DEPTH_UNORM24_MAX);
}

/* The raster kernels' parameters, the same for every variant below:
 *   params, setup, tileOffset (tiles + 1), binEntries,
 *   visIndex (samples · visPlane), visAttr (3 · samples · visPlane),
 *   paintRank (numTris: each input triangle's paint rank with the
 *   painter's algorithm, else its index in the file), tileSlot
 *   (tiles + 1: each non-empty tile's slot) and visPlane (slots · tile²). */
#define CLR_RASTER_PARAMS                                                                                              \
  __constant FrameParams *params, __global const TriSetup *setup, __global const uint *source,                         \
      __global const ClipBary *clipBary, __global const uint *tileOffset, __global const uint *binEntries,             \
      __global uint *visIndex, __global float *visAttr, __global const uint *paintRank, __global const uint *tileSlot, \
      uint visPlane
#define CLR_RASTER_ARGS \
  params, setup, source, clipBary, tileOffset, binEntries, visIndex, visAttr, paintRank, tileSlot, visPlane

/* The method variants are separate kernels (raster, raster_hierarchical,
 * raster_float) rather than branches of one, so that a device compiles only
 * the variant a frame launches (PoCL compiles each kernel at its first
 * launch), and each loop body has its method fixed at compile time. The
 * default, raster, is in the frame program; the other two in the extras
 * program (CLR_EXTRAS, shared.h), which a cold start does not build. */
#if CLR_LANES == 1
/* GPU shape: one work-item per pixel sample, one work-group per tile and
 * sample index. Hierarchical traversal needs nothing here beyond binning.
 * The group walks its tile's bin list in batches of one entry per
 * work-item: each work-item copies one entry's setup record (and paint
 * rank) into local memory, then every work-item tests its sample against
 * the whole batch there. When each work-item read the records itself, from
 * global memory one after another, raster on an H100 took the same 0.74 ms
 * on the IFC house at every resolution, as if bound by the latency of those
 * loads along its longest bin list; with the batches it takes 0.40 ms
 * filling 1080p (the engine 0.84 -> 0.56 ms, yxa_1 0.36 -> 0.24 ms). The
 * loading work-item also stores the record's bounds, and a sample outside
 * them skips the record's edge tests: yxa_1 0.24 -> 0.14 ms, the 1M sphere
 * far 0.59 -> 0.27 ms, the engine 0.56 -> 0.44 ms; the IFC house, whose
 * triangles span its tiles, is unchanged. */
#define CLR_RASTER_BATCH (CLR_TILE_SIZE * CLR_TILE_SIZE)
CLR_INLINE void raster_pixel(CLR_RASTER_PARAMS, const uint edgeMode, __local TriSetup* records, __local int4* bounds,
                             __local float* nearestKeys, __local uint* indices, __local uint* ranks)
{
  const uint px = get_global_id(0), py = get_global_id(1), k = get_global_id(2);
  const uint tile = get_group_id(1) * params->tilesX + get_group_id(0);
  const uint item = get_local_id(1) * CLR_TILE_SIZE + get_local_id(0);
  const int sx = (int)px * CLR_FIXED_ONE + CLR_FIXED_HALF + params->sampleX[k];
  const int sy = (int)py * CLR_FIXED_ONE + CLR_FIXED_HALF + params->sampleY[k];
  const uint begin = tileOffset[tile], end = tileOffset[tile + 1];
  if (begin == end) return;  // the whole group: resolve fills empty tiles without reading the visibility buffer
  const DepthRule rule = raster_depth_rule(params, source, clipBary, paintRank);
  const bool painter = rule.visibility == CLR_VISIBILITY_PAINTER;
  const bool skipHidden = !painter && edgeMode == CLR_EDGES_FIXED;  // raster_nearest_key
  RowBest best;
  row_best_init(&best, rule.clearKey, rule.visibility);
  for (uint first = begin; first < end; first += CLR_RASTER_BATCH) {
    // Step 1: the batch's records into local memory, one per work-item.
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
    // Step 2: this sample against each, in bin order; a sample outside a
    // triangle's bounds is outside the triangle, and one whose kept key is
    // nearer than any of the triangle's fragments keeps it: either skips
    // the edge tests.
    for (uint n = 0; n < count; ++n) {
      const int4 b = bounds[n];
      if (sx < b.x || sy < b.y || sx > b.z || sy > b.w || nearestKeys[n] > best.depth) continue;
      raster_row(&records[n], indices[n], sx, sy, &best, &rule, ranks[n], edgeMode);
    }
  }
  raster_write_row(params, visPlane, k, vis_address(tileSlot[tile], px, py), &best, visIndex, visAttr);
}

/* Each kernel declares the batch's local memory (OpenCL 1.2 allows it only
 * at kernel scope): 256 records of 48 bytes, their bounds, nearest keys
 * and two words each, 19 KB. */
#define CLR_DEFINE_RASTER_PIXEL_KERNEL(name, edgeMode)                                                         \
  __kernel __attribute__((reqd_work_group_size(CLR_TILE_SIZE, CLR_TILE_SIZE, 1))) void name(CLR_RASTER_PARAMS) \
  {                                                                                                            \
    __local TriSetup records[CLR_RASTER_BATCH];                                                                \
    __local int4 bounds[CLR_RASTER_BATCH];                                                                     \
    __local float nearestKeys[CLR_RASTER_BATCH];                                                               \
    __local uint indices[CLR_RASTER_BATCH], ranks[CLR_RASTER_BATCH];                                           \
    raster_pixel(CLR_RASTER_ARGS, edgeMode, records, bounds, nearestKeys, indices, ranks);                     \
  }
#if !CLR_EXTRAS
CLR_DEFINE_RASTER_PIXEL_KERNEL(raster, CLR_EDGES_FIXED)
#else
CLR_DEFINE_RASTER_PIXEL_KERNEL(raster_hierarchical, CLR_EDGES_FIXED)
CLR_DEFINE_RASTER_PIXEL_KERNEL(raster_float, CLR_EDGES_FLOAT)
#endif
#else
#define CLR_FAR_REFRESH 8
CLR_INLINE float raster_tile_far(const RowBest best[CLR_TILE_SIZE / CLR_LANES][CLR_TILE_SIZE])
{
  floatL far = best[0][0].depth;
  for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col)
    for (int row = 0; row < CLR_TILE_SIZE; ++row) far = max(far, best[col][row].depth);
  return clr_max_lanes(far);
}

/* CPU shape: one work-item per tile and sample index, as llvmpipe's
 * per-tile threads. Each triangle is tested only on the rows its bounds
 * span, a 16-pixel vector row at a time; the tile's nearest fragments stay
 * in private memory. */
CLR_INLINE void raster_tile(CLR_RASTER_PARAMS, uint tileX, uint tileY, uint k, const uint edgeMode,
                            const bool hierarchical)
{
  const uint tile = tileY * params->tilesX + tileX;
  const int firstY = (int)tileY * CLR_TILE_SIZE;
  const uint begin = tileOffset[tile], end = tileOffset[tile + 1];
  if (begin == end) return;  // resolve fills empty tiles without reading the visibility buffer
  // Step 1: the tile's sample positions and its nearest fragments so far.
  const int offsetX = params->sampleX[k], offsetY = params->sampleY[k];
  const DepthRule rule = raster_depth_rule(params, source, clipBary, paintRank);
  const bool painter = rule.visibility == CLR_VISIBILITY_PAINTER;
  // The default depth rule (float32, z-buffer) as constants: its row loops,
  // specialised below, have no branch on the rule, so the compiler keeps
  // their masks in mask registers (raster on yxa_1 filling 1080p 1.98 ->
  // 1.79 ms, the engine filling it 9.80 -> 9.41 ms).
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
  const bool skipHidden = !painter && edgeMode == CLR_EDGES_FIXED;  // raster_nearest_key
  float tileFar = rule.clearKey;
  bool stale = false;  // an entry since the last refresh reached the rows
  // Step 2: each binned triangle, on the rows and row segments its bounds span.
  for (uint n = begin; n < end; ++n) {
    const uint s = binEntries[n];
    __global const TriSetup* t = &setup[s];
#ifdef CLR_PREFETCH
    // The records of a bin are scattered: fetch a later one's while this one is tested.
    if (n + CLR_PREFETCH < end) __builtin_prefetch(&setup[binEntries[n + CLR_PREFETCH]]);
#endif
    if (skipHidden) {
      if ((n - begin) % CLR_FAR_REFRESH == CLR_FAR_REFRESH - 1 && stale) {
        tileFar = raster_tile_far(best);
        stale = false;
      }
      // (the default rule's test with its format a constant)
      const float nearest = defaultRule ? raster_nearest_key(t->z[0], t->z[1], t->z[2], CLR_DEPTH_FLOAT32)
                                        : raster_nearest_key(t->z[0], t->z[1], t->z[2], rule.depthMode);
      if (nearest > tileFar) continue;
      stale = true;
    }
    const uint rank = painter ? paintRank[clr_source_triangle(source[s], clipBary)] : 0u;
    const int4 bounds = CLR_RECORD_BOUNDS(*t);
    const int minX = bounds.x, minY = bounds.y, maxX = bounds.z, maxY = bounds.w;
    const bool small = maxX - minX <= CLR_EDGE32_SPAN && maxY - minY <= CLR_EDGE32_SPAN;
    const int centreY = CLR_FIXED_HALF + offsetY;
    const int rowBegin = max(0, ((minY - centreY + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS) - firstY);
    const int rowEnd = min(CLR_TILE_SIZE - 1, ((maxY - centreY) >> CLR_SUBPIXEL_BITS) - firstY);
    // Hierarchical: a tile inside all three edges needs no inside test.
    bool acceptAll = false;
    if (hierarchical) {
      const TriSetup tri = *t;
      acceptAll = bin_tile_class(&tri, params, (int)tileX, (int)tileY) > 0;
    }
    for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col) {
      const int firstSx = (int)(tileX * CLR_TILE_SIZE + col * CLR_LANES) * CLR_FIXED_ONE + CLR_FIXED_HALF + offsetX;
      if (firstSx > maxX || firstSx + (CLR_LANES - 1) * CLR_FIXED_ONE < minX) continue;
      // A large triangle's segment: the rows that can hold a sample inside,
      // in 32-bit lanes where its edge functions fit (near its edges).
      int rowFirst = rowBegin, rowLast = rowEnd;
      bool rows32 = small;
      if (edgeMode == CLR_EDGES_FIXED && !small && !(hierarchical && acceptAll)) {
        rows32 = raster_segment_rows(t, firstSx, firstY, centreY, &rowFirst, &rowLast);
        if (rowFirst > rowLast) continue;
      }
      if (edgeMode == CLR_EDGES_FIXED && rows32 && defaultRule) {
        raster_rows_fixed32(t, s, sx[col], (firstY + rowFirst) * CLR_FIXED_ONE + centreY, rowFirst, rowLast, best[col],
                            &zbufferFloat32, rank, hierarchical && acceptAll);
        continue;
      }
      if (edgeMode == CLR_EDGES_FIXED && rows32) {
        raster_rows_fixed32(t, s, sx[col], (firstY + rowFirst) * CLR_FIXED_ONE + centreY, rowFirst, rowLast, best[col],
                            &rule, rank, hierarchical && acceptAll);
        continue;
      }
      if (edgeMode == CLR_EDGES_FIXED && defaultRule) {
        raster_rows_fixed(t, s, sx[col], (firstY + rowFirst) * CLR_FIXED_ONE + centreY, rowFirst, rowLast, best[col],
                          &zbufferFloat32, rank, hierarchical && acceptAll);
        continue;
      }
      if (edgeMode == CLR_EDGES_FIXED) {
        raster_rows_fixed(t, s, sx[col], (firstY + rowFirst) * CLR_FIXED_ONE + centreY, rowFirst, rowLast, best[col],
                          &rule, rank, hierarchical && acceptAll);
        continue;
      }
      for (int row = rowFirst; row <= rowLast; ++row) {
        const int sy = (firstY + row) * CLR_FIXED_ONE + centreY;
        raster_row(t, s, sx[col], sy, &best[col][row], &rule, rank, edgeMode);
      }
    }
  }
  // Step 3: write the tile's block of the sample plane.
  const uint slot = tileSlot[tile];
  for (int col = 0; col < CLR_TILE_SIZE / CLR_LANES; ++col)
    for (int row = 0; row < CLR_TILE_SIZE; ++row)
      raster_write_row(params, visPlane, k, vis_address(slot, col * CLR_LANES, row), &best[col][row], visIndex,
                       visAttr);
}

/* A CPU-shape raster kernel: its method fixed at compile time, its body one
 * called function (CLR_KERNEL_BODY, shared.h). */
#define CLR_RASTER_TILE_KERNEL(name, edgeMode, hierarchical)                            \
  CLR_KERNEL_BODY void name##_body(CLR_RASTER_PARAMS, uint tileX, uint tileY, uint k)   \
  {                                                                                     \
    raster_tile(CLR_RASTER_ARGS, tileX, tileY, k, edgeMode, hierarchical);              \
  }                                                                                     \
  __kernel __attribute__((reqd_work_group_size(1, 1, 1))) void name(CLR_RASTER_PARAMS)  \
  {                                                                                     \
    name##_body(CLR_RASTER_ARGS, get_global_id(0), get_global_id(1), get_global_id(2)); \
  }
#if !CLR_EXTRAS
CLR_RASTER_TILE_KERNEL(raster, CLR_EDGES_FIXED, false)
#else
CLR_RASTER_TILE_KERNEL(raster_hierarchical, CLR_EDGES_FIXED, true)
CLR_RASTER_TILE_KERNEL(raster_float, CLR_EDGES_FLOAT, false)
#endif
#endif
