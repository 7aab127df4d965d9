/* resolve_lambert.cl — stage 6's lean kernel for the default frame (lambert, one sample, perspective-correct, no
 * point light, textures or vertex colours; host resolve.cpp picks it): the general kernel's pixels bit for bit
 * (tested). Lane values are built in vector types: rows of few triangles run by run, rows of many lane by lane.
 * Row store, prefetch, background and kernel shape come from resolve.h, which both resolve kernels include.
 */
#pragma OPENCL FP_CONTRACT OFF
#if !CLR_EXTRAS /* the frame program (CLR_EXTRAS, shared.h) */
#include "resolve.h"

/* What resolve_lambert reads of the lanes' fragments. */
typedef struct LambertLanes {
  uintL source;         // the source words (shared.h)
  floatL clipW[3];      // w_clip at the setup vertices (record_clip_w)
  floatL normal[3][3];  // [input vertex][component]
  floatL albedo[3];
  intL x[3], y[3];  // the setup vertices, read only when the barycentrics are recomputed
  floatL scale;     // clr_inv_area2, likewise
} LambertLanes;

/* Reads what lambert needs of setup record s (record, source, indices, material, normals, base colour) into the
 * lanes of `in`; into every lane without a select when `in` is the first run's constant all-lanes mask. */
CLR_HOT void resolve_lambert_take(__constant FrameParams* params, __global const TriSetup* setup,
                                  __global const uint* source, __global const ClipBary* clipBary,
                                  __global const uint* indices, __global const float* positions,
                                  __global const float* normals, __global const uint* triMaterial,
                                  __global const Material* materials, uint s, intL in, bool vertices, LambertLanes* f)
{
#define CLR_TAKE(lanes, value) (lanes) = select((lanes), (value), in)
  __global const TriSetup* t = &setup[s];
  const uint from = source[s], triId = clr_source_triangle(from, clipBary);
  const uint vertex[3] = {indices[3 * triId], indices[3 * triId + 1], indices[3 * triId + 2]};
  float w[3];
  record_clip_w(params, positions, clipBary, from, vertex, w);
  CLR_TAKE(f->source, (uintL)from);
  for (int i = 0; i < 3; ++i) CLR_TAKE(f->clipW[i], (floatL)w[i]);
  if (vertices) {
    for (int i = 0; i < 3; ++i) {
      CLR_TAKE(f->x[i], (intL)t->x[i]);
      CLR_TAKE(f->y[i], (intL)t->y[i]);
    }
    CLR_TAKE(f->scale, (floatL)CLR_RECORD_INV_AREA2(*t));
  }
  const bool materialsOn = (params->sceneFlags & CLR_SCENE_MATERIALS) != 0;
  const Material m = materials[params->sceneFlags & CLR_SCENE_TRI_MATERIALS ? triMaterial[triId] : 0];
  const float grey[3] = {CLR_GREY_R, CLR_GREY_G, CLR_GREY_B};
  for (int j = 0; j < 3; ++j) {
    const float3 n = vload3(vertex[j], normals);
    CLR_TAKE(f->normal[j][0], (floatL)n.x);
    CLR_TAKE(f->normal[j][1], (floatL)n.y);
    CLR_TAKE(f->normal[j][2], (floatL)n.z);
    CLR_TAKE(f->albedo[j], (floatL)(materialsOn ? m.baseColor[j] : grey[j]));
  }
#undef CLR_TAKE
}

/* resolve_lambert_take for every lane, for rows of many runs: staged branch-free gathers with independent loads
 * (their cache misses overlap): records, then indices and materials, then normals and base colours. Uncovered
 * lanes read record 0. With `vertices` it recomputes the barycentrics from the gathered vertices. The base colour
 * is three statements: a loop over the greys compiles to an inner loop per lane. */
