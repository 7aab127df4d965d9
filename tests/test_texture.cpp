// test_texture.cpp — base-colour textures: nearest, bilinear and trilinear
// sampling (kernels/texture.h) against the formulas on crafted textures,
// wrap modes, mip chains (host/io/texture.cpp), a glTF with an embedded texture
// and the warnings for missing and corrupt image files.
#include "cli_support.h"
#include "test_support.h"
#include "io/texture.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace {

// A screen-filling quad (identity MVP, w = 1) whose (u, v) run linearly from
// (u0, v0) at the bottom-left corner to (u1, v1) at the top-right one.
clr::Mesh quad(const clr::Texture& texture, float u0, float v0, float u1, float v1, glm::vec4 factor = glm::vec4(1))
{
  clr::Mesh m;
  m.positions = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  m.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  m.uvs = {u0, v0, u1, v0, u1, v1, u0, v1};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.triMaterial = {0, 0};
  Material mat{};
  for (int k = 0; k < 4; ++k) mat.baseColor[k] = factor[k];
  mat.texture = 0;
  m.materials = {mat};
  m.textures = {texture};
  return m;
}

std::vector<uint32_t> renderTexture(const clr::Mesh& mesh, uint32_t width, uint32_t height, uint32_t filter)
{
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(mesh);
  clr::FrameSettings s = test::idSettings(width, height);
  s.shadeMode = CLR_SHADE_TEXTURE;
  s.texFilter = filter;
  std::vector<uint32_t> rgba;
  pipeline.render(s, rgba);
  return rgba;
}

// The pixel (x, y), y up, of an image read back top row first.
uint32_t at(const std::vector<uint32_t>& rgba, uint32_t width, uint32_t height, uint32_t x, uint32_t y)
{
  return rgba[size_t(height - 1 - y) * width + x];
}

int channel(uint32_t texel, int k)
{
  return int((texel >> (8 * k)) & 0xFFu);
}

// The host's wrap of texture.h.
int wrap(int i, int n, uint32_t mode)
{
  if (mode == CLR_WRAP_CLAMP) return std::clamp(i, 0, n - 1);
  if (mode == CLR_WRAP_MIRROR) {
    const int m = ((i % (2 * n)) + 2 * n) % (2 * n);
    return m < n ? m : 2 * n - 1 - m;
  }
  return ((i % n) + n) % n;
}

// A texture of distinct texels: R = 16·x + 1, G = 16·y + 2, B = 7.
clr::Texture distinct(uint32_t w, uint32_t h, uint32_t wrapS = CLR_WRAP_REPEAT, uint32_t wrapT = CLR_WRAP_REPEAT)
{
  clr::Texture t;
  t.name = "distinct";
  t.width = w;
  t.height = h;
  t.wrapS = wrapS;
  t.wrapT = wrapT;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) t.rgba.push_back((16 * x + 1) | (16 * y + 2) << 8 | 7u << 16 | 0xFF000000u);
  return t;
}

// Bilinear sample of level data (w × h) at texel-space point (fx, fy) + 0.5.
glm::dvec3 bilinear(const std::vector<uint32_t>& texels, uint32_t w, uint32_t h, double u, double v, uint32_t wrapS,
                    uint32_t wrapT)
{
  const double fx = u * w - 0.5, fy = v * h - 0.5;
  const double x0 = std::floor(fx), y0 = std::floor(fy), ax = fx - x0, ay = fy - y0;
  auto texel = [&](double x, double y) {
    const uint32_t t = texels[size_t(wrap(int(y), int(h), wrapT)) * w + wrap(int(x), int(w), wrapS)];
    return glm::dvec3(channel(t, 0), channel(t, 1), channel(t, 2));
  };
  return (texel(x0, y0) * (1 - ax) + texel(x0 + 1, y0) * ax) * (1 - ay) +
         (texel(x0, y0 + 1) * (1 - ax) + texel(x0 + 1, y0 + 1) * ax) * ay;
}

