// test_kernels.cpp — each pipeline stage launched on the OpenCL device with
// small crafted inputs, checked against exact expectations or the oracle.
#include "depth.h"
#include "test_support.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

using test::Geometry;
using test::screen;

namespace {

glm::mat4 perspectiveCamera(glm::vec3 eye, glm::vec3 target, float aspect, float zNear = 0.5f, float zFar = 100.0f)
{
  return glm::perspective(glm::radians(60.0f), aspect, zNear, zFar) * glm::lookAt(eye, target, {0, 1, 0});
}

size_t pixel(uint32_t width, uint32_t x, uint32_t y)
{
  return size_t(y) * width + x;
}

}  // namespace

TEST_CASE("transform matches the oracle bit for bit", "[transform]")
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-20.0f, 20.0f);
  Geometry g;
  for (int i = 0; i < 999; ++i) g.addVertex({coord(rng), coord(rng), coord(rng)});
  g.indices = {0, 1, 2};
  const glm::mat4 mvp = perspectiveCamera({3, 4, 30}, {0, 0, 0}, 1.5f);
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  pipeline.beginFrame(test::idSettings(64, 64, mvp));
  pipeline.transform();
  const std::vector<cl_float4> clip = pipeline.readClipPositions();
  REQUIRE(clip.size() == 999);
  for (size_t v = 0; v < clip.size(); ++v) {
    const glm::vec4 expected = ref::transformVertex(mvp, &g.positions[3 * v]);
    REQUIRE(std::memcmp(&clip[v], &expected, sizeof expected) == 0);
  }
}

TEST_CASE("setup snaps to 1/256 pixel and orients triangles counter-clockwise", "[setup]")
{
  // Vertices on the subpixel grid map exactly through an identity MVP.
  Geometry g;
  g.addTriangle(screen(1.25f, 2.5f, 0.1f, 32, 32), screen(5.5f, 25.75f, 0.2f, 32, 32),
                screen(20.0f, 3.0f, 0.3f, 32, 32));  // clockwise on screen
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  std::vector<uint32_t> rgba;
  const clr::FrameStats stats = pipeline.render(test::idSettings(32, 32), rgba);
  const std::vector<clr::SetupRecord> setup = pipeline.readSetup();
  REQUIRE(stats.setupTriangles == 1);
  REQUIRE(setup.size() == 1);
  const clr::SetupRecord& t = setup[0];
  CHECK(t.flags == CLR_FLAG_BACKFACING);
  // Vertices 1 and 2 were swapped to make the triangle counter-clockwise.
  CHECK(t.x[0] == 320);
  CHECK(t.y[0] == 640);
  CHECK(t.x[1] == 5120);
  CHECK(t.y[1] == 768);
  CHECK(t.x[2] == 1408);
  CHECK(t.y[2] == 6592);
  CHECK(t.z[1] == Approx(0.5f * 0.3f + 0.5f));
  const double area2 = double(t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - double(t.x[2] - t.x[0]) * (t.y[1] - t.y[0]);
  CHECK(area2 > 0);
  CHECK(t.invArea2 == 1.0f / float(area2));
  CHECK(t.triId == 0);
  CHECK(t.clipSlot == CLR_NOT_CLIPPED);
}

TEST_CASE("setup culls degenerate, non-finite, outside and back-facing triangles", "[setup]")
{
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Geometry g;
  g.addTriangle(screen(2, 2, 0, 32, 32), screen(10, 10, 0, 32, 32), screen(20, 20, 0, 32, 32));  // collinear
  g.addTriangle(screen(2, 2, 0, 32, 32), screen(2, 2, 0, 32, 32), screen(20, 3, 0, 32, 32));     // repeated vertex
  g.addTriangle({nan, 0, 0}, {0.5f, 0, 0}, {0, 0.5f, 0});                                        // NaN
  g.addTriangle({-0.5f, -0.5f, 0}, {inf, 0, 0}, {0, 0.5f, 0});                                   // Inf
  g.addTriangle({2, 2, 0}, {3, 2, 0}, {2, 3, 0});                                                // outside
  g.addTriangle(screen(4.6f, 4.6f, 0, 32, 32), screen(5.4f, 4.6f, 0, 32, 32),
                screen(4.6f, 5.4f, 0, 32, 32));                                                // covers no pixel centre
  g.addTriangle(screen(1, 1, 0, 32, 32), screen(31, 1, 0, 32, 32), screen(1, 31, 0, 32, 32));  // valid, CCW
  g.addTriangle(screen(31, 31, 0, 32, 32), screen(31, 2, 0, 32, 32), screen(2, 31, 0, 32, 32));  // valid, CW

  SECTION("without back-face culling the two valid triangles survive")
  {
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(g.mesh());
    std::vector<uint32_t> rgba;
    const clr::FrameStats stats = pipeline.render(test::idSettings(32, 32), rgba);
    CHECK(stats.trianglesIn == 8);
    CHECK(stats.setupTriangles == 2);
    CHECK(stats.trianglesCulled == 6);
    const std::vector<clr::SetupRecord> setup = pipeline.readSetup();
    REQUIRE(setup.size() == 2);
    CHECK(setup[0].triId == 6);
    CHECK(setup[1].triId == 7);
    // The NaN and Inf triangles leave the rest of the scene intact.
    const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::idSettings(32, 32));
    const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {32, 32, false});
    CHECK(test::countDifferences(ids, expected.triId) == 0);
  }
  SECTION("with --cull back the clockwise one goes too")
  {
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(g.mesh());
    std::vector<uint32_t> rgba;
    const clr::FrameStats stats = pipeline.render(test::idSettings(32, 32, glm::mat4(1.0f), true), rgba);
    CHECK(stats.setupTriangles == 1);
    CHECK(pipeline.readSetup().at(0).triId == 6);
  }
}

