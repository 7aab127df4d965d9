/* micro.h — the micro-triangle path: an unclipped triangle whose pixel bounds lie in one tile and hold at most
 * microMax pixel positions (setup's microMax argument, 0 = off) skips binning and the tile raster.
 * Count pass: its tile claims a micro slot in tileMicro (once per tile; micro_claim_tile), which adds one hole entry
 * to the tile's bin count, so the tile gets a visibility slot and every reader sees it non-empty; no entry is written
 * (the hole is the bin's last entry, raster stops before it). A tile that finds no slot (a speculative frame's
 * microKey is full) bins its triangles as usual. Emit: the record is written as usual; then every sample of every
 * pixel in its bounds is tested with raster's integer edge functions and fill rule (micro_sample), and a covered one
 * takes atom_min of (depth key bits << 32 | tie order) in microKey (micro_address).
 * Raster merges a tile's microKey entries into its nearest fragments with raster_depth_test's rule (micro_take) and
 * resets them to CLR_MICRO_CLEAR, so microKey is all ones between frames. The tie order is the setup index in the
 * file's order (fileOrder), else the paint rank, with microRecord[rank] = setup index for the merge.
 * Needs cl_khr_int64_extended_atomics; where the device lacks it the host keeps microMax 0 and these compile out.
 */
#ifndef CLR_MICRO_H
#define CLR_MICRO_H

#if defined(cl_khr_int64_extended_atomics)
#pragma OPENCL EXTENSION cl_khr_int64_extended_atomics : enable
#define CLR_MICRO_ATOMICS 1
#else
#define CLR_MICRO_ATOMICS 0
#endif

/* An empty microKey entry. */
#define CLR_MICRO_CLEAR 0xFFFFFFFFFFFFFFFFul

/* Whether a surviving lane may take the micro path: one tile, at most microMax pixel positions. */
CLR_INLINE bool micro_lane(uint microMax, int4 tiles, int pixels)
{
  return microMax > 0 && tiles.x == tiles.z && tiles.y == tiles.w && pixels <= (int)microMax;
}

/* A tileMicro word: 0 no micro triangle, CLR_MICRO_FULL none could take a slot, else 1 + the tile's micro slot. */
#define CLR_MICRO_FULL 0xFFFFFFFFu
CLR_INLINE bool micro_slotted(uint word)
{
  return word != 0 && word != CLR_MICRO_FULL;
}

/* Raster: tile's tileMicro word where the tile holds a micro slot, else 0; with a slot, *end (the end of its bin
 * entries) drops the hole. */
CLR_INLINE uint micro_tile_slot(__global const uint* tileMicro, uint tile, uint* end)
{
  const uint word = tileMicro[tile];
  if (!micro_slotted(word)) return 0u;
  --*end;
  return word;
}

/* Count pass: a micro slot for tile, claimed once per tile (slots numbered by CLR_COUNTER_MICRO_TILES, below
 * microCap, the microKey slots of a speculative frame); the claim adds the tile's hole entry. Returns whether the
 * tile has a slot; without one its triangles are binned. *last and *lastSlotted cache the tile looked at last. */
CLR_INLINE bool micro_claim_tile(uint tile, uint* last, bool* lastSlotted, uint microCap, __global uint* tileMicro,
                                 __global uint* tileCount, __global uint* counters)
{
  if (tile == *last) return *lastSlotted;
  uint word = atomic_add(&tileMicro[tile], 0u);
  if (word == 0) {
    const uint slot = atomic_inc(&counters[CLR_COUNTER_MICRO_TILES]);
    const uint mine = slot < microCap ? slot + 1 : CLR_MICRO_FULL;
    word = atomic_cmpxchg(&tileMicro[tile], 0u, mine);
    if (word == 0) {  // this claim won (a lost one leaves its slot number unused)
      word = mine;
      if (mine != CLR_MICRO_FULL) atomic_inc(&tileCount[tile]);
    }
  }
  *last = tile;
  *lastSlotted = micro_slotted(word);
  return *lastSlotted;
}

/* Sample k of pixel (x, y) in microKey, the tile's word being `word` (micro_slotted): a block of CLR_TILE_SIZE²
 * entries per micro slot and sample index. */
CLR_INLINE uint micro_address(uint word, uint samples, uint k, uint x, uint y)
{
  return vis_address((word - 1) * samples + k, x, y);
}

/* A depth key's bits in an order that unsigned compares keep: a float key below the clear key is never NaN, and −0
 * is taken as +0 (raster's float compare ties them). */
CLR_INLINE uint micro_key_bits(float key)
{
  const uint bits = as_uint(key == 0.0f ? 0.0f : key);
  return (bits & 0x80000000u) ? ~bits : bits | 0x80000000u;
}
CLR_INLINE float micro_bits_key(uint bits)
{
  return as_float((bits & 0x80000000u) ? bits & 0x7FFFFFFFu : ~bits);
}

/* Record t's depth key and screen barycentrics at sample (sx, sy); false where the sample is outside. Raster's
 * integer edge functions and fill rule (raster_rows) and raster_depth_test's float steps, so the same bits. */
