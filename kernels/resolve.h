/* resolve.h — what the resolve kernels share (resolve.cl and its lean lambert kernel, resolve_lambert.cl): RGBA8
 * packing, the lanes' fragments and their gather, barycentrics and the 1/w rule, shading of a sample plane, the id
 * mode, row stores and prefetch, the kernels' parameters (CLR_RESOLVE_PARAMS) and work shape (CLR_RESOLVE_KERNEL).
 * The frame program only (CLR_EXTRAS, shared.h). See resolve.cl for the stage's contract.
 */
#ifndef CLR_RESOLVE_H
#define CLR_RESOLVE_H
#include "transform.h"
#include "shade.h"
#include "vis.h"

/* RGBA8 (R in the low byte, alpha 255) from colour channels in [0, 1]. */
CLR_INLINE uintL pack_rgba(floatL r, floatL g, floatL b)
{
  const floatL lo = 0.0f, hi = 1.0f, big = 8388608.0f;  // 2^23
  // Round to nearest even as convert_uint_sat_rte: the clamped channel ×255 is in [0, 255], where adding 2^23 leaves
  // no fraction bits and subtracting it is exact (clr_rint without its selects for negative and large values).
  const uintL qr = convert_uintL((clamp(r, lo, hi) * 255.0f + big) - big);
  const uintL qg = convert_uintL((clamp(g, lo, hi) * 255.0f + big) - big);
  const uintL qb = convert_uintL((clamp(b, lo, hi) * 255.0f + big) - big);
  return qr | (qg << 8) | (qb << 16) | 0xFF000000u;
}

/* The lanes' fragments: source words, 1/w at the setup vertices, barycentric gradients and the attributes the
 * need flags select. Uncovered lanes hold some triangle's values; the background replaces them. */
#define CLR_RESOLVE_MAX_RUNS 8 /* the most runs of lanes a row reads run by run */
typedef struct ResolveLanes {
  bool needNormals, needUvs, needColours, needPositions, needGradients, needMaterial;
  intL covered;
  uintL source;         // the source words (shared.h)
  uintL material;       // the materials' indices (0 without materials)
  floatL clipW[3];      // w_clip at the setup vertices (record_clip_w)
  floatL normal[3][3];  // [input vertex][component]
  floatL uv[3][2];      // [input vertex][component]
  floatL colour[3][4];  // [input vertex][RGBA]
  floatL pos[3][3];     // [input vertex][component], world space
  floatL grad[3][2];    // [setup vertex][d/dx, d/dy]: screen barycentric per pixel
} ResolveLanes;

/* Per-pixel gradients of b_i = E_i / (2·area): ∂b_i/∂x = (y_{i+1} − y_{i+2}) / (2·area),
 * ∂b_i/∂y = (x_{i+2} − x_{i+1}) / (2·area), × CLR_FIXED_ONE. */
CLR_INLINE float resolve_gradient(__global const TriSetup* t, int i, int d)
{
  const int a = (i + 1) % 3, b = (i + 2) % 3;
  const float scale = CLR_RECORD_INV_AREA2(*t) * (float)CLR_FIXED_ONE;
  return (d == 0 ? (float)(t->y[a] - t->y[b]) : (float)(t->x[b] - t->x[a])) * scale;
}

/* Reads what the shading needs of setup record s (record, source, indices, material, attributes) into the lanes
 * of `in` by a select (every lane when `in` is all lanes), keeping values in registers (bench/ab.sh --shade). */
CLR_HOT void resolve_take(__constant FrameParams* params, __global const TriSetup* setup, __global const uint* source,
                          __global const ClipBary* clipBary, __global const uint* indices,
                          __global const float* positions, __global const float* normals, __global const float* uvs,
                          __global const float* colours, __global const uint* triMaterial, uint s, intL in,
                          ResolveLanes* g)
{
#define CLR_TAKE(lanes, value) (lanes) = select((lanes), (value), in)
  __global const TriSetup* t = &setup[s];
  const uint word = source[s], tri = clr_source_triangle(word, clipBary);
  const uint vertex[3] = {indices[3 * tri], indices[3 * tri + 1], indices[3 * tri + 2]};
  float w[3];
  record_clip_w(params, positions, clipBary, word, vertex, w);
  CLR_TAKE(g->source, (uintL)word);
  for (int i = 0; i < 3; ++i) CLR_TAKE(g->clipW[i], (floatL)w[i]);
  for (int i = 0; g->needGradients && i < 3; ++i)
    for (int d = 0; d < 2; ++d) CLR_TAKE(g->grad[i][d], (floatL)resolve_gradient(t, i, d));
  if (g->needMaterial) CLR_TAKE(g->material, (uintL)triMaterial[tri]);
  for (int j = 0; j < 3; ++j) {
    const uint v = vertex[j];
    for (int k = 0; g->needNormals && k < 3; ++k) CLR_TAKE(g->normal[j][k], (floatL)normals[3 * v + k]);
    for (int k = 0; g->needPositions && k < 3; ++k) CLR_TAKE(g->pos[j][k], (floatL)positions[3 * v + k]);
    for (int k = 0; g->needUvs && k < 2; ++k) CLR_TAKE(g->uv[j][k], (floatL)uvs[2 * v + k]);
    for (int k = 0; g->needColours && k < 4; ++k) CLR_TAKE(g->colour[j][k], (floatL)colours[4 * v + k]);
  }
#undef CLR_TAKE
}