TEST_CASE("setup culls a small triangle that covers no pixel centre by raster's own test", "[setup]")
{
  const uint32_t W = 16, H = 16;
  auto settings = [&](bool cull) {
    clr::FrameSettings s = test::idSettings(W, H);
    s.cullSampleFree = cull;
    return s;
  };
  SECTION("a centre on the shared diagonal of two one-pixel triangles goes to the one whose edge holds it")
  {
    // The square (4, 4)-(5, 5) halved through its pixel centre (4.5, 4.5):
    // on the first triangle's exclusive (upper right) edge, on the second's
    // inclusive (left) edge.
    Geometry g;
    g.addTriangle(screen(4, 4, 0, W, H), screen(5, 4, 0, W, H), screen(4, 5, 0, W, H));
    g.addTriangle(screen(5, 5, 0, W, H), screen(4, 5, 0, W, H), screen(5, 4, 0, W, H));
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(g.mesh());
    std::vector<uint32_t> rgba;
    CHECK(pipeline.render(settings(false), rgba).setupTriangles == 2);
    const clr::FrameStats stats = pipeline.render(settings(true), rgba);
    CHECK(stats.setupTriangles == 1);
    CHECK(stats.trianglesCulled == 1);
    CHECK(pipeline.readSetup().at(0).triId == 1);
    const std::vector<uint32_t> ids = test::renderTriIds(pipeline, settings(true));
    CHECK(ids[pixel(W, 4, 4)] == 1);
    CHECK(ids == test::renderTriIds(pipeline, settings(false)));
  }
  SECTION("a sliver across two centres' bounds that passes between them")
  {
    Geometry g;
    g.addTriangle(screen(4.4f, 4.6f, 0, W, H), screen(5.6f, 5.6f, 0, W, H), screen(5.6f, 5.65f, 0, W, H));
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(g.mesh());
    std::vector<uint32_t> rgba;
    CHECK(pipeline.render(settings(false), rgba).setupTriangles == 1);
    CHECK(pipeline.render(settings(true), rgba).setupTriangles == 0);
  }
  SECTION("thousands of random small triangles: the oracle's counts, and the same pixels either way")
  {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> position(-2.0f, 66.0f), size(0.1f, 2.5f), angle(0.0f, 6.2832f),
        depth(-0.9f, 0.9f);
    Geometry g;
    for (int i = 0; i < 6000; ++i) {
      const float x = position(rng), y = position(rng), z = depth(rng);
      glm::vec3 corner[3];
      for (glm::vec3& c : corner) {
        const float r = size(rng), a = angle(rng);
        c = screen(x + r * std::cos(a), y + r * std::sin(a), z, 64, 64);
      }
      g.addTriangle(corner[0], corner[1], corner[2]);
    }
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(g.mesh());
    clr::FrameSettings on = test::idSettings(64, 64), off = on;
    off.cullSampleFree = false;
    std::vector<uint32_t> rgba;
    const clr::FrameStats culled = pipeline.render(on, rgba), kept = pipeline.render(off, rgba);
    ref::Options o{64, 64, false};
    const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), o);
    o.cullSampleFree = false;
    CHECK(culled.setupTriangles == expected.setupTriangles);
    CHECK(kept.setupTriangles == ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), o).setupTriangles);
    CHECK(culled.setupTriangles + 500 < kept.setupTriangles);  // premise: many cover no centre
    const std::vector<uint32_t> ids = test::renderTriIds(pipeline, on);
    CHECK(test::countDifferences(ids, expected.triId) == 0);
    CHECK(ids == test::renderTriIds(pipeline, off));
    on.shadeMode = off.shadeMode = CLR_SHADE_LAMBERT;
    std::vector<uint32_t> withCull, withoutCull;
    pipeline.render(on, withCull);
    pipeline.render(off, withoutCull);
    CHECK(withCull == withoutCull);
  }
}

