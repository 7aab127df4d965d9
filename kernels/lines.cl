/* lines.cl — wireframe edges and line segments, binned into the triangles' tiles and drawn per tile after resolve.
 *
 * Segments (LineSeg) come from setup records (lines_from_setup) or the host; lines_bin_count / scan /
 * lines_bin_fill bin every tile with pixel centres within LineParams.reach. lines_draw: one work-item per tile; per
 * pixel the largest coverage of any segment passing the depth test, so a shared edge draws once.
 *  Bresenham: end pixels (x >> 8, y >> 8), both drawn; decision d = 2a(i + 1) − b − 2bk (a = |minor delta|,
 *    b = |major delta|, k = minor steps before step i), closed form at the tile's first column, then +2a, −2b.
 *    Ties go to the lower minor coordinate, so both directions draw the same pixels. Coverage 1.
 *  Anti-aliased: a butt-ended rectangle of width w; with distance d across and s along,
 *    cover = [F(w/2 − d) − F(−w/2 − d)] · [F(L − s) − F(−s)], F the pixel square's area on one side of a line
 *    (exact trapezoid): exact away from the ends, approximate within a pixel of them.
 * Depth is affine in screen space; a pixel draws when depth <= visible depth + depthBias + (|dz/dx| + |dz/dy|)·
 * (reach + 0.75) against sample 0 (1 for background): the slope term spans pixel centre to the line's depth point,
 * so visible edges pass and hidden ones fail.
 */
#pragma OPENCL FP_CONTRACT OFF
#include "vis.h"
#if CLR_EXTRAS /* the extras program (CLR_EXTRAS, shared.h) */

/* The three edges of every setup record. A clipped sub-triangle keeps only edges on an input edge (both ends weigh
 * one input vertex exactly zero, which clipping preserves): no fan diagonals or near cuts. Dead records skip. */
__kernel void lines_from_setup(__global const TriSetup* setup, uint numSetup,
                               __global const uint* source,        // numSetup: source words
                               __global const ClipBary* clipBary,  // clip slots
                               __global LineSeg* segs)             // 3 · numSetup
{
  const uint s = get_global_id(0);
  if (s >= numSetup) return;
  const TriSetup t = setup[s];
  const uint from = source[s], clipSlot = clr_source_clip_slot(from), triId = clr_source_triangle(from, clipBary);
  const bool clipped = clipSlot != CLR_NOT_CLIPPED;
  ClipBary w;
  if (clipped) w = clipBary[clipSlot];
  const bool dead = clipped && (w.flags & CLR_FLAG_DEAD) != 0;
  for (int e = 0; e < 3; ++e) {
    const int a = e, b = (e + 1) % 3;
    LineSeg seg;
    seg.x[0] = t.x[a];
    seg.y[0] = t.y[a];
    seg.x[1] = t.x[b];
    seg.y[1] = t.y[b];
    seg.z[0] = t.z[a];
    seg.z[1] = t.z[b];
    seg.triId = triId;
    bool skip = dead;
    if (clipped && !dead) {
      bool onInputEdge = false;
      for (int j = 0; j < 3; ++j) onInputEdge = onInputEdge || (w.w[a][j] == 0.0f && w.w[b][j] == 0.0f);
      skip = !onInputEdge;
    }
    seg.flags = skip ? CLR_LINE_SKIP : 0u;
    segs[3 * s + e] = seg;
  }
}

/* The ends in pixel units: end pixel centres (Bresenham) or exact ends; exact in float (|x| <= 2^24, fixed.h). */
CLR_INLINE float4 line_ends(const LineSeg* s, __constant LineParams* lp)
{
  const float k = 1.0f / CLR_FIXED_ONE;
  if (lp->method == CLR_LINE_BRESENHAM)
    return (float4)((float)(s->x[0] >> CLR_SUBPIXEL_BITS) + 0.5f, (float)(s->y[0] >> CLR_SUBPIXEL_BITS) + 0.5f,
                    (float)(s->x[1] >> CLR_SUBPIXEL_BITS) + 0.5f, (float)(s->y[1] >> CLR_SUBPIXEL_BITS) + 0.5f);
  return (float4)((float)s->x[0] * k, (float)s->y[0] * k, (float)s->x[1] * k, (float)s->y[1] * k);
}