CLR_HOT void resolve_lambert_gather(__constant FrameParams* params, __global const TriSetup* setup,
                                    __global const uint* source, __global const ClipBary* clipBary,
                                    __global const uint* indices, __global const float* positions,
                                    __global const float* normals, __global const uint* triMaterial,
                                    __global const Material* materials, const uint* index, uintL indexLanes,
                                    uint firstX, uint py, bool vertices, LambertLanes* f, floatL* b1, floatL* b2)
{
  uint triId[CLR_LANES], from[CLR_LANES], vertex[3][CLR_LANES], material[CLR_LANES];
  float normal[3][3][CLR_LANES], albedo[3][CLR_LANES];
  int vx[3][CLR_LANES], vy[3][CLR_LANES];
  CLR_NO_UNROLL
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    __global const TriSetup* t = resolve_lane_record(setup, source, clipBary, index, lane, from, triId);
    if (vertices)
      for (int i = 0; i < 3; ++i) {
        vx[i][lane] = t->x[i];
        vy[i][lane] = t->y[i];
      }
  }
  const bool materialsOn = (params->sceneFlags & CLR_SCENE_MATERIALS) != 0;
  const bool perTriangle = (params->sceneFlags & CLR_SCENE_TRI_MATERIALS) != 0;
  CLR_NO_UNROLL
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    for (int j = 0; j < 3; ++j) vertex[j][lane] = indices[3 * triId[lane] + j];
    material[lane] = perTriangle ? triMaterial[triId[lane]] : 0;
  }
  CLR_NO_UNROLL
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    for (int j = 0; j < 3; ++j) {
      const float3 n = vload3(vertex[j][lane], normals);
      normal[j][0][lane] = n.x;
      normal[j][1][lane] = n.y;
      normal[j][2][lane] = n.z;
    }
    const Material m = materials[material[lane]];
    albedo[0][lane] = materialsOn ? m.baseColor[0] : CLR_GREY_R;
    albedo[1][lane] = materialsOn ? m.baseColor[1] : CLR_GREY_G;
    albedo[2][lane] = materialsOn ? m.baseColor[2] : CLR_GREY_B;
  }
  resolve_clip_w_lanes(params, positions, clipBary, from, vertex, f->clipW);
  if (vertices) {
    // All lanes at once (clr_inv_area2L), not run by run with a division and seven selects per run.
    const intL x0 = CLR_LOAD_LANES(vx[0]), x1 = CLR_LOAD_LANES(vx[1]), x2 = CLR_LOAD_LANES(vx[2]);
    const intL y0 = CLR_LOAD_LANES(vy[0]), y1 = CLR_LOAD_LANES(vy[1]), y2 = CLR_LOAD_LANES(vy[2]);
    vis_barycentrics(x0, y0, x1, y1, x2, y2, clr_inv_area2L(x0, y0, x1, y1, x2, y2), indexLanes != CLR_NONE,
                     resolve_sample_x(params, firstX, 0), resolve_sample_y(params, py, 0), b1, b2);
  }
  f->source = CLR_LOAD_LANES(from);
  for (int i = 0; i < 3; ++i) {
    f->albedo[i] = CLR_LOAD_LANES(albedo[i]);
    for (int k = 0; k < 3; ++k) f->normal[i][k] = CLR_LOAD_LANES(normal[i][k]);
  }
}

/* Step 2 of resolve_lambert_row: resolve_shade's lambert path in lane types, same operations in the same order.
 * Returns the packed colours, the background where not `covered`. */
CLR_HOT uintL resolve_lambert_colour(__constant FrameParams* params, __global const ClipBary* clipBary,
                                     const LambertLanes* f, floatL b1, floatL b2, intL covered, uint background)
{
  // Step 1: the 1/w rule,
  const floatL q[3] = {1.0f / f->clipW[0], 1.0f / f->clipW[1], 1.0f / f->clipW[2]};  // setup_make's 1/w
  const floatL b[3] = {1.0f - b1 - b2, b1, b2};
  floatL lambda[3];
  const floatL eyeDepth = 1.0f / (b[0] * q[0] + b[1] * q[1] + b[2] * q[2]);
  for (int i = 0; i < 3; ++i) lambda[i] = b[i] * (q[i] * eyeDepth);
  // Step 2: the weights mu_j of the input vertices (resolve_vertex_weights,
  // resolve.cl, as in the general kernel), and which lanes are back faces.
  floatL mu[3], noUvs[3][2];
  intL backL;
  resolve_vertex_weights(clipBary, f->source, covered, lambda, mu, &backL, false, noUvs, noUvs);
  floatL n[3];
  for (int k = 0; k < 3; ++k) {
    n[k] = 0.0f;
    for (int j = 0; j < 3; ++j) n[k] += mu[j] * f->normal[j][k];
  }
  resolve_unit_normal(n, select((floatL)1.0f, (floatL)-1.0f, backL));
  floatL diffuse, specular;
  const floatL p0[3] = {0.0f, 0.0f, 0.0f};
  shade_lights(params, n, p0, false, &diffuse, &specular);
  const floatL light = CLR_AMBIENT + CLR_DIFFUSE * diffuse, highlight = CLR_SPECULAR * specular;
  const ColourL lit =
      colour_make(f->albedo[0] * light + highlight, f->albedo[1] * light + highlight, f->albedo[2] * light + highlight);
  const ColourL c = colour_select(colour_unpack(background), lit, covered);
  return pack_rgba(c.r, c.g, c.b);
}

