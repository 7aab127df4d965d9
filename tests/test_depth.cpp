// test_depth.cpp — the depth formats (float32, unorm24, reversed-Z) and the
// painter's algorithm: each format's compare and clear on crafted scenes,
// unorm24 quantisation ties, near-plane clipping with the reversed
// projection, a z-fighting case that float32 and unorm24 lose and reversed
// wins, and cyclically overlapping triangles that defeat the painter's
// algorithm. Every expectation is an exact pixel count or ID.
#include "cli_support.h"
#include "render/depth.h"
#include "test_support.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

using test::Geometry;
using test::screen;

namespace {

const uint32_t kModes[] = {CLR_DEPTH_FLOAT32, CLR_DEPTH_UNORM24, CLR_DEPTH_REVERSED};

clr::FrameSettings depthSettings(uint32_t width, uint32_t height, uint32_t depthMode,
                                 const glm::mat4& mvp = glm::mat4(1.0f))
{
  clr::FrameSettings s = test::keepingVis(test::idSettings(width, height, mvp));  // the tests read the depth plane
  s.depthMode = depthMode;
  return s;
}

size_t count(const std::vector<uint32_t>& ids, uint32_t id)
{
  return size_t(std::count(ids.begin(), ids.end(), id));
}

// unorm24's key of a GL window depth, with raster.cl's float operations.
float unormKey(float z)
{
  return std::nearbyint(std::clamp(z, 0.0f, 1.0f) * CLR_DEPTH_UNORM24_MAX);
}

// Two clip z values (w = 1) whose GL window depths differ as floats but
// quantise to the same 24-bit value: zNear < zFar.
void unormTiePair(float& zNear, float& zFar)
{
  // Window depths in [0.25, 0.5) are 2^-25 apart as floats, about two per
  // unorm24 step; clip z on the 2^-24 grid maps to them exactly.
  for (int i = 0; i < 64; ++i) {
    const float a = -0.375f + float(i) * 0x1p-24f, b = a + 0x1p-24f;
    const float wa = a * 0.5f + 0.5f, wb = b * 0.5f + 0.5f;
    if (wa != wb && unormKey(wa) == unormKey(wb)) {
      zNear = a;
      zFar = b;
      return;
    }
  }
  FAIL("no unorm24 tie pair found");
}

}  // namespace

TEST_CASE("depth: each format's compare and clear on a crafted scene", "[raster][depth]")
{
  const uint32_t W = 64, H = 32;
  // Step 1: an overlapping pair (0 at clip z 0.6 drawn first, 1 at 0.4), and
  // two single triangles: 2 at clip z 1 (GL far value, reversed near value)
  // and 3 at clip z 0 (reversed far value).
  Geometry g;
  g.addTriangle(screen(1, 1, 0.6f, W, H), screen(24, 1, 0.6f, W, H), screen(1, 30, 0.6f, W, H));
  g.addTriangle(screen(6, 1, 0.4f, W, H), screen(29, 1, 0.4f, W, H), screen(6, 30, 0.4f, W, H));
  g.addTriangle(screen(33, 1, 1.0f, W, H), screen(47, 1, 1.0f, W, H), screen(33, 30, 1.0f, W, H));
  g.addTriangle(screen(49, 1, 0.0f, W, H), screen(63, 1, 0.0f, W, H), screen(49, 30, 0.0f, W, H));
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  const size_t overlapPixel = 10 * W + 10;  // inside 0 and 1
  for (uint32_t mode : kModes) {
    INFO("depth mode " << clr::depthModeName(mode));
    const std::vector<uint32_t> ids = test::renderTriIds(pipeline, depthSettings(W, H, mode));
    // Step 2: the oracle with the same format agrees pixel for pixel.
    ref::Options o{W, H, false};
    o.depthMode = mode;
    const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), o);
    CHECK(test::countDifferences(ids, expected.triId) == 0);
    // Step 3: the known results. GL formats: smaller z is nearer, z = 1 is
    // the clear value; reversed: larger z is nearer, z = 0 is the clear value.
    const bool reversed = mode == CLR_DEPTH_REVERSED;
    CHECK(ids[overlapPixel] == (reversed ? 0u : 1u));
    CHECK(count(ids, 2) == (reversed ? count(expected.triId, 2) : 0u));
    CHECK(count(ids, 3) == (reversed ? 0u : count(expected.triId, 3)));
    CHECK(count(ids, reversed ? 2 : 3) > 150);
    // Step 4: the depth plane: window depth of the visible fragment (as the
    // format stores it) and the clear value where nothing was drawn.
    const std::vector<VisSample> vis = pipeline.readVis();
    const float z1 = 0.4f * 0.5f + 0.5f;
    CHECK(vis[overlapPixel].depth == (reversed                    ? 0.6f
                                      : mode == CLR_DEPTH_UNORM24 ? unormKey(z1) / CLR_DEPTH_UNORM24_MAX
                                                                  : z1));
    const size_t emptyPixel = 25 * W + 20;  // in a drawn tile, outside every triangle
    CHECK(ids[emptyPixel] == ref::kNone);
    CHECK(vis[emptyPixel].depth == (reversed ? 0.0f : 1.0f));
  }
}

