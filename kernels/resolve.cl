/* resolve.cl — stage 6: attribute resolve and shading.
 *
 * One work-item per CLR_LANES pixels of a row (lanes.h), shaded together in
 * lane types after the per-pixel gathers. Pixels of a tile that binning
 * left empty are background, without a visibility read. Per covered pixel
 * it reads the visibility sample, turns its
 * screen-space barycentrics b_i into perspective-correct ones with the 1/w
 * rule of the notes, λ_i = (b_i / w_i) / Σ_j (b_j / w_j), maps them to the
 * input triangle's vertices (through ClipBary when the triangle was clipped,
 * through the vertex swap when it was back-facing), interpolates the vertex
 * normal and shades into RGBA8 (R in the low byte), top row first.
 *   lambert: grey albedo, ambient + diffuse from FrameParams.lightDir,
 *            two-sided (back faces use the flipped normal)
 *   normal:  the interpolated world normal mapped from [−1, 1] to [0, 255]
 *   depth:   1 − (eye depth − near) / (far − near), eye depth = 1 / Σ b_i/w_i
 *   id:      input triangle index + 1 as 24-bit RGB, background black
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
} ResolveLanes;

CLR_INLINE void resolve_gather(__global const uint* visIndex, uint count, __global const TriSetup* setup,
                               __global const ClipBary* clipBary, __global const uint* indices,
                               __global const float* normals, bool needNormals, ResolveLanes* g)
{
  // Step 0: a row inside one triangle (common for large triangles) needs one
  // gather; its barycentrics still differ per lane.
  g->uniform = count == CLR_LANES;
  for (uint lane = 1; lane < count && g->uniform; ++lane) g->uniform = visIndex[lane] == visIndex[0];
  if (g->uniform)
    for (uint lane = 0; lane < CLR_LANES; ++lane) g->setupIndex[lane] = visIndex[lane];
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    // With every lane on one triangle, lane 0's gathers serve all (see uniform).
    if (g->uniform && lane > 0) break;
    // Step 1: the visible triangle (lanes past the viewport read as empty).
    const uint index = lane < count ? visIndex[lane] : CLR_NONE;
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
    // Step 3: the input vertices' normals.
    for (int j = 0; j < 3; ++j) {
      const float3 n = covered && needNormals ? vload3(indices[3 * t.triId + j], normals) : (float3)(0.0f);
      g->normal[j][0][lane] = n.x;
      g->normal[j][1][lane] = n.y;
      g->normal[j][2][lane] = n.z;
    }
  }
}

__kernel __attribute__((reqd_work_group_size(CLR_TILE_SIZE / CLR_LANES, CLR_TILE_SIZE, 1))) void resolve(
    __constant FrameParams* params,
    __global const uint* visIndex,    // width · height, unwritten in empty tiles
    __global const float* visAttr,    // 3 planes of width · height: depth, b1, b2
    __global const uint* tileOffset,  // tiles + 1
    __global const TriSetup* setup, __global const ClipBary* clipBary,
    __global const uint* indices,   // 3·numTris
    __global const float* normals,  // 3·numVerts
    __global uint* image)           // width · height
{
  const uint firstX = get_global_id(0) * CLR_LANES, py = get_global_id(1);
  if (py >= params->height || firstX >= params->width) return;
  const uint count = min((uint)CLR_LANES, params->width - firstX);
  __global uint* out = &image[(params->height - 1 - py) * params->width + firstX];
  const uint background = params->shadeMode == CLR_SHADE_LAMBERT ? 0xFF261F1Au : 0xFF000000u;
  // Step 1: a tile without triangles is background; raster left it unwritten.
  const uint tile = (py / CLR_TILE_SIZE) * params->tilesX + firstX / CLR_TILE_SIZE;
  if (tileOffset[tile] == tileOffset[tile + 1]) {
    for (uint lane = 0; lane < count; ++lane) out[lane] = background;
    return;
  }
  // Step 2: gather, then load the lanes.
  ResolveLanes g;
  const uint mode = params->shadeMode;
  const uint plane = params->width * params->height, p = py * params->width + firstX;
  resolve_gather(&visIndex[p], count, setup, clipBary, indices, normals,
                 mode == CLR_SHADE_LAMBERT || mode == CLR_SHADE_NORMAL, &g);
  const intL covered = CLR_LOAD_LANES(g.setupIndex) != CLR_NONE;
  // A per-triangle value for every lane: broadcast when the row is uniform.
#define CLR_PER_LANE(array, type) (g.uniform ? (type)((array)[0]) : CLR_LOAD_LANES(array))
  uintL colour;
  if (mode == CLR_SHADE_ID) {
    colour = ((CLR_PER_LANE(g.triId, uintL) + 1u) & 0xFFFFFFu) | 0xFF000000u;
  } else {
    // Step 3: perspective-correct barycentrics (1/w rule) of the setup vertices.
    // A row cut by the viewport's edge reads its lanes one by one, zero past the edge.
    float cutB1[CLR_LANES], cutB2[CLR_LANES];
    for (uint lane = 0; count < CLR_LANES && lane < CLR_LANES; ++lane) {
      cutB1[lane] = lane < count ? visAttr[plane + p + lane] : 0.0f;
      cutB2[lane] = lane < count ? visAttr[2 * plane + p + lane] : 0.0f;
    }
    const floatL b1 = count == CLR_LANES ? CLR_LOAD_LANES(&visAttr[plane + p]) : CLR_LOAD_LANES(cutB1);
    const floatL b2 = count == CLR_LANES ? CLR_LOAD_LANES(&visAttr[2 * plane + p]) : CLR_LOAD_LANES(cutB2);
    const floatL b0 = 1.0f - b1 - b2;
    const floatL q0 = b0 * CLR_PER_LANE(g.invW[0], floatL), q1 = b1 * CLR_PER_LANE(g.invW[1], floatL),
                 q2 = b2 * CLR_PER_LANE(g.invW[2], floatL);
    const floatL invWSum = q0 + q1 + q2;
    const floatL eyeDepth = 1.0f / invWSum;  // w, interpolated as 1/w is
    const floatL lambda[3] = {q0 * eyeDepth, q1 * eyeDepth, q2 * eyeDepth};
    if (mode == CLR_SHADE_DEPTH) {
      const floatL grey = 1.0f - (eyeDepth - params->zNear) / (params->zFar - params->zNear);
      colour = pack_rgba(grey, grey, grey);
    } else {
      // Step 4: weights of the input vertices, and the interpolated normal.
      floatL n[3] = {0.0f, 0.0f, 0.0f};
      for (int j = 0; j < 3; ++j) {
        floatL mu = 0.0f;
        for (int i = 0; i < 3; ++i) mu += lambda[i] * CLR_PER_LANE(g.weight[i][j], floatL);
        for (int k = 0; k < 3; ++k) n[k] += mu * CLR_PER_LANE(g.normal[j][k], floatL);
      }
      const floatL len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const intL degenerate = CLR_NOT(len > 0.0f);
      // Two-sided: back faces use the flipped normal.
      const floatL sign = select((floatL)1.0f, (floatL)-1.0f, CLR_PER_LANE(g.backfacing, uintL) != 0u);
      const floatL inv = sign / select(len, (floatL)1.0f, degenerate);
      const floatL nx = select(n[0] * inv, (floatL)0.0f, degenerate);
      const floatL ny = select(n[1] * inv, (floatL)0.0f, degenerate);
      const floatL nz = select(n[2] * inv, sign, degenerate);
      if (mode == CLR_SHADE_NORMAL) {
        colour = pack_rgba(nx * 0.5f + 0.5f, ny * 0.5f + 0.5f, nz * 0.5f + 0.5f);
      } else {
        // Step 5: Lambert.
        const floatL diffuse =
            max(nx * params->lightDir[0] + ny * params->lightDir[1] + nz * params->lightDir[2], (floatL)0.0f);
        const floatL light = 0.12f + 0.88f * diffuse;
        colour = pack_rgba(0.80f * light, 0.78f * light, 0.74f * light);
      }
    }
  }
#undef CLR_PER_LANE
  // Step 6: write, background where nothing was covered.
  colour = select((uintL)background, colour, covered);
  if (count == CLR_LANES) {
    CLR_STORE_LANES(colour, out);
    return;
  }
  uint result[CLR_LANES];
  CLR_STORE_LANES(colour, result);
  for (uint lane = 0; lane < count; ++lane) out[lane] = result[lane];
}