/* One attribute of `components` floats of the lanes' three input vertices, into out[j · components + k]. */
CLR_INLINE void resolve_gather_attribute(__global const float* values, uint components, const uint vertex[3][CLR_LANES],
                                         floatL* out)
{
  for (int j = 0; j < 3; ++j) {
    float lanes[4][CLR_LANES];
    CLR_NO_UNROLL
    for (uint lane = 0; lane < CLR_LANES; ++lane)
      for (uint k = 0; k < components; ++k) lanes[k][lane] = values[components * vertex[j][lane] + k];
    for (uint k = 0; k < components; ++k) out[j * components + k] = CLR_LOAD_LANES(lanes[k]);
  }
}

/* Step 1 of the lane-by-lane gathers (also resolve_lambert_gather): lane `lane`'s record (0 if uncovered: a tile
 * with a bin has one), source word and input triangle into the per-lane arrays. */
CLR_HOT __global const TriSetup* resolve_lane_record(__global const TriSetup* setup, __global const uint* source,
                                                     __global const ClipBary* clipBary, const uint* index, uint lane,
                                                     uint* from, uint* tri)
{
  const uint s = index[lane] != CLR_NONE ? index[lane] : 0;
  from[lane] = source[s];
  tri[lane] = clr_source_triangle(from[lane], clipBary);
  return &setup[s];
}

/* record_clip_w (transform.cl) for every lane: from[lane] the source words, vertex[j][lane] the input vertices. */
CLR_HOT void resolve_clip_w_lanes(__constant FrameParams* params, __global const float* positions,
                                  __global const ClipBary* clipBary, const uint* from, const uint vertex[3][CLR_LANES],
                                  floatL clipW[3])
{
  float w[3][CLR_LANES];
  uint clipped = 0;  // bit lane: a clipped record
  CLR_NO_UNROLL
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    for (int j = 0; j < 3; ++j) w[j][lane] = transform_w(params, positions, vertex[j][lane]);
    clipped |= (clr_source_clip_slot(from[lane]) != CLR_NOT_CLIPPED ? 1u : 0u) << lane;
  }
  const uintL word = CLR_LOAD_LANES(from);
  const intL back = (word & CLR_SOURCE_BACKFACING) != 0;
  const floatL w0 = CLR_LOAD_LANES(w[0]), w1 = CLR_LOAD_LANES(w[1]), w2 = CLR_LOAD_LANES(w[2]);
  clipW[0] = w0;
  clipW[1] = select(w1, w2, back);
  clipW[2] = select(w2, w1, back);
  if (!clipped) return;
  float q[3][CLR_LANES];
  for (int i = 0; i < 3; ++i) CLR_STORE_LANES(clipW[i], q[i]);
  for (; clipped; clipped &= clipped - 1) {
    const uint lane = 31 - clz(clipped & (0u - clipped));  // the lowest set bit
    for (int i = 0; i < 3; ++i) q[i][lane] = clipBary[clr_source_clip_slot(from[lane])].clipW[i];
  }
  for (int i = 0; i < 3; ++i) clipW[i] = CLR_LOAD_LANES(q[i]);
}

/* resolve_take for every lane, for rows of many runs: staged gathers with independent loads (their cache misses
 * overlap): records and sources, then indices and materials, then attributes. Uncovered lanes read record 0. */
CLR_HOT void resolve_gather_lanes(__constant FrameParams* params, __global const TriSetup* setup,
                                  __global const uint* source, __global const ClipBary* clipBary,
                                  __global const uint* indices, __global const float* positions,
                                  __global const float* normals, __global const float* uvs,
                                  __global const float* colours, __global const uint* triMaterial, const uint* index,
                                  ResolveLanes* g)
{
  // Step 1: the records and source words.
  uint from[CLR_LANES], tri[CLR_LANES], material[CLR_LANES], vertex[3][CLR_LANES];
  float grad[3][2][CLR_LANES];
  CLR_NO_UNROLL
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    __global const TriSetup* t = resolve_lane_record(setup, source, clipBary, index, lane, from, tri);
    for (int i = 0; g->needGradients && i < 3; ++i)
      for (int d = 0; d < 2; ++d) grad[i][d][lane] = resolve_gradient(t, i, d);
  }
  // Step 2: the vertex indices and materials.
  CLR_NO_UNROLL
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    for (int j = 0; j < 3; ++j) vertex[j][lane] = indices[3 * tri[lane] + j];
    material[lane] = g->needMaterial ? triMaterial[tri[lane]] : 0u;
  }
  // Step 3: 1/w, the attributes, and everything into lane types.
  resolve_clip_w_lanes(params, positions, clipBary, from, vertex, g->clipW);
  if (g->needNormals) resolve_gather_attribute(normals, 3, vertex, &g->normal[0][0]);
  if (g->needPositions) resolve_gather_attribute(positions, 3, vertex, &g->pos[0][0]);
  if (g->needUvs) resolve_gather_attribute(uvs, 2, vertex, &g->uv[0][0]);
  if (g->needColours) resolve_gather_attribute(colours, 4, vertex, &g->colour[0][0]);
  g->source = CLR_LOAD_LANES(from);
  g->material = CLR_LOAD_LANES(material);
  for (int i = 0; i < 3; ++i)
    for (int d = 0; g->needGradients && d < 2; ++d) g->grad[i][d] = CLR_LOAD_LANES(grad[i][d]);
}

