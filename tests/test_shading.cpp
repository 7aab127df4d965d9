// test_shading.cpp — the shading modes of resolve (kernels/shade.h) against
// the same formulas evaluated on the host in double precision, anti-aliasing
// with every mode, and the lazy attribute uploads of Pipeline.
#include "test_support.h"

#include "render/flags.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

namespace {

constexpr uint32_t W = 64, H = 64;

// Lighting constants of kernels/shade.h.
constexpr double kAmbient = 0.12, kDiffuse = 0.88, kSpecular = 0.4, kShininess = 32.0;
const glm::dvec3 kGrey(0.80, 0.78, 0.74);

// One tilted triangle with distinct normals, colours and a material; the
// camera looks at it in perspective.
struct Scene {
  glm::dvec3 v[3] = {{-1.2, -0.9, -0.3}, {1.3, -0.7, 0.2}, {-0.1, 1.1, -0.1}};
  glm::dvec3 n[3] = {{-0.3, -0.2, 1.0}, {0.4, -0.1, 1.0}, {0.0, 0.5, 0.8}};
  glm::dvec4 c[3] = {{1.0, 0.2, 0.1, 1}, {0.1, 0.9, 0.2, 1}, {0.2, 0.3, 1.0, 1}};
  glm::dvec2 uv[3] = {{0.0, 0.0}, {0.95, 0.0}, {0.0, 0.95}};  // inside [0, 1): uv has no wrap seam
  glm::dvec3 factor{0.9, 0.7, 0.5};
  glm::dvec3 eye{0.3, 0.2, 3.0};
  glm::dvec3 lightDir = glm::normalize(glm::dvec3(0.4, 0.6, 0.7));
  glm::dvec3 point{-0.8, 0.9, 1.2};
  double range = 1.5;
  glm::mat4 mvp = glm::perspective(glm::radians(50.0f), 1.0f, 0.5f, 10.0f) *
                  glm::lookAt(glm::vec3(eye), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));

  clr::Mesh mesh() const
  {
    clr::Mesh m;
    for (int i = 0; i < 3; ++i) {
      m.positions.insert(m.positions.end(), {float(v[i].x), float(v[i].y), float(v[i].z)});
      m.normals.insert(m.normals.end(), {float(n[i].x), float(n[i].y), float(n[i].z)});
      m.colors.insert(m.colors.end(), {float(c[i].r), float(c[i].g), float(c[i].b), float(c[i].a)});
      m.uvs.insert(m.uvs.end(), {float(uv[i].x), float(uv[i].y)});
    }
    m.indices = {0, 1, 2};
    m.triMaterial = {0};
    Material mat{};
    mat.baseColor[0] = float(factor.r);
    mat.baseColor[1] = float(factor.g);
    mat.baseColor[2] = float(factor.b);
    mat.baseColor[3] = 1.0f;
    mat.texture = -1;
    m.materials = {mat};
    return m;
  }
  clr::FrameSettings settings(uint32_t mode, bool pointLight) const
  {
    clr::FrameSettings s = test::idSettings(W, H, mvp);
    s.shadeMode = mode;
    s.eye = glm::vec3(eye);
    s.lightDir = glm::vec3(lightDir);
    s.pointLightOn = pointLight;
    s.pointLight = glm::vec3(point);
    s.pointLightRange = float(range);
    s.zNear = 0.5f;
    s.zFar = 10.0f;
    return s;
  }
};

// Diffuse and specular sums of shade.h at point p, unit normal nrm.
void hostLights(const Scene& s, bool pointLight, glm::dvec3 nrm, glm::dvec3 p, double& diffuse, double& specular)
{
  const glm::dvec3 view = glm::normalize(s.eye - p);
  diffuse = specular = 0.0;
  auto add = [&](glm::dvec3 l, double atten) {
    const double ndotl = glm::dot(nrm, l);
    diffuse += atten * std::max(ndotl, 0.0);
    if (ndotl > 0.0) specular += atten * std::pow(std::max(glm::dot(nrm, glm::normalize(l + view)), 0.0), kShininess);
  };
  add(s.lightDir, 1.0);
  if (pointLight) {
    const glm::dvec3 d = s.point - p;
    add(glm::normalize(d), 1.0 / (1.0 + glm::dot(d, d) / (s.range * s.range)));
  }
}

// Texture coordinates at world barycentrics mu (perspective-correct).
glm::dvec2 uvAt(const Scene& s, glm::dvec3 mu)
{
  return mu.x * s.uv[0] + mu.y * s.uv[1] + mu.z * s.uv[2];
}

// The checker's grey (kernels/shade.h: 1/8 squares, 0.9 and 0.25) at uv.
double checkerGrey(glm::dvec2 uv)
{
  return (int(std::floor(uv.x * 8.0)) + int(std::floor(uv.y * 8.0))) % 2 ? 0.25 : 0.9;
}

// Whether uv lies within `margin` (in squares) of a checker square's edge.
bool nearCheckerEdge(glm::dvec2 uv, double margin)
{
  auto near = [&](double t) { return std::abs(t * 8.0 - std::round(t * 8.0)) < margin; };
  return near(uv.x) || near(uv.y);
}