double worstDifference(uint32_t got, glm::dvec3 want)
{
  double worst = 0;
  for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(channel(got, k) - want[k]));
  return worst;
}

}  // namespace

TEST_CASE("nearest sampling returns the exact texel under each pixel centre", "[texture]")
{
  // 4×4 texels over 16×16 pixels: texel (i / 4, j / 4) under pixel (i, j).
  const clr::Texture t = distinct(4, 4);
  const std::vector<uint32_t> rgba = renderTexture(quad(t, 0, 0, 1, 1), 16, 16, CLR_FILTER_NEAREST);
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      INFO("pixel " << x << ", " << y);
      CHECK(at(rgba, 16, 16, x, y) == t.rgba[(y / 4) * 4 + x / 4]);
    }
}

TEST_CASE("wrap modes: repeat, clamp and mirror per axis", "[texture]")
{
  // u and v run from −1 to 2 over 24 pixels: texel-space x = −4 + (i + 0.5)/2,
  // never on a texel boundary, so nearest sampling is exact.
  const uint32_t wrapS = GENERATE(CLR_WRAP_REPEAT, CLR_WRAP_CLAMP, CLR_WRAP_MIRROR);
  const uint32_t wrapT = GENERATE(CLR_WRAP_REPEAT, CLR_WRAP_CLAMP, CLR_WRAP_MIRROR);
  const clr::Texture t = distinct(4, 4, wrapS, wrapT);
  const std::vector<uint32_t> rgba = renderTexture(quad(t, -1, -1, 2, 2), 24, 24, CLR_FILTER_NEAREST);
  for (uint32_t y = 0; y < 24; ++y)
    for (uint32_t x = 0; x < 24; ++x) {
      const int tx = int(std::floor(-4.0 + (x + 0.5) / 2.0)), ty = int(std::floor(-4.0 + (y + 0.5) / 2.0));
      INFO("wrap " << wrapS << "/" << wrapT << ", pixel " << x << ", " << y);
      CHECK(at(rgba, 24, 24, x, y) == t.rgba[size_t(wrap(ty, 4, wrapT)) * 4 + wrap(tx, 4, wrapS)]);
    }
}

TEST_CASE("bilinear sampling weights the four texels around the point", "[texture]")
{
  const uint32_t wrapMode = GENERATE(CLR_WRAP_REPEAT, CLR_WRAP_CLAMP, CLR_WRAP_MIRROR);
  // 8×8 texels over 16×16 pixels: texel-space x = (i + 0.5)/2, weights 0.25, 0.75.
  const clr::Texture t = distinct(8, 8, wrapMode, wrapMode);
  const std::vector<uint32_t> rgba = renderTexture(quad(t, 0, 0, 1, 1), 16, 16, CLR_FILTER_BILINEAR);
  double worst = 0;
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x)
      worst = std::max(worst, worstDifference(at(rgba, 16, 16, x, y), bilinear(t.rgba, 8, 8, (x + 0.5) / 16,
                                                                               (y + 0.5) / 16, wrapMode, wrapMode)));
  // Tolerance: 0.5 level of rounding; the weights are exact in float.
  CHECK(worst <= 0.5 + 1e-3);
  // A known position: pixel (5, 5) lies at texel-space (2.75, 2.75), 0.25
  // past texel 2's centre towards texel 3: R = 16·(0.75·2 + 0.25·3) + 1 = 37, G = 38.
  CHECK(channel(at(rgba, 16, 16, 5, 5), 0) == 37);
  CHECK(channel(at(rgba, 16, 16, 5, 5), 1) == 38);
}

