/* resolve.cl — stage 6: attribute resolve, shading and the sample filter.
 *
 * One work-item per CLR_LANES pixels of a row (lanes.h), shaded together in
 * lane types after the per-pixel gathers. Pixels of a tile that binning
 * left empty are background, without a visibility read. Per covered sample
 * it reads the visibility sample, turns its screen-space barycentrics b_i
 * into perspective-correct ones with the 1/w rule of the notes,
 * λ_i = (b_i / w_i) / Σ_j (b_j / w_j) (or keeps λ_i = b_i with
 * CLR_INTERP_AFFINE, the weaker method), maps them to the input triangle's
 * vertices (through ClipBary when the triangle was clipped, through the
 * vertex swap when it was back-facing), interpolates what the shading reads
 * and shades:
 *   lambert: grey albedo, ambient + diffuse from FrameParams.lightDir,
 *            two-sided (back faces use the flipped normal)
 *   normal:  the interpolated world normal mapped from [−1, 1] to [0, 1]
 *   depth:   1 − (eye depth − near) / (far − near), eye depth = 1 / Σ b_i/w_i
 *   uv:      (u, v) as red and green, wrapped to [0, 1)
 *   checker: white and grey squares of 1/8 in u and v
 *   id:      input triangle index + 1 as 24-bit RGB, background black
 * Anti-aliasing (FrameParams.samples > 1): every sample's colour, clamped to
 * [0, 1], is averaged with equal weights (the box filter of the notes) and
 * rounded to RGBA8 (R in the low byte), top row first. With MSAA
 * (shadeEverySample = 0) a pixel shades each covering triangle once, at the
 * first of its samples that the triangle covers, and the triangle's other
 * samples reuse that colour; SSAA shades every sample. The id mode is not
 * filtered: a pixel shows the triangle (or background) that holds most of
 * its samples, ties to the lower sample index, so the encoding stays exact.
 */
#pragma OPENCL FP_CONTRACT OFF

/* RGBA8 (R in the low byte, alpha 255) from colour channels in [0, 1]. */
CLR_INLINE uintL pack_rgba(floatL r, floatL g, floatL b)
{
  const floatL lo = 0.0f, hi = 1.0f;
  const uintL qr = convert_uintL_sat_rte(clamp(r, lo, hi) * 255.0f);
  const uintL qg = convert_uintL_sat_rte(clamp(g, lo, hi) * 255.0f);
  const uintL qb = convert_uintL_sat_rte(clamp(b, lo, hi) * 255.0f);
  return qr | (qg << 8) | (qb << 16) | 0xFF000000u;
}

/* What resolve needs of the CLR_LANES pixels' fragments, gathered per lane:
 * screen barycentrics, the triangle's 1/w, the weights of the input
 * triangle's vertices in each setup vertex (identity, swapped or ClipBary)
 * and the input vertex normals. */
typedef struct ResolveLanes {
  bool uniform;  // all lanes show one triangle: only lane 0 of the per-triangle arrays is filled
  uint setupIndex[CLR_LANES], triId[CLR_LANES], backfacing[CLR_LANES];
  float invW[3][CLR_LANES];
  float weight[3][3][CLR_LANES];  // [setup vertex][input vertex][lane]
  float normal[3][3][CLR_LANES];  // [input vertex][component][lane]
  float uv[3][2][CLR_LANES];      // [input vertex][component][lane]
} ResolveLanes;

/* What the shading mode reads of the input vertices. */
#define CLR_NEEDS_NORMALS(mode) ((mode) == CLR_SHADE_LAMBERT || (mode) == CLR_SHADE_NORMAL)
#define CLR_NEEDS_UVS(mode) ((mode) == CLR_SHADE_UV || (mode) == CLR_SHADE_CHECKER)

