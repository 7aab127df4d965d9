/* setup.cl — stage 3: triangle setup, in two passes.
 *
 * setup_count and setup_emit run the same per-triangle procedure: cull
 * non-finite and trivially outside triangles, clip (clip.cl), apply the
 * viewport matrix of the notes (x_s = x_ndc·W/2 + W/2, y up), snap to the
 * CLR_SUBPIXEL_BITS grid, compute the exact 64-bit doubled area, cull
 * zero-area, back-facing (when asked) and sample-free triangles, and orient
 * the survivors counter-clockwise. setup_count writes how many screen
 * triangles each input triangle yields; after an exclusive scan, setup_emit
 * writes them at their offsets. Output order is therefore input order,
 * whatever the scheduling.
 */
#pragma OPENCL FP_CONTRACT OFF

/* Floor and ceiling of a / CLR_FIXED_ONE for signed a. */
inline int fixed_floor(int a)
{
  return a >> CLR_SUBPIXEL_BITS;
}
inline int fixed_ceil(int a)
{
  return (a + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS;
}

/* Inclusive pixel range whose centres (i + 0.5) can lie in the triangle,
 * clamped to the viewport. Empty when x0 > x1 or y0 > y1. */
inline int4 setup_pixel_bounds(const TriSetup* t, uint width, uint height)
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
inline bool setup_make(const float4* c, __constant FrameParams* params, uint triId, TriSetup* out, float3* bary)
{
  // Step 1: viewport transform and snapping.
  for (int i = 0; i < 3; ++i) {
    if (!(c[i].w > 0.0f)) return false;
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
  if (area2 == 0) return false;
  out->flags = 0;
  if (area2 < 0) {
    if (params->cullBack) return false;
    int ti = out->x[1];
    out->x[1] = out->x[2];
    out->x[2] = ti;
    ti = out->y[1];
    out->y[1] = out->y[2];
    out->y[2] = ti;
    float tf = out->z[1];
    out->z[1] = out->z[2];
    out->z[2] = tf;
    tf = out->invW[1];
    out->invW[1] = out->invW[2];
    out->invW[2] = tf;
    if (bary) {
      float3 tb = bary[1];
      bary[1] = bary[2];
      bary[2] = tb;
    }
    area2 = -area2;
    out->flags = CLR_FLAG_BACKFACING;
  }
  // Step 3: cull triangles whose bounds hold no pixel centre.
  const int4 b = setup_pixel_bounds(out, params->width, params->height);
  if (b.x > b.z || b.y > b.w) return false;
  out->invArea2 = 1.0f / convert_float(area2);
  out->triId = triId;
  out->clipSlot = CLR_NOT_CLIPPED;
  return true;
}

/* Runs the whole per-triangle procedure. Writes up to CLR_MAX_SUBTRIS
 * triangles (and, when clipped, their ClipBary records) and returns their
 * count; *clipped tells whether clipping was needed. */
inline int setup_triangle(uint tri, __constant FrameParams* params, __global const float4* clipPos,
                          __global const uint* indices, TriSetup* subs, ClipBary* subBary, bool* clipped)
{
  *clipped = false;
  // Step 1: fetch, reject non-finite and trivially outside triangles.
  float4 c[3];
  uint code[3];
  for (int i = 0; i < 3; ++i) {
    c[i] = clipPos[indices[3 * tri + i]];
    if (!clip_is_finite(c[i])) return 0;
    code[i] = clip_outcode(c[i], params->guardX, params->guardY);
  }
  const uint allOut = code[0] & code[1] & code[2];
  if (allOut & (1u | (0x1Fu << 5))) return 0;
  const uint anyOut = (code[0] | code[1] | code[2]) & 0x1Fu;

  // Step 2: the common case, no clipping needed.
  if (!anyOut) return setup_make(c, params, tri, &subs[0], 0) ? 1 : 0;

  // Step 3: clip, then fan the polygon into triangles.
  *clipped = true;
  ClipVertex poly[CLR_MAX_CLIP_VERTS];
  for (int i = 0; i < 3; ++i) {
    poly[i].pos = c[i];
    poly[i].bary = (float3)((float)(i == 0), (float)(i == 1), (float)(i == 2));
  }
  const int n = clip_polygon(poly, 3, anyOut, params->guardX, params->guardY);
  int count = 0;
  for (int k = 1; k + 1 < n; ++k) {
    const float4 sc[3] = {poly[0].pos, poly[k].pos, poly[k + 1].pos};
    float3 sb[3] = {poly[0].bary, poly[k].bary, poly[k + 1].bary};
    if (!setup_make(sc, params, tri, &subs[count], sb)) continue;
    for (int i = 0; i < 3; ++i) {
      subBary[count].w[i][0] = sb[i].x;
      subBary[count].w[i][1] = sb[i].y;
      subBary[count].w[i][2] = sb[i].z;
    }
    ++count;
  }
  return count;
}

/* Pass 1: how many screen triangles each input triangle yields. */
__kernel void setup_count(__constant FrameParams* params,
                          __global const float4* clipPos,  // numVerts
                          __global const uint* indices,    // 3·numTris
                          __global uint* triCount,         // numTris + 1
                          __global uint* counters)         // CLR_NUM_COUNTERS
{
  const uint tri = get_global_id(0);
  if (tri >= params->numTris) return;
  TriSetup subs[CLR_MAX_SUBTRIS];
  ClipBary subBary[CLR_MAX_SUBTRIS];
  bool clipped;
  const int count = setup_triangle(tri, params, clipPos, indices, subs, subBary, &clipped);
  triCount[tri] = (uint)count;
  if (clipped) {
    atomic_inc(&counters[CLR_COUNTER_CLIPPED_TRIS]);
    atomic_add(&counters[CLR_COUNTER_CLIP_SLOTS], (uint)count);
  }
  if (count == 0) atomic_inc(&counters[CLR_COUNTER_CULLED_TRIS]);
}

/* Pass 2: writes the screen triangles at their scanned offsets. */
__kernel void setup_emit(__constant FrameParams* params,
                         __global const float4* clipPos,  // numVerts
                         __global const uint* indices,    // 3·numTris
                         __global const uint* triOffset,  // numTris + 1, scanned
                         __global TriSetup* setup,        // triOffset[numTris]
                         __global ClipBary* clipBary,     // CLIP_SLOTS counter
                         __global uint* counters)
{
  const uint tri = get_global_id(0);
  if (tri >= params->numTris) return;
  TriSetup subs[CLR_MAX_SUBTRIS];
  ClipBary subBary[CLR_MAX_SUBTRIS];
  bool clipped;
  const int count = setup_triangle(tri, params, clipPos, indices, subs, subBary, &clipped);
  const uint base = triOffset[tri];
  for (int k = 0; k < count; ++k) {
    if (clipped) {
      const uint slot = atomic_inc(&counters[CLR_COUNTER_CLIP_CURSOR]);
      subs[k].clipSlot = slot;
      clipBary[slot] = subBary[k];
    }
    setup[base + k] = subs[k];
  }
}
