/* diff.cl — the backward passes of the library's differentiable calls
 * (host/pipeline/diff.cpp; python/clraster/torch.py's autograd Functions).
 *
 * DIFF_SPAN consecutive pixels per work-item over a batch of images
 * (B · H · W, image-major, row 0 at the bottom). Each reads its pixels'
 * rast (u, v, z/w, id in nvdiffrast's encoding) and the incoming gradients,
 * sums the per-vertex gradients of each run of one triangle in private and
 * adds them with float atomics (the order of the sums is unspecified, so
 * results vary in the last bits between runs).
 *
 *  rasterize_grad: d rast / d pos through u, v, z/w and rast_db, all
 *    evaluated analytically at the pixel centre s = (x_ndc, y_ndc, 1) with
 *    coverage held fixed. With the clip vertices P_i = (x_i, y_i, w_i),
 *    r_i = P_j × P_k (i, j, k cyclic), k_i = r_i · s, S = Σ k_i:
 *      u = k_0 / S, v = k_1 / S, z/w = Σ k_i z_i / Σ k_i w_i,
 *      du/dx_ndc = (r_0.x − u R.x) / S with R = Σ r_i (rast_outputs.cl),
 *    and the chain rule runs back through those formulas to P and z.
 *  interpolate_grad (DIFF_SPAN pixels per work-item): out = u a0 + v a1 + (1 − u − v) a2 and
 *    out_da = (db.x dsdu + db.z dsdv, db.y dsdu + db.w dsdv) with dsdu =
 *    a0 − a2, dsdv = a1 − a2: gradients to attr (atomic), to rast's u and v
 *    (channels 2 and 3 get 0, as in nvdiffrast) and to rast_db.
 * A pixel whose id names no triangle (background, or beyond numTriangles)
 * contributes nothing and gets zero gradients.
 */
#pragma OPENCL FP_CONTRACT OFF
#if CLR_EXTRAS /* the extras program (CLR_EXTRAS, shared.h) */

/* nvdiffrast's triangle-id encoding, decoded (rast_outputs.cl encodes). */
CLR_INLINE uint diff_decode_id(float f)
{
  if (!(f > 0.0f)) return 0u;
  return f <= 16777216.0f ? (uint)f : as_uint(f) - 0x4a800000u;
}

/* *p += v for a float in global memory, by compare-and-swap. */
CLR_INLINE void diff_atomic_add(volatile __global float* p, float v)
{
  if (v == 0.0f) return;
  volatile __global uint* bits = (volatile __global uint*)p;
  uint seen = *bits, expected;
  do {
    expected = seen;
    seen = atomic_cmpxchg(bits, expected, as_uint(as_float(expected) + v));
  } while (seen != expected);
}

/* Pixels per work-item of rasterize_grad and interpolate_grad, and the channels interpolate_grad sums in private at
 * a time. */
#define DIFF_SPAN 16u
#define DIFF_CHUNK 8u

/* Pixel p's share of d L / d pos: gv[j], the gradient of its triangle's vertex j (x, y, z, w), at pos offset vi[j];
 * false where p adds nothing (no triangle, zero upstream gradient, a degenerate triangle). */