TEST_CASE("depth: unorm24 quantisation ties go to the earlier triangle", "[raster][depth]")
{
  const uint32_t W = 32, H = 32;
  float zNear = 0, zFar = 0;
  unormTiePair(zNear, zFar);
  const float windowNear = zNear * 0.5f + 0.5f, windowFar = zFar * 0.5f + 0.5f;
  REQUIRE(windowNear < windowFar);
  REQUIRE(unormKey(windowNear) == unormKey(windowFar));
  for (int nearerFirst = 0; nearerFirst < 2; ++nearerFirst) {
    INFO("nearer drawn " << (nearerFirst ? "first" : "second"));
    Geometry g;
    const float z0 = nearerFirst ? zNear : zFar, z1 = nearerFirst ? zFar : zNear;
    g.addTriangle(screen(1, 1, z0, W, H), screen(30, 1, z0, W, H), screen(1, 30, z0, W, H));
    g.addTriangle(screen(1, 1, z1, W, H), screen(30, 1, z1, W, H), screen(1, 30, z1, W, H));
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(g.mesh());
    const uint32_t nearer = nearerFirst ? 0 : 1;
    // float32 tells the depths apart: the nearer triangle everywhere.
    const std::vector<uint32_t> f32 = test::renderTriIds(pipeline, depthSettings(W, H, CLR_DEPTH_FLOAT32));
    const size_t covered = count(f32, nearer);
    CHECK(covered == count(ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {W, H, false}).triId, nearer));
    CHECK(covered > 400);
    CHECK(count(f32, 1 - nearer) == 0);
    // unorm24 sees a tie: the earlier triangle (0) everywhere, in both orders.
    const std::vector<uint32_t> u24 = test::renderTriIds(pipeline, depthSettings(W, H, CLR_DEPTH_UNORM24));
    CHECK(count(u24, 0) == covered);
    CHECK(count(u24, 1) == 0);
    const std::vector<VisSample> vis = pipeline.readVis();
    CHECK(vis[5 * W + 5].depth == unormKey(windowNear) / CLR_DEPTH_UNORM24_MAX);
    ref::Options o{W, H, false};
    o.depthMode = CLR_DEPTH_UNORM24;
    CHECK(test::countDifferences(u24, ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), o).triId) == 0);
  }
}

