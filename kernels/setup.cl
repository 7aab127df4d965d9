/* setup.cl — stage 3: triangle setup: count, scan, emit.
 *
 * Per input triangle: cull non-finite and trivially outside triangles,
 * clip those that cross the near plane or the guard band (clip.cl), apply
 * the viewport matrix of the notes (x_s = x_ndc·W/2 + W/2, y up), snap to
 * the CLR_SUBPIXEL_BITS grid, compute the exact 64-bit doubled area, cull
 * zero-area, back-facing (when asked) and sample-free triangles, and orient
 * the survivors counter-clockwise.
 *
 * setup_count writes how many screen triangles each input triangle yields:
 * 0 or 1 when no clipping is needed, and a reservation of CLR_MAX_SUBTRIS
 * when it is (such triangles are also listed for setup_clip). After an
 * exclusive scan, setup_emit writes the unclipped triangles at their
 * offsets and setup_clip clips the listed ones, padding unused reserved
 * slots with CLR_FLAG_DEAD records that binning skips. Output order is input
 * order, whatever the scheduling. setup_count and setup_emit keep the
 * common path free of loops and atomics, so PoCL vectorises them across
 * work-items; the rare clipping path runs in its own kernel.
 */
#pragma OPENCL FP_CONTRACT OFF

/* Floor and ceiling of a / CLR_FIXED_ONE for signed a. */
CLR_INLINE int fixed_floor(int a)
{
  return a >> CLR_SUBPIXEL_BITS;
}
CLR_INLINE int fixed_ceil(int a)
{
  return (a + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS;
}

/* Inclusive pixel range whose centres (i + 0.5) can lie in the triangle,
 * clamped to the viewport. Empty when x0 > x1 or y0 > y1. */
CLR_INLINE int4 setup_pixel_bounds(const TriSetup* t, uint width, uint height)
{
  const int minX = min(t->x[0], min(t->x[1], t->x[2]));
  const int maxX = max(t->x[0], max(t->x[1], t->x[2]));
  const int minY = min(t->y[0], min(t->y[1], t->y[2]));
  const int maxY = max(t->y[0], max(t->y[1], t->y[2]));
  int4 r;
  r.x = max(0, fixed_ceil(minX - CLR_FIXED_HALF));
  r.y = max(0, fixed_ceil(minY - CLR_FIXED_HALF));
  r.z = min((int)width - 1, fixed_floor(maxX - CLR_FIXED_HALF));
  r.w = min((int)height - 1, fixed_floor(maxY - CLR_FIXED_HALF));
  return r;
}

/* Builds one screen triangle from three clip-space vertices. Returns false
 * when it is culled. bary (may be null) holds the sub-vertices' input
 * barycentrics and is swapped along with the vertices. */
CLR_INLINE bool setup_make(const float4* c, __constant FrameParams* params, uint triId, TriSetup* out, float3* bary)
{
  // Straight-line code (no early return), so PoCL can vectorise callers.
  // Step 1: viewport transform and snapping.
  bool valid = true;
  for (int i = 0; i < 3; ++i) {
    valid = valid && c[i].w > 0.0f;
    const float invW = 1.0f / c[i].w;
    const float xs = c[i].x * invW * params->halfWidth + params->halfWidth;
    const float ys = c[i].y * invW * params->halfHeight + params->halfHeight;
    const float zs = c[i].z * invW * 0.5f + 0.5f;
    out->x[i] = convert_int_rte(xs * (float)CLR_FIXED_ONE);
    out->y[i] = convert_int_rte(ys * (float)CLR_FIXED_ONE);
    out->z[i] = zs;
    out->invW[i] = invW;
  }
  // Step 2: exact doubled signed area; cull zero and (optionally) back faces.
  long area2 = (long)(out->x[1] - out->x[0]) * (long)(out->y[2] - out->y[0]) -
               (long)(out->x[2] - out->x[0]) * (long)(out->y[1] - out->y[0]);
  const bool back = area2 < 0;
  valid = valid && area2 != 0 && !(back && params->cullBack);
  // Step 3: orient counter-clockwise by swapping vertices 1 and 2.
  const int x1 = out->x[1], y1 = out->y[1];
  const float z1 = out->z[1], w1 = out->invW[1];
  out->x[1] = back ? out->x[2] : x1;
  out->x[2] = back ? x1 : out->x[2];
  out->y[1] = back ? out->y[2] : y1;
  out->y[2] = back ? y1 : out->y[2];
  out->z[1] = back ? out->z[2] : z1;
  out->z[2] = back ? z1 : out->z[2];
  out->invW[1] = back ? out->invW[2] : w1;
  out->invW[2] = back ? w1 : out->invW[2];
  if (bary && back) {
    const float3 b1 = bary[1];
    bary[1] = bary[2];
    bary[2] = b1;
  }
  area2 = back ? -area2 : area2;
  out->flags = back ? CLR_FLAG_BACKFACING : 0u;
  // Step 4: cull triangles whose bounds hold no pixel centre.
  const int4 b = setup_pixel_bounds(out, params->width, params->height);
  valid = valid && b.x <= b.z && b.y <= b.w;
  out->invArea2 = 1.0f / convert_float(area2);
  out->triId = triId;
  out->clipSlot = CLR_NOT_CLIPPED;
  return valid;
}

/* Field-by-field copy to global memory: a whole-struct copy becomes a
 * memcpy, which PoCL's vectoriser cannot widen across work-items. */
CLR_INLINE void setup_store(__global TriSetup* dst, const TriSetup* t)
{
  for (int i = 0; i < 3; ++i) {
    dst->x[i] = t->x[i];
    dst->y[i] = t->y[i];
    dst->z[i] = t->z[i];
    dst->invW[i] = t->invW[i];
  }
  dst->invArea2 = t->invArea2;
  dst->triId = t->triId;
  dst->clipSlot = t->clipSlot;
  dst->flags = t->flags;
}

/* How an input triangle is handled. */
#define CLR_SETUP_CULLED 0u
#define CLR_SETUP_SIMPLE 1u
#define CLR_SETUP_CLIP 2u
#define CLR_SETUP_PADDING 3u /* work-item past the last triangle */

/* Fetches the triangle's clip positions and classifies it; *clipPlanes
 * receives the planes (clip.cl bits 0-4) that clipping must use. */
CLR_INLINE uint setup_classify(uint tri, __global const float4* clipPos, __global const uint* indices,
                               __constant FrameParams* params, float4* c, uint* clipPlanes)
{
  uint code[3];
  bool finite = true;
  for (int i = 0; i < 3; ++i) {
    c[i] = clipPos[indices[3 * tri + i]];
    finite = finite && clip_is_finite(c[i]);
    code[i] = clip_outcode(c[i], params->guardX, params->guardY);
  }
  const uint allOut = code[0] & code[1] & code[2];
  *clipPlanes = (code[0] | code[1] | code[2]) & 0x1Fu;
  if (!finite || (allOut & (1u | (0x1Fu << 5)))) return CLR_SETUP_CULLED;
  return *clipPlanes ? CLR_SETUP_CLIP : CLR_SETUP_SIMPLE;
}

/* Pass 1: how many screen triangles each input triangle yields. */
__kernel __attribute__((reqd_work_group_size(64, 1, 1))) void setup_count(__constant FrameParams* params,
                                                                          __global const float4* clipPos,  // numVerts
                                                                          __global const uint* indices,    // 3·numTris
                                                                          __global uint* triCount,  // numTris + 1
                                                                          __global uint* counters,  // CLR_NUM_COUNTERS
                                                                          __global uint* clipList,
                                                                          uint clipListCapacity)
{
  __local uchar kind[64];
  const uint tri = get_global_id(0), lid = get_local_id(0);
  // Step 1: classify and count, one triangle per work-item.
  uint k = CLR_SETUP_PADDING;
  if (tri < params->numTris) {
    float4 c[3];
    uint clipPlanes;
    k = setup_classify(tri, clipPos, indices, params, c, &clipPlanes);
    uint count = k == CLR_SETUP_CLIP ? CLR_MAX_SUBTRIS : 0u;
    if (k == CLR_SETUP_SIMPLE) {
      TriSetup t;
      count = setup_make(c, params, tri, &t, 0) ? 1u : 0u;
      k = count ? k : CLR_SETUP_CULLED;
    }
    triCount[tri] = count;
  }
  kind[lid] = (uchar)k;
  barrier(CLK_LOCAL_MEM_FENCE);
  // Step 2: one work-item per group updates the counters and the clip list.
  if (lid != 0) return;
  const uint groupFirst = get_group_id(0) * 64;
  uint culled = 0, clipped = 0;
  for (uint i = 0; i < 64; ++i) {
    culled += kind[i] == CLR_SETUP_CULLED;
    clipped += kind[i] == CLR_SETUP_CLIP;
  }
  if (culled) atomic_add(&counters[CLR_COUNTER_CULLED_TRIS], culled);
  if (!clipped) return;
  uint slot = atomic_add(&counters[CLR_COUNTER_CLIPPED_TRIS], clipped);
  for (uint i = 0; i < 64; ++i)
    if (kind[i] == CLR_SETUP_CLIP) {
      if (slot < clipListCapacity) clipList[slot] = groupFirst + i;
      ++slot;
    }
}

/* Pass 2: writes the unclipped screen triangles at their scanned offsets. */
__kernel void setup_emit(__constant FrameParams* params,
                         __global const float4* clipPos,  // numVerts
                         __global const uint* indices,    // 3·numTris
                         __global const uint* triOffset,  // numTris + 1, scanned
                         __global TriSetup* setup)        // triOffset[numTris]
{
  const uint tri = get_global_id(0);
  if (tri >= params->numTris) return;
  float4 c[3];
  uint clipPlanes;
  if (setup_classify(tri, clipPos, indices, params, c, &clipPlanes) != CLR_SETUP_SIMPLE) return;
  TriSetup t;
  if (setup_make(c, params, tri, &t, 0)) setup_store(&setup[triOffset[tri]], &t);
}

/* Pass 3: clips the listed triangles and fills their reserved slots. */
__kernel void setup_clip(__constant FrameParams* params,
                         __global const float4* clipPos,  // numVerts
                         __global const uint* indices,    // 3·numTris
                         __global const uint* triOffset,  // numTris + 1, scanned
                         __global const uint* clipList,   // CLIPPED_TRIS counter
                         __global TriSetup* setup,        // triOffset[numTris]
                         __global ClipBary* clipBary,     // CLR_MAX_SUBTRIS · CLIPPED_TRIS
                         __global uint* counters)
{
  const uint i = get_global_id(0);
  if (i >= counters[CLR_COUNTER_CLIPPED_TRIS]) return;
  const uint tri = clipList[i];
  float4 c[3];
  uint clipPlanes;
  setup_classify(tri, clipPos, indices, params, c, &clipPlanes);
  // Step 1: clip in homogeneous space.
  ClipVertex poly[CLR_MAX_CLIP_VERTS];
  for (int v = 0; v < 3; ++v) {
    poly[v].pos = c[v];
    poly[v].bary = (float3)((float)(v == 0), (float)(v == 1), (float)(v == 2));
  }
  const int n = clip_polygon(poly, 3, clipPlanes, params->guardX, params->guardY);
  // Step 2: fan the polygon; set up and write each surviving triangle.
  const uint base = triOffset[tri];
  uint count = 0;
  for (int k = 1; k + 1 < n; ++k) {
    const float4 sc[3] = {poly[0].pos, poly[k].pos, poly[k + 1].pos};
    float3 sb[3] = {poly[0].bary, poly[k].bary, poly[k + 1].bary};
    TriSetup t;
    if (!setup_make(sc, params, tri, &t, sb)) continue;
    const uint slot = atomic_inc(&counters[CLR_COUNTER_CLIP_SLOTS]);
    for (int v = 0; v < 3; ++v) {
      clipBary[slot].w[v][0] = sb[v].x;
      clipBary[slot].w[v][1] = sb[v].y;
      clipBary[slot].w[v][2] = sb[v].z;
    }
    t.clipSlot = slot;
    setup[base + count++] = t;
  }
  // Step 3: pad the reservation with records that binning skips.
  for (uint k = count; k < CLR_MAX_SUBTRIS; ++k) {
    TriSetup dead = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, 0.0f, tri, CLR_NOT_CLIPPED, CLR_FLAG_DEAD};
    setup[base + k] = dead;
  }
  atomic_add(&counters[CLR_COUNTER_DEAD_RECORDS], CLR_MAX_SUBTRIS - count);
  if (count == 0) atomic_inc(&counters[CLR_COUNTER_CULLED_TRIS]);
}