// The expected colour (0..255 per channel) of a mode at world barycentrics mu.
glm::dvec3 expectedColour(const Scene& s, uint32_t mode, bool pointLight, glm::dvec3 mu, double eyeDepth)
{
  const glm::dvec3 p = mu.x * s.v[0] + mu.y * s.v[1] + mu.z * s.v[2];
  const glm::dvec3 colour = glm::dvec3(mu.x * s.c[0] + mu.y * s.c[1] + mu.z * s.c[2]);
  const glm::dvec3 albedo = s.factor * colour;
  // The triangle faces the eye (counter-clockwise on screen): no flip.
  const glm::dvec3 smooth = glm::normalize(mu.x * s.n[0] + mu.y * s.n[1] + mu.z * s.n[2]);
  double d = 0, sp = 0;
  glm::dvec3 out(0.0);
  switch (mode) {
    case CLR_SHADE_NORMAL: out = smooth * 0.5 + 0.5; break;
    case CLR_SHADE_ID: out = glm::dvec3(1.0 / 255.0, 0.0, 0.0); break;  // triangle 0's id, 1, as 24-bit RGB
    case CLR_SHADE_UV: out = glm::dvec3(uvAt(s, mu), 0.0); break;       // no wrap: uv lies in [0, 1)
    case CLR_SHADE_CHECKER: out = glm::dvec3(checkerGrey(uvAt(s, mu))); break;
    case CLR_SHADE_DEPTH: out = glm::dvec3(1.0 - (eyeDepth - 0.5) / (10.0 - 0.5)); break;
    case CLR_SHADE_COLOR: out = colour; break;
    case CLR_SHADE_TEXTURE: out = albedo; break;
    case CLR_SHADE_LAMBERT:
      hostLights(s, pointLight, smooth, p, d, sp);
      out = albedo * (kAmbient + kDiffuse * d);
      break;
    case CLR_SHADE_PHONG:
      hostLights(s, pointLight, smooth, p, d, sp);
      out = albedo * (kAmbient + kDiffuse * d) + kSpecular * sp;
      break;
    case CLR_SHADE_FLAT: {
      const glm::dvec3 face = glm::normalize(glm::cross(s.v[1] - s.v[0], s.v[2] - s.v[0]));
      hostLights(s, pointLight, face, (s.v[0] + s.v[1] + s.v[2]) / 3.0, d, sp);
      out = albedo * (kAmbient + kDiffuse * d) + kSpecular * sp;
      break;
    }
    case CLR_SHADE_GOURAUD: {
      double dj = 0, sj = 0;
      for (int j = 0; j < 3; ++j) {
        hostLights(s, pointLight, glm::normalize(s.n[j]), s.v[j], dj, sj);
        d += mu[j] * dj;
        sp += mu[j] * sj;
      }
      out = albedo * (kAmbient + kDiffuse * d) + kSpecular * sp;
      break;
    }
    default:
      FAIL("shading mode " << (mode < CLR_NUM_SHADE_MODES ? clr::kShadeModeNames[mode] : "?")
                           << " has no host formula in test_shading.cpp");
  }
  return glm::clamp(out, 0.0, 1.0) * 255.0;
}

// World barycentrics of the ray through screen point (sx, sy) and its eye depth.
glm::dvec3 rayBarycentrics(const Scene& s, double sx, double sy, double& eyeDepth)
{
  const glm::dmat4 inv = glm::inverse(glm::dmat4(s.mvp));
  const glm::dvec2 ndc(sx / W * 2 - 1, sy / H * 2 - 1);
  const glm::dvec4 a = inv * glm::dvec4(ndc, -1, 1), b = inv * glm::dvec4(ndc, 1, 1);
  const glm::dvec3 from = glm::dvec3(a) / a.w, dir = glm::dvec3(b) / b.w - from;
  const glm::dvec3 nrm = glm::cross(s.v[1] - s.v[0], s.v[2] - s.v[0]);
  const double t = glm::dot(s.v[0] - from, nrm) / glm::dot(dir, nrm);
  const glm::dvec3 hit = from + t * dir;
  const double area = glm::dot(nrm, nrm);
  eyeDepth = glm::dot(hit - s.eye, glm::normalize(-s.eye));  // the camera looks at the origin
  return {glm::dot(glm::cross(s.v[2] - s.v[1], hit - s.v[1]), nrm) / area,
          glm::dot(glm::cross(s.v[0] - s.v[2], hit - s.v[2]), nrm) / area,
          glm::dot(glm::cross(s.v[1] - s.v[0], hit - s.v[0]), nrm) / area};
}

// The same through pixel (x, y)'s centre; whether it is clear of the edges.
bool hitBarycentrics(const Scene& s, uint32_t x, uint32_t y, glm::dvec3& mu, double& eyeDepth)
{
  mu = rayBarycentrics(s, x + 0.5, y + 0.5, eyeDepth);
  return mu.x > 0.02 && mu.y > 0.02 && mu.z > 0.02;
}