/* The fragments of a row with a covered lane (index: setup indices, CLR_NONE past the viewport; indexLanes as a
 * vector). Up to CLR_RESOLVE_MAX_RUNS runs: run by run (resolve_take), the first into every lane; more runs:
 * resolve_gather_lanes. What to gather follows the mode and sceneFlags. */
CLR_CALLED void resolve_gather(__constant FrameParams* params, const uint* index, uintL indexLanes,
                               __global const TriSetup* setup, __global const uint* source,
                               __global const ClipBary* clipBary, __global const uint* indices,
                               __global const float* positions, __global const float* normals,
                               __global const float* uvs, __global const float* colours,
                               __global const uint* triMaterial, ResolveLanes* g)
{
  // Step 1: what the shading reads.
  const uint mode = params->shadeMode, flags = params->sceneFlags;
  g->covered = indexLanes != CLR_NONE;
  g->needNormals = CLR_NEEDS_NORMALS(mode);
  g->needUvs = CLR_NEEDS_UVS(mode) || (flags & CLR_SCENE_TEXTURES);
  g->needColours = (flags & CLR_SCENE_COLORS) != 0;
  g->needPositions = CLR_NEEDS_POSITIONS(mode, params->pointLightOn);
  g->needGradients = (flags & CLR_SCENE_TEXTURES) && params->texFilter == CLR_FILTER_TRILINEAR;
  g->needMaterial = (flags & CLR_SCENE_TRI_MATERIALS) != 0;
  g->material = 0u;
  // Step 2: the lanes that start a covered run.
  uint starts = 0;
  for (uint lane = 0; lane < CLR_LANES; ++lane)
    starts |= (index[lane] != CLR_NONE && (lane == 0 || index[lane] != index[lane - 1]) ? 1u : 0u) << lane;
  if (popcount(starts) > CLR_RESOLVE_MAX_RUNS) {
    resolve_gather_lanes(params, setup, source, clipBary, indices, positions, normals, uvs, colours, triMaterial, index,
                         g);
    return;
  }
  // Step 3: run by run.
  uint lane = 31 - clz(starts & (0u - starts));  // the lowest set bit
  resolve_take(params, setup, source, clipBary, indices, positions, normals, uvs, colours, triMaterial, index[lane],
               (intL)(-1), g);
  CLR_NO_UNROLL
  for (starts &= starts - 1; starts; starts &= starts - 1) {
    lane = 31 - clz(starts & (0u - starts));
    resolve_take(params, setup, source, clipBary, indices, positions, normals, uvs, colours, triMaterial, index[lane],
                 indexLanes == index[lane], g);
  }
}

/* For the clipped lanes (`clippedL`): mu_j = Σ_i λ_i · w_ij over the ClipBary weights (the general sum's order),
 * back faces, and with `uvs` the setup vertices' uv = Σ_j w_ij · uv_j. Both resolve kernels call it. */
CLR_INLINE void resolve_clipped_lanes(__global const ClipBary* clipBary, uintL sourceL, intL clippedL,
                                      const floatL lambda[3], floatL mu[3], intL* backL, bool uvs,
                                      const floatL uv[3][2], floatL uvAt[3][2])
{
  int clippedLane[CLR_LANES], clippedBack[CLR_LANES];
  uint from[CLR_LANES];
  CLR_STORE_LANES(clippedL, clippedLane);
  CLR_STORE_LANES(sourceL, from);
  float l[3][CLR_LANES], m[3][CLR_LANES], u[3][2][CLR_LANES], at[3][2][CLR_LANES];
  for (int i = 0; i < 3; ++i) {
    CLR_STORE_LANES(lambda[i], l[i]);
    CLR_STORE_LANES(mu[i], m[i]);
    for (int k = 0; uvs && k < 2; ++k) {
      CLR_STORE_LANES(uv[i][k], u[i][k]);
      CLR_STORE_LANES(uvAt[i][k], at[i][k]);
    }
  }
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    clippedBack[lane] = 0;
    if (!clippedLane[lane]) continue;
    __global const ClipBary* w = &clipBary[clr_source_clip_slot(from[lane])];
    for (int j = 0; j < 3; ++j) {
      m[j][lane] = 0.0f;
      for (int i = 0; i < 3; ++i) m[j][lane] += l[i][lane] * w->w[i][j];
    }
    for (int i = 0; uvs && i < 3; ++i)
      for (int k = 0; k < 2; ++k) {
        at[i][k][lane] = 0.0f;
        for (int j = 0; j < 3; ++j) at[i][k][lane] += w->w[i][j] * u[j][k][lane];
      }
    clippedBack[lane] = (w->flags & CLR_FLAG_BACKFACING) ? -1 : 0;
  }
  for (int j = 0; j < 3; ++j) {
    mu[j] = CLR_LOAD_LANES(m[j]);
    for (int k = 0; uvs && k < 2; ++k) uvAt[j][k] = CLR_LOAD_LANES(at[j][k]);
  }
  *backL = *backL | CLR_LOAD_LANES(clippedBack);
}