TEST_CASE("depth: reversed-Z clips at its near plane z <= w, same pixels as the oracle", "[clip][depth]")
{
  // The scene of the GL near-plane test (test_transform.cpp), with the reversed projection.
  const uint32_t W = 80, H = 60;
  const glm::mat4 mvp = clr::reversedPerspective(glm::radians(60.0f), float(W) / H, 0.5f, 50.0f) *
                        glm::lookAt(glm::vec3(0, 1, 0), glm::vec3(0, 1, -1), glm::vec3(0, 1, 0));
  Geometry g;
  g.addTriangle({-2, 0, 3}, {2, 0, -10}, {-2, 0.5f, -10});            // one vertex behind the eye
  g.addTriangle({1, 2, 2}, {3, 2, 4}, {2, 1.5f, -8});                 // two vertices behind
  g.addTriangle({-1, 0, 1}, {1, 0, 1}, {0, 1, 2});                    // wholly behind: culled
  g.addTriangle({-1, 0.2f, -0.3f}, {1, 0.2f, -0.3f}, {0, 2, -0.3f});  // in front of the eye, nearer than near: culled
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  std::vector<uint32_t> rgba;
  const clr::FrameSettings settings = depthSettings(W, H, CLR_DEPTH_REVERSED, mvp);
  const clr::FrameStats stats = pipeline.render(settings, rgba);
  CHECK(stats.trianglesClipped == 2);
  CHECK(stats.trianglesCulled == 2);
  CHECK(stats.setupTriangles == 3);
  // Every visible fragment lies between far (0) and near (1).
  const std::vector<uint32_t> ids = test::readTriIds(pipeline);
  const std::vector<VisSample> vis = pipeline.readVis();
  for (size_t p = 0; p < vis.size(); ++p)
    if (ids[p] != ref::kNone) REQUIRE((vis[p].depth >= 0.0f && vis[p].depth <= 1.0f));
  ref::Options o{W, H, false};
  o.depthMode = CLR_DEPTH_REVERSED;
  const ref::Result expected = ref::rasterize(g.positions, g.indices, mvp, o);
  CHECK(expected.clippedTriangles == 2);
  CHECK(test::countDifferences(ids, expected.triId) == 0);
  CHECK(count(ids, 0) > 200);
  CHECK(count(ids, 1) > 50);
  // The GL projection of the same camera shows the same triangles on nearly
  // the same pixels: only the clipped edges' float rounding may differ.
  const glm::mat4 glMvp = glm::perspective(glm::radians(60.0f), float(W) / H, 0.5f, 50.0f) *
                          glm::lookAt(glm::vec3(0, 1, 0), glm::vec3(0, 1, -1), glm::vec3(0, 1, 0));
  const std::vector<uint32_t> glIds = test::renderTriIds(pipeline, depthSettings(W, H, CLR_DEPTH_FLOAT32, glMvp));
  CHECK(test::countDifferences(ids, glIds) <= 8);
}

TEST_CASE("depth: planes 1e-4 of their distance apart at far/near 1e5: float32 and unorm24 misorder, reversed not",
          "[raster][depth][zfight]")
{
  // Two planes facing the camera squarely (constant depth each) at eye
  // distance 80000 and 79992, near 1, far 100000. GL window depth there is
  // 1 − 1.25e-5, where float32 and unorm24 steps are 6e-8 and the planes
  // differ by 1.25e-9: both formats store the same value, so the tie goes
  // to the earlier plane. Reversed depth is 1.25e-5, where floats step by
  // 1.7e-12, so the planes stay apart.
  const uint32_t W = 32, H = 32;
  const float zNear = 1.0f, zFar = 1e5f, d = 80000.0f, eps = 8.0f;
  for (int nearerFirst = 0; nearerFirst < 2; ++nearerFirst) {
    Geometry g;
    for (int k = 0; k < 2; ++k) {
      const float z = (k == 0) == (nearerFirst == 1) ? -(d - eps) : -d;
      g.addTriangle({-d, -d, z}, {d, -d, z}, {-d, d, z});
      g.addTriangle({d, -d, z}, {d, d, z}, {-d, d, z});
    }
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(g.mesh());
    for (uint32_t mode : kModes) {
      const glm::mat4 mvp = mode == CLR_DEPTH_REVERSED
                                ? clr::reversedPerspective(glm::radians(60.0f), 1.0f, zNear, zFar)
                                : glm::perspective(glm::radians(60.0f), 1.0f, zNear, zFar);
      const std::vector<uint32_t> ids = test::renderTriIds(pipeline, depthSettings(W, H, mode, mvp));
      size_t wrong = 0;
      for (uint32_t id : ids) wrong += id == ref::kNone || (id / 2 == 0) != (nearerFirst == 1);
      INFO("depth mode " << clr::depthModeName(mode) << ", nearer drawn " << (nearerFirst ? "first" : "second"));
      // Wrong pixels, of 1024: the GL formats lose every pixel when the
      // nearer plane comes second, reversed none in either order.
      CHECK(wrong == (mode != CLR_DEPTH_REVERSED && !nearerFirst ? W * H : 0u));
    }
  }
}

