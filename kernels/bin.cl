/* bin.cl — stage 4: binning screen triangles into CLR_TILE_SIZE² tiles.
 *
 * Two passes with a scan between them, so memory follows the actual counts
 * and no triangle is ever dropped: bin_count adds one to every tile that a
 * triangle's pixel bounds touch; the host scans the counts into offsets,
 * sizes binEntries from the total, and bin_fill writes each triangle's setup
 * index into its tiles. The order inside a tile is not deterministic; the
 * raster kernel breaks depth ties by setup index, which is input order.
 */

/* Tiles touched by a triangle's pixel bounds; empty for padding records. */
CLR_INLINE int4 bin_tile_range(const TriSetup* t, __constant FrameParams* params)
{
  if (t->flags & CLR_FLAG_DEAD) return (int4)(0, 0, -1, -1);
  const int4 px = setup_pixel_bounds(t, params->width, params->height);
  return px / CLR_TILE_SIZE;
}

__kernel void bin_count(__constant FrameParams* params, __global const TriSetup* setup, uint numSetup,
                        __global uint* tileCount)  // tiles + 1
{
  const uint s = get_global_id(0);
  if (s >= numSetup) return;
  const TriSetup t = setup[s];
  const int4 r = bin_tile_range(&t, params);
  for (int ty = r.y; ty <= r.w; ++ty)
    for (int tx = r.x; tx <= r.z; ++tx) atomic_inc(&tileCount[ty * params->tilesX + tx]);
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
  for (int ty = r.y; ty <= r.w; ++ty)
    for (int tx = r.x; tx <= r.z; ++tx) {
      const uint tile = ty * params->tilesX + tx;
      binEntries[tileOffset[tile] + atomic_inc(&tileCursor[tile])] = s;
    }
}