TEST_CASE("fill rule: left and bottom edges are inside, right and top edges outside", "[raster]")
{
  const uint32_t W = 16, H = 16;
  auto covered = [&](glm::vec2 a, glm::vec2 b, glm::vec2 c, uint32_t x, uint32_t y) {
    Geometry g;
    g.addTriangle(screen(a.x, a.y, 0, W, H), screen(b.x, b.y, 0, W, H), screen(c.x, c.y, 0, W, H));
    const std::vector<uint32_t> ids = test::renderTriIds(g, test::idSettings(W, H));
    const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {W, H, false});
    REQUIRE(test::countDifferences(ids, expected.triId) == 0);
    return ids[pixel(W, x, y)] == 0;
  };
  // Pixel centres of column 2 lie on x = 2.5, of row 2 on y = 2.5.
  SECTION("left edge (vertical, going down on a CCW triangle)")
  {
    CHECK(covered({2.5f, 1}, {10, 1}, {2.5f, 12}, 2, 5));
  }
  SECTION("right edge (vertical, going up)")
  {
    CHECK_FALSE(covered({3, 1}, {10.5f, 1}, {10.5f, 12}, 10, 5));
    CHECK(covered({3, 1}, {10.5f, 1}, {10.5f, 12}, 9, 5));
  }
  SECTION("bottom edge (horizontal, left to right)")
  {
    CHECK(covered({1, 2.5f}, {12, 2.5f}, {6, 12}, 6, 2));
  }
  SECTION("top edge (horizontal, right to left)")
  {
    CHECK_FALSE(covered({6, 1}, {12, 9.5f}, {1, 9.5f}, 6, 9));
    CHECK(covered({6, 1}, {12, 9.5f}, {1, 9.5f}, 6, 8));
  }
  SECTION("the same edges with the vertex order reversed (clockwise input)")
  {
    CHECK(covered({2.5f, 12}, {10, 1}, {2.5f, 1}, 2, 5));
    CHECK_FALSE(covered({10.5f, 12}, {10.5f, 1}, {3, 1}, 10, 5));
    CHECK(covered({6, 12}, {12, 2.5f}, {1, 2.5f}, 6, 2));
    CHECK_FALSE(covered({1, 9.5f}, {12, 9.5f}, {6, 1}, 6, 9));
  }
  SECTION("a vertex on a pixel centre is owned by exactly one triangle of a fan")
  {
    // Eight triangles fan around the centre of pixel (8, 8).
    Geometry g;
    const glm::vec2 c(8.5f, 8.5f);
    const glm::vec2 ring[8] = {{14, 8.5f}, {14, 14}, {8.5f, 14}, {3, 14}, {3, 8.5f}, {3, 3}, {8.5f, 3}, {14, 3}};
    for (int k = 0; k < 8; ++k) {
      const glm::vec2 a = ring[k], b = ring[(k + 1) % 8];
      g.addTriangle(screen(c.x, c.y, 0, W, H), screen(a.x, a.y, 0, W, H), screen(b.x, b.y, 0, W, H));
    }
    int owners = 0;
    for (size_t t = 0; t < g.numTris(); ++t) {
      Geometry one;
      one.positions.assign(g.positions.begin() + 9 * t, g.positions.begin() + 9 * t + 9);
      one.indices = {0, 1, 2};
      owners += test::renderTriIds(one, test::idSettings(W, H))[pixel(W, 8, 8)] == 0;
    }
    CHECK(owners == 1);
  }
}

TEST_CASE("barycentrics match the exact edge-function ratios and sum to 1", "[raster]")
{
  const Geometry g = test::randomTriangles(11, 200);
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::keepingVis(test::idSettings(96, 80)));
  const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {96, 80, false});
  REQUIRE(test::countDifferences(ids, expected.triId) == 0);
  const std::vector<VisSample> vis = pipeline.readVis();
  size_t checked = 0;
  for (size_t p = 0; p < vis.size(); ++p) {
    if (vis[p].setupIndex == CLR_NONE) continue;
    // Tolerance: b = float(E) · float(1/area): two roundings of 2^-24
    // relative each, on values <= 1, so 2.5e-7 absolute bounds the error.
    const glm::dvec3 exact = expected.bary[p];
    const double b0 = 1.0 - double(vis[p].b1) - double(vis[p].b2);
    REQUIRE(std::abs(vis[p].b1 - exact.y) <= 2.5e-7);
    REQUIRE(std::abs(vis[p].b2 - exact.z) <= 2.5e-7);
    REQUIRE(std::abs(b0 - exact.x) <= 5e-7);
    REQUIRE(std::abs(exact.x + exact.y + exact.z - 1.0) <= 1e-12);
    REQUIRE(vis[p].depth == expected.depth[p]);
    ++checked;
  }
  CHECK(checked > 1000);
}