TEST_CASE("visibility: the painter's algorithm fails on cyclically overlapping triangles", "[raster][painter]")
{
  // Step 1: three triangles around a centre, each a wedge from a near apex
  // (clip z −0.8) to a far base (0.8). Wedge i crosses wedge i+1 near its
  // own base and the other's apex, so 1 covers 0, 2 covers 1 and 0 covers
  // 2: no back-to-front order exists (the notes' cyclic overlap, 004).
  const uint32_t W = 64, H = 64;
  const glm::vec2 centre(32, 32);
  Geometry g;
  for (int i = 0; i < 3; ++i) {
    const float a0 = glm::radians(90.0f + 120.0f * i), a1 = glm::radians(90.0f + 120.0f * (i + 1));
    const glm::vec2 v0 = centre + 16.0f * glm::vec2(std::cos(a0), std::sin(a0));
    const glm::vec2 v1 = centre + 16.0f * glm::vec2(std::cos(a1), std::sin(a1));
    const glm::vec2 dir = glm::normalize(v1 - v0), side(-dir.y, dir.x);
    const glm::vec2 apex = v0 - 12.0f * dir, base = v1 + 12.0f * dir;
    g.addTriangle(screen(apex.x, apex.y, -0.8f, W, H), screen(base.x + 5 * side.x, base.y + 5 * side.y, 0.8f, W, H),
                  screen(base.x - 5 * side.x, base.y - 5 * side.y, 0.8f, W, H));
  }
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  // Step 2: the z-buffer against the scalar oracle, and the cycle in it.
  const std::vector<uint32_t> zbuffer = test::renderTriIds(pipeline, test::idSettings(W, H));
  const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {W, H, false});
  CHECK(test::countDifferences(zbuffer, expected.triId) == 0);
  // Step 3: the painter's algorithm, against painting each triangle's
  // oracle coverage in the pipeline's sorted order.
  clr::FrameSettings painter = test::idSettings(W, H);
  painter.visibility = CLR_VISIBILITY_PAINTER;
  const std::vector<uint32_t> painted = test::renderTriIds(pipeline, painter);
  const std::vector<uint32_t> order = pipeline.paintOrder();
  REQUIRE(order.size() == 3);
  // Equal farthest depths (0.8): ties draw the later input triangle first.
  CHECK(order == std::vector<uint32_t>{2, 1, 0});
  std::vector<std::vector<uint32_t>> cover(3);  // each triangle's oracle coverage alone
  std::vector<uint32_t> byHand(size_t(W) * H, ref::kNone);
  for (uint32_t t = 0; t < 3; ++t) {
    const std::vector<uint32_t> one(g.indices.begin() + 3 * t, g.indices.begin() + 3 * t + 3);
    cover[t] = ref::rasterize(g.positions, one, glm::mat4(1.0f), {W, H, false}).triId;
  }
  for (uint32_t t : order)
    for (size_t p = 0; p < byHand.size(); ++p)
      if (cover[t][p] != ref::kNone) byHand[p] = t;
  CHECK(test::countDifferences(painted, byHand) == 0);
  // Step 4: the cycle in the z-buffer: where exactly triangles i and i+1
  // overlap, i+1 is on top, for i = 0, 1, 2.
  size_t overlap[3] = {0, 0, 0}, painterWrong[3] = {0, 0, 0};
  for (uint32_t i = 0; i < 3; ++i) {
    const uint32_t j = (i + 1) % 3, k = (i + 2) % 3;
    for (size_t p = 0; p < zbuffer.size(); ++p) {
      if (cover[i][p] == ref::kNone || cover[j][p] == ref::kNone || cover[k][p] != ref::kNone) continue;
      ++overlap[i];
      CHECK(zbuffer[p] == j);
      painterWrong[i] += painted[p] != j;
    }
    CHECK(overlap[i] > 10);
  }
  // Step 5: the painter's wrong pixels. Painting 2, 1, 0 puts 0 over 1 and
  // 1 over 2, against the z-buffer, and gets only 0 over 2 right: two of the
  // three overlaps (19 and 21 pixels) wrong, nothing else.
  size_t wrong = 0;
  for (size_t p = 0; p < painted.size(); ++p) wrong += painted[p] != zbuffer[p];
  INFO("overlaps " << overlap[0] << ", " << overlap[1] << ", " << overlap[2]);
  CHECK(painterWrong[0] == overlap[0]);
  CHECK(painterWrong[1] == overlap[1]);
  CHECK(painterWrong[2] == 0);
  CHECK(wrong == overlap[0] + overlap[1]);
  CHECK(wrong == 40);
}