TEST_CASE("mip chains: 2x2 box filter down to 1x1, odd sides repeat their edge", "[texture]")
{
  clr::Texture t = distinct(5, 3);
  const clr::TexturePack pack = clr::packTextures({t, distinct(1, 1)});
  REQUIRE(pack.descs.size() == 2);
  const TextureDesc& d = pack.descs[0];
  CHECK(d.levels == 3);  // 5×3, 2×1, 1×1
  CHECK(d.levelOffset[0] == 0);
  CHECK(d.levelOffset[1] == 15);
  CHECK(d.levelOffset[2] == 17);
  CHECK(pack.descs[1].levels == 1);
  CHECK(pack.descs[1].levelOffset[0] == 18);
  CHECK(pack.texels.size() == 19);
  // Level 1 texel (1, 0): texels (2..3, 0..1): R = (33 + 49 + 33 + 49 + 2) / 4.
  CHECK(channel(pack.texels[16], 0) == (33 + 49 + 33 + 49 + 2) / 4);
  CHECK(channel(pack.texels[16], 1) == (2 + 2 + 18 + 18 + 2) / 4);
}

TEST_CASE("trilinear filtering picks the mip level from the screen derivatives", "[texture]")
{
  // A 1-texel black and white checker of 64×64: every level from 1 on is
  // uniform grey 128, so a pixel is (1 − t)·bilinear(level 0) + t·128 with
  // t = clamp(λ, 0, 1). On the screen-aligned quad ∂u/∂x = ∂v/∂y = s / 16
  // for (u, v) over [0, s]² on 16 pixels: ρ = 64·s/16, λ = log2 ρ.
  clr::Texture t;
  t.name = "checker";
  t.width = t.height = 64;
  for (uint32_t y = 0; y < 64; ++y)
    for (uint32_t x = 0; x < 64; ++x) t.rgba.push_back((x + y) % 2 ? 0xFFFFFFFFu : 0xFF000000u);
  const clr::TexturePack pack = clr::packTextures({t});
  REQUIRE(pack.descs[0].levels == 7);
  for (uint32_t l = 1; l < 7; ++l) CHECK(pack.texels[pack.descs[0].levelOffset[l]] == 0xFF808080u);
  const double lambda = GENERATE(-1.0, 0.0, 0.25, 0.5, 0.75, 1.5, 3.0, 8.0);
  const double s = std::pow(2.0, lambda) * 16.0 / 64.0;
  const std::vector<uint32_t> rgba = renderTexture(quad(t, 0, 0, float(s), float(s)), 16, 16, CLR_FILTER_TRILINEAR);
  const double mix = std::clamp(lambda, 0.0, 1.0);
  double worst = 0;
  for (uint32_t y = 0; y < 16; ++y)
    for (uint32_t x = 0; x < 16; ++x) {
      const glm::dvec3 base =
          bilinear(t.rgba, 64, 64, (x + 0.5) / 16 * s, (y + 0.5) / 16 * s, CLR_WRAP_REPEAT, CLR_WRAP_REPEAT);
      worst = std::max(worst, worstDifference(at(rgba, 16, 16, x, y), base * (1 - mix) + glm::dvec3(128.0) * mix));
    }
  INFO("lambda " << lambda);
  // Tolerance: 0.5 level of rounding plus float error in λ (log2 of a
  // derivative computed from the edge functions, ~1e-6 relative).
  CHECK(worst <= 0.6);
}