TEST_CASE("z-test keeps the nearest fragment, ties go to the earlier triangle", "[raster]")
{
  const uint32_t W = 32, H = 32;
  auto quadPair = [&](float zFirst, float zSecond, float shift) {
    Geometry g;
    g.addTriangle(screen(1, 1, zFirst, W, H), screen(30, 1, zFirst, W, H), screen(1, 30, zFirst, W, H));
    g.addTriangle(screen(1 + shift, 1, zSecond, W, H), screen(30 + shift, 1, zSecond, W, H),
                  screen(1 + shift, 30, zSecond, W, H));
    return test::renderTriIds(g, test::idSettings(W, H));
  };
  SECTION("nearer wins in either input order")
  {
    CHECK(quadPair(0.5f, -0.2f, 0)[pixel(W, 5, 5)] == 1);
    CHECK(quadPair(-0.2f, 0.5f, 0)[pixel(W, 5, 5)] == 0);
  }
  SECTION("equal depth: the earlier triangle wins everywhere, every run")
  {
    Geometry g;
    for (int copy = 0; copy < 64; ++copy)
      g.addTriangle(screen(1, 1, 0.25f, W, H), screen(30, 1, 0.25f, W, H), screen(1, 30, 0.25f, W, H));
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(g.mesh());
    const std::vector<uint32_t> first = test::renderTriIds(pipeline, test::idSettings(W, H));
    size_t covered = 0;
    for (uint32_t id : first) {
      REQUIRE((id == 0 || id == ref::kNone));
      covered += id == 0;
    }
    CHECK(covered > 300);
    for (int run = 0; run < 3; ++run) CHECK(test::renderTriIds(pipeline, test::idSettings(W, H)) == first);
  }
  SECTION("a fragment exactly at the far value fails GL LESS")
  {
    Geometry g;
    g.addTriangle(screen(1, 1, 1.0f, W, H), screen(30, 1, 1.0f, W, H), screen(1, 30, 1.0f, W, H));
    const std::vector<uint32_t> ids = test::renderTriIds(g, test::idSettings(W, H));
    CHECK(std::count(ids.begin(), ids.end(), ref::kNone) == long(ids.size()));
  }
}

TEST_CASE("raster's skip of hidden triangles keeps a fragment that rounding brings in front", "[raster]")
{
  // Raster skips a bin entry whose nearest vertex lies behind the depths
  // kept: every depth of its tile in the CPU shape (raster_tile), the
  // sample's own in the GPU shape (raster_pixel). The interpolated depth
  // can round past the nearest vertex's depth (where the barycentrics'
  // float sum exceeds 1), so the skip keeps a margin. Here an occluding square
  // covers tile 0 just in front of the two near vertices of a steep
  // triangle, four times, before it (all in tile 0 and in one setup batch,
  // so binned in order: the skip has seen the tile covered when the
  // triangle comes, the ninth entry); the pixel centres on the edge
  // between those vertices (a horizontal bottom edge, which the fill rule
  // keeps) are where the sum rounds. For each depth format the search looks
  // for a triangle that the oracle shows somewhere in front of the
  // occluder; the device must show the same pixels. Without the margin the
  // triangle is skipped (in float32 and reversed; unorm24's key steps hide
  // the rounding in the case found).
  const uint32_t W = 32, H = 32;
  const float step = 1.0f / CLR_FIXED_ONE;
  for (uint32_t mode : {CLR_DEPTH_FLOAT32, CLR_DEPTH_UNORM24, CLR_DEPTH_REVERSED}) {
    INFO("depth mode " << clr::depthModeName(mode));
    // Window depth of clip z with w = 1 (raster oracle), and which way is near.
    const bool reversed = mode == CLR_DEPTH_REVERSED;
    const auto window = [&](float z) { return reversed ? z * 1.0f : z * 1.0f * 0.5f + 0.5f; };
    const float toward = reversed ? 1.0f : -1.0f;
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> rowOf(1, CLR_TILE_SIZE / 2), subpixels(0, (CLR_TILE_SIZE - 1) * CLR_FIXED_ONE);
    std::uniform_real_distribution<float> nearDepth(-0.74f, -0.5f), farDepth(0.6f, 0.95f);
    bool found = false;
    for (int attempt = 0; attempt < 4000 && !found; ++attempt) {
      // Step 1: the triangle: vertices 1 and 2 near, on a row of pixel
      // centres (2 right of 1), vertex 0 above them, far.
      const float zNear = toward * -nearDepth(rng), row = float(rowOf(rng)) + 0.5f;
      float x1 = float(subpixels(rng)) * step, x2 = float(subpixels(rng)) * step;
      if (x1 > x2) std::swap(x1, x2);
      if (x2 - x1 < 2.0f) continue;
      const float zFar = toward * -farDepth(rng);
      const glm::vec3 v0 =
          screen(float(subpixels(rng)) * step, row + 1.0f + float(subpixels(rng) / 2) * step, zFar, W, H);
      const glm::vec3 v1 = screen(x1, row, zNear, W, H), v2 = screen(x2, row, zNear, W, H);
      // Step 2: the occluder's depth: the nearest window depth in front of
      // theirs that a clip z gives.
      float zFront = zNear;
      while (window(zFront) == window(zNear)) zFront = std::nextafter(zFront, toward);
      Geometry g;
      const float edge = float(CLR_TILE_SIZE);
      for (int copy = 0; copy < 4; ++copy) {
        g.addTriangle(screen(0, 0, zFront, W, H), screen(edge, 0, zFront, W, H), screen(0, edge, zFront, W, H));
        g.addTriangle(screen(edge, 0, zFront, W, H), screen(edge, edge, zFront, W, H), screen(0, edge, zFront, W, H));
      }
      g.addTriangle(v0, v1, v2);
      ref::Options o{W, H, false};
      o.depthMode = mode;
      const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), o);
      if (std::count(expected.triId.begin(), expected.triId.end(), 8u) == 0) continue;
      // Step 3: a case found; the device must agree.
      INFO("attempt " << attempt);
      clr::FrameSettings settings = test::idSettings(W, H);
      settings.depthMode = mode;
      CHECK(test::countDifferences(test::renderTriIds(g, settings), expected.triId) == 0);
      found = true;
    }
    if (!found) FAIL("no triangle rounded in front of the occluder: the test no longer tests the margin");
  }
}

