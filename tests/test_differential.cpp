// test_differential.cpp — thousands of random triangles, slivers and
// shared-edge meshes through the kernels and through the scalar oracle:
// the triangle-ID images must be identical, with the bounding-box scan and
// with exact span tables (both exact methods of coverage).
#include "test_support.h"

#include "render/flags.h"
#include "pipeline/pipeline.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cstring>
#include <random>

namespace {

const uint32_t kWidth = 200, kHeight = 150;  // not a multiple of the tile size

glm::mat4 camera()
{
  return glm::perspective(glm::radians(50.0f), float(kWidth) / kHeight, 0.25f, 40.0f) *
         glm::lookAt(glm::vec3(0.3f, 0.8f, 6.0f), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
}

// The exact traversals, one per GENERATE run of a test case.
uint32_t exactTraversal()
{
  return GENERATE(CLR_TRAVERSAL_BBOX, CLR_TRAVERSAL_SPANS);
}

clr::FrameSettings settingsFor(uint32_t traversal, uint32_t width, uint32_t height,
                               const glm::mat4& mvp = glm::mat4(1.0f), bool cullBack = false)
{
  clr::FrameSettings s = test::idSettings(width, height, mvp, cullBack);
  s.traversal = traversal;
  return s;
}

// The kernels' ids against the oracle's through camera(). Under Oclgrind
// (test::underOclgrind) at 40 x 30 pixels: the same view, so the same
// triangles set up, clipped and culled, on a 25th of the pixels, still not a
// multiple of the tile size.
void compare(const test::Geometry& g, uint32_t traversal, bool cullBack = false)
{
  const glm::mat4 mvp = camera();
  const uint32_t width = test::underOclgrind() ? 40 : kWidth, height = test::underOclgrind() ? 30 : kHeight;
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  std::vector<uint32_t> rgba;
  const clr::FrameSettings settings = settingsFor(traversal, width, height, mvp, cullBack);
  const clr::FrameStats stats = pipeline.render(settings, rgba);
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, settings);
  INFO("traversal " << clr::traversalName(traversal));
  const ref::Result expected = ref::rasterize(g.positions, g.indices, mvp, {width, height, cullBack});
  size_t covered = 0;
  for (uint32_t id : expected.triId) covered += id != ref::kNone;
  INFO("triangles " << g.numTris() << ", covered pixels " << covered);
  CHECK(stats.setupTriangles == expected.setupTriangles);
  CHECK(stats.trianglesClipped == expected.clippedTriangles);
  CHECK(stats.trianglesCulled == expected.culledTriangles);
  CHECK(test::countDifferences(ids, expected.triId) == 0);
  CHECK(covered > 0);
}

}  // namespace

TEST_CASE("differential: random overlapping triangles, some through the near plane", "[differential]")
{
  const uint32_t traversal = exactTraversal();
  const unsigned seed = GENERATE(1u, 2u, 3u);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> centre(-4.0f, 4.0f), depth(-8.0f, 7.0f), size(0.02f, 3.0f), unit(-1, 1);
  test::Geometry g;
  for (int t = 0; t < 3000; ++t) {
    const glm::vec3 c(centre(rng), centre(rng), depth(rng));
    const float s = size(rng) * (t % 10 == 0 ? 4.0f : 1.0f);
    g.addTriangle(c + s * glm::vec3(unit(rng), unit(rng), unit(rng)),
                  c + s * glm::vec3(unit(rng), unit(rng), unit(rng)),
                  c + s * glm::vec3(unit(rng), unit(rng), unit(rng)));
  }
  compare(g, traversal);
  compare(g, traversal, true);
}

TEST_CASE("differential: more near-plane crossings than the initial clip list holds", "[differential][clip]")
{
  const uint32_t traversal = exactTraversal();
  // 3000 triangles straddling the eye's plane: the clip list (1024 at first)
  // must grow and the frame be recounted, with nothing lost.
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> coord(-3.0f, 3.0f), behind(6.5f, 9.0f), ahead(-4.0f, 4.0f);
  test::Geometry g;
  for (int t = 0; t < 3000; ++t)
    g.addTriangle({coord(rng), coord(rng), behind(rng)}, {coord(rng), coord(rng), ahead(rng)},
                  {coord(rng), coord(rng), ahead(rng)});
  compare(g, traversal);
}

TEST_CASE("differential: slivers thinner than a subpixel", "[differential]")
{
  const uint32_t traversal = exactTraversal();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> coord(-3.0f, 3.0f), depth(-3.0f, 3.0f), tiny(-2e-4f, 2e-4f);
  test::Geometry g;
  for (int t = 0; t < 3000; ++t) {
    const glm::vec3 a(coord(rng), coord(rng), depth(rng)), b(coord(rng), coord(rng), depth(rng));
    const glm::vec3 mid = 0.5f * (a + b) + glm::vec3(tiny(rng), tiny(rng), tiny(rng));
    g.addTriangle(a, b, mid);
  }
  compare(g, traversal);
}

