// test_raster.cpp — the raster kernel on small crafted scenes: the fill
// rule, barycentrics, the z-test and its ties, the skip of hidden bin
// entries, and bins longer than the GPU shape's batch, against the oracle.
#include "render/depth.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using test::Geometry;
using test::pixel;
using test::screen;

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