/* Tiles of the viewport holding pixel centres within `reach` of the ends'
 * bounding box; empty (x > z) when none. */
CLR_INLINE int4 line_tile_range(float4 e, float reach, __constant FrameParams* params)
{
  const float minX = min(e.x, e.z) - reach, maxX = max(e.x, e.z) + reach;
  const float minY = min(e.y, e.w) - reach, maxY = max(e.y, e.w) + reach;
  // Pixel i's centre is i + 0.5; clamp before converting (ends may lie far out).
  const float w = (float)params->width, h = (float)params->height;
  if (maxX < 0.0f || maxY < 0.0f || minX > w || minY > h) return (int4)(0, 0, -1, -1);
  const int x0 = max(0, (int)ceil(max(minX, -1.0f) - 0.5f)),
            x1 = min((int)params->width - 1, (int)floor(min(maxX, w) - 0.5f));
  const int y0 = max(0, (int)ceil(max(minY, -1.0f) - 0.5f)),
            y1 = min((int)params->height - 1, (int)floor(min(maxY, h) - 0.5f));
  if (x0 > x1 || y0 > y1) return (int4)(0, 0, -1, -1);
  return (int4)(x0, y0, x1, y1) / CLR_TILE_SIZE;
}

/* Whether tile (tx, ty)'s centres may lie within `reach` of the line: centre distance less the tile's half extent
 * along the normal, half a pixel conservative for float rounding (coordinates up to 2^17 px). */
CLR_INLINE bool line_touches_tile(float4 e, float reach, int tx, int ty)
{
  const float extent = 0.5f * (CLR_TILE_SIZE - 1);
  const float cx = (float)(tx * CLR_TILE_SIZE) + 0.5f + extent, cy = (float)(ty * CLR_TILE_SIZE) + 0.5f + extent;
  const float dx = e.z - e.x, dy = e.w - e.y;
  const float len = sqrt(dx * dx + dy * dy);
  if (len == 0.0f) return true;  // a point: the bounds decided
  const float dist = fabs(dx * (cy - e.y) - dy * (cx - e.x)) / len;
  return dist <= reach + extent * (fabs(dx) + fabs(dy)) / len + 0.5f;
}

/* Both binning passes for segment n: +1 to each tile it may touch (count), or n into that tile's bin at the
 * scanned offset plus a per-tile cursor (fill: tileCount is then the cursor). */
CLR_INLINE void lines_bin(__constant FrameParams* params, __constant LineParams* lp, __global const LineSeg* segs,
                          __global uint* tileCount, bool fill, __global const uint* tileOffset,
                          __global uint* binEntries)
{
  const uint n = get_global_id(0);
  if (n >= lp->numSegments) return;
  const LineSeg s = segs[n];
  if (s.flags & CLR_LINE_SKIP) return;
  const float4 e = line_ends(&s, lp);
  const int4 r = line_tile_range(e, lp->reach, params);
  for (int ty = r.y; ty <= r.w; ++ty)
    for (int tx = r.x; tx <= r.z; ++tx) {
      if (!line_touches_tile(e, lp->reach, tx, ty)) continue;
      const uint tile = ty * params->tilesX + tx;
      const uint at = atomic_inc(&tileCount[tile]);
      if (fill) binEntries[tileOffset[tile] + at] = n;
    }
}

__kernel void lines_bin_count(__constant FrameParams* params, __constant LineParams* lp,
                              __global const LineSeg* segs,  // lp->numSegments
                              __global uint* tileCount)      // tiles + 1
{
  lines_bin(params, lp, segs, tileCount, false, tileCount, tileCount);
}

__kernel void lines_bin_fill(__constant FrameParams* params, __constant LineParams* lp,
                             __global const LineSeg* segs,     // lp->numSegments
                             __global const uint* tileOffset,  // tiles + 1, scanned
                             __global uint* tileCursor,        // tiles, zeroed
                             __global uint* binEntries)        // tileOffset[tiles]
{
  lines_bin(params, lp, segs, tileCursor, true, tileOffset, binEntries);
}

