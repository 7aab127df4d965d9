// test_oracle.cpp — the anti-aliasing oracles checked on their own, without
// OpenCL: exact coverage against known areas, the supersampled reference
// against exact coverage (within its stratified-sampling bound), its fill
// rule, depth order and perspective-correct barycentrics.
#include "exact_coverage.h"
#include "supersample_reference.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace {

using oracle::ScreenVertex;

std::vector<ScreenVertex> flat(const std::vector<glm::dvec2>& xy, double z = 0.5)
{
  std::vector<ScreenVertex> v;
  for (const glm::dvec2& p : xy) v.push_back({p, z, 1.0});
  return v;
}

// A shading function whose colour says which triangle a sample went to.
glm::dvec3 idColour(uint32_t t, glm::dvec3)
{
  return glm::dvec3(t == 0, t == 1, t >= 2);
}

// n×n jittered cells of side `cell` from origin o, 2 triangles each (border
// vertices fixed): a mesh, so the triangles do not overlap.
std::vector<glm::dvec2> jitteredGrid(glm::dvec2 o, double cell, int n, std::mt19937& rng)
{
  std::uniform_real_distribution<double> jitter(-0.3 * cell, 0.3 * cell);
  std::vector<glm::dvec2> grid;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool border = i == 0 || j == 0 || i == n || j == n;
      grid.push_back(o + cell * glm::dvec2(i, j) + (border ? glm::dvec2(0.0) : glm::dvec2(jitter(rng), jitter(rng))));
    }
  std::vector<glm::dvec2> tris;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const glm::dvec2 a = grid[j * (n + 1) + i], b = grid[j * (n + 1) + i + 1];
      const glm::dvec2 c = grid[(j + 1) * (n + 1) + i + 1], d = grid[(j + 1) * (n + 1) + i];
      tris.insert(tris.end(), {a, b, c, a, c, d});
    }
  return tris;
}

}  // namespace

TEST_CASE("exact coverage: a triangle's pixel areas sum to its area, in either orientation", "[oracle]")
{
  const uint32_t W = 32, H = 24;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(0.0, W), y(0.0, H);
  for (int n = 0; n < 50; ++n) {
    const glm::dvec2 a(x(rng), y(rng)), b(x(rng), y(rng)), c(x(rng), y(rng));
    const std::vector<double> ccw = oracle::exactCoverage({a, b, c}, W, H);
    const std::vector<double> cw = oracle::exactCoverage({a, c, b}, W, H);
    double sum = 0.0;
    for (double v : ccw) sum += v;
    CHECK(sum == Approx(oracle::triangleArea(a, b, c)).margin(1e-12));
    CHECK(ccw == cw);
  }
}

TEST_CASE("exact coverage: a pixel square split into two triangles is exactly 1 there, 0 elsewhere", "[oracle]")
{
  const uint32_t W = 8, H = 8;
  const std::vector<double> cov = oracle::exactCoverage({{3, 5}, {4, 5}, {4, 6}, {3, 5}, {4, 6}, {3, 6}}, W, H);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) CHECK(cov[y * W + x] == (x == 3 && y == 5 ? 1.0 : 0.0));
}

TEST_CASE("exact coverage: a triangle inside one pixel gives its own area", "[oracle]")
{
  const uint32_t W = 6, H = 6;
  const glm::dvec2 a(2.1, 3.2), b(2.9, 3.3), c(2.4, 3.95);
  const std::vector<double> cov = oracle::exactCoverage({a, b, c}, W, H);
  for (uint32_t p = 0; p < W * H; ++p)
    CHECK(cov[p] == (p == 3 * W + 2 ? Approx(oracle::triangleArea(a, b, c)).margin(1e-15) : Approx(0.0)));
}

TEST_CASE("exact coverage: a half-plane-like triangle gives 0.5 on the pixels its edge bisects", "[oracle]")
{
  const uint32_t N = 16;
  // Step 1: the diagonal y = x, the covered side below it (x > y).
  std::vector<double> cov = oracle::exactCoverage({{-1000, -1000}, {1000, -1000}, {1000, 1000}}, N, N);
  for (uint32_t y = 0; y < N; ++y)
    for (uint32_t x = 0; x < N; ++x) {
      const double expected = x == y ? 0.5 : (x > y ? 1.0 : 0.0);
      CHECK(cov[y * N + x] == Approx(expected).margin(1e-12));
    }
  // Step 2: the anti-diagonal x + y = N, covered above it.
  cov = oracle::exactCoverage({{N + 1000.0, -1000}, {-1000, N + 1000.0}, {3000, 3000}}, N, N);
  for (uint32_t y = 0; y < N; ++y)
    for (uint32_t x = 0; x < N; ++x) {
      const double expected = x + y == N - 1 ? 0.5 : (x + y >= N ? 1.0 : 0.0);
      CHECK(cov[y * N + x] == Approx(expected).margin(1e-12));
    }
}