TEST_CASE("a glTF with an embedded PNG loads, keeps its sampler and factor, and samples exactly", "[texture]")
{
  // Step 1: a 2×2 PNG (top row red, green; bottom row blue, white) as a data URI.
  const unsigned char pixels[] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  std::string png;
  stbi_write_png_to_func(
      [](void* ctx, void* data, int size) { static_cast<std::string*>(ctx)->append((char*)data, size); }, &png, 2, 2, 4,
      pixels, 8);
  auto base64 = [](const std::string& in) {
    static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < in.size(); i += 3) {
      uint32_t n = uint32_t((unsigned char)in[i]) << 16;
      if (i + 1 < in.size()) n |= uint32_t((unsigned char)in[i + 1]) << 8;
      if (i + 2 < in.size()) n |= uint32_t((unsigned char)in[i + 2]);
      out += abc[(n >> 18) & 63];
      out += abc[(n >> 12) & 63];
      out += i + 1 < in.size() ? abc[(n >> 6) & 63] : '=';
      out += i + 2 < in.size() ? abc[n & 63] : '=';
    }
    return out;
  };
  // Step 2: a quad, positions then glTF texture coordinates (v down).
  const float geometry[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, 0, 1, 1, 1, 1, 0, 0, 0};
  const uint16_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string bin((const char*)geometry, sizeof geometry);
  bin.append((const char*)indices, sizeof indices);
  const std::string gltf =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2,"material":0}]}],
  "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,0.5,1,1],"baseColorTexture":{"index":0}}}],
  "textures":[{"source":0,"sampler":0}],"samplers":[{"wrapS":33648,"wrapT":33071}],
  "images":[{"uri":"data:image/png;base64,)" +
      base64(png) + R"("}],
  "buffers":[{"byteLength":92,"uri":"data:application/octet-stream;base64,)" +
      base64(bin) + R"("}],
  "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":80},{"buffer":0,"byteOffset":80,"byteLength":12}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},
    {"bufferView":0,"byteOffset":48,"componentType":5126,"count":4,"type":"VEC2"},
    {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}]})";
  const std::string path = test::writeFile("embedded.gltf", gltf);
  // Step 3: the texture, its wrap modes and the factor.
  const clr::Mesh mesh = clr::loadScene(path);
  REQUIRE(mesh.textures.size() == 1);
  REQUIRE(mesh.triMaterial.size() == 2);
  const Material& material = mesh.materials.at(mesh.triMaterial[0]);
  CHECK(material.texture == 0);
  CHECK(material.baseColor[1] == 0.5f);
  const clr::Texture& t = mesh.textures[0];
  CHECK((t.width == 2 && t.height == 2));
  CHECK(t.wrapS == CLR_WRAP_MIRROR);
  CHECK(t.wrapT == CLR_WRAP_CLAMP);
  // Rows bottom first: blue, white, then red, green.
  CHECK(t.rgba == std::vector<uint32_t>{0xFFFF0000u, 0xFFFFFFFFu, 0xFF0000FFu, 0xFF00FF00u});
  // Step 4: rendered with nearest sampling: quadrants times the factor (G halved).
  const std::vector<uint32_t> rgba = renderTexture(mesh, 8, 8, CLR_FILTER_NEAREST);
  CHECK(at(rgba, 8, 8, 1, 1) == 0xFFFF0000u);  // blue, bottom left
  CHECK(at(rgba, 8, 8, 6, 1) == 0xFFFF80FFu);  // white × (1, 0.5, 1)
  CHECK(at(rgba, 8, 8, 1, 6) == 0xFF0000FFu);  // red, top left
  CHECK(at(rgba, 8, 8, 6, 6) == 0xFF008000u);  // green × 0.5
}