/* The lean common case (see the file contract; Pipeline::resolve launches it): gathers only what lambert reads,
 * computing as resolve_shade does, so pixels are bit-identical (tested). A separate kernel because the general
 * one's gathers and branches cost frame and compile time (bench/ab.sh). */
CLR_HOT void resolve_lambert_row(CLR_RESOLVE_PARAMS, uint firstX, uint py)
{
  if (py >= params->height || firstX >= params->width) return;
  const uint count = min((uint)CLR_LANES, params->width - firstX);
  __global uint* out = clr_image_pixel(params, image, firstX, py);
  const uint background = CLR_BACKGROUND(CLR_SHADE_LAMBERT);
  const uint tile = (py / CLR_TILE_SIZE) * params->tilesX + firstX / CLR_TILE_SIZE;
  if (tileOffset[tile] == tileOffset[tile + 1]) {
    store_row((uintL)background, count, out);
    return;
  }
  const uint plane = visPlane, p = vis_address(tileSlot[tile], firstX, py);
  uint index[CLR_LANES];
  const uintL indexLanes = vis_load_index_lanes(params, visIndex, p, count, index);
  resolve_prefetch_rows(params, prefetchRows, tileOffset, tile, visIndex, p, py, setup, source, clipBary, indices,
                        positions, normals);
  const intL covered = indexLanes != CLR_NONE;
  uintL colour = (uintL)background;
  if (CLR_ANY(covered)) {
    // Step 1: the row's triangle values and screen barycentrics. Up to CLR_RESOLVE_MAX_RUNS runs (a run starts at
    // each bit of `starts`): run by run (resolve_lambert_take), the first into every lane, later ones selected. More
    // runs (tiny triangles): staged lane gathers (resolve_lambert_gather), overlapping more cache misses.
    // Uncovered lanes hold some triangle's values until the background replaces them.
    floatL b1, b2;
    // Without the barycentric planes, the records' vertices recompute them.
    const bool vertices = !resolve_read_barycentrics(params, visAttr, plane, p, count, 0, &b1, &b2);
    if (!CLR_ANY(indexLanes != index[0])) {  // a vector compare, not a branch per lane
      // A uniform row has its own copy of the steps: its LambertLanes stays in registers, the runs' goes to memory.
      LambertLanes one;
      resolve_lambert_take(params, setup, source, clipBary, indices, positions, normals, triMaterial, materials,
                           index[0], (intL)(-1), vertices, &one);
      if (vertices)
        vis_barycentrics(one.x[0], one.y[0], one.x[1], one.y[1], one.x[2], one.y[2], one.scale, covered,
                         resolve_sample_x(params, firstX, 0), resolve_sample_y(params, py, 0), &b1, &b2);
      store_row(resolve_lambert_colour(params, clipBary, &one, b1, b2, covered, background), count, out);
      return;
    }
    uint starts = 0;  // bit lane: a covered run starts there
    for (uint lane = 0; lane < CLR_LANES; ++lane)
      starts |= (index[lane] != CLR_NONE && (lane == 0 || index[lane] != index[lane - 1]) ? 1u : 0u) << lane;
    LambertLanes f;
    if (popcount(starts) > CLR_RESOLVE_MAX_RUNS) {
      resolve_lambert_gather(params, setup, source, clipBary, indices, positions, normals, triMaterial, materials,
                             index, indexLanes, firstX, py, vertices, &f, &b1, &b2);
    } else {
      uint lane = 31 - clz(starts & (0u - starts));  // the lowest set bit
      resolve_lambert_take(params, setup, source, clipBary, indices, positions, normals, triMaterial, materials,
                           index[lane], (intL)(-1), vertices, &f);
      CLR_NO_UNROLL
      for (starts &= starts - 1; starts; starts &= starts - 1) {
        lane = 31 - clz(starts & (0u - starts));
        resolve_lambert_take(params, setup, source, clipBary, indices, positions, normals, triMaterial, materials,
                             index[lane], indexLanes == index[lane], vertices, &f);
      }
      if (vertices)
        vis_barycentrics(f.x[0], f.y[0], f.x[1], f.y[1], f.x[2], f.y[2], f.scale, covered,
                         resolve_sample_x(params, firstX, 0), resolve_sample_y(params, py, 0), &b1, &b2);
    }
    colour = resolve_lambert_colour(params, clipBary, &f, b1, b2, covered, background);
  }
  // Step 3: store the row.
  store_row(colour, count, out);
}

CLR_RESOLVE_KERNEL(resolve_lambert, resolve_lambert_row)
#endif