// Whether all of pixel (x, y) lies in one checker square, clear of its edges
// by 0.01 square: then every sample of the pixel, wherever it lies, shows
// that square's grey. The map from screen to uv is projective, so the pixel's
// image is the quadrilateral of its corners' images; when the four lie in one
// (convex) square, so does the whole pixel.
bool inOneCheckerSquare(const Scene& s, uint32_t x, uint32_t y)
{
  double eyeDepth;
  const glm::dvec2 first = uvAt(s, rayBarycentrics(s, x, y, eyeDepth));
  for (int corner = 0; corner < 4; ++corner) {
    const glm::dvec2 uv = uvAt(s, rayBarycentrics(s, x + corner % 2, y + corner / 2, eyeDepth));
    if (nearCheckerEdge(uv, 0.01) || glm::floor(uv * 8.0) != glm::floor(first * 8.0)) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("shading modes match their formulas evaluated on the host", "[shade]")
{
  const uint32_t mode = GENERATE(range(0u, CLR_NUM_SHADE_MODES));  // every mode of kShadeModeNames
  const bool pointLight = GENERATE(false, true);
  const Scene scene;
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(scene.mesh());
  std::vector<uint32_t> rgba;
  pipeline.render(scene.settings(mode, pointLight), rgba);
  double worst = 0, highlight = 0;
  size_t checked = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      glm::dvec3 mu;
      double eyeDepth;
      if (!hitBarycentrics(scene, x, y, mu, eyeDepth)) continue;
      // The checker jumps at its squares' edges: a centre within 0.01 square
      // (0.05 px here) of one, 50 times the barycentrics' snapping error, may
      // land on either side.
      if (mode == CLR_SHADE_CHECKER && nearCheckerEdge(uvAt(scene, mu), 0.01)) continue;
      const uint32_t got = rgba[size_t(H - 1 - y) * W + x];
      const glm::dvec3 want = expectedColour(scene, mode, pointLight, mu, eyeDepth);
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(double((got >> (8 * k)) & 0xFFu) - want[k]));
      ++checked;
      double d, sp;
      hostLights(scene, pointLight, glm::normalize(mu.x * scene.n[0] + mu.y * scene.n[1] + mu.z * scene.n[2]),
                 mu.x * scene.v[0] + mu.y * scene.v[1] + mu.z * scene.v[2], d, sp);
      highlight = std::max(highlight, kSpecular * sp * 255.0);
    }
  INFO(clr::kShadeModeNames[mode] << (pointLight ? " with the point light" : "") << ": " << checked << " pixels, worst "
                                  << worst << " levels");
  CHECK(checked > 800);
  // The scene has a specular highlight worth checking (Phong's, at least).
  CHECK(highlight > 20.0);
  // Tolerance: 0.5 level from rounding to 8 bits, plus float arithmetic and
  // the snapping of vertices to 1/256 pixel, which moves the barycentrics by
  // about 1e-3 of a pixel (measured worst: 0.506 levels, Phong with the
  // point light).
  CHECK(worst <= 0.55);
  // Every mode shows something other than black on this scene.
  CHECK(size_t(std::count(rgba.begin(), rgba.end(), 0xFF000000u)) < rgba.size());
}

TEST_CASE("the point light changes only the lit modes, and its attenuation follows the range", "[shade]")
{
  Scene scene;
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(scene.mesh());
  std::vector<uint32_t> off, on, far;
  pipeline.render(scene.settings(CLR_SHADE_PHONG, false), off);
  pipeline.render(scene.settings(CLR_SHADE_PHONG, true), on);
  CHECK(off != on);
  // A vanishing range attenuates the point light to nothing.
  clr::FrameSettings s = scene.settings(CLR_SHADE_PHONG, true);
  s.pointLightRange = 1e-6f;
  pipeline.render(s, far);
  CHECK(far == off);
  std::vector<uint32_t> normalOff, normalOn;
  pipeline.render(scene.settings(CLR_SHADE_NORMAL, false), normalOff);
  pipeline.render(scene.settings(CLR_SHADE_NORMAL, true), normalOn);
  CHECK(normalOff == normalOn);
}

