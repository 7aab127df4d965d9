/* diff_antialias.cl — nvdiffrast's analytic antialias (Laine et al. 2020,
 * "Modular Primitives for High-Performance Differentiable Rendering"),
 * forward and backward (host/pipeline/diff.cpp; python/clraster/torch.py).
 *
 * One work-item per pixel p of a batch (B · H · W, image-major, row 0 at
 * the bottom) looks at two pairs: p and its right neighbour, p and the
 * pixel of the next row. Where the pair's triangle ids differ, the nearer
 * triangle (background is farthest) is tested for a silhouette edge that
 * crosses the segment between the two pixel centres: an edge whose
 * neighbour triangle (opp: per triangle, the vertex opposite each edge
 * across it, −1 on a boundary) lies on the same side in screen space, or
 * none. Of the crossing edges, the one farthest along the segment, and
 * only if it runs more across the segment than along it, is taken; its
 * crossing dc (0 at the triangle's pixel, 1 at the other, within a 1/16
 * pixel tolerance, then clamped) gives alpha = ±(0.5 − dc), and the pixel
 * on the far side of the segment's middle is blended by alpha toward the
 * other's colour: out[target] += alpha · (c1 − c0).
 * antialias_grad redoes the analysis and writes d L / d colour (atomic)
 * and d L / d pos of the edge's two vertices through the crossing point
 * (zero where alpha saturated at 0.5), scaled by posBoost.
 */
#pragma OPENCL FP_CONTRACT OFF
#if CLR_EXTRAS /* the extras program (CLR_EXTRAS, shared.h) */

typedef struct AaPair {
  float alpha;          // 0: nothing to blend
  uint pixel0, pixel1;  // the pair, pixel1 to the right or the next row
  uint tri, edge;       // the nearer triangle and its silhouette edge (opposite vertex `edge`)
  float fx, fy;         // the centre of the triangle's own pixel, in pixel units from the image centre
  int down;             // 1: the pair is vertical (x and y swapped in the analysis)
} AaPair;

CLR_INLINE bool aa_same_sign(float a, float b)
{
  return (as_int(a) ^ as_int(b)) >= 0;
}

/* Whether n0 / d0 > n1 / d1 (signs of d taken into account). */
CLR_INLINE bool aa_rational_gt(float n0, float n1, float d0, float d1)
{
  return (n0 * d1 > n1 * d0) == aa_same_sign(d0, d1);
}

CLR_INLINE AaPair aa_analyse(__global const float4* rast, __global const float* pos, uint posStride,
                             __global const int* tri, __global const int* opp, uint numTriangles, uint width,
                             uint height, uint p, int down)
{
  AaPair r;
  r.alpha = 0.0f;
  const uint pixel = p % (width * height), px = pixel % width, py = pixel / width, image = p / (width * height);
  if (down ? py + 1u >= height : px + 1u >= width) return r;
  r.pixel0 = p;
  r.pixel1 = p + (down ? width : 1u);
  r.down = down;
  const float4 a = rast[r.pixel0], b = rast[r.pixel1];
  const uint id0 = diff_decode_id(a.w), id1 = diff_decode_id(b.w);
  if (id0 == id1) return r;
  // Step 1: the nearer triangle, seen from its own pixel.
  const bool first = id0 != 0u && (id1 == 0u || a.z < b.z);
  const uint id = first ? id0 : id1;
  if (id > numTriangles) return r;
  r.tri = id - 1u;
  const float xh = 0.5f * (float)width, yh = 0.5f * (float)height;
  r.fx = (float)(px + (!first && !down ? 1u : 0u)) + 0.5f - xh;
  r.fy = (float)(py + (!first && down ? 1u : 0u)) + 0.5f - yh;
  // Step 2: the triangle and its neighbours across each edge, in pixels from that centre.
  float x[3], y[3], ox[3], oy[3];
  for (int i = 0; i < 3; ++i) {
    const int v = tri[3 * r.tri + i], o = opp[3 * r.tri + i];
    const uint vi = (uint)v * 4u + image * posStride, oi = o < 0 ? vi : (uint)o * 4u + image * posStride;
    x[i] = pos[vi] / pos[vi + 3u] * xh - r.fx;
    y[i] = pos[vi + 1u] / pos[vi + 3u] * yh - r.fy;
    ox[i] = pos[oi] / pos[oi + 3u] * xh - r.fx;
    oy[i] = pos[oi + 1u] / pos[oi + 3u] * yh - r.fy;
  }
  const float bb = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  float wing[3];
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    wing[i] = (x[j] - ox[i]) * (y[k] - oy[i]) - (x[k] - ox[i]) * (y[j] - oy[i]);
  }
  if (!aa_same_sign(wing[0], bb) && !aa_same_sign(wing[1], bb) && !aa_same_sign(wing[2], bb)) return r;
  // Step 3: along the pair's axis (x; y for a vertical pair), the crossing edges' positions.
  if (down)
    for (int i = 0; i < 3; ++i) {
      const float t = x[i];
      x[i] = y[i];
      y[i] = t;
    }
  const float ds = first ? 1.0f : -1.0f;
  float d[3], dxs[3], dys[3];
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    dxs[i] = x[k] - x[j];
    dys[i] = y[k] - y[j];
    d[i] = ds * (x[j] * dys[i] - y[j] * dxs[i]);
    if (aa_same_sign(y[j], y[k])) {
      d[i] = -FLT_MAX;
      dys[i] = 1.0f;
    }
  }
  const bool g10 = aa_rational_gt(d[1], d[0], dys[1], dys[0]), g20 = aa_rational_gt(d[2], d[0], dys[2], dys[0]);
  const bool g21 = aa_rational_gt(d[2], d[1], dys[2], dys[1]);
  const int e = g20 && g21 ? 2 : g10 ? 1 : 0;
  if (!aa_same_sign(wing[e], bb) || fabs(dys[e]) < fabs(dxs[e])) return r;
  const float dc = d[e] / dys[e], eps = 0.0625f;
  if (!(dc > -eps && dc < 1.0f + eps)) return r;
  r.edge = (uint)e;
  r.alpha = ds * (0.5f - fmin(fmax(dc, 0.0f), 1.0f));
  return r;
}