TEST_CASE("differential: shared-edge meshes (jittered grids at several depths)", "[differential]")
{
  const uint32_t traversal = exactTraversal();
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> jitter(-0.3f, 0.3f);
  test::Geometry g;
  for (int layer = 0; layer < 4; ++layer) {
    const int n = 24;
    std::vector<uint32_t> ids;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        ids.push_back(g.addVertex({-5 + 10.0f * i / n + jitter(rng) * 0.4f, -4 + 8.0f * j / n + jitter(rng) * 0.4f,
                                   -2.0f * layer + jitter(rng)}));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const uint32_t v = ids[j * (n + 1) + i], r = v + 1, u = v + n + 1, ur = u + 1;
        g.indices.insert(g.indices.end(), {v, r, ur, v, ur, u});
      }
  }
  compare(g, traversal);
}

TEST_CASE("differential: setup skips clusters beside the view and keeps those partly in it", "[differential][setup]")
{
  const uint32_t traversal = exactTraversal();
  // A field of 9 x 9 patches of 16 x 8 quads: 256 triangles each, one of
  // setup's clusters (CLR_CLUSTER_TRIS) per patch, wider than the view, so
  // that the count pass skips the patches wholly beside it, unloaded
  // (setup_cluster_outside), and must keep those that straddle its edges.
  // (51 of the patches lie wholly beside the view, 18 straddle its edges,
  // 12 lie inside: their corners projected with camera().)
  static_assert(16 * 8 * 2 == CLR_CLUSTER_TRIS, "one patch per cluster");
  test::Geometry g;
  for (int pj = -4; pj <= 4; ++pj)
    for (int pi = -4; pi <= 4; ++pi) {
      const glm::vec3 corner(pi * 2.3f - 1.0f, pj * 1.4f - 0.6f, -1.0f - 0.4f * float((pi + pj) & 3));
      const uint32_t first = g.addVertex(corner);
      for (int j = 0; j <= 8; ++j)
        for (int i = 0; i <= 16; ++i)
          if (i || j) g.addVertex(corner + glm::vec3(0.125f * i, 0.15f * j, 0.05f * float(i % 3)));
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 16; ++i) {
          const uint32_t v = first + j * 17 + i, r = v + 1, u = v + 17, ur = u + 1;
          g.indices.insert(g.indices.end(), {v, r, ur, v, ur, u});
        }
    }
  REQUIRE(g.numTris() == 81 * CLR_CLUSTER_TRIS);
  compare(g, traversal);
  compare(g, traversal, true);
}

TEST_CASE("differential: setup's clusters inside the view, and beside its near and far planes", "[differential][setup]")
{
  const uint32_t traversal = exactTraversal();
  // Patches of 16 x 8 quads, one of setup's clusters each: the count pass
  // takes a cluster whose corners all lie inside every plane as simple
  // without classifying its triangles (setup_cluster_place). Patches wholly
  // in view; two of them with a vertex at -inf x or NaN y (their bounds are
  // NaN, so classify culls the non-finite triangles: with the bounds over
  // the finite vertices only, the -inf vertex snaps and draws across the
  // view); one between the eye and the near plane, small enough to lie
  // inside the side planes there; one through the far plane. (Without the
  // near or the far plane in the inside test, this test fails.)
  static_assert(16 * 8 * 2 == CLR_CLUSTER_TRIS, "one patch per cluster");
  test::Geometry g;
  const auto patch = [&g](glm::vec3 corner, glm::vec3 across, glm::vec3 up, float wobble = 0.03f) {
    const uint32_t first = uint32_t(g.positions.size() / 3);
    for (int j = 0; j <= 8; ++j)
      for (int i = 0; i <= 16; ++i)
        g.addVertex(corner + (float(i) / 16) * across + (float(j) / 8) * up + glm::vec3(0, 0, wobble * float(i % 3)));
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 16; ++i) {
        const uint32_t v = first + j * 17 + i, r = v + 1, u = v + 17, ur = u + 1;
        g.indices.insert(g.indices.end(), {v, r, ur, v, ur, u});
      }
    return first;
  };
  for (int k = 0; k < 6; ++k)
    patch({-2.0f + 0.7f * float(k % 3), -1.5f + 1.2f * float(k / 3), -0.5f * float(k % 2)}, {1.1f, 0.2f, 0.3f},
          {0.1f, 0.9f, 0.0f});
  const uint32_t infinite = patch({-1.0f, 0.2f, 1.0f}, {1.2f, 0.0f, 0.0f}, {0.0f, 0.8f, 0.2f});
  g.positions[3 * (infinite + 40)] = -INFINITY;
  const uint32_t nan = patch({0.4f, -0.9f, 1.5f}, {1.0f, 0.1f, 0.0f}, {0.0f, 0.7f, 0.0f});
  g.positions[3 * (nan + 77) + 1] = NAN;
  // The eye is at (0.3, 0.8, 6) looking at the origin; the near plane 0.25 away.
  const glm::vec3 eye(0.3f, 0.8f, 6.0f), ahead = glm::normalize(-eye);
  patch(eye + 0.1f * ahead + glm::vec3(-0.002f, 0.0f, 0.0f), {0.004f, 0.0f, 0.0f}, 0.25f * ahead, 0.0f);
  patch(eye + 37.0f * ahead + glm::vec3(-3.0f, -2.0f, 0.0f), {6.0f, 0.0f, 0.0f}, 6.0f * ahead + glm::vec3(0, 4, 0));
  REQUIRE(g.numTris() == 10 * CLR_CLUSTER_TRIS);
  compare(g, traversal);
}