TEST_CASE("supersample coverage agrees with exact coverage within 2/S per edge through a pixel", "[oracle]")
{
  const uint32_t W = 40, H = 32, S = 16;
  const bool jitter = GENERATE(false, true);
  std::mt19937 rng(11);
  // Step 1: a jittered mesh and, apart from it, a few disjoint random triangles.
  std::vector<glm::dvec2> xy = jitteredGrid({1.3, 2.7}, 3.1, 7, rng);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 8; ++k) {
    const glm::dvec2 cell(25.0 + 7.0 * (k % 2), 1.0 + 3.9 * (k / 2));
    for (int i = 0; i < 3; ++i) xy.push_back(cell + glm::dvec2(6.5 * u(rng), 3.6 * u(rng)));
  }
  oracle::SupersampleOptions o;
  o.width = W;
  o.height = H;
  o.samplesPerAxis = S;
  o.jitter = jitter;
  const oracle::SupersampleResult r = oracle::supersampleRender(flat(xy), idColour, o);
  const std::vector<double> exact = oracle::exactCoverage(xy, W, H);
  // Step 2: per pixel, the edges that may cross it (bounding boxes meet), k.
  std::vector<int> edges(size_t(W) * H, 0);
  for (size_t t = 0; t < xy.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      const glm::dvec2 a = xy[t + e], b = xy[t + (e + 1) % 3];
      for (uint32_t y = 0; y < H; ++y)
        for (uint32_t x = 0; x < W; ++x)
          edges[y * W + x] += std::min(a.x, b.x) <= x + 1 && std::max(a.x, b.x) >= x && std::min(a.y, b.y) <= y + 1 &&
                              std::max(a.y, b.y) >= y;
    }
  // Step 3: |error| <= k·(2S − 1)/S²; pixels no edge meets agree exactly.
  double worst = 0.0, total = 0.0;
  for (size_t p = 0; p < exact.size(); ++p) {
    const double err = std::fabs(r.coverage[p] - exact[p]);
    INFO("pixel " << p % W << "," << p / W << " exact " << exact[p] << " sampled " << r.coverage[p]);
    CHECK(err <= edges[p] * (2.0 * S - 1.0) / (double(S) * S) + 1e-12);
    worst = std::max(worst, err);
    total += exact[p];
  }
  INFO("jitter " << jitter << ", worst error " << worst);
  CHECK(worst > 0.0);
  CHECK(total > 400.0);
  // Step 4: the thread count changes nothing.
  o.threads = 2;
  const oracle::SupersampleResult r2 = oracle::supersampleRender(flat(xy), idColour, o);
  CHECK(r2.coverage == r.coverage);
  CHECK(r2.color == r.color);
}

TEST_CASE("supersample fill rule: a sample on a shared edge belongs to exactly one triangle", "[oracle]")
{
  oracle::SupersampleOptions o;
  o.width = o.height = 3;
  o.samplesPerAxis = 4;  // sample centres at 1/8, 3/8, 5/8, 7/8: the diagonal meets four
  const size_t centre = 1 * 3 + 1;
  // Step 1: the diagonal is the lower-right triangle's left edge (inclusive),
  // the upper-left one's right edge, in either order and orientation.
  const std::vector<glm::dvec2> lowerRight = {{1, 1}, {2, 1}, {2, 2}}, upperLeft = {{1, 1}, {2, 2}, {1, 2}};
  for (int order = 0; order < 4; ++order) {
    std::vector<glm::dvec2> xy = order % 2 ? upperLeft : lowerRight;
    const std::vector<glm::dvec2>& second = order % 2 ? lowerRight : upperLeft;
    xy.insert(xy.end(), second.begin(), second.end());
    if (order >= 2) std::swap(xy[1], xy[2]);  // first triangle clockwise
    const oracle::SupersampleResult r = oracle::supersampleRender(flat(xy), idColour, o);
    const glm::dvec3 c = r.color[centre];
    CHECK(r.coverage[centre] == 1.0);
    CHECK((order % 2 ? c.y : c.x) == 10.0 / 16.0);  // 6 below the diagonal + 4 on it
    CHECK((order % 2 ? c.x : c.y) == 6.0 / 16.0);
  }
  // Step 2: a horizontal edge through the sample row y = 1 + 3/8 is the upper
  // rectangle's bottom edge (inclusive), the lower one's top edge.
  const double yMid = 1.375;
  const std::vector<glm::dvec2> xy = {{1, 1},    {2, 1},    {2, yMid}, {1, 1},    {2, yMid}, {1, yMid},
                                      {1, yMid}, {2, yMid}, {2, 2},    {1, yMid}, {2, 2},    {1, 2}};
  const oracle::SupersampleResult r = oracle::supersampleRender(
      flat(xy), [](uint32_t t, glm::dvec3) { return glm::dvec3(t < 2, t >= 2, 0); }, o);
  CHECK(r.coverage[centre] == 1.0);
  CHECK(r.color[centre].x == 4.0 / 16.0);
  CHECK(r.color[centre].y == 12.0 / 16.0);
}