CLR_INLINE bool micro_sample(const TriSetup* t, int sx, int sy, uint depthMode, float* key, float* b1, float* b2)
{
  const long e0 = bin_edge_at(t->x[1], t->y[1], t->x[2], t->y[2], sx, sy);
  const long e1 = bin_edge_at(t->x[2], t->y[2], t->x[0], t->y[0], sx, sy);
  const long e2 = bin_edge_at(t->x[0], t->y[0], t->x[1], t->y[1], sx, sy);
  const bool inside = e0 > (CLR_EDGE_HOLDS_SAMPLES(t->x[1], t->y[1], t->x[2], t->y[2]) ? -1 : 0) &&
                      e1 > (CLR_EDGE_HOLDS_SAMPLES(t->x[2], t->y[2], t->x[0], t->y[0]) ? -1 : 0) &&
                      e2 > (CLR_EDGE_HOLDS_SAMPLES(t->x[0], t->y[0], t->x[1], t->y[1]) ? -1 : 0);
  const float invArea2 = CLR_RECORD_INV_AREA2(*t);
  *b1 = (float)e1 * invArea2;
  *b2 = (float)e2 * invArea2;
  const float z = t->z[0] + *b1 * (t->z[1] - t->z[0]) + *b2 * (t->z[2] - t->z[0]);
  *key = depthMode == CLR_DEPTH_UNORM24    ? rint(clamp(z, 0.0f, 1.0f) * CLR_DEPTH_UNORM24_MAX)
         : depthMode == CLR_DEPTH_REVERSED ? -z
                                           : z;
  return inside;
}

#if CLR_MICRO_ATOMICS
/* Emit: the fragments of record t (tie order `order`) at every sample of pixel bounds b, in the micro slot of its
 * one tile (tileMicro word `word`); a key at or beyond the clear key is no fragment (raster_write_row). Blocks of
 * 2×2 pixels in vectors, so that coverage takes no branch: micro_sample's integers and float steps, lane by lane. */
CLR_INLINE void micro_emit(__constant FrameParams* params, const TriSetup* t, uint order, int4 b, uint word,
                           __global ulong* microKey)
{
  const uint depthMode = params->depthMode, samples = params->samples;
  const float clearKey = depthMode == CLR_DEPTH_UNORM24    ? CLR_DEPTH_UNORM24_MAX
                         : depthMode == CLR_DEPTH_REVERSED ? -0.0f
                                                           : 1.0f;
  const long dx0 = t->x[2] - t->x[1], dy0 = t->y[2] - t->y[1], dx1 = t->x[0] - t->x[2], dy1 = t->y[0] - t->y[2];
  const long dx2 = t->x[1] - t->x[0], dy2 = t->y[1] - t->y[0];
  const long low0 = CLR_EDGE_HOLDS_SAMPLES(t->x[1], t->y[1], t->x[2], t->y[2]) ? -1 : 0;
  const long low1 = CLR_EDGE_HOLDS_SAMPLES(t->x[2], t->y[2], t->x[0], t->y[0]) ? -1 : 0;
  const long low2 = CLR_EDGE_HOLDS_SAMPLES(t->x[0], t->y[0], t->x[1], t->y[1]) ? -1 : 0;
  const float invArea2 = CLR_RECORD_INV_AREA2(*t);
  const float4 dz1 = t->z[1] - t->z[0], dz2 = t->z[2] - t->z[0];
  const int4 cx = (int4)(0, 1, 0, 1), cy = (int4)(0, 0, 1, 1);
  for (uint k = 0; k < samples; ++k)
    for (int y = b.y; y <= b.w; y += 2)
      for (int x = b.x; x <= b.z; x += 2) {
        const int4 px = x + cx, py = y + cy;
        const int4 sx = px * CLR_FIXED_ONE + (CLR_FIXED_HALF + params->sampleX[k]);
        const int4 sy = py * CLR_FIXED_ONE + (CLR_FIXED_HALF + params->sampleY[k]);
        const long4 e0 = dx0 * convert_long4(sy - t->y[1]) - dy0 * convert_long4(sx - t->x[1]);
        const long4 e1 = dx1 * convert_long4(sy - t->y[2]) - dy1 * convert_long4(sx - t->x[2]);
        const long4 e2 = dx2 * convert_long4(sy - t->y[0]) - dy2 * convert_long4(sx - t->x[0]);
        const int4 inside = convert_int4((e0 > low0) & (e1 > low1) & (e2 > low2)) & (px <= b.z) & (py <= b.w);
        if (!any(inside)) continue;
        const float4 b1 = convert_float4(e1) * invArea2, b2 = convert_float4(e2) * invArea2;
        const float4 z = t->z[0] + b1 * dz1 + b2 * dz2;
        const float4 key = depthMode == CLR_DEPTH_UNORM24    ? rint(clamp(z, 0.0f, 1.0f) * CLR_DEPTH_UNORM24_MAX)
                           : depthMode == CLR_DEPTH_REVERSED ? -z
                                                             : z;
        int lanes[4];
        float keys[4];
        vstore4(inside & (key < clearKey), 0, lanes);
        vstore4(key, 0, keys);
        for (int lane = 0; lane < 4; ++lane)
          if (lanes[lane])
            atom_min(&microKey[micro_address(word, samples, k, (uint)(x + (lane & 1)), (uint)(y + (lane >> 1)))],
                     (ulong)micro_key_bits(keys[lane]) << 32 | order);
      }
}
#endif

/* Raster: whether the micro fragment m (not CLR_MICRO_CLEAR) is nearer than the kept fragment (index, key), by
 * raster_depth_test's rule; sets *s to its setup index. rankOf is the kept record's tie order (its paint rank). */
CLR_INLINE bool micro_take(ulong m, uint keptIndex, float keptKey, bool fileOrder, __global const uint* microRecord,
                           __global const uint* source, __global const ClipBary* clipBary,
                           __global const uint* fileRank, uint* s)
{
  const float key = micro_bits_key((uint)(m >> 32));
  const uint order = (uint)m;
  *s = fileOrder ? order : microRecord[order];
  if (key < keptKey) return true;
  if (!(key == keptKey)) return false;  // (a micro key is below the clear key, so keptIndex is a record)
  if (fileOrder) return order < keptIndex;
  return order < fileRank[clr_source_triangle(source[keptIndex], clipBary)];
}

#endif /* CLR_MICRO_H */
