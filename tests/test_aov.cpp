// test_aov.cpp — the visibility-buffer outputs (kernels/aov.cl, host/pipeline/aov.cpp):
// every channel against values computed on the host from the visibility
// buffer, the barycentrics and depths against the analytic ray hit, the EXR
// read back with tinyexr bit for bit, and the --aov command line.
#include "pipeline/aov.h"
#include "cli_support.h"
#include "test_support.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <tinyexr.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace {

constexpr uint32_t W = 96, H = 64;

// A front-facing triangle, a back-facing one and a ground triangle that the
// near plane clips, seen through a perspective camera.
struct AovScene {
  glm::mat4 mvp;
  clr::Mesh mesh;
  AovScene()
  {
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 1, 2), glm::vec3(0, 0.6f, -1), glm::vec3(0, 1, 0));
    mvp = glm::perspective(glm::radians(60.0f), float(W) / H, 0.5f, 100.0f) * view;
    const float v[] = {-1.2f, 0.9f, -3.0f, -0.2f, 0.8f, -2.5f, -0.7f, 1.8f, -3.5f,    // CCW from the eye
                       0.3f,  0.9f, -3.0f, 0.9f,  1.9f, -4.0f, 1.4f,  0.8f, -2.5f,    // CW: back-facing
                       -6.0f, 0.0f, 3.0f,  6.0f,  0.0f, 3.0f,  0.0f,  0.0f, -60.0f};  // crosses the near plane
    const float n[] = {1, 0.1f, 0, 0, 1, 0.2f, 0.2f, 0,    1, 0, 0, 1, 0.5f, 0.5f,
                       0, 0,    1, 0, 0, 1,    0,    0.3f, 1, 0, 0, 1, 0.3f};
    mesh.positions.assign(v, v + 27);
    mesh.normals.assign(n, n + 27);
    mesh.indices = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  }
  glm::dvec3 vertex(uint32_t tri, int j) const
  {
    const uint32_t i = mesh.indices[3 * tri + j];
    return {mesh.positions[3 * i], mesh.positions[3 * i + 1], mesh.positions[3 * i + 2]};
  }
};

// Renders the scene and returns the AOV planes.
std::vector<float> renderAov(clr::Pipeline& pipeline, const AovScene& scene)
{
  pipeline.uploadScene(scene.mesh);
  clr::FrameSettings s = test::keepingVis(test::idSettings(W, H, scene.mvp));  // the AOVs read the planes
  s.shadeMode = CLR_SHADE_NORMAL;
  std::vector<uint32_t> rgba;
  pipeline.render(s, rgba);
  pipeline.aov();
  return pipeline.readAov();
}

}  // namespace