TEST_CASE("differential: triangles at the bound of 32-bit edge functions", "[differential][raster]")
{
  const uint32_t traversal = exactTraversal();
  // raster evaluates edge functions in 32 bits when a triangle's bounds span
  // at most 64 pixels each way (CLR_EDGE32_SPAN), in 64 bits otherwise:
  // overlapping triangles just under, at and over that span, and large ones
  // whose edge functions overflow 32 bits, wide, tall and sliver-thin, in
  // both windings, must match the 64-bit oracle. (A bound of 256 pixels
  // instead makes this test fail.)
  const uint32_t size = 512;
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), depth(-0.9f, 0.9f);
  const float spans[] = {63.5f, 63.99f, 64.0f, 64.01f, 64.5f, 30.0f, 200.0f, 400.0f};
  test::Geometry g;
  for (int t = 0; t < 1500; ++t) {
    const float w = spans[t % 8], h = t % 3 == 0 ? w : spans[(t / 8) % 8] * (t % 5 == 0 ? 0.02f : 1.0f);
    const float x0 = unit(rng) * (float(size) - w), y0 = unit(rng) * (float(size) - h);
    glm::vec2 v[3] = {{x0, y0}, {x0 + w, y0 + unit(rng) * h}, {x0 + unit(rng) * w, y0 + h}};
    if (t % 2) std::swap(v[1], v[2]);
    g.addTriangle(test::screen(v[0].x, v[0].y, depth(rng), size, size),
                  test::screen(v[1].x, v[1].y, depth(rng), size, size),
                  test::screen(v[2].x, v[2].y, depth(rng), size, size));
  }
  const std::vector<uint32_t> ids = test::renderTriIds(g, settingsFor(traversal, size, size));
  const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {size, size, false});
  size_t covered = 0;
  for (uint32_t id : expected.triId) covered += id != ref::kNone;
  CHECK(covered > size * size / 2);
  INFO("traversal " << clr::traversalName(traversal));
  CHECK(test::countDifferences(ids, expected.triId) == 0);
}