TEST_CASE("raster walks a tile of more bin entries than the GPU shape's batch", "[raster]")
{
  // The GPU shape copies a tile's records into local memory 256 at a time
  // (raster_pixel): 700 overlapping triangles in one tile, at random depths,
  // take three batches, and the nearest fragment can come from any of them.
  // Under Oclgrind (tests/oclgrind_check.sh) this also checks the batches'
  // barriers for races.
  const uint32_t W = 32, H = 32;
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> corner(0.0f, float(CLR_TILE_SIZE)), depth(-0.9f, 0.9f);
  Geometry g;
  for (int t = 0; t < 700; ++t)
    g.addTriangle(screen(corner(rng), corner(rng), depth(rng), W, H),
                  screen(corner(rng), corner(rng), depth(rng), W, H),
                  screen(corner(rng), corner(rng), depth(rng), W, H));
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::idSettings(W, H));
  const std::vector<uint32_t> offsets = pipeline.readTileOffsets();
  CHECK(offsets[1] - offsets[0] > 2 * CLR_TILE_SIZE * CLR_TILE_SIZE);
  const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {W, H, false});
  CHECK(test::countDifferences(ids, expected.triId) == 0);
  size_t uncovered = 0;  // in tile 0, which the triangles nearly fill
  for (uint32_t y = 0; y < CLR_TILE_SIZE; ++y)
    for (uint32_t x = 0; x < CLR_TILE_SIZE; ++x) uncovered += ids[y * W + x] == ref::kNone;
  CHECK(uncovered < 8);
}

TEST_CASE("binning keeps every triangle, however many share a tile", "[bin]")
{
  const uint32_t W = 64, H = 48;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> cell(0, CLR_TILE_SIZE - 1);
  Geometry g;
  // Step 1: 20000 small triangles inside tile 0, each over a pixel centre.
  const int many = 20000;
  for (int t = 0; t < many; ++t) {
    const float x = cell(rng) + 0.5f, y = cell(rng) + 0.5f;
    g.addTriangle(screen(x - 0.25f, y - 0.25f, 0, W, H), screen(x + 0.5f, y - 0.25f, 0, W, H),
                  screen(x - 0.25f, y + 0.5f, 0, W, H));
  }
  // Step 2: one triangle over the whole viewport.
  g.addTriangle({-3, -3, 0.5f}, {5, -3, 0.5f}, {-3, 5, 0.5f});
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::idSettings(W, H));
  const std::vector<uint32_t> offsets = pipeline.readTileOffsets();
  const std::vector<uint32_t> entries = pipeline.readBinEntries();
  const uint32_t tiles = pipeline.params().tilesX * pipeline.params().tilesY;
  REQUIRE(offsets.size() == tiles + 1);
  CHECK(offsets[1] - offsets[0] == uint32_t(many + 1));
  for (uint32_t t = 1; t < tiles; ++t) CHECK(offsets[t + 1] - offsets[t] == 1);
  CHECK(entries.size() == size_t(many) + tiles);
  std::vector<uint32_t> tile0(entries.begin(), entries.begin() + offsets[1]);
  std::sort(tile0.begin(), tile0.end());
  for (int t = 0; t <= many; ++t) REQUIRE(tile0[t] == uint32_t(t));
  const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {W, H, false});
  CHECK(test::countDifferences(ids, expected.triId) == 0);
}