/* |dz/dx| + |dz/dy| of a setup triangle's window depth, per pixel. */
CLR_INLINE float line_depth_slope(__global const TriSetup* t)
{
  const float s = CLR_RECORD_INV_AREA2(*t) * (float)CLR_FIXED_ONE;
  const float dz1 = t->z[1] - t->z[0], dz2 = t->z[2] - t->z[0];
  const float gx = s * (dz1 * (float)(t->y[2] - t->y[0]) + dz2 * (float)(t->y[0] - t->y[1]));
  const float gy = s * (dz1 * (float)(t->x[0] - t->x[2]) + dz2 * (float)(t->x[1] - t->x[0]));
  return fabs(gx) + fabs(gy);
}

/* A tile's per-pixel state: [row][column], row 0 at the tile's bottom. */
typedef struct LineTile {
  int x0, y0;                                 // the tile's first pixel
  float cover[CLR_TILE_SIZE][CLR_TILE_SIZE];  // largest coverage so far
  float limit[CLR_TILE_SIZE][CLR_TILE_SIZE];  // deepest depth that passes; −inf outside the viewport
} LineTile;

CLR_INLINE void line_plot(LineTile* tile, int px, int py, float z, float c)
{
  const int col = px - tile->x0, row = py - tile->y0;
  if (z <= tile->limit[row][col]) tile->cover[row][col] = max(tile->cover[row][col], c);
}

/* Bresenham, the steps of the segment that fall in the tile. */
CLR_INLINE void line_bresenham(const LineSeg* s, LineTile* tile)
{
  // Step 1: end pixels, major axis, deltas and directions.
  const int px0 = s->x[0] >> CLR_SUBPIXEL_BITS, py0 = s->y[0] >> CLR_SUBPIXEL_BITS;
  const int px1 = s->x[1] >> CLR_SUBPIXEL_BITS, py1 = s->y[1] >> CLR_SUBPIXEL_BITS;
  const bool xMajor = abs(px1 - px0) >= abs(py1 - py0);
  const int m0 = xMajor ? px0 : py0, m1 = xMajor ? px1 : py1;
  const int n0 = xMajor ? py0 : px0, n1 = xMajor ? py1 : px1;
  const long b = abs(m1 - m0), a = abs(n1 - n0);
  const int sm = m1 >= m0 ? 1 : -1, sn = n1 >= n0 ? 1 : -1;
  const bool tieSteps = sn < 0;  // ties go to the lower minor coordinate
  // Step 2: the steps i whose major coordinate lies in the tile.
  const int tileM0 = xMajor ? tile->x0 : tile->y0, tileN0 = xMajor ? tile->y0 : tile->x0;
  const int tileM1 = tileM0 + CLR_TILE_SIZE - 1, tileN1 = tileN0 + CLR_TILE_SIZE - 1;
  long iBegin = sm > 0 ? (long)tileM0 - m0 : (long)m0 - tileM1;
  long iEnd = sm > 0 ? (long)tileM1 - m0 : (long)m0 - tileM0;
  iBegin = max(iBegin, 0L);
  iEnd = min(iEnd, b);
  if (iBegin > iEnd) return;
  // Step 3: d at iBegin in closed form (k = a·i/b rounded half down, half up when ties step), then incremental.
  long k = b == 0 ? 0 : (2 * a * iBegin + b - (tieSteps ? 0 : 1)) / (2 * b);
  long d = 2 * a * (iBegin + 1) - b - 2 * b * k;
  for (long i = iBegin; i <= iEnd; ++i) {
    const int m = m0 + sm * (int)i, n = n0 + sn * (int)k;
    if (n >= tileN0 && n <= tileN1) {
      const float z = b == 0 ? s->z[0] : s->z[0] + (s->z[1] - s->z[0]) * ((float)i / (float)b);
      line_plot(tile, xMajor ? m : n, xMajor ? n : m, z, 1.0f);
    }
    if (d > 0 || (tieSteps && d == 0)) {
      ++k;
      d -= 2 * b;
    }
    d += 2 * a;
  }
}

/* Area of the unit pixel on the side u <= t of a line with unit normal magnitudes p >= q: the CDF of p·X + q·Y,
 * X, Y uniform on [−1/2, 1/2] (quadratic ramps of width q, linear middle of slope 1/p). The profile holds
 * lo = (p − q)/2, hi = (p + q)/2, 1/p, 1/(2pq) (ramps only; empty when q = 0). CLR_LANES offsets, branch-free. */
