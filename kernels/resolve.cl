/* resolve.cl — stage 6: attribute resolve and shading.
 *
 * One work-item per CLR_LANES pixels of a row (lanes.h). Pixels of a tile
 * that binning left empty are background, without a visibility read. Per
 * covered pixel it reads the visibility sample, turns its
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

CLR_INLINE uint pack_rgba(float3 c)
{
  const uint3 q = convert_uint3_sat_rte(clamp(c, 0.0f, 1.0f) * 255.0f);
  return q.x | (q.y << 8) | (q.z << 16) | 0xFF000000u;
}

/* Shades one visibility sample into RGBA8. */
CLR_INLINE uint resolve_pixel(__constant FrameParams* params, VisSample v, __global const TriSetup* setup,
                              __global const ClipBary* clipBary, __global const uint* indices,
                              __global const float* normals)
{
  if (v.setupIndex == CLR_NONE) return params->shadeMode == CLR_SHADE_LAMBERT ? 0xFF261F1Au : 0xFF000000u;
  const TriSetup t = setup[v.setupIndex];
  if (params->shadeMode == CLR_SHADE_ID) return ((t.triId + 1) & 0xFFFFFFu) | 0xFF000000u;
  // Step 1: perspective-correct barycentrics (1/w rule).
  const float b0 = 1.0f - v.b1 - v.b2;
  const float q0 = b0 * t.invW[0], q1 = v.b1 * t.invW[1], q2 = v.b2 * t.invW[2];
  const float invWSum = q0 + q1 + q2;
  float3 lambda = (float3)(q0, q1, q2) / invWSum;
  // Step 2: map to the input triangle's vertex order.
  if (t.clipSlot != CLR_NOT_CLIPPED) {
    const ClipBary cb = clipBary[t.clipSlot];
    float3 mu = (float3)(0.0f);
    for (int i = 0; i < 3; ++i) {
      const float li = i == 0 ? lambda.x : (i == 1 ? lambda.y : lambda.z);
      mu += li * (float3)(cb.w[i][0], cb.w[i][1], cb.w[i][2]);
    }
    lambda = mu;
  } else if (t.flags & CLR_FLAG_BACKFACING) {
    lambda = lambda.xzy;
  }
  if (params->shadeMode == CLR_SHADE_DEPTH) {
    const float eyeDepth = 1.0f / invWSum;
    const float g = 1.0f - (eyeDepth - params->zNear) / (params->zFar - params->zNear);
    return pack_rgba((float3)(g));
  }
  // Step 3: interpolate and shade the normal.
  const uint i0 = indices[3 * t.triId], i1 = indices[3 * t.triId + 1], i2 = indices[3 * t.triId + 2];
  float3 n = lambda.x * vload3(i0, normals) + lambda.y * vload3(i1, normals) + lambda.z * vload3(i2, normals);
  const float len = length(n);
  n = len > 0.0f ? n / len : (float3)(0.0f, 0.0f, 1.0f);
  if (t.flags & CLR_FLAG_BACKFACING) n = -n;
  if (params->shadeMode == CLR_SHADE_NORMAL) return pack_rgba(n * 0.5f + 0.5f);
  const float3 light = (float3)(params->lightDir[0], params->lightDir[1], params->lightDir[2]);
  const float diffuse = max(dot(n, light), 0.0f);
  const float3 albedo = (float3)(0.80f, 0.78f, 0.74f);
  return pack_rgba(albedo * (0.12f + 0.88f * diffuse));
}

__kernel __attribute__((reqd_work_group_size(CLR_TILE_SIZE / CLR_LANES, CLR_TILE_SIZE, 1))) void resolve(
    __constant FrameParams* params,
    __global const VisSample* vis,    // width · height, unwritten in empty tiles
    __global const uint* tileOffset,  // tiles + 1
    __global const TriSetup* setup, __global const ClipBary* clipBary,
    __global const uint* indices,   // 3·numTris
    __global const float* normals,  // 3·numVerts
    __global uint* image)           // width · height
{
  const uint firstX = get_global_id(0) * CLR_LANES, py = get_global_id(1);
  if (py >= params->height || firstX >= params->width) return;
  const uint count = min((uint)CLR_LANES, params->width - firstX);
  __global const VisSample* in = &vis[py * params->width + firstX];
  __global uint* out = &image[(params->height - 1 - py) * params->width + firstX];
  // Step 1: a tile without triangles is background; raster left it unwritten.
  const uint tile = (py / CLR_TILE_SIZE) * params->tilesX + firstX / CLR_TILE_SIZE;
  if (tileOffset[tile] == tileOffset[tile + 1]) {
    VisSample none;
    none.setupIndex = CLR_NONE;
    const uint background = resolve_pixel(params, none, setup, clipBary, indices, normals);
    for (uint lane = 0; lane < count; ++lane) out[lane] = background;
    return;
  }
  // Step 2: shade each pixel.
  for (uint lane = 0; lane < count; ++lane)
    out[lane] = resolve_pixel(params, in[lane], setup, clipBary, indices, normals);
}
