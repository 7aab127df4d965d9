// test_watertight.cpp — a jittered grid mesh that covers the viewport must
// cover every pixel exactly once: no holes, no double hits. Coverage counts
// come from the kernels themselves: the triangles are split into 18 classes
// whose members never touch (cell (i mod 3, j mod 3), lower or upper half),
// each class is rendered alone, and the per-pixel counts are summed. Both
// exact traversals (bounding-box scan, span tables) must pass.
#include "test_support.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <random>

namespace {

// Counts, per pixel, how many triangles of the mesh cover its centre.
std::vector<int> coverageCounts(const std::vector<glm::vec3>& grid, int n, const clr::FrameSettings& settings)
{
  std::vector<int> counts(size_t(settings.width) * settings.height, 0);
  for (int cls = 0; cls < 18; ++cls) {
    test::Geometry g;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if ((i % 3) * 6 + (j % 3) * 2 + 0 != cls && (i % 3) * 6 + (j % 3) * 2 + 1 != cls) continue;
        const glm::vec3 v = grid[j * (n + 1) + i], r = grid[j * (n + 1) + i + 1];
        const glm::vec3 u = grid[(j + 1) * (n + 1) + i], ur = grid[(j + 1) * (n + 1) + i + 1];
        if (cls % 2 == 0)
          g.addTriangle(v, r, ur);
        else
          g.addTriangle(v, ur, u);
      }
    if (g.numTris() == 0) continue;
    const std::vector<uint32_t> ids = test::renderTriIds(g, settings);
    for (size_t p = 0; p < ids.size(); ++p) counts[p] += ids[p] != ref::kNone;
  }
  return counts;
}

}  // namespace

TEST_CASE("watertight: a jittered screen grid covers every pixel exactly once", "[watertight]")
{
  const uint32_t W = 128, H = 128;
  const int n = 20;
  std::mt19937 rng(GENERATE(21u, 22u));
  // Jitter on the 1/256 grid, with a share of vertices exactly on pixel
  // centres and on pixel-centre rows/columns, where the fill rule decides.
  // The jitter (at most 300/256 + 1 px against 7.2 px cells) keeps every
  // quad convex, so the mesh never folds over itself.
  std::vector<glm::vec3> grid;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      glm::vec2 p(-8.0f + (W + 16.0f) * i / n, -8.0f + (H + 16.0f) * j / n);
      const bool border = i == 0 || j == 0 || i == n || j == n;
      if (!border) p = test::jitterVertex(p.x, p.y, 300, rng);
      grid.push_back(test::screen(p.x, p.y, 0.0f, W, H));
    }
  // Premise: no triangle is inverted, so a double hit would be a raster bug.
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const glm::vec3 v = grid[j * (n + 1) + i], r = grid[j * (n + 1) + i + 1];
      const glm::vec3 u = grid[(j + 1) * (n + 1) + i], ur = grid[(j + 1) * (n + 1) + i + 1];
      auto area = [](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      };
      REQUIRE(area(v, r, ur) > 0);
      REQUIRE(area(v, ur, u) > 0);
    }
  clr::FrameSettings settings = test::idSettings(W, H);
  settings.traversal = GENERATE(CLR_TRAVERSAL_BBOX, CLR_TRAVERSAL_SPANS);
  INFO("traversal " << settings.traversal);
  const std::vector<int> counts = coverageCounts(grid, n, settings);
  size_t holes = 0, doubles = 0;
  for (int c : counts) holes += c == 0, doubles += c > 1;
  CHECK(holes == 0);
  CHECK(doubles == 0);
}

TEST_CASE("watertight: a ground grid clipped by the near plane has no seams", "[watertight][clip]")
{
  const uint32_t W = 160, H = 120;
  const int n = 24;
  // The grid runs from behind the eye to far ahead, so rows of triangles
  // are clipped by the near plane and meet along clipped edges.
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> jitter(-0.2f, 0.2f);
  std::vector<glm::vec3> grid;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      grid.push_back({-60.0f + 120.0f * i / n + (border ? 0 : jitter(rng)), 0.0f,
                      10.0f - 70.0f * j / n + (border ? 0 : jitter(rng))});
    }
  const glm::mat4 mvp = glm::perspective(glm::radians(70.0f), float(W) / H, 0.1f, 200.0f) *
                        glm::lookAt(glm::vec3(0, 1, 0), glm::vec3(0, 0.2f, -3), glm::vec3(0, 1, 0));
  clr::FrameSettings settings = test::idSettings(W, H, mvp);
  settings.traversal = GENERATE(CLR_TRAVERSAL_BBOX, CLR_TRAVERSAL_SPANS);
  INFO("traversal " << settings.traversal);
  const std::vector<int> counts = coverageCounts(grid, n, settings);
  // Below the horizon every pixel sees the plane: its rows y < H/2 - margin.
  size_t holes = 0, doubles = 0, checked = 0;
  for (uint32_t y = 0; y < H / 3; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const int c = counts[size_t(y) * W + x];
      holes += c == 0;
      ++checked;
    }
  for (int c : counts) doubles += c > 1;
  CHECK(checked > 0);
  CHECK(holes == 0);
  CHECK(doubles == 0);
}