TEST_CASE("each tile's bin holds exactly the setup triangles whose pixel bounds touch it", "[bin]")
{
  // A coherent mesh of small triangles in row order, as setup's count pass
  // tallies them for the two tiles it counted last (bin_tally) and the emit
  // pass writes them: one-tile triangles, two-tile ones across a tile edge,
  // four-tile ones at tile corners, and every 37th a larger one over several
  // tiles between them, whose two halves share their tiles (the passes bin
  // such a run with one atomic add per tile: bin_count_range_run and
  // bin_fill_range_run). The expected bins come from the records' snapped
  // vertices, as bin_pixel_bounds takes them.
  const uint32_t W = 100, H = 70;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> jitter(-0.3f, 0.3f), depth(-0.9f, 0.9f);
  Geometry g;
  const float cell = 1.7f;
  int n = 0;
  for (float y = 0.2f; y + cell < float(H); y += cell)
    for (float x = 0.2f; x + cell < float(W); x += cell, ++n) {
      const float z = depth(rng), big = n % 37 == 0 ? 30.0f : cell;
      const glm::vec3 a = screen(x + jitter(rng), y + jitter(rng), z, W, H);
      const glm::vec3 b = screen(x + big + jitter(rng), y + jitter(rng), z, W, H);
      const glm::vec3 c = screen(x + jitter(rng), y + cell + jitter(rng), z, W, H);
      g.addTriangle(a, b, c);
      g.addTriangle(b, screen(x + big + jitter(rng), y + cell + jitter(rng), z, W, H), c);
    }
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::idSettings(W, H));
  const std::vector<uint32_t> offsets = pipeline.readTileOffsets();
  const std::vector<uint32_t> entries = pipeline.readBinEntries();
  const std::vector<clr::SetupRecord> setup = pipeline.readSetup();
  const uint32_t tilesX = pipeline.params().tilesX, tiles = tilesX * pipeline.params().tilesY;
  // Step 1: each record's tiles (one sample per pixel, at the centre).
  std::vector<std::vector<uint32_t>> expected(tiles);
  size_t oneTile = 0, twoTiles = 0, more = 0, moreAfterSameRange = 0;
  std::array<int, 4> previousRange{-1, -1, -1, -1};
  for (uint32_t s = 0; s < setup.size(); ++s) {
    const clr::SetupRecord& r = setup[s];
    const int minX = std::min({r.x[0], r.x[1], r.x[2]}), maxX = std::max({r.x[0], r.x[1], r.x[2]});
    const int minY = std::min({r.y[0], r.y[1], r.y[2]}), maxY = std::max({r.y[0], r.y[1], r.y[2]});
    const int half = CLR_FIXED_ONE / 2;
    const int x0 = std::max(0, (minX - half + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS);
    const int y0 = std::max(0, (minY - half + CLR_FIXED_ONE - 1) >> CLR_SUBPIXEL_BITS);
    const int x1 = std::min(int(W) - 1, (maxX - half) >> CLR_SUBPIXEL_BITS);
    const int y1 = std::min(int(H) - 1, (maxY - half) >> CLR_SUBPIXEL_BITS);
    REQUIRE((x0 <= x1 && y0 <= y1));  // setup keeps only triangles over a pixel centre
    const int tx0 = x0 / CLR_TILE_SIZE, tx1 = x1 / CLR_TILE_SIZE, ty0 = y0 / CLR_TILE_SIZE, ty1 = y1 / CLR_TILE_SIZE;
    const int count = (tx1 - tx0 + 1) * (ty1 - ty0 + 1);
    oneTile += count == 1;
    twoTiles += count == 2;
    more += count > 2;
    const std::array<int, 4> range{tx0, ty0, tx1, ty1};
    moreAfterSameRange += count > 2 && range == previousRange;
    previousRange = range;
    for (int ty = ty0; ty <= ty1; ++ty)
      for (int tx = tx0; tx <= tx1; ++tx) expected[ty * tilesX + tx].push_back(s);
  }
  // Step 2: the bins, tile by tile, in any order within a tile.
  REQUIRE(offsets.size() == tiles + 1);
  CHECK(offsets[tiles] == entries.size());
  for (uint32_t t = 0; t < tiles; ++t) {
    std::vector<uint32_t> bin(entries.begin() + offsets[t], entries.begin() + offsets[t + 1]);
    std::sort(bin.begin(), bin.end());
    CHECK(bin == expected[t]);
  }
  CHECK((oneTile > 1000 && twoTiles > 100 && more > 20));  // the premise: all three kinds occur,
  CHECK(moreAfterSameRange > 5);                           // and runs on one range of several tiles
  const ref::Result reference = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {W, H, false});
  CHECK(test::countDifferences(ids, reference.triId) == 0);
}

TEST_CASE("near-plane clipping: no projection through w <= 0, same pixels as the oracle", "[clip]")
{
  const uint32_t W = 80, H = 60;
  const glm::mat4 mvp = perspectiveCamera({0, 1, 0}, {0, 1, -1}, float(W) / H, 0.5f, 50.0f);
  Geometry g;
  g.addTriangle({-2, 0, 3}, {2, 0, -10}, {-2, 0.5f, -10});  // one vertex behind the eye
  g.addTriangle({1, 2, 2}, {3, 2, 4}, {2, 1.5f, -8});       // two vertices behind
  g.addTriangle({-1, 0, 1}, {1, 0, 1}, {0, 1, 2});          // wholly behind: culled
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  std::vector<uint32_t> rgba;
  const clr::FrameStats stats = pipeline.render(test::keepingVis(test::idSettings(W, H, mvp)), rgba);
  CHECK(stats.trianglesClipped == 2);
  CHECK(stats.trianglesCulled == 1);
  CHECK(stats.setupTriangles == 3);
  // ClipBary rows are convex weights of the input vertices.
  size_t live = 0;
  for (const ClipBary& cb : pipeline.readClipBary()) {
    if (cb.flags & CLR_FLAG_DEAD) continue;
    ++live;
    for (int i = 0; i < 3; ++i) {
      const float sum = cb.w[i][0] + cb.w[i][1] + cb.w[i][2];
      CHECK(std::abs(sum - 1.0f) < 1e-6f);  // three float lerps of weights summing to 1
      for (int j = 0; j < 3; ++j) CHECK((cb.w[i][j] >= -1e-6f && cb.w[i][j] <= 1.0f + 1e-6f));
    }
  }
  CHECK(live == 3);  // the three setup triangles are all clipped ones
  for (const VisSample& v : pipeline.readVis())
    REQUIRE((std::isfinite(v.depth) && std::isfinite(v.b1) && std::isfinite(v.b2)));
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::idSettings(W, H, mvp));
  const ref::Result expected = ref::rasterize(g.positions, g.indices, mvp, {W, H, false});
  CHECK(expected.clippedTriangles == 2);
  CHECK(test::countDifferences(ids, expected.triId) == 0);
  CHECK(std::count(ids.begin(), ids.end(), 0u) > 200);
  CHECK(std::count(ids.begin(), ids.end(), 1u) > 50);
}