/* The input vertices' weights mu_j: lambda, with 1 and 2 swapped for a back face, or through ClipBary when clipped
 * (the same floats as summing over an identity or swap matrix). *backL: lanes whose normal flips (source word or
 * ClipBary flag). With `uvs`, the setup vertices' uv through the same map into uvAt. */
CLR_INLINE void resolve_vertex_weights(__global const ClipBary* clipBary, uintL sourceL, intL covered,
                                       const floatL lambda[3], floatL mu[3], intL* backL, bool uvs,
                                       const floatL uv[3][2], floatL uvAt[3][2])
{
  const intL clippedL = ((sourceL & CLR_SOURCE_CLIPPED) != 0u) & covered;
  const intL swappedL = ((sourceL & CLR_SOURCE_BACKFACING) != 0u) & CLR_NOT(clippedL);
  *backL = swappedL;
  mu[0] = lambda[0];
  mu[1] = select(lambda[1], lambda[2], swappedL);
  mu[2] = select(lambda[2], lambda[1], swappedL);
  for (int k = 0; uvs && k < 2; ++k) {
    uvAt[0][k] = uv[0][k];
    uvAt[1][k] = select(uv[1][k], uv[2][k], swappedL);
    uvAt[2][k] = select(uv[2][k], uv[1][k], swappedL);
  }
  if (CLR_ANY(clippedL)) resolve_clipped_lanes(clipBary, sourceL, clippedL, lambda, mu, backL, uvs, uv, uvAt);
}

/* The colour of a row of samples, channels in [0, 1]. */
typedef struct ColourL {
  floatL r, g, b;
} ColourL;

CLR_INLINE ColourL colour_make(floatL r, floatL g, floatL b)
{
  const floatL lo = 0.0f, hi = 1.0f;
  ColourL c = {clamp(r, lo, hi), clamp(g, lo, hi), clamp(b, lo, hi)};
  return c;
}

/* Every lane the colour of an RGBA8 value (pack_rgba's layout), such as the background. */
CLR_INLINE ColourL colour_unpack(uint rgba)
{
  ColourL c = {(floatL)((rgba & 0xFFu) / 255.0f), (floatL)(((rgba >> 8) & 0xFFu) / 255.0f),
               (floatL)(((rgba >> 16) & 0xFFu) / 255.0f)};
  return c;
}

CLR_INLINE ColourL colour_select(ColourL a, ColourL b, intL mask)
{
  ColourL c = {select(a.r, b.r, mask), select(a.g, b.g, mask), select(a.b, b.b, mask)};
  return c;
}

/* Loads lanes of a float plane row, past the viewport's edge as 0. */
CLR_INLINE floatL load_float_lanes(__global const float* row, uint count)
{
  if (count == CLR_LANES) return CLR_LOAD_LANES(row);
  float lanes[CLR_LANES];
  for (uint lane = 0; lane < CLR_LANES; ++lane) lanes[lane] = lane < count ? row[lane] : 0.0f;
  return CLR_LOAD_LANES(lanes);
}

/* The sample positions of a row's lanes for sample k, in fixed point. */
CLR_INLINE intL resolve_sample_x(__constant FrameParams* params, uint firstX, uint k)
{
  return ((int)firstX + CLR_LANE_INDEX) * CLR_FIXED_ONE + CLR_FIXED_HALF + params->sampleX[k];
}
CLR_INLINE int resolve_sample_y(__constant FrameParams* params, uint py, uint k)
{
  return (int)py * CLR_FIXED_ONE + CLR_FIXED_HALF + params->sampleY[k];
}

/* The lanes' screen barycentrics at sample k recomputed from the records (vis_barycentrics, raster.cl): raster's
 * floats. Each run's record is read once and selected into its lanes; CLR_NONE lanes read record 0, discarded. */