TEST_CASE("AOV channels match the host's values from the visibility buffer", "[aov]")
{
  const AovScene scene;
  clr::Pipeline pipeline(test::context());
  const std::vector<float> aov = renderAov(pipeline, scene);
  const std::vector<VisSample> vis = pipeline.readVis(0);
  const std::vector<clr::SetupRecord> setup = pipeline.readSetup();
  const std::vector<ClipBary> clip = pipeline.readClipBary();
  const size_t P = size_t(W) * H;
  auto at = [&](int c, size_t p) { return double(aov[c * P + p]); };
  size_t perTri[3] = {0, 0, 0}, clipped = 0;
  for (size_t p = 0; p < P; ++p) {
    if (vis[p].setupIndex == CLR_NONE) {
      // Step 1: background.
      CHECK(at(CLR_AOV_TRIANGLE_ID, p) == -1.0);
      CHECK(at(CLR_AOV_BARY_U, p) == 0.0);
      CHECK(at(CLR_AOV_Z_W, p) == 1.0);
      CHECK(std::isinf(at(CLR_AOV_EYE_DEPTH, p)));
      continue;
    }
    // Step 2: the host's values, in double, from the same visibility sample.
    const clr::SetupRecord& t = setup[vis[p].setupIndex];
    const double b[3] = {1.0 - double(vis[p].b1) - double(vis[p].b2), vis[p].b1, vis[p].b2};
    double q[3], sum = 0;
    for (int i = 0; i < 3; ++i) sum += q[i] = b[i] * double(t.invW[i]);
    double mu[3] = {0, 0, 0}, muScreen[3] = {0, 0, 0};
    const bool isClipped = t.clipSlot != CLR_NOT_CLIPPED, swapped = !isClipped && (t.flags & CLR_FLAG_BACKFACING);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int input = swapped && i != 0 ? 3 - i : i;
        const double w = isClipped ? double(clip.at(t.clipSlot).w[i][j]) : double(input == j);
        mu[j] += q[i] / sum * w;
        muScreen[j] += b[i] * w;
      }
    glm::dvec3 n(0.0);
    for (int j = 0; j < 3; ++j) {
      const uint32_t v = scene.mesh.indices[3 * t.triId + j];
      n += mu[j] * glm::dvec3(scene.mesh.normals[3 * v], scene.mesh.normals[3 * v + 1], scene.mesh.normals[3 * v + 2]);
    }
    n = glm::normalize(n);
    // Step 3: ids and window depth exactly; the rest within float rounding
    // of a few operations on values of magnitude <= 1 (eye depth relative).
    CHECK(at(CLR_AOV_TRIANGLE_ID, p) == double(t.triId));
    CHECK(at(CLR_AOV_Z_W, p) == double(vis[p].depth));
    CHECK(at(CLR_AOV_BARY_U, p) == Approx(mu[1]).margin(1e-5));
    CHECK(at(CLR_AOV_BARY_V, p) == Approx(mu[2]).margin(1e-5));
    CHECK(at(CLR_AOV_SCREEN_U, p) == Approx(muScreen[1]).margin(1e-5));
    CHECK(at(CLR_AOV_SCREEN_V, p) == Approx(muScreen[2]).margin(1e-5));
    CHECK(at(CLR_AOV_EYE_DEPTH, p) == Approx(1.0 / sum).epsilon(1e-5));
    CHECK(at(CLR_AOV_NORMAL_X, p) == Approx(n.x).margin(1e-5));
    CHECK(at(CLR_AOV_NORMAL_Y, p) == Approx(n.y).margin(1e-5));
    CHECK(at(CLR_AOV_NORMAL_Z, p) == Approx(n.z).margin(1e-5));
    // Step 4: the kernel's own float operations, in its order, give its
    // channels bit for bit: every step is an IEEE operation (no contraction,
    // correctly rounded division and square root), so a driver that rounds
    // one differently (NVIDIA's length() did) fails here.
    const float bf[3] = {1.0f - vis[p].b1 - vis[p].b2, vis[p].b1, vis[p].b2};
    const float qf[3] = {bf[0] * t.invW[0], bf[1] * t.invW[1], bf[2] * t.invW[2]};
    const float eyeDepth = 1.0f / (qf[0] + qf[1] + qf[2]);
    float muf[3] = {0.0f, 0.0f, 0.0f};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int input = swapped && i != 0 ? 3 - i : i;
        muf[j] += (qf[i] * eyeDepth) * (isClipped ? clip.at(t.clipSlot).w[i][j] : float(input == j));
      }
    float nf[3] = {0.0f, 0.0f, 0.0f};
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) nf[k] += muf[j] * scene.mesh.normals[3 * scene.mesh.indices[3 * t.triId + j] + k];
    const float len = std::sqrt(nf[0] * nf[0] + nf[1] * nf[1] + nf[2] * nf[2]);
    CHECK(aov[CLR_AOV_BARY_U * P + p] == muf[1]);
    CHECK(aov[CLR_AOV_BARY_V * P + p] == muf[2]);
    CHECK(aov[CLR_AOV_EYE_DEPTH * P + p] == eyeDepth);
    for (int k = 0; k < 3; ++k) CHECK(aov[(CLR_AOV_NORMAL_X + k) * P + p] == (len > 0.0f ? nf[k] / len : 0.0f));
    ++perTri[t.triId];
    clipped += isClipped;
  }
  // Every kind of triangle is seen: front, back-facing, clipped.
  CHECK(perTri[0] > 30);
  CHECK(perTri[1] > 30);
  CHECK(perTri[2] > 300);
  CHECK(clipped == perTri[2]);
  for (const clr::SetupRecord& r : setup)
    if (r.triId == 1) CHECK(r.flags == CLR_FLAG_BACKFACING);
  CHECK(std::count_if(setup.begin(), setup.end(), [](const clr::SetupRecord& r) { return r.triId == 1; }) == 1);
}