/* visIndex: the lanes' setup indices, CLR_NONE past the viewport's edge. */
CLR_INLINE void resolve_gather(const uint* visIndex, __global const TriSetup* setup, __global const ClipBary* clipBary,
                               __global const uint* indices, __global const float* normals, __global const float* uvs,
                               uint mode, ResolveLanes* g)
{
  // Step 0: a row inside one triangle (common for large triangles) needs one
  // gather; its barycentrics still differ per lane.
  g->uniform = true;
  for (uint lane = 1; lane < CLR_LANES && g->uniform; ++lane) g->uniform = visIndex[lane] == visIndex[0];
  if (g->uniform)
    for (uint lane = 0; lane < CLR_LANES; ++lane) g->setupIndex[lane] = visIndex[lane];
  const bool needNormals = CLR_NEEDS_NORMALS(mode), needUvs = CLR_NEEDS_UVS(mode);
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    // With every lane on one triangle, lane 0's gathers serve all (see uniform).
    if (g->uniform && lane > 0) break;
    // Step 1: the visible triangle.
    const uint index = visIndex[lane];
    g->setupIndex[lane] = index;
    // Neighbouring pixels mostly show the same triangle: reuse its gathers.
    if (lane > 0 && index == g->setupIndex[lane - 1]) {
      g->triId[lane] = g->triId[lane - 1];
      g->backfacing[lane] = g->backfacing[lane - 1];
      for (int i = 0; i < 3; ++i) {
        g->invW[i][lane] = g->invW[i][lane - 1];
        for (int j = 0; j < 3; ++j) {
          g->weight[i][j][lane] = g->weight[i][j][lane - 1];
          g->normal[i][j][lane] = g->normal[i][j][lane - 1];
        }
        for (int j = 0; j < 2; ++j) g->uv[i][j][lane] = g->uv[i][j][lane - 1];
      }
      continue;
    }
    const bool covered = index != CLR_NONE;
    const TriSetup t = setup[covered ? index : 0];
    g->triId[lane] = t.triId;
    g->backfacing[lane] = (t.flags & CLR_FLAG_BACKFACING) != 0;
    for (int i = 0; i < 3; ++i) g->invW[i][lane] = covered ? t.invW[i] : 1.0f;
    // Step 2: input-vertex weights of each setup vertex.
    const bool clipped = covered && t.clipSlot != CLR_NOT_CLIPPED;
    const bool swapped = !clipped && (t.flags & CLR_FLAG_BACKFACING);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int identity = swapped && i != 0 ? 3 - i : i;  // setup vertices 1, 2 are input 2, 1
        g->weight[i][j][lane] = clipped ? clipBary[t.clipSlot].w[i][j] : (float)(identity == j);
      }
    // Step 3: the input vertices' normals and texture coordinates.
    for (int j = 0; j < 3; ++j) {
      const uint v = covered ? indices[3 * t.triId + j] : 0;
      const float3 n = covered && needNormals ? vload3(v, normals) : (float3)(0.0f);
      const float2 uv = covered && needUvs ? vload2(v, uvs) : (float2)(0.0f);
      g->normal[j][0][lane] = n.x;
      g->normal[j][1][lane] = n.y;
      g->normal[j][2][lane] = n.z;
      g->uv[j][0][lane] = uv.x;
      g->uv[j][1][lane] = uv.y;
    }
  }
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

CLR_INLINE ColourL colour_select(ColourL a, ColourL b, intL mask)
{
  ColourL c = {select(a.r, b.r, mask), select(a.g, b.g, mask), select(a.b, b.b, mask)};
  return c;
}

/* Loads lanes of a plane row, past the viewport's edge as fill. */
CLR_INLINE void load_index_lanes(__global const uint* row, uint count, uint* lanes)
{
  if (count == CLR_LANES) {
    CLR_STORE_LANES(CLR_LOAD_LANES(row), lanes);
    return;
  }
  for (uint lane = 0; lane < CLR_LANES; ++lane) lanes[lane] = lane < count ? row[lane] : CLR_NONE;
}
CLR_INLINE floatL load_float_lanes(__global const float* row, uint count)
{
  if (count == CLR_LANES) return CLR_LOAD_LANES(row);
  float lanes[CLR_LANES];
  for (uint lane = 0; lane < CLR_LANES; ++lane) lanes[lane] = lane < count ? row[lane] : 0.0f;
  return CLR_LOAD_LANES(lanes);
}