CLR_INLINE void resolve_recompute_barycentrics(__constant FrameParams* params, __global const TriSetup* setup,
                                               const uint* index, uintL lanes, uint firstX, uint py, uint k, floatL* b1,
                                               floatL* b2)
{
  // Step 1: the first run's record in every lane, later runs selected into theirs (lanes: index as a vector).
  __global const TriSetup* t = &setup[index[0] != CLR_NONE ? index[0] : 0];
  intL x0 = t->x[0], y0 = t->y[0], x1 = t->x[1], y1 = t->y[1], x2 = t->x[2], y2 = t->y[2];
  floatL scale = CLR_RECORD_INV_AREA2(*t);
  if (CLR_ANY(lanes != index[0])) {
    CLR_NO_UNROLL
    for (uint lane = 1; lane < CLR_LANES; ++lane) {
      if (index[lane] == index[lane - 1]) continue;
      t = &setup[index[lane] != CLR_NONE ? index[lane] : 0];
      const intL run = lanes == index[lane];
      x0 = select(x0, (intL)t->x[0], run);
      y0 = select(y0, (intL)t->y[0], run);
      x1 = select(x1, (intL)t->x[1], run);
      y1 = select(y1, (intL)t->y[1], run);
      x2 = select(x2, (intL)t->x[2], run);
      y2 = select(y2, (intL)t->y[2], run);
      scale = select(scale, (floatL)CLR_RECORD_INV_AREA2(*t), run);
    }
  }
  // Step 2: the edge functions and barycentrics, as raster has them.
  vis_barycentrics(x0, y0, x1, y1, x2, y2, scale, lanes != CLR_NONE, resolve_sample_x(params, firstX, k),
                   resolve_sample_y(params, py, k), b1, b2);
}

/* Reads the lanes' barycentrics at sample k from the planes if the frame has them; else returns false. */
CLR_INLINE bool resolve_read_barycentrics(__constant FrameParams* params, __global const float* visAttr, uint visPlane,
                                          uint p, uint count, uint k, floatL* b1, floatL* b2)
{
  if (!params->visAttributes) return false;
  *b1 = load_float_lanes(&visAttr[(3 * k + 1) * visPlane + p], count);
  *b2 = load_float_lanes(&visAttr[(3 * k + 2) * visPlane + p], count);
  return true;
}

/* The lanes' screen barycentrics at sample k: read from the planes when raster wrote them, else recomputed. */
CLR_INLINE void resolve_barycentrics(__constant FrameParams* params, __global const float* visAttr, uint visPlane,
                                     uint p, uint count, uint k, __global const TriSetup* setup, const uint* index,
                                     uintL indexLanes, uint firstX, uint py, floatL* b1, floatL* b2)
{
  if (!resolve_read_barycentrics(params, visAttr, visPlane, p, count, k, b1, b2))
    resolve_recompute_barycentrics(params, setup, index, indexLanes, firstX, py, k, b1, b2);
}

/* Stores the first `count` lanes of an RGBA8 row (it may end at the viewport edge); a whole aligned row streams
 * past the caches (CLR_STREAM_STORE, lanes.h). */
CLR_INLINE void store_row(uintL colour, uint count, __global uint* out)
{
  if (count == CLR_LANES) {
    if (CLR_STREAMS && ((size_t)out % sizeof(uintL)) == 0)
      CLR_STREAM_STORE(colour, (__global uintL*)out);
    else
      CLR_STORE_LANES(colour, out);
    return;
  }
  uint result[CLR_LANES];
  CLR_STORE_LANES(colour, result);
  for (uint lane = 0; lane < count; ++lane) out[lane] = result[lane];
}

/* The lanes' unit normal (back faces flip it); a zero normal becomes the one facing the eye in window space. */
CLR_INLINE void resolve_unit_normal(floatL n[3], floatL sign)
{
  const floatL len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const intL degenerate = CLR_NOT(len > 0.0f);
  const floatL inv = sign / select(len, (floatL)1.0f, degenerate);
  n[0] = select(n[0] * inv, (floatL)0.0f, degenerate);
  n[1] = select(n[1] * inv, (floatL)0.0f, degenerate);
  n[2] = select(n[2] * inv, sign, degenerate);
}

/* Everything a sample's shading reads: the buffers behind the gathers. */
typedef struct ShadeInputs {
  __global const Material* materials;
  __global const TextureDesc* texDescs;
  __global const uint* texels;
} ShadeInputs;