CLR_INLINE bool diff_rasterize_pixel(__global const float* pos, uint posStride, __global const int* tri,
                                     uint numTriangles, uint numVertices, __global const float4* rast,
                                     __global const float4* gradRast, __global const float4* gradDb, uint withDb,
                                     uint width, uint height, uint p, uint* vi, float4* gv)
{
  const uint id = diff_decode_id(rast[p].w);
  if (id == 0u || id > numTriangles) return false;
  const float4 g = gradRast[p];
  const float4 gd = withDb ? gradDb[p] : (float4)(0.0f);
  if (all(g.xyz == (float3)(0.0f)) && all(gd == (float4)(0.0f))) return false;
  // Step 1: the triangle's clip vertices and the pixel centre.
  const uint image = p / (width * height), pixel = p % (width * height);
  const uint px = pixel % width, py = pixel / width;
  for (int j = 0; j < 3; ++j) {
    const int v = tri[3 * (id - 1u) + j];
    if (v < 0 || (uint)v >= numVertices) return false;
    vi[j] = (uint)v * 4u + image * posStride;
  }
  float3 P[3];
  float z[3];
  for (int j = 0; j < 3; ++j) {
    P[j] = (float3)(pos[vi[j]], pos[vi[j] + 1u], pos[vi[j] + 3u]);
    z[j] = pos[vi[j] + 2u];
  }
  const float3 s =
      (float3)(2.0f * ((float)px + 0.5f) / (float)width - 1.0f, 2.0f * ((float)py + 0.5f) / (float)height - 1.0f, 1.0f);
  // Step 2: the forward formulas.
  const float3 r[3] = {cross(P[1], P[2]), cross(P[2], P[0]), cross(P[0], P[1])};
  const float3 R = r[0] + r[1] + r[2];
  const float k[3] = {dot(r[0], s), dot(r[1], s), dot(r[2], s)};
  const float S = k[0] + k[1] + k[2];
  const float D = k[0] * P[0].z + k[1] * P[1].z + k[2] * P[2].z;
  if (S == 0.0f || D == 0.0f) return false;
  const float l0 = k[0] / S, l1 = k[1] / S;
  const float zw = (k[0] * z[0] + k[1] * z[1] + k[2] * z[2]) / D;
  const float a0 = (r[0].x - l0 * R.x) / S, b0 = (r[0].y - l0 * R.y) / S;
  const float a1 = (r[1].x - l1 * R.x) / S, b1 = (r[1].y - l1 * R.y) / S;
  // Step 3: back through rast_db = (a0·2/W, b0·2/H, a1·2/W, b1·2/H).
  const float ga0 = gd.x * 2.0f / (float)width, gb0 = gd.y * 2.0f / (float)height;
  const float ga1 = gd.z * 2.0f / (float)width, gb1 = gd.w * 2.0f / (float)height;
  const float gl0 = g.x - (ga0 * R.x + gb0 * R.y) / S, gl1 = g.y - (ga1 * R.x + gb1 * R.y) / S;
  float3 gR = (float3)(-(ga0 * l0 + ga1 * l1) / S, -(gb0 * l0 + gb1 * l1) / S, 0.0f);
  float gS = -(ga0 * a0 + gb0 * b0 + ga1 * a1 + gb1 * b1) / S;
  float3 gr[3] = {(float3)(ga0 / S, gb0 / S, 0.0f), (float3)(ga1 / S, gb1 / S, 0.0f), (float3)(0.0f)};
  // Step 4: back through u = k0 / S, v = k1 / S and z/w = Σ k z / Σ k w.
  float gk[3] = {gl0 / S, gl1 / S, 0.0f};
  gS -= (gl0 * l0 + gl1 * l1) / S;
  float gz[3] = {0.0f, 0.0f, 0.0f}, gw[3] = {0.0f, 0.0f, 0.0f};
  for (int i = 0; i < 3; ++i) {
    gk[i] += g.z * (z[i] - zw * P[i].z) / D;
    gz[i] = g.z * k[i] / D;
    gw[i] = -g.z * zw * k[i] / D;
  }
  // Step 5: back through k_i = r_i · s, S = R · s, R = Σ r_i, r_i = P_j × P_k.
  gR += gS * s;
  for (int i = 0; i < 3; ++i) gr[i] += gk[i] * s + gR;
  float3 gP[3] = {cross(P[1], gr[2]) + cross(gr[1], P[2]), cross(P[2], gr[0]) + cross(gr[2], P[0]),
                  cross(P[0], gr[1]) + cross(gr[0], P[1])};
  for (int j = 0; j < 3; ++j) gv[j] = (float4)(gP[j].x, gP[j].y, gz[j], gP[j].z + gw[j]);
  return true;
}

