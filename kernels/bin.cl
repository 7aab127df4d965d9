/* bin.cl — stage 4: binning screen triangles into CLR_TILE_SIZE² tiles. Setup's passes count and fill the bins
 * of unclipped triangles with the helpers of bin.h; this file's kernel fills the clipped triangles' bins.
 */
#include "bin.h"

#if !CLR_EXTRAS /* the frame program (CLR_EXTRAS, shared.h) */
/* Pass 2 for clipped triangles, one work-item per reserved slot from clipList[i]: writes the record's source word
 * (its ClipBary slot) and bins it unless it is padding. */
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
  const int row = clr_image_row(params, clipBary[i].triId);
  bin_fill_tiles(&t, bin_tile_range(&t, params, row), s, params, tileOffset, tileCursor, binEntries);
}
#endif