TEST_CASE("differential: huge triangles whose edge functions leave 32 bits inside a tile", "[differential][raster]")
{
  const uint32_t traversal = exactTraversal();
  // raster tests a large triangle's tile rows in 32 bits where all three
  // edge functions fit an int over the rows kept (near its edges), and
  // keeps only the rows an edge can hold (raster_segment_rows): triangles
  // reaching 30000 pixels beyond a 256-pixel viewport, edges long and
  // nearly level (a row step beyond 2^31) or tall (a spread over 16 lanes
  // beyond 2^31), wide ones whose edge functions leave 32 bits a few rows
  // into a tile, and ones with a vertex inside, in both windings, must
  // match the 64-bit oracle. (Without either bound of that fit, with the
  // fit checked at the first row only, or keeping a row less at either end,
  // this test fails.)
  const uint32_t size = 256;
  const float reach = 30000.0f;
  std::mt19937 rng(34);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), far(-reach, reach + size);
  test::Geometry g;
  for (int t = 0; t < 1200; ++t) {
    const glm::vec2 inside(unit(rng) * size, unit(rng) * size), offset(unit(rng) * 8.0f - 4.0f, unit(rng) * 8.0f);
    glm::vec2 v[3];
    switch (t % 6) {
      case 0:  // a long, nearly level sliver through the viewport
        v[0] = {-reach, inside.y};
        v[1] = {reach, inside.y + offset.x};
        v[2] = {unit(rng) * size, inside.y + offset.y};
        break;
      case 1:  // a tall sliver
        v[0] = {inside.x, -reach};
        v[1] = {inside.x + offset.x, reach};
        v[2] = {inside.x + offset.y, unit(rng) * size};
        break;
      case 4:  // 2200-4300 pixels tall, 1-4 wide: an edge spreads beyond 2^31 over 16 lanes, one side of it
               // within an int
      {
        const float h = 2200.0f + 2100.0f * unit(rng), w = 1.0f + 3.0f * unit(rng);
        v[0] = {inside.x, inside.y - h / 2};
        v[1] = {inside.x + offset.x, inside.y + h / 2};
        v[2] = {inside.x + w, inside.y + (unit(rng) - 0.5f) * h};
        break;
      }
      case 5:  // 2000-5000 pixels wide, 20-60 tall: an edge function leaves 32 bits a few rows into a tile
      {
        const float w = 2000.0f + 3000.0f * unit(rng), h = 20.0f + 40.0f * unit(rng);
        v[0] = {inside.x - w / 2, inside.y};
        v[1] = {inside.x + w / 2, inside.y + offset.x};
        v[2] = {inside.x + (unit(rng) - 0.5f) * w, inside.y + h};
        break;
      }
      case 2:  // one vertex inside, two far away
        v[0] = inside;
        v[1] = {far(rng), far(rng)};
        v[2] = {far(rng), far(rng)};
        break;
      default:  // all three far away
        v[0] = {far(rng), far(rng)};
        v[1] = {far(rng), far(rng)};
        v[2] = {far(rng), far(rng)};
    }
    if (t % 12 >= 6) std::swap(v[1], v[2]);
    // Slivers in front, the triangles that cover the viewport behind them.
    const float z0 = t % 6 < 2 || t % 6 >= 4 ? -0.9f : t % 6 == 2 ? -0.3f : 0.3f;
    g.addTriangle(test::screen(v[0].x, v[0].y, z0 + 0.6f * unit(rng), size, size),
                  test::screen(v[1].x, v[1].y, z0 + 0.6f * unit(rng), size, size),
                  test::screen(v[2].x, v[2].y, z0 + 0.6f * unit(rng), size, size));
  }
  const std::vector<uint32_t> ids = test::renderTriIds(g, settingsFor(traversal, size, size));
  const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {size, size, false});
  size_t covered = 0;
  std::vector<bool> shown(g.numTris(), false);
  for (uint32_t id : expected.triId)
    if (id != ref::kNone) {
      ++covered;
      shown[id] = true;
    }
  INFO("triangles shown: " << std::count(shown.begin(), shown.end(), true) << ", traversal "
                           << clr::traversalName(traversal));
  CHECK(covered == size * size);
  CHECK(std::count(shown.begin(), shown.end(), true) > 100);
  CHECK(test::countDifferences(ids, expected.triId) == 0);
}

TEST_CASE("differential: one-pixel and 16-pixel-row raster kernels agree bit for bit", "[differential][raster]")
{
  // The GPU shape (one work-item per pixel) is checked here on the test
  // device too, for the exact traversals and for the float walk.
  const uint32_t traversal = GENERATE(CLR_TRAVERSAL_BBOX, CLR_TRAVERSAL_SPANS, CLR_TRAVERSAL_SPANS_FLOAT);
  INFO("traversal " << clr::traversalName(traversal));
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> coord(-4.0f, 4.0f), depth(-6.0f, 6.0f), unit(-1, 1);
  test::Geometry g;
  for (int t = 0; t < 2000; ++t) {
    const glm::vec3 c(coord(rng), coord(rng), depth(rng));
    g.addTriangle(c + glm::vec3(unit(rng), unit(rng), unit(rng)), c + glm::vec3(unit(rng), unit(rng), unit(rng)),
                  c + glm::vec3(unit(rng), unit(rng), unit(rng)));
  }
  std::vector<std::vector<VisSample>> vis;
  for (int row : {1, 16}) {
    clr::ClContext ctx(test::context().info.name, row);
    clr::Pipeline pipeline(ctx);
    pipeline.uploadScene(g.mesh());
    std::vector<uint32_t> rgba;
    pipeline.render(settingsFor(traversal, kWidth, kHeight, camera()), rgba);
    vis.push_back(pipeline.readVis());
  }
  REQUIRE(vis[0].size() == vis[1].size());
  size_t covered = 0;
  for (size_t p = 0; p < vis[0].size(); ++p) {
    REQUIRE(std::memcmp(&vis[0][p], &vis[1][p], sizeof(VisSample)) == 0);
    covered += vis[0][p].setupIndex != CLR_NONE;
  }
  CHECK(covered > 1000);
}