/* DIFF_SPAN consecutive pixels per work-item; each run of pixels of one triangle sums its vertex gradients in
 * private and adds them with one atomic add per value. */
__kernel void rasterize_grad(__global const float* pos,  // posImages · numVertices · 4
                             uint posStride,             // floats per image of pos; 0: shared
                             __global const int* tri, uint numTriangles, uint numVertices,
                             __global const float4* rast,      // numPixels
                             __global const float4* gradRast,  // numPixels
                             __global const float4* gradDb,    // numPixels, when withDb
                             uint withDb, uint width, uint height, uint numPixels,
                             __global float* gradPos)  // pos's layout
{
  const uint first = get_global_id(0) * DIFF_SPAN;
  if (first >= numPixels) return;
  const uint end = min(first + DIFF_SPAN, numPixels);
  uint cur[3] = {0u, 0u, 0u};
  float4 acc[3] = {(float4)(0.0f), (float4)(0.0f), (float4)(0.0f)};
  bool have = false;
  for (uint p = first; p <= end; ++p) {
    uint vi[3] = {0u, 0u, 0u};
    float4 gv[3];
    const bool ok = p < end && diff_rasterize_pixel(pos, posStride, tri, numTriangles, numVertices, rast, gradRast,
                                                    gradDb, withDb, width, height, p, vi, gv);
    const bool same = ok && have && vi[0] == cur[0] && vi[1] == cur[1] && vi[2] == cur[2];
    if (have && !same) {
      for (int j = 0; j < 3; ++j) {
        diff_atomic_add(gradPos + cur[j], acc[j].x);
        diff_atomic_add(gradPos + cur[j] + 1u, acc[j].y);
        diff_atomic_add(gradPos + cur[j] + 2u, acc[j].z);
        diff_atomic_add(gradPos + cur[j] + 3u, acc[j].w);
      }
      have = false;
    }
    if (!ok) continue;
    if (!have) {
      for (int j = 0; j < 3; ++j) {
        cur[j] = vi[j];
        acc[j] = (float4)(0.0f);
      }
      have = true;
    }
    for (int j = 0; j < 3; ++j) acc[j] += gv[j];
  }
}

/* The attr offsets of pixel p's triangle's vertices (in its image), or false where p names none. */
CLR_INLINE bool diff_attr_vertices(__global const float4* rast, __global const int* tri, uint numTriangles,
                                   uint numVertices, uint numAttrs, uint attrStride, uint pixelsPerImage, uint p,
                                   uint* vi)
{
  const uint id = diff_decode_id(rast[p].w);
  if (id == 0u || id > numTriangles) return false;
  for (int j = 0; j < 3; ++j) {
    const int v = tri[3 * (id - 1u) + j];
    if (v < 0 || (uint)v >= numVertices) return false;
    vi[j] = (uint)v * numAttrs + (p / pixelsPerImage) * attrStride;
  }
  return true;
}

/* DIFF_SPAN consecutive pixels per work-item: their rast and rast_db gradients, then the attr gradients summed
 * in private over each run of pixels of one triangle, so that a run costs one atomic add per value. */
