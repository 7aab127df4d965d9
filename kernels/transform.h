/* transform.h — the vertex transform every stage that reads positions shares: clip = mvp · (x, y, z, 1) for one
 * vertex or a lane of them, 1/w of a record's vertices, and the position stride of -D CLR_CLIP_INPUT (clip-space
 * input, the library's rasterize). Used by transform.cl, setup.cl, clip.h, resolve.h, aov.cl and rast_outputs.cl.
 * Sums run in a fixed order with contraction off, so the test oracle reproduces them bit for bit. With
 * -D CLR_CLIP_INPUT=1 (host/api/api.cpp) positions are clip-space float4 already and transform_vertex reads them
 * unchanged: every later stage is the frame's.
 */
#ifndef CLR_TRANSFORM_H
#define CLR_TRANSFORM_H
#pragma OPENCL FP_CONTRACT OFF

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

/* Clip w of vertex v: transform_vertex(...).w, the same operations. */
CLR_INLINE float transform_w(__constant FrameParams* params, __global const float* positions, uint v)
{
#if CLR_CLIP_INPUT
  return positions[4 * v + 3];
#else
  return CLR_TRANSFORM_ROW(params->mvp, 3, positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
#endif
}

/* w_clip at the vertices of the record with source word `from` whose input triangle has vertices v[0..2] (records
 * hold none, shared.h): a clipped record's from its ClipBary slot; else input vertex i's (1 and 2 swapped when
 * back-facing). The floats setup_make divides, so 1.0f / w is its 1/w bit for bit. */
CLR_INLINE void record_clip_w(__constant FrameParams* params, __global const float* positions,
                              __global const ClipBary* clipBary, uint from, const uint v[3], float w[3])
{
  const uint slot = clr_source_clip_slot(from);
  if (slot != CLR_NOT_CLIPPED) {
    for (int i = 0; i < 3; ++i) w[i] = clipBary[slot].clipW[i];
    return;
  }
  const bool back = (from & CLR_SOURCE_BACKFACING) != 0;
  const float w1 = transform_w(params, positions, v[1]), w2 = transform_w(params, positions, v[2]);
  w[0] = transform_w(params, positions, v[0]);
  w[1] = back ? w2 : w1;
  w[2] = back ? w1 : w2;
}

/* Clip coordinate `row` of the lanes' positions: transform_vertex's operations in lane types. */
CLR_INLINE floatL transform_lanes(__constant FrameParams* params, int row, floatL px, floatL py, floatL pz)
{
  return CLR_TRANSFORM_ROW(params->mvp, row, px, py, pz);
}

#endif /* CLR_TRANSFORM_H */