TEST_CASE("the kernels divide and take square roots correctly rounded", "[device]")
{
  // Setup's 1 / w places the vertices, so a division off by an ulp moves a
  // vertex to another subpixel. NVIDIA's driver (H100, 580.159) rounded it
  // so without -cl-fp32-correctly-rounded-divide-sqrt: 1 to 5 pixels of
  // 30,000 took other triangles than the oracle's in the differential tests.
  const clr::ClContext& ctx = test::context();
  const bool offered =
      (ctx.info.device.getInfo<CL_DEVICE_SINGLE_FP_CONFIG>() & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
  REQUIRE(offered);  // every device clraster has run on offers it; without it coverage may part from the oracle
  CHECK(ctx.buildOptions().find("-cl-fp32-correctly-rounded-divide-sqrt") != std::string::npos);
  // Step 1: the frame program's options on a kernel of divisions and roots.
  const char* source = R"CLC(
__kernel void divide_sqrt(__global const float* in, __global float* quotient, __global float* root)
{
  const size_t i = get_global_id(0);
  quotient[i] = 1.0f / in[i];
  root[i] = sqrt(in[i]);
}
)CLC";
  cl::Program program(ctx.context, std::string(source));
  program.build({ctx.info.device}, ctx.buildOptions().c_str());
  // Step 2: w values of every magnitude a clip-space w takes, each mantissa random.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> mantissa(1.0f, 2.0f);
  std::uniform_int_distribution<int> exponent(-40, 40);
  const size_t n = 1 << 16;
  std::vector<float> in(n), quotient(n), root(n);
  for (float& w : in) w = std::ldexp(mantissa(rng), exponent(rng));
  cl::Buffer inBuffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, n * sizeof(float), in.data());
  cl::Buffer quotientBuffer(ctx.context, CL_MEM_WRITE_ONLY, n * sizeof(float));
  cl::Buffer rootBuffer(ctx.context, CL_MEM_WRITE_ONLY, n * sizeof(float));
  cl::Kernel kernel(program, "divide_sqrt");
  kernel.setArg(0, inBuffer), kernel.setArg(1, quotientBuffer), kernel.setArg(2, rootBuffer);
  ctx.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(n));
  ctx.queue.enqueueReadBuffer(quotientBuffer, CL_TRUE, 0, n * sizeof(float), quotient.data());
  ctx.queue.enqueueReadBuffer(rootBuffer, CL_TRUE, 0, n * sizeof(float), root.data());
  // Step 3: bit for bit what the host's IEEE division and square root give.
  size_t wrongQuotients = 0, wrongRoots = 0;
  for (size_t i = 0; i < n; ++i) {
    wrongQuotients += quotient[i] != 1.0f / in[i];
    wrongRoots += root[i] != std::sqrt(in[i]);
  }
  CHECK(wrongQuotients == 0);
  CHECK(wrongRoots == 0);
}

TEST_CASE("a kernel build failure reports the device's build log", "[device]")
{
  const clr::ClContext& ctx = test::context();
  try {
    // CLR_TILE_SIZE is spliced into array sizes and attributes: a non-number breaks the build.
    clr::buildProgram(ctx.context, ctx.info.device, "-cl-std=CL1.2 -D CLR_TILE_SIZE=not_a_number");
    FAIL("the build should have failed");
  } catch (const clr::Error& e) {
    const std::string message = e.what();
    CHECK(message.find("kernel build failed on " + ctx.info.name) != std::string::npos);
    CHECK(message.find("not_a_number") != std::string::npos);  // quoted by the compiler's log
  }
}