__kernel void interpolate_grad(__global const float* attr,  // attrImages · numVertices · numAttrs
                               uint attrStride,             // floats per image of attr; 0: shared
                               uint numVertices, uint numAttrs, __global const float4* rast, __global const int* tri,
                               uint numTriangles,
                               __global const float* gradOut,  // numPixels · numAttrs
                               __global const float4* db,      // numPixels, when numDiff
                               __global const float* gradDa,   // numPixels · 2 · numDiff
                               __global const int* diff,       // numDiff attribute indices in 0..numAttrs-1
                               uint numDiff, uint pixelsPerImage, uint numPixels,
                               __global float* gradAttr,   // attr's layout
                               __global float4* gradRast,  // numPixels
                               __global float4* gradDb)    // numPixels, when numDiff
{
  const uint first = get_global_id(0) * DIFF_SPAN;
  if (first >= numPixels) return;
  const uint end = min(first + DIFF_SPAN, numPixels);
  // Step 1: per pixel, d L / d (u, v) and d L / d rast_db.
  for (uint p = first; p < end; ++p) {
    uint vi[3];
    if (!diff_attr_vertices(rast, tri, numTriangles, numVertices, numAttrs, attrStride, pixelsPerImage, p, vi)) {
      gradRast[p] = (float4)(0.0f);
      if (numDiff) gradDb[p] = (float4)(0.0f);
      continue;
    }
    float gu = 0.0f, gv = 0.0f;
    for (uint c = 0; c < numAttrs; ++c) {
      const float go = gradOut[(size_t)p * numAttrs + c];
      gu += go * (attr[vi[0] + c] - attr[vi[2] + c]);
      gv += go * (attr[vi[1] + c] - attr[vi[2] + c]);
    }
    gradRast[p] = (float4)(gu, gv, 0.0f, 0.0f);
    if (!numDiff) continue;
    float4 gdb = (float4)(0.0f);
    for (uint k = 0; k < numDiff; ++k) {
      const uint c = (uint)diff[k];
      const float g0 = gradDa[((size_t)p * numDiff + k) * 2u], g1 = gradDa[((size_t)p * numDiff + k) * 2u + 1u];
      const float dsdu = attr[vi[0] + c] - attr[vi[2] + c], dsdv = attr[vi[1] + c] - attr[vi[2] + c];
      gdb += (float4)(g0 * dsdu, g1 * dsdu, g0 * dsdv, g1 * dsdv);
    }
    gradDb[p] = gdb;
  }
  // Step 2: d L / d attr, DIFF_CHUNK channels at a time, flushed when the triangle changes.
  for (uint c0 = 0; c0 < numAttrs; c0 += DIFF_CHUNK) {
    const uint nc = min(DIFF_CHUNK, numAttrs - c0);
    float acc[3][DIFF_CHUNK];
    uint cur[3] = {0u, 0u, 0u};
    bool have = false;
    for (uint p = first; p <= end; ++p) {
      uint vi[3] = {0u, 0u, 0u};
      const bool ok = p < end && diff_attr_vertices(rast, tri, numTriangles, numVertices, numAttrs, attrStride,
                                                    pixelsPerImage, p, vi);
      const bool same = ok && have && vi[0] == cur[0] && vi[1] == cur[1] && vi[2] == cur[2];
      if (have && !same) {
        for (int j = 0; j < 3; ++j)
          for (uint i = 0; i < nc; ++i) diff_atomic_add(gradAttr + cur[j] + c0 + i, acc[j][i]);
        have = false;
      }
      if (!ok) continue;
      if (!have) {
        for (int j = 0; j < 3; ++j) {
          cur[j] = vi[j];
          for (uint i = 0; i < DIFF_CHUNK; ++i) acc[j][i] = 0.0f;
        }
        have = true;
      }
      const float u = rast[p].x, v = rast[p].y, w = 1.0f - u - v;
      for (uint i = 0; i < nc; ++i) {
        const float go = gradOut[(size_t)p * numAttrs + c0 + i];
        acc[0][i] += u * go;
        acc[1][i] += v * go;
        acc[2][i] += w * go;
      }
      if (!numDiff) continue;
      const float4 d = db[p];
      for (uint k = 0; k < numDiff; ++k) {
        const uint i = (uint)diff[k] - c0;
        if (i >= nc) continue;
        const float g0 = gradDa[((size_t)p * numDiff + k) * 2u], g1 = gradDa[((size_t)p * numDiff + k) * 2u + 1u];
        const float gsu = g0 * d.x + g1 * d.y, gsv = g0 * d.z + g1 * d.w;
        acc[0][i] += gsu;
        acc[1][i] += gsv;
        acc[2][i] -= gsu + gsv;
      }
    }
  }
}
#endif