TEST_CASE("anti-aliasing works with every shading mode", "[shade][aa]")
{
  const uint32_t mode = GENERATE(range(0u, CLR_NUM_SHADE_MODES));  // every mode of kShadeModeNames
  const uint32_t samples = GENERATE(4u, 16u);
  const bool ssaa = GENERATE(false, true);
  const Scene scene;
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(scene.mesh());
  std::vector<uint32_t> plain, aa;
  clr::FrameSettings s = scene.settings(mode, true);
  pipeline.render(s, plain);
  s.samples = samples;
  s.shadeEverySample = ssaa;
  pipeline.render(s, aa);
  INFO(clr::kShadeModeNames[mode] << ", " << samples << " samples, " << (ssaa ? "SSAA" : "MSAA"));
  // Step 1: inside the triangle (clear of its edges), every sample shows
  // it: the pixel is its colour at points within half a pixel of the
  // centre, which differs from the centre's by a few levels at most.
  // The checker is the exception: its colour jumps at each square's edge,
  // so there only pixels inside one square count, and both images must show
  // that square's grey.
  const uint32_t background = plain[0];
  size_t blended = 0, inside = 0;
  int worstInside = 0;
  double worstGrey = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      glm::dvec3 mu;
      double eyeDepth;
      const size_t p = size_t(H - 1 - y) * W + x;
      if (hitBarycentrics(scene, x, y, mu, eyeDepth) && mu.x > 0.06 && mu.y > 0.06 && mu.z > 0.06) {
        if (mode == CLR_SHADE_CHECKER && !inOneCheckerSquare(scene, x, y)) continue;
        ++inside;
        for (int k = 0; k < 3; ++k) {
          const int a = int((plain[p] >> (8 * k)) & 0xFFu), b = int((aa[p] >> (8 * k)) & 0xFFu);
          worstInside = std::max(worstInside, std::abs(a - b));
          if (mode == CLR_SHADE_CHECKER) {
            const double want = 255.0 * checkerGrey(uvAt(scene, mu));
            worstGrey = std::max({worstGrey, std::abs(a - want), std::abs(b - want)});
          }
        }
      } else if (aa[p] != plain[p] && aa[p] != background) {
        ++blended;
      }
    }
  // Step 2: id stays exact; every other mode blends along the edges.
  CAPTURE(inside, blended, worstInside, worstGrey);
  CHECK(inside > (mode == CLR_SHADE_CHECKER ? 300u : 600u));
  if (mode == CLR_SHADE_ID) {
    CHECK(worstInside == 0);
  } else if (mode == CLR_SHADE_CHECKER) {
    // Inside one square every sample has the same grey: the averages agree
    // to the rounding of 8 bits (0.9 · 255 = 229.5 may round either way),
    // and a lookup of the wrong square is off by 166 levels.
    CHECK(worstInside <= 1);
    CHECK(worstGrey <= 0.55);
    CHECK(blended > 20);
  } else {
    // The specular highlight varies fastest.
    CHECK(worstInside <= 12);
    CHECK(blended > 20);
  }
}

TEST_CASE("only the attributes the shading reads are uploaded, each once", "[shade]")
{
  Scene scene;
  clr::Mesh mesh = scene.mesh();
  clr::Texture t;
  t.name = "crafted";
  t.width = t.height = 2;
  t.rgba = {0xFF0000FFu, 0xFF00FF00u, 0xFFFF0000u, 0xFFFFFFFFu};
  mesh.textures = {t};
  mesh.materials[0].texture = 0;
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(mesh);
  std::vector<uint32_t> rgba;
  using P = clr::Pipeline;
  // Step 1: id and depth read positions and indices only.
  pipeline.render(scene.settings(CLR_SHADE_ID, false), rgba);
  CHECK(pipeline.resident() == 0u);
  const size_t bytesAfterId = pipeline.deviceBytes();
  pipeline.render(scene.settings(CLR_SHADE_DEPTH, false), rgba);
  CHECK(pipeline.resident() == 0u);
  // Step 2: each mode adds what it reads; nothing is uploaded twice.
  pipeline.render(scene.settings(CLR_SHADE_NORMAL, false), rgba);
  CHECK(pipeline.resident() == uint32_t(P::kResidentNormals));
  CHECK(pipeline.deviceBytes() > bytesAfterId);
  pipeline.render(scene.settings(CLR_SHADE_COLOR, false), rgba);
  CHECK(pipeline.resident() == uint32_t(P::kResidentNormals | P::kResidentColors));
  pipeline.render(scene.settings(CLR_SHADE_TEXTURE, false), rgba);
  const uint32_t all =
      P::kResidentNormals | P::kResidentColors | P::kResidentUvs | P::kResidentMaterials | P::kResidentTextures;
  CHECK(pipeline.resident() == all);
  const size_t bytesAll = pipeline.deviceBytes();
  pipeline.render(scene.settings(CLR_SHADE_PHONG, true), rgba);
  pipeline.render(scene.settings(CLR_SHADE_ID, false), rgba);
  CHECK(pipeline.resident() == all);
  CHECK(pipeline.deviceBytes() == bytesAll);
  // Step 3: a new scene starts from positions and indices again.
  pipeline.uploadScene(mesh);
  CHECK(pipeline.resident() == 0u);
  pipeline.render(scene.settings(CLR_SHADE_FLAT, false), rgba);
  CHECK(pipeline.resident() ==
        uint32_t(P::kResidentColors | P::kResidentUvs | P::kResidentMaterials | P::kResidentTextures));
}