typedef struct SquareProfile {
  float lo, hi, invP, inv2pq;
} SquareProfile;

CLR_INLINE floatL line_square_cdf(floatL t, const SquareProfile* f)
{
  const floatL rampLow = (t + f->hi) * (t + f->hi) * f->inv2pq;
  const floatL rampHigh = 1.0f - (f->hi - t) * (f->hi - t) * f->inv2pq;
  floatL r = 0.5f + t * f->invP;
  r = select(r, rampLow, t < -f->lo);
  r = select(r, rampHigh, t > f->lo);
  r = select(r, (floatL)0.0f, t <= -f->hi);
  return select(r, (floatL)1.0f, t >= f->hi);
}

/* Anti-aliased: the tile's rows near the segment, CLR_LANES pixels at a time. */
CLR_INLINE void line_antialiased(const LineSeg* s, float4 e, float width, LineTile* tile)
{
  // Step 1: direction, length, the square's profile across and along it.
  const float dx = e.z - e.x, dy = e.w - e.y;
  const float len = sqrt(dx * dx + dy * dy);
  if (len == 0.0f) return;  // no area
  const float tx = dx / len, ty = dy / len;
  const float p = max(fabs(tx), fabs(ty)), q = min(fabs(tx), fabs(ty));
  SquareProfile f;
  f.lo = 0.5f * (p - q);
  f.hi = 0.5f * (p + q);
  f.invP = 1.0f / p;
  f.inv2pq = q > 0.0f ? 1.0f / (2.0f * p * q) : 0.0f;
  const float halfWidth = 0.5f * width;
  // A pixel overlaps the rectangle only if its centre is within w/2 + hi (its half extent across) of the line.
  const float reach = halfWidth + f.hi;
  // Step 2: the tile's rows and columns within reach of the ends' bounds.
  const float y0 = (float)tile->y0, x0 = (float)tile->x0;
  const int rowBegin = max(0, (int)ceil(max(min(e.y, e.w) - reach, y0 - 1.0f) - 0.5f) - tile->y0);
  const int rowEnd =
      min(CLR_TILE_SIZE - 1, (int)floor(min(max(e.y, e.w) + reach, y0 + CLR_TILE_SIZE + 1.0f) - 0.5f) - tile->y0);
  const int colBegin = max(0, (int)ceil(max(min(e.x, e.z) - reach, x0 - 1.0f) - 0.5f) - tile->x0);
  const int colEnd =
      min(CLR_TILE_SIZE - 1, (int)floor(min(max(e.x, e.z) + reach, x0 + CLR_TILE_SIZE + 1.0f) - 0.5f) - tile->x0);
  for (int row = rowBegin; row <= rowEnd; ++row) {
    // Step 3: the row's columns within reach across the line (all if horizontal), one pixel wider for rounding.
    const float ry = y0 + (float)row + 0.5f - e.y;
    int first = colBegin, last = colEnd;
    if (fabs(ty) > 1e-3f) {
      const float xa = (ry * tx - reach) / ty + e.x, xb = (ry * tx + reach) / ty + e.x;
      const float lo = x0 - 2.0f, hi = x0 + CLR_TILE_SIZE + 2.0f;  // keeps the conversions in range
      first = max(first, (int)floor(clamp(min(xa, xb), lo, hi)) - 1 - tile->x0);
      last = min(last, (int)ceil(clamp(max(xa, xb), lo, hi)) + 1 - tile->x0);
    }
    for (int col = first / CLR_LANES * CLR_LANES; col <= last; col += CLR_LANES) {
      // Step 4: coverage from the distance across and the position along.
      const floatL rx = convert_floatL(tile->x0 + col + CLR_LANE_INDEX) + 0.5f - e.x;
      const floatL along = rx * tx + ry * ty, across = ry * tx - rx * ty;
      const floatL coverAcross = line_square_cdf(halfWidth - across, &f) - line_square_cdf(-halfWidth - across, &f);
      const floatL coverAlong = line_square_cdf(len - along, &f) - line_square_cdf(-along, &f);
      const floatL c = coverAcross * coverAlong;
      if (!CLR_ANY(c > 0.0f)) continue;
      // Step 5: depth at the centre's projection; keep the larger coverage where the depth test passes.
      const floatL at = clamp(along / len, (floatL)0.0f, (floatL)1.0f);
      const floatL z = s->z[0] + (s->z[1] - s->z[0]) * at;
      const floatL cover = CLR_LOAD_LANES(&tile->cover[row][col]);
      const intL pass = (c > 0.0f) & (z <= CLR_LOAD_LANES(&tile->limit[row][col]));
      CLR_STORE_LANES(select(cover, max(cover, c), pass), &tile->cover[row][col]);
    }
  }
}