TEST_CASE("visibility: the painter's algorithm matches the z-buffer without cyclic overlap", "[raster][painter]")
{
  // Triangles at distinct constant depths, in a shuffled order, overlapping.
  const uint32_t W = 48, H = 48;
  Geometry g;
  const float depths[] = {0.1f, -0.5f, 0.7f, -0.2f, 0.3f, 0.0f};
  for (int i = 0; i < 6; ++i) {
    const float x = 4.0f + 5.0f * i, z = depths[i];
    g.addTriangle(screen(x, 2, z, W, H), screen(x + 20, 4, z, W, H), screen(x + 4, 40, z, W, H));
  }
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  const std::vector<uint32_t> zbuffer = test::renderTriIds(pipeline, test::idSettings(W, H));
  // (Negative clip z lies beyond the reversed far plane, so only the GL formats.)
  for (uint32_t mode : {CLR_DEPTH_FLOAT32, CLR_DEPTH_UNORM24}) {
    INFO("depth mode " << clr::depthModeName(mode));
    clr::FrameSettings painter = depthSettings(W, H, mode);
    painter.visibility = CLR_VISIBILITY_PAINTER;
    CHECK(test::countDifferences(test::renderTriIds(pipeline, painter), zbuffer) == 0);
    CHECK(pipeline.paintOrder() == std::vector<uint32_t>{2, 4, 0, 5, 3, 1});
  }
}

TEST_CASE("cli: --depth and --visibility, --depth auto's choice in --stats", "[cli][depth]")
{
  test::expectError("render -o x.png --depth float16", "--depth: unknown value 'float16'");
  test::expectError("render -o x.png --visibility sorted", "--visibility: unknown value 'sorted'");
  const std::string png = test::tempDir() + "/depth.png";
  // The built-in scene's default near and far: float32.
  test::Run r = test::run("render -o '" + png + "' --size 64x48 --depth auto --stats");
  REQUIRE(r.status == 0);
  CHECK(r.out.find("\"depth\":\"float32\",\"depth_reason\":\"far/near") != std::string::npos);
  CHECK(r.out.find("\"visibility\":\"zbuffer\"") != std::string::npos);
  // far/near 1e5 > 1e4: reversed.
  r = test::run("render -o '" + png +
                "' --size 64x48 --near 0.01 --far 1000 --depth auto --visibility painter --stats");
  REQUIRE(r.status == 0);
  CHECK(r.out.find("\"depth\":\"reversed\",\"depth_reason\":\"far/near 1e+05 > 1e+04") != std::string::npos);
  CHECK(r.out.find("\"visibility\":\"painter\"") != std::string::npos);
  // Every format renders the built-in scene to the same triangle IDs.
  std::string first;
  for (const char* depth : {"float32", "unorm24", "reversed"}) {
    r = test::run("render -o '" + png + "' --size 160x120 --shade id --depth " + std::string(depth));
    REQUIRE(r.status == 0);
    const std::string image = test::slurp(png);
    if (first.empty()) first = image;
    CHECK(image == first);
  }
}