namespace {

// A bumpy grid seen at a grazing angle, the near plane cutting into it
// (clipped triangles), every third triangle wound the other way (back faces,
// drawn two-sided), three untextured materials and tilted normals, in a
// width x height viewport; under Oclgrind half as wide and high, the same
// view on a quarter of the pixels.
struct GrazingGrid {
  clr::Mesh mesh;
  clr::FrameSettings settings;
};
GrazingGrid grazingGrid(uint32_t width, uint32_t height)
{
  if (test::underOclgrind()) width /= 2, height /= 2;
  GrazingGrid g;
  clr::Mesh& mesh = g.mesh;
  const int n = 24;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = -2.0f + 4.0f * float(i) / n, z = -2.0f + 4.0f * float(j) / n;
      mesh.positions.insert(mesh.positions.end(), {x, 0.15f * std::sin(3.0f * x) * std::cos(2.0f * z), z});
      mesh.normals.insert(mesh.normals.end(), {0.3f * std::sin(5.0f * z), 1.0f, 0.2f * std::cos(4.0f * x)});
      mesh.uvs.insert(mesh.uvs.end(), {float(i) / n, float(j) / n});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      for (const auto& tri : {std::array<uint32_t, 3>{a, c, b}, std::array<uint32_t, 3>{b, c, d}}) {
        const bool flip = mesh.indices.size() / 3 % 3 == 0;
        mesh.indices.insert(mesh.indices.end(), {tri[0], flip ? tri[2] : tri[1], flip ? tri[1] : tri[2]});
        mesh.triMaterial.push_back(uint32_t(i + j) % 3);
      }
    }
  for (int k = 0; k < 3; ++k) {
    Material mat{};
    mat.baseColor[0] = 0.3f + 0.3f * float(k);
    mat.baseColor[1] = 0.9f - 0.2f * float(k);
    mat.baseColor[2] = 0.5f;
    mat.baseColor[3] = 1.0f;
    mat.texture = -1;
    mesh.materials.push_back(mat);
  }
  const glm::mat4 mvp = glm::perspective(glm::radians(70.0f), float(width) / float(height), 0.6f, 20.0f) *
                        glm::lookAt(glm::vec3(0.2f, 0.35f, 1.2f), glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0, 1, 0));
  g.settings = test::idSettings(width, height, mvp);
  g.settings.shadeMode = CLR_SHADE_LAMBERT;
  g.settings.lightDir = glm::normalize(glm::vec3(0.3f, 0.8f, 0.4f));
  return g;
}

}  // namespace

TEST_CASE("the lean lambert resolve gives the general resolve's pixels bit for bit", "[shade]")
{
  // Step 1: the grazing grid in a viewport whose width is not a multiple of 16.
  const GrazingGrid grid = grazingGrid(100, 70);
  const clr::Mesh& mesh = grid.mesh;
  clr::FrameSettings settings = grid.settings;

  // Step 2: both kernels on the same frame.
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(mesh);
  std::vector<uint32_t> lean, general;
  const clr::FrameStats leanStats = pipeline.render(settings, lean);
  settings.leanResolve = false;
  const clr::FrameStats generalStats = pipeline.render(settings, general);
  CHECK(leanStats.leanResolve);
  CHECK_FALSE(generalStats.leanResolve);
  CHECK(leanStats.trianglesClipped > 0);

  // Step 3: the frame shows all three materials and back faces, and the
  // pixels agree exactly (both kernels do the same float operations).
  std::set<uint32_t> colours(lean.begin(), lean.end());
  CHECK(colours.size() > 100);
  const std::vector<uint32_t> ids = test::readTriIds(pipeline);
  std::set<uint32_t> materialsSeen;
  bool backSeen = false;
  for (const uint32_t id : ids)
    if (id != ref::kNone) {
      materialsSeen.insert(mesh.triMaterial[id]);
      backSeen = backSeen || id % 3 == 0;
    }
  CHECK(materialsSeen.size() == 3);
  CHECK(backSeen);
  CHECK(lean == general);

  // Step 4: the frames the lean kernel does not serve run the general one.
  settings.leanResolve = true;
  settings.samples = 4;
  CHECK_FALSE(pipeline.render(settings, general).leanResolve);
  settings.samples = 1;
  settings.pointLightOn = true;
  CHECK_FALSE(pipeline.render(settings, general).leanResolve);
  settings.pointLightOn = false;
  settings.interpMode = CLR_INTERP_AFFINE;
  CHECK_FALSE(pipeline.render(settings, general).leanResolve);
}