/* Shades the lanes of one sample plane from its gathered fragments. */
CLR_CALLED ColourL resolve_shade(__constant FrameParams* params, __global const ClipBary* clipBary,
                                 const ResolveLanes* g, const ShadeInputs* in, floatL b1, floatL b2)
{
  const uint mode = params->shadeMode;
  // Step 1: the 1/w rule or affine; then q_i holds q_i·w, q_i = 1/w_i (1 when affine), so λ_i = b_i·q_i.
  const floatL b[3] = {1.0f - b1 - b2, b1, b2};
  floatL q[3], lambda[3], eyeDepth;
  for (int i = 0; i < 3; ++i) q[i] = 1.0f / g->clipW[i];  // setup_make's 1/w (record_clip_w)
  if (params->interpMode == CLR_INTERP_AFFINE) {
    eyeDepth = b[0] / q[0] + b[1] / q[1] + b[2] / q[2];  // w interpolated in screen space
    for (int i = 0; i < 3; ++i) {
      lambda[i] = b[i];
      q[i] = 1.0f;
    }
  } else {
    eyeDepth = 1.0f / (b[0] * q[0] + b[1] * q[1] + b[2] * q[2]);  // w, interpolated as 1/w is
    for (int i = 0; i < 3; ++i) {
      q[i] = q[i] * eyeDepth;
      lambda[i] = b[i] * q[i];
    }
  }
  if (mode == CLR_SHADE_DEPTH) {
    const floatL grey = 1.0f - (eyeDepth - params->zNear) / (params->zFar - params->zNear);
    return colour_make(grey, grey, grey);
  }
  // Step 2: input vertex weights (and setup vertices' uv for the derivatives), and an attribute's value.
  floatL mu[3], uvAt[3][2];
  intL backL;
  resolve_vertex_weights(clipBary, g->source, g->covered, lambda, mu, &backL, g->needGradients, g->uv, uvAt);
#define CLR_INTERPOLATE(out, array, components)                     \
  for (int k = 0; k < (components); ++k) {                          \
    (out)[k] = 0.0f;                                                \
    for (int j = 0; j < 3; ++j) (out)[k] += mu[j] * g->array[j][k]; \
  }
  // Step 3: uv and, for trilinear, their derivatives (file contract; affine: Σ_i ∂b_i/∂x · a_i).
  floatL uv[2] = {0.0f, 0.0f}, duvdx[2] = {0.0f, 0.0f}, duvdy[2] = {0.0f, 0.0f};
  if (g->needUvs) {
    CLR_INTERPOLATE(uv, uv, 2)
    if (g->needGradients)
      for (int i = 0; i < 3; ++i) {
        const floatL gx = g->grad[i][0] * q[i], gy = g->grad[i][1] * q[i];
        for (int k = 0; k < 2; ++k) {
          duvdx[k] += gx * (uvAt[i][k] - uv[k]);
          duvdy[k] += gy * (uvAt[i][k] - uv[k]);
        }
      }
  }
  if (mode == CLR_SHADE_UV) return colour_make(uv[0] - floor(uv[0]), uv[1] - floor(uv[1]), (floatL)0.0f);
  if (mode == CLR_SHADE_CHECKER) {
    const intL odd = (convert_intL(floor(uv[0] * 8.0f)) + convert_intL(floor(uv[1] * 8.0f))) & 1;
    const floatL grey = select((floatL)0.9f, (floatL)0.25f, odd != 0);
    return colour_make(grey, grey, grey);
  }
  // Step 4: the vertex colour, the albedo.
  floatL colour[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  if (g->needColours) CLR_INTERPOLATE(colour, colour, 4)
  if (mode == CLR_SHADE_COLOR) return colour_make(colour[0], colour[1], colour[2]);
  floatL albedo[3] = {0.0f, 0.0f, 0.0f};
  if (mode != CLR_SHADE_NORMAL) {
    shade_albedo(params, in->materials, in->texDescs, in->texels, g->material, uv, duvdx, duvdy, albedo);
    for (int k = 0; k < 3; ++k) albedo[k] *= colour[k];
  }
  if (mode == CLR_SHADE_TEXTURE) return colour_make(albedo[0], albedo[1], albedo[2]);
  // Step 5: the normal and the point: interpolated, or the face's for flat; back faces flip the normal.
  const floatL sign = select((floatL)1.0f, (floatL)-1.0f, backL);
  floatL n[3], p[3] = {0.0f, 0.0f, 0.0f}, diffuse, specular;
  if (mode == CLR_SHADE_FLAT) {
    floatL v[3][3];
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) v[j][k] = g->pos[j][k];
    const floatL e1[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
    const floatL e2[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    for (int k = 0; k < 3; ++k) p[k] = (v[0][k] + v[1][k] + v[2][k]) * (1.0f / 3.0f);  // lit at the centroid
  } else {
    CLR_INTERPOLATE(n, normal, 3)
    if (g->needPositions) CLR_INTERPOLATE(p, pos, 3)
  }
  resolve_unit_normal(n, sign);
  if (mode == CLR_SHADE_NORMAL) return colour_make(n[0] * 0.5f + 0.5f, n[1] * 0.5f + 0.5f, n[2] * 0.5f + 0.5f);
  // Step 6: the lights: per vertex and interpolated (Gouraud), or here.
  if (mode == CLR_SHADE_GOURAUD) {
    diffuse = 0.0f;
    specular = 0.0f;
    for (int j = 0; j < 3; ++j) {
      floatL nj[3], pj[3], d, s;
      for (int k = 0; k < 3; ++k) {
        nj[k] = g->normal[j][k];
        pj[k] = g->pos[j][k];
      }
      resolve_unit_normal(nj, sign);
      shade_lights(params, nj, pj, true, &d, &s);
      diffuse += mu[j] * d;
      specular += mu[j] * s;
    }
  } else {
    shade_lights(params, n, p, mode != CLR_SHADE_LAMBERT, &diffuse, &specular);
  }
  const floatL light = CLR_AMBIENT + CLR_DIFFUSE * diffuse, highlight = CLR_SPECULAR * specular;
  return colour_make(albedo[0] * light + highlight, albedo[1] * light + highlight, albedo[2] * light + highlight);
#undef CLR_INTERPOLATE
}

/* A setup record's input triangle by its index in the file (fileTri). */
CLR_INLINE uint resolve_file_triangle(__constant FrameParams* params, __global const uint* fileTri, uint source,
                                      __global const ClipBary* clipBary)
{
  const uint tri = clr_source_triangle(source, clipBary);
  return params->fileOrder ? tri : fileTri[tri];
}

/* The id mode: the input triangle that holds most samples of each pixel,
 * by its index in the file (fileTri). */
CLR_INLINE uintL resolve_id(__constant FrameParams* params, __global const uint* visIndex, uint visPlane, uint p,
                            uint count, __global const uint* source, __global const ClipBary* clipBary,
                            __global const uint* fileTri)
{
  // Step 1: the most frequent setup index per lane (CLR_NONE counts too).
  const uint plane = visPlane, samples = params->samples;
  uint winner[CLR_LANES];
  vis_load_index_lanes(params, visIndex, p, count, winner);
  if (samples > 1) {
    uint lanes[CLR_MAX_SAMPLES][CLR_LANES];
    for (uint k = 0; k < samples; ++k) vis_load_index_lanes(params, visIndex, k * plane + p, count, lanes[k]);
    for (uint lane = 0; lane < count; ++lane) {
      uint best = 0;
      for (uint k = 0; k < samples; ++k) {
        uint votes = 0;
        for (uint j = 0; j < samples; ++j) votes += lanes[j][lane] == lanes[k][lane];
        if (votes > best) {
          best = votes;
          winner[lane] = lanes[k][lane];
        }
      }
    }
  }
  // Step 2: its input triangle, + 1 as 24-bit RGB (0 = background).
  uint rgb[CLR_LANES];
  for (uint lane = 0; lane < CLR_LANES; ++lane)
    rgb[lane] = winner[lane] == CLR_NONE
                    ? 0u
                    : ((resolve_file_triangle(params, fileTri, source[winner[lane]], clipBary) + 1u) & 0xFFFFFFu);
  return CLR_LOAD_LANES(rgb) | 0xFF000000u;
}

/* The resolve kernels' parameters: the buffers of shared.h, prefetchRows (resolve_prefetch) and fileTri. */
#define CLR_RESOLVE_PARAMS                                                                                        \
  __constant FrameParams *params, __global const uint *visIndex, __global const float *visAttr,                   \
      __global const uint *tileOffset, __global const TriSetup *setup, __global const uint *source,               \
      __global const ClipBary *clipBary, __global const uint *indices, __global const float *positions,           \
      __global const float *normals, __global const float *uvs, __global const float *colours,                    \
      __global const uint *triMaterial, __global const Material *materials, __global const TextureDesc *texDescs, \
      __global const uint *texels, __global uint *image, __global const uint *tileSlot, uint visPlane,            \
      uint prefetchRows, __global const uint *fileTri, __global uint *tileBlank
#define CLR_RESOLVE_ARGS                                                                                     \
  params, visIndex, visAttr, tileOffset, setup, source, clipBary, indices, positions, normals, uvs, colours, \
      triMaterial, materials, texDescs, texels, image, tileSlot, visPlane, prefetchRows, fileTri, tileBlank

#ifdef CLR_PREFETCH
/* Prefetch for tiles of many small triangles (> 128 binned), whose scattered records miss the caches. The host asks
 * for it (prefetchRows) when a frame gathers > 2 MB and it pays in the first frames (PrefetchChooser, resolve.cpp):
 * that depends on the mesh's memory order, not only its size. While row p is gathered it fetches, once per run,
 * the records and sources three rows ahead, indices two ahead, normals one ahead. Smaller tiles stay cached, where
 * prefetching costs more than it saves (bench/ab.sh). Called, not inlined, so the common path compiles unchanged. */
CLR_CALLED void resolve_prefetch(__constant FrameParams* params, __global const uint* visIndex, uint p, uint rowInTile,
                                 __global const TriSetup* setup, __global const uint* source,
                                 __global const ClipBary* clipBary, __global const uint* indices,
                                 __global const float* positions, __global const float* normals)
{
  uint previous = CLR_NONE;
  for (uint lane = 0; lane < CLR_LANES && rowInTile + 3 < CLR_TILE_SIZE; ++lane) {
    const uint next = vis_index_at(params, visIndex, p + 3 * CLR_TILE_SIZE + lane);
    if (next != CLR_NONE && next != previous) {
      __builtin_prefetch(&setup[next]);
      __builtin_prefetch(&source[next]);
    }
    previous = next;
  }
  previous = CLR_NONE;
  for (uint lane = 0; lane < CLR_LANES && rowInTile + 2 < CLR_TILE_SIZE; ++lane) {
    const uint next = vis_index_at(params, visIndex, p + 2 * CLR_TILE_SIZE + lane);
    if (next != CLR_NONE && next != previous)
      __builtin_prefetch(&indices[3 * clr_source_triangle(source[next], clipBary)]);
    previous = next;
  }
  previous = CLR_NONE;
  // Positions (for 1/w) always; the normals buffer is a placeholder in modes that do not read it.
  const bool normalsBound = CLR_NEEDS_NORMALS(params->shadeMode);
  for (uint lane = 0; lane < CLR_LANES && rowInTile + 1 < CLR_TILE_SIZE; ++lane) {
    const uint next = vis_index_at(params, visIndex, p + CLR_TILE_SIZE + lane);
    if (next != CLR_NONE && next != previous) {
      const uint tri = clr_source_triangle(source[next], clipBary);
      for (int v = 0; v < 3; ++v) {
        const uint vertex = indices[3 * tri + v];
        __builtin_prefetch(&positions[CLR_POSITION_STRIDE * vertex]);
        if (normalsBound) __builtin_prefetch(&normals[3 * vertex]);
      }
    }
    previous = next;
  }
}
#endif

/* resolve_prefetch for row p (image row py) of `tile` when prefetchRows asks and the tile holds > 128 entries;
 * nothing without CLR_PREFETCH. Both resolve kernels call it. */
CLR_INLINE void resolve_prefetch_rows(__constant FrameParams* params, uint prefetchRows,
                                      __global const uint* tileOffset, uint tile, __global const uint* visIndex, uint p,
                                      uint py, __global const TriSetup* setup, __global const uint* source,
                                      __global const ClipBary* clipBary, __global const uint* indices,
                                      __global const float* positions, __global const float* normals)
{
#ifdef CLR_PREFETCH
  if (prefetchRows && tileOffset[tile + 1] - tileOffset[tile] > 128)
    resolve_prefetch(params, visIndex, p, py % CLR_TILE_SIZE, setup, source, clipBary, indices, positions, normals);
#endif
}

/* The resolve kernels (resolve; resolve_lambert in resolve_lambert.cl) in the host's work shape (resolve.cpp). CPU
 * (a row as wide as a tile): a work-item resolves a whole tile in a group of one, so PoCL keeps one set of the
 * row's private arrays, not 16 (which overflow L1); the loop is a CLR_KERNEL_BODY. GPU: a work-item per row. */
#if CLR_LANES == CLR_TILE_SIZE
/* Fills tile (tileX, tileY) with the background if it has no bin entries, and says whether it did: one test and
 * 16 row stores, without the row functions' set-up. A tile already background (tileBlank, set here and cleared for
 * a tile with entries; the host zeroes all when size, background or lines change the image) is left as it is. */
CLR_INLINE bool resolve_empty_tile(__constant FrameParams* params, __global const uint* tileOffset,
                                   __global uint* tileBlank, __global uint* image, uint tileX, uint tileY)
{
  const uint tile = tileY * params->tilesX + tileX;
  if (tileOffset[tile] != tileOffset[tile + 1]) {
    tileBlank[tile] = 0;
    return false;
  }
  if (tileBlank[tile]) return true;
  const uint firstX = tileX * CLR_TILE_SIZE, count = min((uint)CLR_LANES, params->width - firstX);
  const uintL background = (uintL)CLR_BACKGROUND(params->shadeMode);
  const uint rows = min((uint)CLR_TILE_SIZE, params->height - tileY * CLR_TILE_SIZE);
  for (uint row = 0; row < rows; ++row)
    store_row(background, count, clr_image_pixel(params, image, firstX, tileY * CLR_TILE_SIZE + row));
  tileBlank[tile] = 1;
  return true;
}

#define CLR_RESOLVE_KERNEL(name, resolveRow)                                                \
  CLR_KERNEL_BODY void name##_body(CLR_RESOLVE_PARAMS, uint tileX, uint tileY)              \
  {                                                                                         \
    if (resolve_empty_tile(params, tileOffset, tileBlank, image, tileX, tileY)) return;     \
    for (uint row = 0; row < CLR_TILE_SIZE; ++row)                                          \
      resolveRow(CLR_RESOLVE_ARGS, (tileX * CLR_TILE_SIZE), (tileY * CLR_TILE_SIZE + row)); \
  }                                                                                         \
  __kernel __attribute__((reqd_work_group_size(1, 1, 1))) void name(CLR_RESOLVE_PARAMS)     \
  {                                                                                         \
    name##_body(CLR_RESOLVE_ARGS, get_global_id(0), get_global_id(1));                      \
  }
#else
#define CLR_RESOLVE_KERNEL(name, resolveRow)                                                             \
  __kernel __attribute__((reqd_work_group_size(CLR_TILE_SIZE / CLR_LANES, CLR_TILE_SIZE, 1))) void name( \
      CLR_RESOLVE_PARAMS)                                                                                \
  {                                                                                                      \
    resolveRow(CLR_RESOLVE_ARGS, get_global_id(0) * CLR_LANES, get_global_id(1));                        \
  }
#endif

#endif /* CLR_RESOLVE_H */