TEST_CASE("scan_chunks gives exclusive sums and non-zero counts and lists setup sources", "[scan]")
{
  // scan.cl's three phases launched as the pipeline launches them (scan.cpp),
  // in the device's work shape, against sums computed here: plain scans of
  // uint counts (with values near 2^26, so sums pass 2^32 and the 64-bit
  // total and the uint entries' wrap are checked), the same with the
  // non-zero counts, and the setup counts' listing (bytes 0, 1 or
  // CLR_MAX_SUBTRIS). Sizes around a step (64 values) and a chunk, and one
  // past 4096 chunks of 64, where a chunk spans several steps.
  const clr::ClContext& ctx = test::context();
  std::mt19937 rng(23);
  for (uint32_t n : {1u, 63u, 64u, 65u, 1000u, 4096u * 64u + 4321u}) {
    INFO("n = " << n);
    const clr::ScanChunks c = clr::scanChunks(n);
    for (int mode = 0; mode < 3; ++mode) {  // plain, with non-zero counts, listing
      INFO("mode " << mode);
      const bool alsoNonZero = mode == 1, listing = mode == 2;
      // Step 1: counts, mostly zero or small, some large.
      std::vector<uint32_t> values(size_t(n) + 1, 0u);
      std::vector<uint8_t> bytes(n);
      std::uniform_int_distribution<int> kind(0, 9);
      for (uint32_t i = 0; i < n; ++i) {
        const int k = kind(rng);
        values[i] = k < 4 ? 0u : k < 8 ? uint32_t(k) : (1u << 26) + uint32_t(k);
        bytes[i] = uint8_t(k < 3 ? 0 : k < 8 ? 1 : CLR_MAX_SUBTRIS);
      }
      // Step 2: the three phases.
      uint64_t listed = 0;
      for (uint8_t b : bytes) listed += b;
      const size_t secondSize = listing ? size_t(listed) + c.count : size_t(n) + 1;
      cl::Buffer data(ctx.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, values.size() * 4, values.data());
      cl::Buffer counts(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes.size(), bytes.data());
      cl::Buffer partials(ctx.context, CL_MEM_READ_WRITE, 2 * (size_t(c.count) + 1) * 8);
      cl::Buffer second(ctx.context, CL_MEM_READ_WRITE, secondSize * 4);
      const std::vector<uint32_t> zeros(CLR_NUM_COUNTERS, 0u);
      cl::Buffer counters(ctx.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, zeros.size() * 4,
                          const_cast<uint32_t*>(zeros.data()));
      const cl::NDRange group(CLR_SCAN_GROUP(ctx.lanes));
      for (uint32_t phase : {CLR_SCAN_REDUCE, CLR_SCAN_PARTIALS, CLR_SCAN_APPLY}) {
        cl::Kernel kernel(ctx.program, "scan_chunks");
        cl_uint a = 0;
        kernel.setArg(a++, data), kernel.setArg(a++, data), kernel.setArg(a++, n), kernel.setArg(a++, c.size);
        kernel.setArg(a++, c.count), kernel.setArg(a++, partials), kernel.setArg(a++, second);
        kernel.setArg(a++, counts), kernel.setArg(a++, counters);
        kernel.setArg(a++, uint32_t(CLR_COUNTER_SETUP_TOTAL)), kernel.setArg(a++, uint32_t(CLR_COUNTER_SLOT_TOTAL));
        kernel.setArg(a++, phase), kernel.setArg(a++, uint32_t(alsoNonZero)), kernel.setArg(a++, uint32_t(listing));
        const cl::NDRange items = phase == CLR_SCAN_PARTIALS ? group : clr::scanChunkItems(ctx.lanes, c.count);
        ctx.queue.enqueueNDRangeKernel(kernel, cl::NullRange, items, group);
      }
      std::vector<uint32_t> scanned(values.size()), seconds(secondSize), totals(CLR_NUM_COUNTERS);
      ctx.queue.enqueueReadBuffer(data, CL_TRUE, 0, scanned.size() * 4, scanned.data());
      ctx.queue.enqueueReadBuffer(second, CL_TRUE, 0, seconds.size() * 4, seconds.data());
      ctx.queue.enqueueReadBuffer(counters, CL_TRUE, 0, totals.size() * 4, totals.data());
      // Step 3: the sums here, compared.
      const auto total64 = [&](int at) { return uint64_t(totals[at]) | uint64_t(totals[at + 1]) << 32; };
      uint64_t sum = 0, nonZero = 0;
      size_t wrongSums = 0, wrongNonZero = 0, wrongSources = 0;
      for (uint32_t i = 0; i < n; ++i) {
        if (listing) {
          for (uint32_t k = 0; k < bytes[i]; ++k)
            wrongSources += seconds[sum + k] != (bytes[i] == 1 ? i : CLR_SOURCE_CLIPPED | i);
          sum += bytes[i];
          continue;
        }
        wrongSums += scanned[i] != uint32_t(sum);
        wrongNonZero += alsoNonZero && seconds[i] != uint32_t(nonZero);
        sum += values[i];
        nonZero += values[i] != 0;
      }
      CHECK(wrongSums == 0);
      CHECK(wrongNonZero == 0);
      CHECK(wrongSources == 0);
      CHECK(total64(CLR_COUNTER_SETUP_TOTAL) == sum);
      if (!listing) CHECK(scanned[n] == uint32_t(sum));
      if (alsoNonZero) CHECK(seconds[n] == uint32_t(nonZero));
      if (alsoNonZero) CHECK(total64(CLR_COUNTER_SLOT_TOTAL) == nonZero);
      if (n > 4096u * 64u && !listing) CHECK(sum > (uint64_t(1) << 32));  // the totals need 64 bits
    }
  }
}
