// test_setup.cpp — triangle setup on the device (setup.cl): snapping to
// the 1/256-pixel grid, orientation, and the culling of degenerate,
// non-finite, outside, back-facing and sample-free triangles, checked against
// exact values and the oracle.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using test::Geometry;
using test::pixel;
using test::screen;

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
    // (A quarter of them under Oclgrind: the same culls, fewer of each.)
    const int count = test::underOclgrind() ? 1500 : 6000;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> position(-2.0f, 66.0f), size(0.1f, 2.5f), angle(0.0f, 6.2832f),
        depth(-0.9f, 0.9f);
    Geometry g;
    for (int i = 0; i < count; ++i) {
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
    CHECK(culled.setupTriangles + count / 12 < kept.setupTriangles);  // premise: many cover no centre
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