/* Shades the lanes of one sample plane from its gathered fragments. */
CLR_INLINE ColourL resolve_shade(__constant FrameParams* params, const ResolveLanes* g, floatL b1, floatL b2)
{
  // A per-triangle value for every lane: broadcast when the row is uniform.
#define CLR_PER_LANE(array, type) (g->uniform ? (type)((array)[0]) : CLR_LOAD_LANES(array))
  const uint mode = params->shadeMode;
  // Step 1: barycentrics of the setup vertices: the 1/w rule, or affine.
  const floatL b0 = 1.0f - b1 - b2;
  const floatL invW0 = CLR_PER_LANE(g->invW[0], floatL), invW1 = CLR_PER_LANE(g->invW[1], floatL),
               invW2 = CLR_PER_LANE(g->invW[2], floatL);
  floatL lambda[3], eyeDepth;
  if (params->interpMode == CLR_INTERP_AFFINE) {
    lambda[0] = b0;
    lambda[1] = b1;
    lambda[2] = b2;
    eyeDepth = b0 / invW0 + b1 / invW1 + b2 / invW2;  // w interpolated in screen space
  } else {
    const floatL q0 = b0 * invW0, q1 = b1 * invW1, q2 = b2 * invW2;
    eyeDepth = 1.0f / (q0 + q1 + q2);  // w, interpolated as 1/w is
    lambda[0] = q0 * eyeDepth;
    lambda[1] = q1 * eyeDepth;
    lambda[2] = q2 * eyeDepth;
  }
  if (mode == CLR_SHADE_DEPTH) {
    const floatL grey = 1.0f - (eyeDepth - params->zNear) / (params->zFar - params->zNear);
    return colour_make(grey, grey, grey);
  }
  // Step 2: weights of the input vertices.
  floatL mu[3];
  for (int j = 0; j < 3; ++j) {
    mu[j] = 0.0f;
    for (int i = 0; i < 3; ++i) mu[j] += lambda[i] * CLR_PER_LANE(g->weight[i][j], floatL);
  }
  if (CLR_NEEDS_UVS(mode)) {
    floatL uv[2] = {0.0f, 0.0f};
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 2; ++k) uv[k] += mu[j] * CLR_PER_LANE(g->uv[j][k], floatL);
    if (mode == CLR_SHADE_UV) return colour_make(uv[0] - floor(uv[0]), uv[1] - floor(uv[1]), (floatL)0.0f);
    const intL odd = (convert_intL(floor(uv[0] * 8.0f)) + convert_intL(floor(uv[1] * 8.0f))) & 1;
    const floatL grey = select((floatL)0.9f, (floatL)0.25f, odd != 0);
    return colour_make(grey, grey, grey);
  }
  // Step 3: the interpolated normal.
  floatL n[3] = {0.0f, 0.0f, 0.0f};
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) n[k] += mu[j] * CLR_PER_LANE(g->normal[j][k], floatL);
  const floatL len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const intL degenerate = CLR_NOT(len > 0.0f);
  // Two-sided: back faces use the flipped normal.
  const floatL sign = select((floatL)1.0f, (floatL)-1.0f, CLR_PER_LANE(g->backfacing, uintL) != 0u);
  const floatL inv = sign / select(len, (floatL)1.0f, degenerate);
  const floatL nx = select(n[0] * inv, (floatL)0.0f, degenerate);
  const floatL ny = select(n[1] * inv, (floatL)0.0f, degenerate);
  const floatL nz = select(n[2] * inv, sign, degenerate);
  if (mode == CLR_SHADE_NORMAL) return colour_make(nx * 0.5f + 0.5f, ny * 0.5f + 0.5f, nz * 0.5f + 0.5f);
  // Step 4: Lambert.
  const floatL diffuse =
      max(nx * params->lightDir[0] + ny * params->lightDir[1] + nz * params->lightDir[2], (floatL)0.0f);
  const floatL light = 0.12f + 0.88f * diffuse;
  return colour_make(0.80f * light, 0.78f * light, 0.74f * light);
#undef CLR_PER_LANE
}

