/* transform.cl — stage 1: vertex transform, clip = mvp · (x, y, z, 1).
 *
 * Sums run in a fixed order with contraction off, so the test oracle reproduces them bit for bit. Frames transform
 * where setup reads (transform_vertex, transform_lanes), so no buffer holds clip positions; the kernel
 * transform_vertices writes them (one work-item per vertex) for the painter's sort and tests: the same floats.
 *
 * With -D CLR_CLIP_INPUT=1 (the library's rasterize, host/api/api.cpp) positions are clip-space float4 already and
 * transform_vertex reads them unchanged: every later stage is the frame's.
 */
#include "transform.h"

#if !CLR_EXTRAS
__kernel void transform_vertices(__global const float* positions,  // 3·numVerts
                                 __constant FrameParams* params,
                                 __global float4* clipPos)  // numVerts
{
  const uint v = get_global_id(0);
  if (v >= params->numVerts) return;
  clipPos[v] = transform_vertex(params, positions, v);
}
#endif