TEST_CASE("missing and corrupt texture files are one-line warnings naming the file and the model renders",
          "[texture][cli]")
{
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
  auto expectWarning = [&](const std::string& model, const std::string& needle, const std::string& out) {
    const test::Run r = test::run("render " + model + " -o " + out);
    INFO("stderr: " << r.err);
    CHECK(r.status == 0);
    CHECK(r.err.find("warning: ") != std::string::npos);
    CHECK(r.err.find(needle) != std::string::npos);
    CHECK(r.err.find("rendered without the texture") != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(test::exists(out));
  };
  // Step 1: a material naming a file that does not exist.
  test::writeFile("missing_tex.mtl", "newmtl m\nKd 1 1 1\nmap_Kd no_such_texture.png\n");
  const std::string missing = test::writeFile("missing_tex.obj", "mtllib missing_tex.mtl\nusemtl m\n" + tri);
  expectWarning(missing, "cannot use 'no_such_texture.png'", test::tempDir() + "/missing_tex.png");
  // Step 2: a file that is not an image.
  test::writeFile("corrupt.png", "this is not a PNG file at all");
  test::writeFile("corrupt_tex.mtl", "newmtl m\nKd 1 1 1\nmap_Kd corrupt.png\n");
  const std::string corrupt = test::writeFile("corrupt_tex.obj", "mtllib corrupt_tex.mtl\nusemtl m\n" + tri);
  expectWarning(corrupt, "cannot use 'corrupt.png'", test::tempDir() + "/corrupt_tex.png");
}

TEST_CASE("trilinear on a perspective plane: the level follows the analytic derivatives of the 1/w rule", "[texture]")
{
  // A ground plane seen at a grazing angle, textured with a 1-texel checker
  // of 128×128 (levels from 1 on: uniform 128), (u, v) = (x, −z) / 8. The
  // host casts each pixel's ray for the exact (u, v) and takes ρ from
  // central differences of the ray hits at ±1e-3 pixel. The plane starts
  // below the eye (z = 0), or reaches behind it (z = 2), so that the near
  // plane clips both triangles and the derivatives come through ClipBary.
  const uint32_t W = 96, H = 64;
  clr::Texture t;
  t.name = "checker";
  t.width = t.height = 128;
  for (uint32_t y = 0; y < 128; ++y)
    for (uint32_t x = 0; x < 128; ++x) t.rgba.push_back((x + y) % 2 ? 0xFFFFFFFFu : 0xFF000000u);
  const glm::mat4 mvp = glm::perspective(glm::radians(60.0f), float(W) / H, 0.5f, 50.0f) *
                        glm::lookAt(glm::vec3(0, 1, 1), glm::vec3(0, 0, -3), glm::vec3(0, 1, 0));
  const float nearZ = GENERATE(0.0f, 2.0f);
  INFO("the plane's near edge at z = " << nearZ);
  clr::Mesh mesh = quad(t, 0, 0, 1, 1);
  mesh.positions = {-4, 0, nearZ, 4, 0, nearZ, 4, 0, -8, -4, 0, -8};
  mesh.uvs = {-0.5f, -nearZ / 8, 0.5f, -nearZ / 8, 0.5f, 1, -0.5f, 1};
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(mesh);
  clr::FrameSettings s = test::idSettings(W, H, mvp);
  s.shadeMode = CLR_SHADE_TEXTURE;
  s.texFilter = CLR_FILTER_TRILINEAR;
  std::vector<uint32_t> rgba;
  const clr::FrameStats stats = pipeline.render(s, rgba);
  CHECK(stats.trianglesClipped == (nearZ > 0 ? 2u : 0u));
  const glm::dmat4 inv = glm::inverse(glm::dmat4(mvp));
  auto uvAt = [&](double px, double py, bool& onPlane) {
    const glm::dvec2 ndc(px / W * 2 - 1, py / H * 2 - 1);
    const glm::dvec4 a = inv * glm::dvec4(ndc, -1, 1), b = inv * glm::dvec4(ndc, 1, 1);
    const glm::dvec3 from = glm::dvec3(a) / a.w, to = glm::dvec3(b) / b.w;
    const glm::dvec3 hit = from + (to - from) * (-from.y / (to.y - from.y));
    onPlane = to.y < from.y && std::abs(hit.x) < 3.9 && hit.z < -0.1 && hit.z > -7.9;
    return glm::dvec2(hit.x / 8.0, -hit.z / 8.0);
  };
  double worst = 0;
  size_t magnified = 0, minified = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      bool on = false, ok = true;
      const glm::dvec2 uv = uvAt(x + 0.5, y + 0.5, on);
      if (!on) continue;
      const double h = 1e-3;
      const glm::dvec2 dx = (uvAt(x + 0.5 + h, y + 0.5, ok) - uvAt(x + 0.5 - h, y + 0.5, ok)) / (2 * h) * 128.0;
      const glm::dvec2 dy = (uvAt(x + 0.5, y + 0.5 + h, ok) - uvAt(x + 0.5, y + 0.5 - h, ok)) / (2 * h) * 128.0;
      const double lambda = std::clamp(0.5 * std::log2(std::max(glm::dot(dx, dx), glm::dot(dy, dy))), 0.0, 7.0);
      const double mix = std::min(lambda, 1.0);
      (lambda < 1.0 ? magnified : minified)++;
      // Near λ = 0..1 the level-0 checker changes by 510 levels per texel:
      // compare there only where a sample's position error (vertex snapping
      // to 1/256 pixel, ~1e-2 texel) cannot matter, i.e. λ ≥ 1 (pure grey),
      // and check the mix weight where λ < 1 on the texel centres' plateau.
      if (lambda >= 1.0 + 1e-3) {
        worst = std::max(worst, worstDifference(at(rgba, W, H, x, y), glm::dvec3(128.0)));
      } else {
        const glm::dvec3 base = bilinear(t.rgba, 128, 128, uv.x, uv.y, CLR_WRAP_REPEAT, CLR_WRAP_REPEAT);
        const glm::dvec3 want = base * (1 - mix) + glm::dvec3(128.0) * mix;
        const double slack = 510.0 * (1 - mix) * 0.02;  // 0.02 texel of position error
        worst = std::max(worst, worstDifference(at(rgba, W, H, x, y), want) - slack);
      }
    }
  INFO(magnified << " pixels with λ < 1, " << minified << " with λ ≥ 1");
  CHECK(magnified > 200);
  CHECK(minified > 200);
  // Tolerance: 0.5 level of rounding, plus float error in λ near λ = 1.
  CHECK(worst <= 1.0);
}