/* The id mode: the input triangle that holds most samples of each pixel. */
CLR_INLINE uintL resolve_id(__constant FrameParams* params, __global const uint* visIndex, uint p, uint count,
                            __global const TriSetup* setup)
{
  // Step 1: the most frequent setup index per lane (CLR_NONE counts too).
  const uint plane = params->width * params->height, samples = params->samples;
  uint winner[CLR_LANES];
  load_index_lanes(&visIndex[p], count, winner);
  if (samples > 1) {
    uint lanes[CLR_MAX_SAMPLES][CLR_LANES];
    for (uint k = 0; k < samples; ++k) load_index_lanes(&visIndex[k * plane + p], count, lanes[k]);
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
    rgb[lane] = winner[lane] == CLR_NONE ? 0u : ((setup[winner[lane]].triId + 1u) & 0xFFFFFFu);
  return CLR_LOAD_LANES(rgb) | 0xFF000000u;
}

__kernel __attribute__((reqd_work_group_size(CLR_TILE_SIZE / CLR_LANES, CLR_TILE_SIZE, 1))) void resolve(
    __constant FrameParams* params,
    __global const uint* visIndex,    // samples · width · height, unwritten in empty tiles
    __global const float* visAttr,    // 3 · samples planes of width · height: depth, b1, b2
    __global const uint* tileOffset,  // tiles + 1
    __global const TriSetup* setup, __global const ClipBary* clipBary,
    __global const uint* indices,   // 3·numTris
    __global const float* normals,  // 3·numVerts
    __global const float* uvs,      // 2·numVerts
    __global uint* image)           // width · height
{
  const uint firstX = get_global_id(0) * CLR_LANES, py = get_global_id(1);
  if (py >= params->height || firstX >= params->width) return;
  const uint count = min((uint)CLR_LANES, params->width - firstX);
  __global uint* out = &image[(params->height - 1 - py) * params->width + firstX];
  const uint mode = params->shadeMode;
  const uint background = mode == CLR_SHADE_LAMBERT ? 0xFF261F1Au : 0xFF000000u;
  // Step 1: a tile without triangles is background; raster left it unwritten.
  const uint tile = (py / CLR_TILE_SIZE) * params->tilesX + firstX / CLR_TILE_SIZE;
  if (tileOffset[tile] == tileOffset[tile + 1]) {
    for (uint lane = 0; lane < count; ++lane) out[lane] = background;
    return;
  }
  const uint plane = params->width * params->height, p = py * params->width + firstX;
  const uint samples = params->samples;
  uintL colour;
  if (mode == CLR_SHADE_ID) {
    colour = resolve_id(params, visIndex, p, count, setup);
  } else {
    // Step 2: each sample plane's colour; MSAA reuses a triangle's colour
    // from the first sample of the pixel that it covers.
    const ColourL backgroundColour = {(floatL)((background & 0xFFu) / 255.0f),
                                      (floatL)(((background >> 8) & 0xFFu) / 255.0f),
                                      (floatL)(((background >> 16) & 0xFFu) / 255.0f)};
    uintL sampleIndex[CLR_MAX_SAMPLES];
    ColourL sampleColour[CLR_MAX_SAMPLES];
    ColourL sum = {0.0f, 0.0f, 0.0f};
    for (uint k = 0; k < samples; ++k) {
      uint index[CLR_LANES];
      load_index_lanes(&visIndex[k * plane + p], count, index);
      sampleIndex[k] = CLR_LOAD_LANES(index);
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
        resolve_gather(index, setup, clipBary, indices, normals, uvs, mode, &g);
        const floatL b1 = load_float_lanes(&visAttr[(3 * k + 1) * plane + p], count);
        const floatL b2 = load_float_lanes(&visAttr[(3 * k + 2) * plane + p], count);
        sampleColour[k] = colour_select(resolve_shade(params, &g, b1, b2), c, done);
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
  if (count == CLR_LANES) {
    CLR_STORE_LANES(colour, out);
    return;
  }
  uint result[CLR_LANES];
  CLR_STORE_LANES(colour, result);
  for (uint lane = 0; lane < count; ++lane) out[lane] = result[lane];
}