TEST_CASE("a scene of one material binds no per-triangle materials and shades as with them", "[shade]")
{
  // Step 1: the grazing grid with every triangle on material 2 (one material), and again with every other
  // triangle on material 3, an exact copy of material 2 (per-triangle materials).
  const GrazingGrid grid = grazingGrid(100, 70);
  clr::Mesh one = grid.mesh, copies = grid.mesh;
  copies.materials.push_back(copies.materials[2]);
  for (size_t t = 0; t < one.triMaterial.size(); ++t) {
    one.triMaterial[t] = 2;
    copies.triMaterial[t] = t % 2 ? 3 : 2;
  }
  clr::Mesh grey = one;
  grey.materials.clear();
  grey.triMaterial.clear();
  // Step 2: modes that read materials, lambert through both resolve kernels: identical pixels, unlike the grey of a
  // scene without materials; and the one-material scene holds 4 bytes per triangle less (the per-triangle buffer).
  clr::Pipeline a(test::context()), b(test::context()), c(test::context());
  a.uploadScene(one);
  b.uploadScene(copies);
  c.uploadScene(grey);
  const std::pair<uint32_t, bool> cases[] = {
      {CLR_SHADE_LAMBERT, true}, {CLR_SHADE_LAMBERT, false}, {CLR_SHADE_TEXTURE, false}, {CLR_SHADE_PHONG, false}};
  for (const auto& [mode, lean] : cases) {
    CAPTURE(mode, lean);
    clr::FrameSettings settings = grid.settings;
    settings.shadeMode = mode;
    settings.leanResolve = lean;
    std::vector<uint32_t> imageA, imageB, imageGrey;
    CHECK(a.render(settings, imageA).leanResolve == lean);
    b.render(settings, imageB);
    c.render(settings, imageGrey);
    CHECK(imageA == imageB);
    CHECK(imageA != imageGrey);
  }
  CHECK(b.deviceBytes() >= a.deviceBytes() + 4 * one.numTris());
}

namespace {

struct RecomputeCase {
  const char* name;
  uint32_t shadeMode, samples;
  bool everySample, lean;
  uint32_t visibility, depthMode;
  uint32_t traversal = CLR_TRAVERSAL_BBOX;
};

// Renders each case with the barycentric planes kept (resolve reads
// raster's barycentrics) and without (resolve recomputes them), and requires
// identical pixels.
void checkRecomputedBarycentrics(const std::vector<RecomputeCase>& cases)
{
  // Step 1: the grazing grid at 160 x 100 (triangles within 64 pixels:
  // raster's 32-bit edge rows) and a large backdrop triangle behind it
  // (its 64-bit rows; its doubled area, about 7·10^9 fixed units², leaves
  // 32 bits, so resolve recomputes its barycentrics in 64 bits: with the
  // 32-bit ones up to 2^33 this test fails).
  GrazingGrid grid = grazingGrid(160, 100);
  clr::Mesh& mesh = grid.mesh;
  const uint32_t first = uint32_t(mesh.positions.size() / 3);
  mesh.positions.insert(mesh.positions.end(), {-19.8f, -4.4f, -7.0f, 19.8f, -4.4f, -7.0f, 0.0f, 19.8f, -7.0f});
  mesh.normals.insert(mesh.normals.end(), {-0.2f, 0.1f, 1.0f, 0.3f, 0.0f, 1.0f, 0.0f, 0.4f, 0.9f});
  mesh.uvs.insert(mesh.uvs.end(), {0.0f, 0.0f, 1.0f, 0.0f, 0.5f, 1.0f});
  mesh.indices.insert(mesh.indices.end(), {first, first + 1, first + 2});
  mesh.triMaterial.push_back(1);
  clr::Pipeline kept(test::context()), recomputed(test::context());
  kept.uploadScene(grid.mesh);
  recomputed.uploadScene(grid.mesh);
  for (const RecomputeCase& c : cases) {
    INFO(c.name);
    clr::FrameSettings settings = grid.settings;
    settings.shadeMode = c.shadeMode;
    settings.samples = c.samples;
    settings.shadeEverySample = c.everySample;
    settings.leanResolve = c.lean;
    settings.visibility = c.visibility;
    settings.depthMode = c.depthMode;
    settings.traversal = c.traversal;
    // Step 2: the same frame with and without the planes.
    std::vector<uint32_t> withPlanes, withoutPlanes;
    settings.keepVisAttributes = true;
    const clr::FrameStats stats = kept.render(settings, withPlanes);
    settings.keepVisAttributes = false;
    recomputed.render(settings, withoutPlanes);
    CHECK(stats.trianglesClipped > 0);
    // Step 3: the frame exercises both raster paths and many colours, and
    // the pixels agree exactly.
    bool wide = false, narrow = false;
    for (const clr::SetupRecord& t : kept.readSetup()) {
      if (t.flags & CLR_FLAG_DEAD) continue;
      const int w = std::max({t.x[0], t.x[1], t.x[2]}) - std::min({t.x[0], t.x[1], t.x[2]});
      (w > 64 * CLR_FIXED_ONE ? wide : narrow) = true;
    }
    CHECK(wide);
    CHECK(narrow);
    const size_t distinct = std::set<uint32_t>(withPlanes.begin(), withPlanes.end()).size();
    CHECK(distinct > (c.shadeMode == CLR_SHADE_DEPTH ? 5u : 100u));  // depth shades in a narrow grey range
    CHECK(withPlanes == withoutPlanes);
  }
}

}  // namespace

TEST_CASE("resolve recomputes raster's barycentrics: lambert frames without the attribute planes are bit-identical",
          "[shade][resolve]")
{
  // Both resolve kernels; this one also runs under Oclgrind in both shapes.
  checkRecomputedBarycentrics({
      {"lean lambert", CLR_SHADE_LAMBERT, 1, false, true, CLR_VISIBILITY_ZBUFFER, CLR_DEPTH_FLOAT32},
      {"general lambert", CLR_SHADE_LAMBERT, 1, false, false, CLR_VISIBILITY_ZBUFFER, CLR_DEPTH_FLOAT32},
  });
}

