/* transform.cl — stage 1: vertex transform, clip = mvp · (x, y, z, 1).
 *
 * Sums run in a fixed order with contraction off, so the test oracle reproduces them bit for bit. Frames transform
 * where setup reads (transform_vertex, transform_lanes), so no buffer holds clip positions; the kernel
 * transform_vertices writes them (one work-item per vertex) for the painter's sort and tests: the same floats.
 *
 * With -D CLR_CLIP_INPUT=1 (the library's rasterize, host/api.cpp) positions are clip-space float4 already and
 * transform_vertex reads them unchanged: every later stage is the frame's.
 */
#pragma OPENCL FP_CONTRACT OFF

/* Clip coordinate `row` (0 x .. 3 w): row of the column-major mvp times (x, y, z, 1), summed left to right. The
 * one formula of both functions below, which must agree bit for bit. */
#define CLR_TRANSFORM_ROW(m, row, x, y, z) \
  ((m)[row] * (x) + (m)[4 + (row)] * (y) + (m)[8 + (row)] * (z) + (m)[12 + (row)])

#ifndef CLR_CLIP_INPUT
#define CLR_CLIP_INPUT 0
#endif
/* Floats per vertex of the positions buffer. */
#define CLR_POSITION_STRIDE (CLR_CLIP_INPUT ? 4 : 3)

/* The clip position of vertex v. */
CLR_INLINE float4 transform_vertex(__constant FrameParams* params, __global const float* positions, uint v)
{
#if CLR_CLIP_INPUT
  return vload4(v, positions);
#else
  const float3 p = (float3)(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
  __constant const float* m = params->mvp;
  return (float4)(CLR_TRANSFORM_ROW(m, 0, p.x, p.y, p.z), CLR_TRANSFORM_ROW(m, 1, p.x, p.y, p.z),
                  CLR_TRANSFORM_ROW(m, 2, p.x, p.y, p.z), CLR_TRANSFORM_ROW(m, 3, p.x, p.y, p.z));
#endif
}

/* Clip coordinate `row` of the lanes' positions: transform_vertex's operations in lane types. */
CLR_INLINE floatL transform_lanes(__constant FrameParams* params, int row, floatL px, floatL py, floatL pz)
{
  return CLR_TRANSFORM_ROW(params->mvp, row, px, py, pz);
}

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
