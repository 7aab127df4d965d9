/* resolve.cl — stage 6: attribute resolve, shading and the sample filter, in rows of CLR_LANES pixels (lanes.h).
 *
 * A work-item resolves a tile row by row (CPU) or one row (GPU); empty tiles are background, unread. Per covered
 * sample: the screen barycentrics b_i (recomputed as raster did, or read from the planes), the 1/w rule
 * λ_i = (b_i / w_i) / Σ_j (b_j / w_j) (λ_i = b_i with CLR_INTERP_AFFINE), mapped to the input vertices (ClipBary,
 * or the back-face swap), then only the attributes the mode reads are interpolated and shaded (shade.h,
 * texture.h). Modes: lambert (two-sided, per pixel), flat (face normal, lit at the centroid), gouraud (lit per
 * vertex, interpolated), phong (per pixel), texture (unlit albedo), color, normal ([−1, 1] to [0, 1]), depth
 * (1 − (eye − near) / (far − near)), uv, checker (1/8 squares), id (index + 1 as 24-bit RGB).
 * Trilinear derivatives are analytic: with q_i = 1/w_i, w = 1 / Σ b_j q_j and ∂b_i/∂x = (y_{i+1} − y_{i+2}) /
 * (2·area), ∂a/∂x = w · Σ_i (∂b_i/∂x) · q_i · (a_i − a), likewise for y.
 * Samples > 1: clamped colours averaged (box filter), rounded to RGBA8. MSAA shades a triangle once per pixel, at
 * its first covered sample; SSAA every sample. The id mode is not filtered: the majority triangle, ties to the
 * lower sample index.
 */
#pragma OPENCL FP_CONTRACT OFF
#if !CLR_EXTRAS /* the frame program (CLR_EXTRAS, shared.h) */
#include "resolve.h"

/* The row of CLR_LANES pixels from (firstX, py). No one-sample specialisation: Oclgrind's 16-lane interpretation
 * mis-computes it. */
CLR_INLINE void resolve_row(CLR_RESOLVE_PARAMS, uint firstX, uint py)
{
  if (py >= params->height || firstX >= params->width) return;
  const uint count = min((uint)CLR_LANES, params->width - firstX);
  __global uint* out = clr_image_pixel(params, image, firstX, py);
  const uint mode = params->shadeMode;
  const uint background = CLR_BACKGROUND(mode);
  // Step 1: a tile without triangles is background; raster left it unwritten.
  const uint tile = (py / CLR_TILE_SIZE) * params->tilesX + firstX / CLR_TILE_SIZE;
  if (tileOffset[tile] == tileOffset[tile + 1]) {
    store_row((uintL)background, count, out);
    return;
  }
  // The row's entries in the tile's block of each sample plane (shared.h).
  const uint plane = visPlane, p = vis_address(tileSlot[tile], firstX, py);
  const uint samples = params->samples;
  resolve_prefetch_rows(params, prefetchRows, tileOffset, tile, visIndex, p, py, setup, source, clipBary, indices,
                        positions, normals);
  uintL colour;
  const ColourL backgroundColour = colour_unpack(background);
  const ShadeInputs inputs = {materials, texDescs, texels};
  if (mode == CLR_SHADE_ID) {
    colour = resolve_id(params, visIndex, visPlane, p, count, source, clipBary, fileTri);
  } else if (samples == 1) {
    // Step 2a: one sample per pixel, shaded where covered.
    uint index[CLR_LANES];
    const uintL indexLanes = vis_load_index_lanes(params, visIndex, p, count, index);
    const intL covered = indexLanes != CLR_NONE;
    ColourL c = backgroundColour;
    if (CLR_ANY(covered)) {
      ResolveLanes g;
      resolve_gather(params, index, indexLanes, setup, source, clipBary, indices, positions, normals, uvs, colours,
                     triMaterial, &g);
      floatL b1, b2;
      resolve_barycentrics(params, visAttr, plane, p, count, 0, setup, index, indexLanes, firstX, py, &b1, &b2);
      c = colour_select(backgroundColour, resolve_shade(params, clipBary, &g, &inputs, b1, b2), covered);
    }
    colour = pack_rgba(c.r, c.g, c.b);
  } else {
    // Step 2b: each sample plane's colour; MSAA reuses a triangle's colour from its first covered sample.
    uintL sampleIndex[CLR_MAX_SAMPLES];
    ColourL sampleColour[CLR_MAX_SAMPLES];
    ColourL sum = {0.0f, 0.0f, 0.0f};
    for (uint k = 0; k < samples; ++k) {
      uint index[CLR_LANES];
      sampleIndex[k] = vis_load_index_lanes(params, visIndex, k * plane + p, count, index);
      const intL covered = sampleIndex[k] != CLR_NONE;
      ColourL c = backgroundColour;
      intL done = CLR_NOT(covered);
      for (uint j = 0; j < k && !params->shadeEverySample; ++j) {
        const intL reuse = CLR_NOT(done) & (sampleIndex[j] == sampleIndex[k]);
        c = colour_select(c, sampleColour[j], reuse);
        done = done | reuse;
      }
      if (!CLR_ANY(CLR_NOT(done))) {
        sampleColour[k] = c;
      } else {
        ResolveLanes g;
        resolve_gather(params, index, sampleIndex[k], setup, source, clipBary, indices, positions, normals, uvs,
                       colours, triMaterial, &g);
        floatL b1, b2;
        resolve_barycentrics(params, visAttr, plane, p, count, k, setup, index, sampleIndex[k], firstX, py, &b1, &b2);
        sampleColour[k] = colour_select(resolve_shade(params, clipBary, &g, &inputs, b1, b2), c, done);
      }
      sum.r += sampleColour[k].r;
      sum.g += sampleColour[k].g;
      sum.b += sampleColour[k].b;
    }
    // Step 3: the box filter, rounded to RGBA8.
    const float weight = 1.0f / (float)samples;
    colour = pack_rgba(sum.r * weight, sum.g * weight, sum.b * weight);
  }
  // Step 4: write.
  store_row(colour, count, out);
}

CLR_RESOLVE_KERNEL(resolve, resolve_row)
#endif