TEST_CASE("Debian's textured test models load their textures, invented materials stay grey", "[texture][models]")
{
  const std::string models = "/usr/share/assimp/models/";
  // Step 1: embedded (GLB), beside the file (glTF 1.0, OBJ + MTL with JPEGs).
  const clr::Mesh box = clr::loadScene(models + "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb");
  REQUIRE(box.textures.size() == 1);
  CHECK((box.textures[0].width == 211 && box.textures[0].height == 211));
  const clr::Mesh truck = clr::loadScene(models + "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf");
  CHECK(truck.textures.size() == 1);
  const clr::Mesh spider = clr::loadScene(models + "OBJ/spider.obj");
  CHECK(spider.textures.size() == 5);
  // Step 2: PLY and OFF materials are assimp's inventions: the built-in grey.
  for (const char* file : {"PLY/cube.ply", "OFF/Wuson.off", "STL/Wuson.stl"}) {
    const clr::Mesh m = clr::loadScene(models + file);
    INFO(file);
    for (const Material& material : m.materials) {
      CHECK(material.baseColor[0] == 0.80f);
      CHECK(material.baseColor[2] == 0.74f);
      CHECK(material.texture == -1);
    }
  }
  // Step 3: the box renders its logo: sky blue and grass green pixels.
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(box);
  clr::FrameSettings s = test::idSettings(64, 64,
                                          glm::perspective(glm::radians(45.0f), 1.0f, 0.5f, 10.0f) *
                                              glm::lookAt(glm::vec3(0, 0, 3), glm::vec3(0), glm::vec3(0, 1, 0)));
  s.shadeMode = CLR_SHADE_TEXTURE;
  std::vector<uint32_t> rgba;
  pipeline.render(s, rgba);
  size_t blue = 0, green = 0;
  for (uint32_t c : rgba) {
    const int r = channel(c, 0), g = channel(c, 1), b = channel(c, 2);
    blue += b > r + 60 && b > g;
    green += g > r + 30 && g > b + 30;
  }
  CHECK(blue > 200);
  CHECK(green > 200);
}