/* Blends channel c of two RGBA8 colours: base + (line − base)·t. */
CLR_INLINE uint line_blend(uint base, uint line, float t)
{
  uint out = 0xFF000000u;
  for (int c = 0; c < 3; ++c) {
    const float b = (float)((base >> (8 * c)) & 0xFFu), l = (float)((line >> (8 * c)) & 0xFFu);
    out |= convert_uint_sat_rte(b + (l - b) * t) << (8 * c);
  }
  return out;
}

/* One work-item per tile: depth limits from sample 0, every binned segment, then the blend into the image. */
__kernel __attribute__((reqd_work_group_size(1, 1, 1))) void lines_draw(
    __constant FrameParams* params, __constant LineParams* lp, __global const LineSeg* segs,
    __global const uint* lineTileOffset,  // tiles + 1
    __global const uint* lineBinEntries,
    __global const uint* triTileOffset,  // tiles + 1: empty triangle tiles hold no visibility samples
    __global const uint* visIndex,       // sample plane 0 (shared.h)
    __global const float* visAttr,       // its window depth plane
    __global const TriSetup* setup,
    __global uint* image,           // width · height, top row first
    __global const uint* tileSlot,  // tiles + 1: visibility-buffer slots (shared.h)
    uint visPlane)
{
  const int tx = get_global_id(0), ty = get_global_id(1);
  const uint tile = ty * params->tilesX + tx;
  const uint begin = lineTileOffset[tile], end = lineTileOffset[tile + 1];
  const bool only = lp->mode == CLR_WIREFRAME_ONLY;
  if (begin == end && !only) return;
  // Step 1: per pixel, the deepest line depth that passes the depth test.
  LineTile t;
  t.x0 = tx * CLR_TILE_SIZE;
  t.y0 = ty * CLR_TILE_SIZE;
  const bool noTriangles = triTileOffset[tile] == triTileOffset[tile + 1];
  const uint slot = noTriangles ? 0u : tileSlot[tile];
  const float slopeReach = lp->reach + 0.75f;
  for (int row = 0; row < CLR_TILE_SIZE; ++row)
    for (int col = 0; col < CLR_TILE_SIZE; ++col) {
      const uint px = t.x0 + col, py = t.y0 + row;
      t.cover[row][col] = 0.0f;
      t.limit[row][col] = -INFINITY;
      if (px >= params->width || py >= params->height || begin == end) continue;
      const uint p = vis_address(slot, px, py);
      const uint index = noTriangles ? CLR_NONE : vis_index_at(params, visIndex, p);
      t.limit[row][col] = index == CLR_NONE ? 1.0f + lp->depthBias
                                            : visAttr[p] + lp->depthBias + line_depth_slope(&setup[index]) * slopeReach;
    }
  // Step 2: the tile's segments.
  for (uint n = begin; n < end; ++n) {
    const LineSeg s = segs[lineBinEntries[n]];
    if (lp->method == CLR_LINE_BRESENHAM)
      line_bresenham(&s, &t);
    else
      line_antialiased(&s, line_ends(&s, lp), lp->width, &t);
  }
  // Step 3: blend the coverage into the image (top row first).
  for (int row = 0; row < CLR_TILE_SIZE; ++row)
    for (int col = 0; col < CLR_TILE_SIZE; ++col) {
      const uint px = t.x0 + col, py = t.y0 + row;
      if (px >= params->width || py >= params->height) continue;
      const float c = t.cover[row][col];
      if (c <= 0.0f && !only) continue;
      __global uint* out = clr_image_pixel(params, image, px, py);
      *out = line_blend(only ? lp->background : *out, lp->colour, c);
    }
}
#endif
