/* transform.cl — stage 1: vertex transform.
 *
 * One work-item per vertex: clip = mvp · (x, y, z, 1). The sum is evaluated
 * in a fixed order with contraction off, so the test oracle can reproduce it
 * bit for bit.
 */
#pragma OPENCL FP_CONTRACT OFF

__kernel void transform_vertices(__global const float* positions,  // 3·numVerts
                                 __constant FrameParams* params,
                                 __global float4* clipPos)  // numVerts
{
  const uint v = get_global_id(0);
  if (v >= params->numVerts) return;
  const float3 p = (float3)(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
  __constant const float* m = params->mvp;
  const float4 c =
      (float4)(m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12], m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
               m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14], m[3] * p.x + m[7] * p.y + m[11] * p.z + m[15]);
  clipPos[v] = c;
}