TEST_CASE("resolve recomputes raster's barycentrics for every sample, shading mode, visibility method and traversal",
          "[shade][aa]")
{
  checkRecomputedBarycentrics({
      {"phong", CLR_SHADE_PHONG, 1, false, true, CLR_VISIBILITY_ZBUFFER, CLR_DEPTH_FLOAT32},
      {"uv", CLR_SHADE_UV, 1, false, true, CLR_VISIBILITY_ZBUFFER, CLR_DEPTH_UNORM24},
      {"depth", CLR_SHADE_DEPTH, 1, false, true, CLR_VISIBILITY_ZBUFFER, CLR_DEPTH_FLOAT32},
      {"msaa 4", CLR_SHADE_LAMBERT, 4, false, true, CLR_VISIBILITY_ZBUFFER, CLR_DEPTH_FLOAT32},
      {"ssaa 8", CLR_SHADE_GOURAUD, 8, true, true, CLR_VISIBILITY_ZBUFFER, CLR_DEPTH_FLOAT32},
      {"painter", CLR_SHADE_LAMBERT, 1, false, true, CLR_VISIBILITY_PAINTER, CLR_DEPTH_FLOAT32},
      {"hierarchical msaa 4", CLR_SHADE_LAMBERT, 4, false, true, CLR_VISIBILITY_ZBUFFER, CLR_DEPTH_FLOAT32,
       CLR_TRAVERSAL_HIERARCHICAL},
  });
}

TEST_CASE(
    "a frame holds the visibility buffer's depth and barycentric planes only when a reader needs them, and no clip "
    "positions",
    "[shade]")
{
  const GrazingGrid grid = grazingGrid(160, 100);
  clr::Pipeline lean(test::context()), full(test::context());
  lean.uploadScene(grid.mesh);
  full.uploadScene(grid.mesh);
  std::vector<uint32_t> rgba;
  clr::FrameSettings settings = grid.settings;
  // Step 1: 2 bytes per sample of a covered tile without the planes (16-bit
  // indices), 14 with; first allocations are exact, and the lean frame's
  // planes are a one-float placeholder (raster.cpp), so the difference is
  // exactly the planes.
  lean.render(settings, rgba);
  settings.keepVisAttributes = true;
  full.render(settings, rgba);
  const uint64_t plane = lean.visPlane();
  REQUIRE(plane > 0);
  CHECK(full.deviceBytes() - lean.deviceBytes() == 12 * plane - sizeof(float));
  CHECK(full.bytesPerPixel() - lean.bytesPerPixel() ==
        Approx(12.0 * plane / (double(settings.width) * settings.height)).epsilon(1e-9));  // the same formula
  // Step 2: readVis gives the setup indices either way, and depth and
  // barycentrics only with the planes (NaN without).
  const std::vector<VisSample> leanVis = lean.readVis(), fullVis = full.readVis();
  REQUIRE(leanVis.size() == fullVis.size());
  size_t covered = 0;
  for (size_t p = 0; p < leanVis.size(); ++p) {
    REQUIRE(leanVis[p].setupIndex == fullVis[p].setupIndex);
    REQUIRE(std::isnan(leanVis[p].depth));
    REQUIRE(std::isfinite(fullVis[p].depth));
    covered += fullVis[p].setupIndex != CLR_NONE;
  }
  CHECK(covered > 1000);
  // Step 3: the readers that need the planes say so instead of reading garbage.
  CHECK_THROWS_WITH(lean.aov(), Catch::Contains("keepVisAttributes"));
  CHECK_THROWS_WITH(lean.lines({}), Catch::Contains("keepVisAttributes"));
  full.aov();
  // Frames with lines or float edges keep the planes without being asked.
  settings.keepVisAttributes = false;
  settings.wireframe = CLR_WIREFRAME_OVERLAY;
  lean.render(settings, rgba);
  CHECK(lean.params().visAttributes == 1u);
  settings.wireframe = CLR_WIREFRAME_OFF;
  settings.edgeMode = CLR_EDGES_FLOAT;
  lean.render(settings, rgba);
  CHECK(lean.params().visAttributes == 1u);
  settings.edgeMode = CLR_EDGES_FIXED;
  lean.render(settings, rgba);
  CHECK(lean.params().visAttributes == 0u);
  // Step 4: a frame holds no clip positions either (setup transforms the
  // vertices it reads); the transform kernel allocates them when asked.
  const size_t before = lean.deviceBytes();
  lean.transform();
  CHECK(lean.deviceBytes() - before == 16 * (grid.mesh.positions.size() / 3));
}

