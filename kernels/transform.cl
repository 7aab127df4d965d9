/* transform.cl — stage 1: vertex transform.
 *
 * clip = mvp · (x, y, z, 1), each sum evaluated in a fixed order with
 * contraction off, so the test oracle can reproduce it bit for bit. A frame
 * transforms the vertices where setup reads them (transform_vertex and
 * transform_lanes, called by setup.cl): nothing holds the clip positions
 * between the stages, which saves 16 bytes per vertex. The kernel
 * transform_vertices writes them all, one work-item per vertex, for the
 * painter's algorithm's host sort and for tests; it computes the same
 * floats.
 */
#pragma OPENCL FP_CONTRACT OFF

/* The clip position of vertex v. */
CLR_INLINE float4 transform_vertex(__constant FrameParams* params, __global const float* positions, uint v)
{
  const float3 p = (float3)(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
  __constant const float* m = params->mvp;
  return (float4)(m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12], m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
                  m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14], m[3] * p.x + m[7] * p.y + m[11] * p.z + m[15]);
}

/* Clip coordinate `row` (0 x, 1 y, 2 z, 3 w) of the lanes' positions
 * (px, py, pz): the same operations as transform_vertex, in lane types. */
CLR_INLINE floatL transform_lanes(__constant FrameParams* params, int row, floatL px, floatL py, floatL pz)
{
  __constant const float* m = params->mvp;
  return m[row] * px + m[4 + row] * py + m[8 + row] * pz + m[12 + row];
}

__kernel void transform_vertices(__global const float* positions,  // 3·numVerts
                                 __constant FrameParams* params,
                                 __global float4* clipPos)  // numVerts
{
  const uint v = get_global_id(0);
  if (v >= params->numVerts) return;
  clipPos[v] = transform_vertex(params, positions, v);
}