__kernel void antialias_fwd(__global const float* color, __global const float4* rast, __global const float* pos,
                            uint posStride, __global const int* tri, __global const int* opp, uint numTriangles,
                            uint width, uint height, uint numPixels, uint channels,
                            __global float* out)  // a copy of color on entry
{
  const uint p = get_global_id(0);
  if (p >= numPixels) return;
  for (int down = 0; down < 2; ++down) {
    const AaPair r = aa_analyse(rast, pos, posStride, tri, opp, numTriangles, width, height, p, down);
    if (r.alpha == 0.0f) continue;
    const uint target = r.alpha > 0.0f ? r.pixel0 : r.pixel1;
    for (uint c = 0; c < channels; ++c) {
      const float delta = color[(size_t)r.pixel1 * channels + c] - color[(size_t)r.pixel0 * channels + c];
      diff_atomic_add(out + (size_t)target * channels + c, r.alpha * delta);
    }
  }
}

__kernel void antialias_grad(__global const float* color, __global const float4* rast, __global const float* pos,
                             uint posStride, __global const int* tri, __global const int* opp, uint numTriangles,
                             uint width, uint height, uint numPixels, uint channels,
                             __global const float* gradOut,  // numPixels · channels
                             float posBoost,
                             __global float* gradColor,  // a copy of gradOut on entry
                             __global float* gradPos)    // pos's layout, zeroed
{
  const uint p = get_global_id(0);
  if (p >= numPixels) return;
  for (int down = 0; down < 2; ++down) {
    const AaPair r = aa_analyse(rast, pos, posStride, tri, opp, numTriangles, width, height, p, down);
    if (r.alpha == 0.0f) continue;
    // Step 1: the colours' gradients and d L / d alpha.
    const uint target = r.alpha > 0.0f ? r.pixel0 : r.pixel1;
    float dd = 0.0f;
    for (uint c = 0; c < channels; ++c) {
      const float g = gradOut[(size_t)target * channels + c];
      dd += g * (color[(size_t)r.pixel1 * channels + c] - color[(size_t)r.pixel0 * channels + c]);
      diff_atomic_add(gradColor + (size_t)r.pixel0 * channels + c, -r.alpha * g);
      diff_atomic_add(gradColor + (size_t)r.pixel1 * channels + c, r.alpha * g);
    }
    if (dd == 0.0f || fabs(r.alpha) >= 0.5f) continue;
    // Step 2: alpha = ±1/2 − xc with xc = (x1 y2 − y1 x2) / (y2 − y1) the edge's crossing of the pair's axis.
    const uint image = p / (width * height);
    const int i1 = ((int)r.edge + 1) % 3, i2 = ((int)r.edge + 2) % 3;
    const uint v1 = (uint)tri[3 * r.tri + i1] * 4u + image * posStride;
    const uint v2 = (uint)tri[3 * r.tri + i2] * 4u + image * posStride;
    float xh = 0.5f * (float)width, yh = 0.5f * (float)height, fx = r.fx, fy = r.fy;
    float4 p1 = vload4(0, pos + v1), p2 = vload4(0, pos + v2);
    if (r.down) {
      p1 = p1.yxzw;
      p2 = p2.yxzw;
      const float t = xh, u = fx;
      xh = yh;
      yh = t;
      fx = fy;
      fy = u;
    }
    const float w1 = 1.0f / p1.w, w2 = 1.0f / p2.w;
    const float x1 = p1.x * w1 * xh - fx, y1 = p1.y * w1 * yh - fy;
    const float x2 = p2.x * w2 * xh - fx, y2 = p2.y * w2 * yh - fy;
    const float dy = y2 - y1, xc = (x1 * y2 - y1 * x2) / dy;
    const float g = -dd * posBoost;  // d L / d xc
    float4 g1 = (float4)(g * y2 / dy * xh * w1, g * (xc - x2) / dy * yh * w1, 0.0f, 0.0f);
    float4 g2 = (float4)(g * -y1 / dy * xh * w2, g * (x1 - xc) / dy * yh * w2, 0.0f, 0.0f);
    g1.w = -(p1.x * g1.x + p1.y * g1.y) * w1;
    g2.w = -(p2.x * g2.x + p2.y * g2.y) * w2;
    if (r.down) {
      g1 = g1.yxzw;
      g2 = g2.yxzw;
    }
    diff_atomic_add(gradPos + v1, g1.x);
    diff_atomic_add(gradPos + v1 + 1u, g1.y);
    diff_atomic_add(gradPos + v1 + 3u, g1.w);
    diff_atomic_add(gradPos + v2, g2.x);
    diff_atomic_add(gradPos + v2 + 1u, g2.y);
    diff_atomic_add(gradPos + v2 + 3u, g2.w);
  }
}
#endif