// (Not under Oclgrind: every small test scene there takes the 16-bit planes.)
TEST_CASE("the visibility buffer's indices are 16 bits wide below 0xFFFF records, with the frames of 24 and 32 bits",
          "[vis]")
{
  // Step 1: the grazing grid (clipped triangles, back faces, materials), in
  // every reader of the visibility buffer: both resolve kernels, MSAA's and
  // the id mode's sample planes, lines (overlay), the AOVs and readVis.
  const GrazingGrid grid = grazingGrid(160, 100);
  clr::Pipeline narrow(test::context()), wide(test::context());
  narrow.uploadScene(grid.mesh);
  wide.uploadScene(grid.mesh);
  struct Case {
    const char* name;
    uint32_t shadeMode, samples;
    bool lean;
    uint32_t wireframe;
  };
  for (const Case& c : {Case{"lean lambert", CLR_SHADE_LAMBERT, 1, true, CLR_WIREFRAME_OFF},
                        Case{"general phong", CLR_SHADE_PHONG, 1, false, CLR_WIREFRAME_OFF},
                        Case{"msaa 4", CLR_SHADE_LAMBERT, 4, true, CLR_WIREFRAME_OFF},
                        Case{"id msaa 4", CLR_SHADE_ID, 4, true, CLR_WIREFRAME_OFF},
                        Case{"lines overlay", CLR_SHADE_LAMBERT, 1, true, CLR_WIREFRAME_OVERLAY}})
    for (const uint32_t bits : {24u, 32u}) {
      INFO(c.name << ", against " << bits << " bits");
      clr::FrameSettings settings = grid.settings;
      settings.shadeMode = c.shadeMode;
      settings.samples = c.samples;
      settings.leanResolve = c.lean;
      settings.wireframe = c.wireframe;
      settings.keepVisAttributes = c.wireframe == CLR_WIREFRAME_OFF;  // for the AOVs (lines keep the planes anyway)
      std::vector<uint32_t> narrowImage, wideImage;
      narrow.render(settings, narrowImage);
      settings.minVisIndexBits = bits;
      wide.render(settings, wideImage);
      // Step 2: 2 against 3 or 4 bytes per sample, and the same pixels and samples.
      REQUIRE(narrow.params().visIndexBits == 16u);
      REQUIRE(wide.params().visIndexBits == bits);
      const double pixels = 160.0 * 100.0;
      CHECK(wide.bytesPerPixel() - narrow.bytesPerPixel() ==
            Approx((bits / 8.0 - 2.0) * narrow.visPlane() * c.samples / pixels));
      CHECK(narrowImage == wideImage);
      for (uint32_t k = 0; k < c.samples; ++k) {
        const std::vector<VisSample> a = narrow.readVis(k), b = wide.readVis(k);
        REQUIRE(a.size() == b.size());
        size_t covered = 0;
        for (size_t p = 0; p < a.size(); ++p) {
          REQUIRE(a[p].setupIndex == b[p].setupIndex);
          covered += a[p].setupIndex != CLR_NONE;
        }
        CHECK(covered > 1000);
      }
      if (settings.keepVisAttributes) {
        narrow.aov();
        wide.aov();
        CHECK(narrow.readAov() == wide.readAov());
      }
    }
}

TEST_CASE("16-bit visibility indices reach index 0xFFFE and more setup records take 24 bits", "[vis]")
{
  // One small triangle around each pixel centre of a 512 x 256 viewport, for
  // the first n pixels: n setup records, pixel i showing record i (the
  // records keep input order: no layout, Pipeline::setLayout). n = 0xFFFE is
  // the most 16 bits hold besides 0xFFFF (none); one more record takes 24
  // bits, whose high bytes reach 1 here; the wide setting takes 32.
  const uint32_t w = 512, h = 256;
  for (const uint32_t n : {0xFFFEu, 0xFFFFu, 0x1A001u}) {
    test::Geometry g;
    for (uint32_t i = 0; i < n; ++i) {
      const float x = float(i % w), y = float(i / w);
      g.addTriangle(test::screen(x + 0.25f, y + 0.25f, 0.5f, w, h), test::screen(x + 0.75f, y + 0.25f, 0.5f, w, h),
                    test::screen(x + 0.5f, y + 0.75f, 0.5f, w, h));
    }
    clr::Pipeline pipeline(test::context());
    pipeline.setLayout(false);
    pipeline.uploadScene(g.mesh());
    for (const bool wide : {false, true}) {
      INFO("setup records: " << n << (wide ? ", 32-bit indices" : ""));
      clr::FrameSettings settings = test::idSettings(w, h);
      settings.minVisIndexBits = wide ? 32 : 16;
      const std::vector<uint32_t> ids = test::renderTriIds(pipeline, settings);
      CHECK(pipeline.params().visIndexBits == (wide ? 32u : n < 0xFFFFu ? 16u : 24u));
      const std::vector<VisSample> vis = pipeline.readVis();
      size_t wrong = 0;
      for (uint32_t p = 0; p < w * h; ++p) {
        const uint32_t expected = p < n ? p : CLR_NONE;
        wrong += vis[p].setupIndex != expected || ids[p] != (p < n ? p : ref::kNone);
      }
      CHECK(wrong == 0);
    }
  }
}