TEST_CASE("AOV barycentrics and depths match the analytic ray hit", "[aov]")
{
  // The world point under each pixel centre: the eye ray meets the visible
  // triangle's plane. Its barycentrics are the perspective-correct channels;
  // its distance along the view axis is the eye depth. Vertices snap to
  // 1/256 pixel, which moves barycentrics by up to about 1/256 of a pixel over
  // the triangle's extent in pixels (> 10 here): 2e-3 absolute. Eye depth:
  // the same relative 2e-3.
  const AovScene scene;
  clr::Pipeline pipeline(test::context());
  const std::vector<float> aov = renderAov(pipeline, scene);
  const glm::dmat4 inv = glm::inverse(glm::dmat4(scene.mvp));
  const size_t P = size_t(W) * H;
  size_t checked = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const size_t p = size_t(y) * W + x;
      const float id = aov[CLR_AOV_TRIANGLE_ID * P + p];
      if (id < 0) continue;
      const uint32_t tri = uint32_t(id);
      // Step 1: the ray through the pixel centre and its hit.
      const glm::dvec2 ndc((x + 0.5) / W * 2 - 1, (y + 0.5) / H * 2 - 1);
      const glm::dvec4 a = inv * glm::dvec4(ndc, -1, 1), b = inv * glm::dvec4(ndc, 1, 1);
      const glm::dvec3 from = glm::dvec3(a) / a.w, to = glm::dvec3(b) / b.w;
      const glm::dvec3 v0 = scene.vertex(tri, 0), v1 = scene.vertex(tri, 1), v2 = scene.vertex(tri, 2);
      const glm::dvec3 nrm = glm::cross(v1 - v0, v2 - v0);
      const glm::dvec3 hit = from + (to - from) * (glm::dot(v0 - from, nrm) / glm::dot(to - from, nrm));
      // Step 2: its barycentrics and eye depth.
      const double area = glm::dot(nrm, nrm);
      const double u = glm::dot(glm::cross(v0 - v2, hit - v2), nrm) / area;
      const double v = glm::dot(glm::cross(v1 - v0, hit - v0), nrm) / area;
      const glm::dvec4 clipHit = glm::dmat4(scene.mvp) * glm::dvec4(hit, 1.0);
      // Pixels at a triangle's edge are left out: snapping may move the edge
      // across their centre.
      if (u < 0.01 || v < 0.01 || 1.0 - u - v < 0.01) continue;
      CHECK(aov[CLR_AOV_BARY_U * P + p] == Approx(u).margin(2e-3));
      CHECK(aov[CLR_AOV_BARY_V * P + p] == Approx(v).margin(2e-3));
      CHECK(aov[CLR_AOV_EYE_DEPTH * P + p] == Approx(clipHit.w).epsilon(2e-3));
      CHECK(aov[CLR_AOV_Z_W * P + p] == Approx(clipHit.z / clipHit.w * 0.5 + 0.5).margin(1e-4));
      ++checked;
    }
  CHECK(checked > 500);
}

