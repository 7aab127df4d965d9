/* transform.cl — stage 1: transform_vertices writes clip = mvp · (x, y, z, 1) of every vertex (one work-item each)
 * for the painter's sort and tests; frames transform where setup reads instead (transform.h, the same floats).
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