TEST_CASE("supersample depth: LESS against 1.0, ties keep the earlier triangle", "[oracle]")
{
  oracle::SupersampleOptions o;
  o.width = o.height = 4;
  o.samplesPerAxis = 4;
  o.background = glm::dvec3(0.25);
  const std::vector<glm::dvec2> big = {{-10, -10}, {30, -10}, {-10, 30}};
  const std::vector<glm::dvec2> small = {{0.5, 0.5}, {3.5, 0.5}, {0.5, 3.5}};
  auto scene = [&](std::vector<std::pair<const std::vector<glm::dvec2>*, double>> tris) {
    std::vector<ScreenVertex> v;
    for (const auto& t : tris)
      for (const glm::dvec2& p : *t.first) v.push_back({p, t.second, 1.0});
    return oracle::supersampleRender(v, idColour, o);
  };
  // Step 1: a later, nearer triangle wins; a later one at equal depth loses.
  oracle::SupersampleResult r = scene({{&big, 0.5}, {&big, 0.25}, {&big, 0.25}});
  for (const glm::dvec3& c : r.color) CHECK(c == glm::dvec3(0, 1, 0));
  // Step 2: an earlier nearer triangle hides a later farther one.
  r = scene({{&small, 0.1}, {&big, 0.2}});
  CHECK(r.color[0] == glm::dvec3(4.0 / 16.0, 12.0 / 16.0, 0));  // samples at 5/8 and 7/8 in x and y
  CHECK(r.color[1 * 4 + 1] == glm::dvec3(1, 0, 0));
  // Step 3: depth 1.0 is the cleared value and never passes.
  r = scene({{&big, 1.0}});
  for (size_t p = 0; p < r.color.size(); ++p) {
    CHECK(r.coverage[p] == 0.0);
    CHECK(r.color[p] == o.background);
  }
}

TEST_CASE("supersample λ: sums to 1 and is the analytic perspective-correct value on a tilted triangle", "[oracle]")
{
  // Step 1: a triangle receding in depth, a pinhole camera at the origin
  // looking down −z: screen = c + f·(X, Y)/(−Z), w = −Z, window depth affine in 1/w.
  const uint32_t W = 48, H = 40;
  const double f = 40.0, nearW = 0.5, farW = 50.0;
  const glm::dvec2 c(W / 2.0, H / 2.0);
  const glm::dvec3 P[3] = {{-3.0, -1.5, -2.0}, {4.0, -1.0, -12.0}, {-1.0, 3.0, -5.0}};
  std::vector<ScreenVertex> v;
  for (const glm::dvec3& p : P) {
    const double w = -p.z;
    v.push_back({c + f * glm::dvec2(p.x, p.y) / w, (1.0 / nearW - 1.0 / w) / (1.0 / nearW - 1.0 / farW), 1.0 / w});
  }
  oracle::SupersampleOptions o;
  o.width = W;
  o.height = H;
  o.samplesPerAxis = 8;
  o.jitter = true;
  double worstSum = 0.0, minLambda = 1.0;
  const oracle::SupersampleResult r = oracle::supersampleRender(
      v,
      [&](uint32_t, glm::dvec3 l) {
        worstSum = std::max(worstSum, std::fabs(l.x + l.y + l.z - 1.0));
        minLambda = std::min({minLambda, l.x, l.y, l.z});
        return l.x * P[0] + l.y * P[1] + l.z * P[2];  // the world-space point
      },
      o);
  CHECK(worstSum < 1e-14);
  CHECK(minLambda >= -1e-14);
  // Step 2: in fully covered pixels, the mean of the rays' hits on the plane.
  const glm::dvec3 n = glm::cross(P[1] - P[0], P[2] - P[0]);
  double worst = 0.0;
  size_t full = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      if (r.coverage[y * W + x] != 1.0) continue;
      ++full;
      glm::dvec3 mean(0.0);
      for (uint32_t sy = 0; sy < o.samplesPerAxis; ++sy)
        for (uint32_t sx = 0; sx < o.samplesPerAxis; ++sx) {
          const glm::dvec2 s = oracle::samplePosition(o, x, y, sx, sy);
          const glm::dvec3 ray((s.x - c.x) / f, (s.y - c.y) / f, -1.0);
          mean += ray * (glm::dot(n, P[0]) / glm::dot(n, ray));
        }
      mean /= double(o.samplesPerAxis * o.samplesPerAxis);
      worst = std::max(worst, glm::length(mean - r.color[y * W + x]));
    }
  INFO("fully covered pixels " << full);
  CHECK(full > 100);
  CHECK(worst < 1e-12);
}