TEST_CASE("a row's texels sampled in lane types are the lane-by-lane sampler's, bit for bit", "[texture]")
{
  // A row whose lanes all show one material samples its texture in lane
  // types (tex_sample_lanes), a row of several materials lane by lane
  // (tex_sample). A ground plane at a grazing angle, cut into 16 × 16 quads,
  // carries a 37 × 23 texture (odd sizes: the wraps' periods are no powers
  // of two) with (u, v) running far past [0, 1]; its triangles name
  // material 0, or materials 0 and 1 in turn, which are the same material.
  // Most of the second frame's rows cross both, so it is sampled lane by
  // lane where the first frame's rows are sampled in lane types. Under
  // Oclgrind a quarter of the pixels: the same view, wraps and filters.
  const uint32_t W = test::underOclgrind() ? 48 : 96, H = test::underOclgrind() ? 32 : 64, N = 16;
  const glm::mat4 mvp = glm::perspective(glm::radians(60.0f), float(W) / H, 0.5f, 50.0f) *
                        glm::lookAt(glm::vec3(0, 1, 1), glm::vec3(0, 0, -3), glm::vec3(0, 1, 0));
  // (u, v) offset by ±1e6 reaches the sampler's clamp to ±2^24 texels.
  const float offset = GENERATE(0.0f, 1.0e6f, -1.0e6f);
  clr::Mesh mesh;
  for (uint32_t j = 0; j <= N; ++j)
    for (uint32_t i = 0; i <= N; ++i) {
      const float x = -4.0f + 8.0f * i / N, z = -8.0f * j / N;
      mesh.positions.insert(mesh.positions.end(), {x, 0.0f, z});
      mesh.normals.insert(mesh.normals.end(), {0.0f, 1.0f, 0.0f});
      mesh.uvs.insert(mesh.uvs.end(), {0.7f * x + 0.15f + offset, -0.6f * z - 1.3f - offset});
    }
  for (uint32_t j = 0; j < N; ++j)
    for (uint32_t i = 0; i < N; ++i) {
      const uint32_t a = j * (N + 1) + i, b = a + 1, c = a + N + 2, d = a + N + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
    }
  clr::Texture t;
  t.name = "odd";
  t.width = 37;
  t.height = 23;
  for (uint32_t y = 0; y < t.height; ++y)
    for (uint32_t x = 0; x < t.width; ++x)
      t.rgba.push_back(((x * 37 + y * 11) & 0xFFu) | ((x * 5 + y * 29) & 0xFFu) << 8 |
                       ((x * 13 + y * 7) & 0xFFu) << 16 | 0xFF000000u);
  Material m{};
  for (int k = 0; k < 4; ++k) m.baseColor[k] = 0.9f;
  m.texture = 0;
  mesh.materials = {m, m};
  const auto [wrapS, wrapT] =
      GENERATE(std::pair{CLR_WRAP_REPEAT, CLR_WRAP_MIRROR}, std::pair{CLR_WRAP_MIRROR, CLR_WRAP_CLAMP},
               std::pair{CLR_WRAP_CLAMP, CLR_WRAP_REPEAT});
  t.wrapS = wrapS;
  t.wrapT = wrapT;
  mesh.textures = {t};
  const uint32_t filter = GENERATE(CLR_FILTER_NEAREST, CLR_FILTER_BILINEAR, CLR_FILTER_TRILINEAR);
  INFO("wrap " << wrapS << ", " << wrapT << ", filter " << filter << ", (u, v) offset " << offset);
  std::vector<uint32_t> frames[2];
  for (int alternate = 0; alternate < 2; ++alternate) {
    mesh.triMaterial.assign(mesh.numTris(), 0);
    for (size_t tri = 0; alternate && tri < mesh.numTris(); ++tri) mesh.triMaterial[tri] = uint32_t(tri % 2);
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(mesh);
    clr::FrameSettings s = test::idSettings(W, H, mvp);
    s.shadeMode = CLR_SHADE_TEXTURE;
    s.texFilter = filter;
    pipeline.render(s, frames[alternate]);
  }
  size_t covered = 0;
  for (uint32_t p : frames[0]) covered += p != frames[0][0];
  CHECK(covered > W * H / 3);
  CHECK(frames[0] == frames[1]);
}
