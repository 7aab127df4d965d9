/* shade.h — lighting and base colour for resolve, in lane types (included by resolve.h).
 *
 * Blinn-Phong: a directional light (lightDir, intensity 1) and an optional point light at pointLight.xyz with
 * attenuation 1 / (1 + (d / pointLight.w)²). With unit normal n and view v = (eye − p) / |eye − p|, each light
 * (direction l, attenuation a) adds D += a·max(n·l, 0) and, where n·l > 0, S += a·max(n·h, 0)^CLR_SHININESS with
 * h = (l + v) / |l + v|. Lit colour = albedo·(CLR_AMBIENT + CLR_DIFFUSE·D) + CLR_SPECULAR·S (lambert: S = 0);
 * albedo = material factor × texture × vertex colour, or CLR_GREY_* without materials.
 */
#ifndef CLR_SHADE_H
#define CLR_SHADE_H
#include "texture.h"
#pragma OPENCL FP_CONTRACT OFF
#if !CLR_EXTRAS /* the frame program (CLR_EXTRAS, shared.h) */

#define CLR_AMBIENT 0.12f
#define CLR_DIFFUSE 0.88f
#define CLR_SPECULAR 0.4f
#define CLR_SHININESS 32 /* = 2^5: computed by squaring */
#define CLR_GREY_R 0.80f
#define CLR_GREY_G 0.78f
#define CLR_GREY_B 0.74f

/* One light's contribution, added to *diffuse and *specular. */
CLR_INLINE void shade_one_light(const floatL n[3], const floatL v[3], floatL lx, floatL ly, floatL lz, floatL atten,
                                bool specular, floatL* diffuse, floatL* spec)
{
  const floatL ndotl = n[0] * lx + n[1] * ly + n[2] * lz;
  *diffuse += atten * max(ndotl, (floatL)0.0f);
  if (!specular) return;
  // Step 1: the half vector (a zero sum, light opposite the eye, gives none).
  const floatL hx = lx + v[0], hy = ly + v[1], hz = lz + v[2];
  const floatL hlen = sqrt(hx * hx + hy * hy + hz * hz);
  const floatL ndoth = (n[0] * hx + n[1] * hy + n[2] * hz) / max(hlen, (floatL)1e-30f);
  // x^32 by five squarings (exact enough, and vector pow is wrong under Oclgrind).
  floatL s = max(ndoth, (floatL)0.0f);
  for (int k = 0; k < 5; ++k) s = s * s;
  const intL lit = (ndotl > 0.0f) & (hlen > 0.0f);
  *spec += select((floatL)0.0f, atten * s, lit);
}

/* Diffuse and specular sums at point p with unit normal n (see above). */
CLR_INLINE void shade_lights(__constant FrameParams* params, const floatL n[3], const floatL p[3], bool specular,
                             floatL* diffuse, floatL* spec)
{
  *diffuse = 0.0f;
  *spec = 0.0f;
  // Step 1: the unit view vector (only Blinn-Phong reads it).
  floatL v[3] = {0.0f, 0.0f, 0.0f};
  if (specular) {
    for (int k = 0; k < 3; ++k) v[k] = (floatL)params->eye[k] - p[k];
    const floatL len = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const floatL inv = 1.0f / max(len, (floatL)1e-30f);
    for (int k = 0; k < 3; ++k) v[k] *= inv;
  }
  // Step 2: the directional light.
  shade_one_light(n, v, (floatL)params->lightDir[0], (floatL)params->lightDir[1], (floatL)params->lightDir[2],
                  (floatL)1.0f, specular, diffuse, spec);
  // Step 3: the point light, attenuated.
  if (params->pointLightOn) {
    const floatL lx = params->pointLight[0] - p[0], ly = params->pointLight[1] - p[1],
                 lz = params->pointLight[2] - p[2];
    const floatL d2 = lx * lx + ly * ly + lz * lz, d = sqrt(d2);
    const floatL inv = 1.0f / max(d, (floatL)1e-30f);
    const float r = params->pointLight[3];
    const floatL atten = 1.0f / (1.0f + d2 / (r * r));
    shade_one_light(n, v, lx * inv, ly * inv, lz * inv, atten, specular, diffuse, spec);
  }
}

/* Each lane's material factor × texture at uv (with its screen derivatives); the caller multiplies vertex colour. */
CLR_INLINE void shade_albedo(__constant FrameParams* params, __global const Material* materials,
                             __global const TextureDesc* texDescs, __global const uint* texels, uintL materialL,
                             const floatL uv[2], const floatL duvdx[2], const floatL duvdy[2], floatL albedo[3])
{
  albedo[0] = CLR_GREY_R;
  albedo[1] = CLR_GREY_G;
  albedo[2] = CLR_GREY_B;
  if (!(params->sceneFlags & CLR_SCENE_MATERIALS)) return;
  const bool textured = (params->sceneFlags & CLR_SCENE_TEXTURES) != 0;
  uint material[CLR_LANES];
  CLR_STORE_LANES(materialL, material);
  // Step 0: one material for the whole row: sample in lane types (tex_sample_lanes: the loop's floats).
  if (!CLR_ANY(materialL != material[0])) {
    const Material m = materials[material[0]];
    albedo[0] = m.baseColor[0];
    albedo[1] = m.baseColor[1];
    albedo[2] = m.baseColor[2];
    if (textured && m.texture >= 0) {
      floatL t[3];
      tex_sample_lanes(&texDescs[m.texture], texels, params->texFilter, uv[0], uv[1], duvdx[0], duvdx[1], duvdy[0],
                       duvdy[1], t);
      for (int k = 0; k < 3; ++k) albedo[k] = m.baseColor[k] * t[k];
    }
    return;
  }
  // Step 1: the lanes' coordinates as scalars.
  float u[CLR_LANES], v[CLR_LANES], ux[CLR_LANES], vx[CLR_LANES], uy[CLR_LANES], vy[CLR_LANES];
  if (textured) {
    CLR_STORE_LANES(uv[0], u);
    CLR_STORE_LANES(uv[1], v);
    CLR_STORE_LANES(duvdx[0], ux);
    CLR_STORE_LANES(duvdx[1], vx);
    CLR_STORE_LANES(duvdy[0], uy);
    CLR_STORE_LANES(duvdy[1], vy);
  }
  // Step 2: per lane, factor × texture.
  float rgb[3][CLR_LANES];
  for (uint lane = 0; lane < CLR_LANES; ++lane) {
    const Material m = materials[material[lane]];
    float4 c = (float4)(m.baseColor[0], m.baseColor[1], m.baseColor[2], m.baseColor[3]);
    if (textured && m.texture >= 0)
      c *= tex_sample(&texDescs[m.texture], texels, params->texFilter, u[lane], v[lane], ux[lane], vx[lane], uy[lane],
                      vy[lane]);
    rgb[0][lane] = c.x;
    rgb[1][lane] = c.y;
    rgb[2][lane] = c.z;
  }
  for (int k = 0; k < 3; ++k) albedo[k] = CLR_LOAD_LANES(rgb[k]);
}
#endif

#endif /* CLR_SHADE_H */