TEST_CASE("AOV EXR reads back exactly with tinyexr", "[aov]")
{
  const AovScene scene;
  clr::Pipeline pipeline(test::context());
  const std::vector<float> aov = renderAov(pipeline, scene);
  const std::string path = test::tempDir() + "/aov_roundtrip.exr";
  clr::writeAovExr(path, W, H, aov);
  // Step 1: header and channels.
  EXRVersion version;
  REQUIRE(ParseEXRVersionFromFile(&version, path.c_str()) == TINYEXR_SUCCESS);
  EXRHeader header;
  InitEXRHeader(&header);
  const char* err = nullptr;
  REQUIRE(ParseEXRHeaderFromFile(&header, &version, path.c_str(), &err) == TINYEXR_SUCCESS);
  for (int c = 0; c < header.num_channels; ++c) header.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
  EXRImage image;
  InitEXRImage(&image);
  REQUIRE(LoadEXRImageFromFile(&image, &header, path.c_str(), &err) == TINYEXR_SUCCESS);
  REQUIRE(image.width == int(W));
  REQUIRE(image.height == int(H));
  const std::vector<std::string>& names = clr::aovChannelNames();
  REQUIRE(header.num_channels == int(names.size()));
  // Step 2: every channel bit for bit, rows top first in the file.
  const size_t P = size_t(W) * H;
  for (int c = 0; c < header.num_channels; ++c) {
    CHECK(header.pixel_types[c] == TINYEXR_PIXELTYPE_FLOAT);
    const auto it = std::find(names.begin(), names.end(), std::string(header.channels[c].name));
    REQUIRE(it != names.end());
    const size_t plane = size_t(it - names.begin());
    const float* data = reinterpret_cast<const float*>(image.images[c]);
    size_t differing = 0;
    for (uint32_t y = 0; y < H; ++y)
      differing += std::memcmp(&data[size_t(H - 1 - y) * W], &aov[plane * P + size_t(y) * W], W * sizeof(float)) != 0;
    CHECK(differing == 0);
  }
  FreeEXRImage(&image);
  FreeEXRHeader(&header);
}

TEST_CASE("cli: --aov writes the EXR and rejects bad combinations", "[cli][aov]")
{
  const std::string dir = test::tempDir();
  const std::string png = dir + "/aov_cli.png", exr = dir + "/aov_cli.exr";
  std::remove(exr.c_str());
  const test::Run r = test::run("render --size 64x48 -o " + png + " --aov " + exr);
  REQUIRE(r.status == 0);
  EXRVersion version;
  CHECK(ParseEXRVersionFromFile(&version, exr.c_str()) == TINYEXR_SUCCESS);
  CHECK(test::leftoverTemps(exr) == 0);
  test::expectError("render -o " + png + " --aov " + dir + "/no/such/dir/x.exr", "x.exr: cannot write");
  test::expectError("render -o " + dir + "/v_%d.png --views " + dir + "/none.json --aov " + exr,
                    "--aov cannot be combined with --views");
  test::expectError("render -o " + png + " --wireframe --shade id", "--wireframe cannot be combined with --shade id");
  test::expectError("render -o " + png + " --line thick", "--line: unknown value 'thick'");
  test::expectError("render -o " + png + " --line-width 0", "--line-width must lie in (0, 16]");
}

TEST_CASE("cli: the AOV planes do not depend on the shading mode", "[cli][aov]")
{
  // Depth shading uploads no normals of its own; the normal planes must still read the mesh's.
  const std::string dir = test::tempDir();
  const std::string model = "/usr/share/assimp/models/OBJ/spider.obj";
  std::string exr[2];
  const char* modes[2] = {"phong", "depth"};
  for (int i = 0; i < 2; ++i) {
    exr[i] = dir + "/aov_mode_" + modes[i] + ".exr";
    std::remove(exr[i].c_str());
    REQUIRE(test::run("render " + model + " --size 160x120 --shade " + modes[i] + " --aov " + exr[i]).status == 0);
  }
  const std::string a = test::slurp(exr[0]), b = test::slurp(exr[1]);
  REQUIRE(!a.empty());
  CHECK(a == b);
}
