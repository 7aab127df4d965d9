// test_lines.cpp — the line stage (kernels/lines.cl): Bresenham pixel for
// pixel against the classic incremental algorithm in all eight octants,
// anti-aliased coverage against the exact area of the line's rectangle, and
// the wireframe's depth test against the triangles.
#include "exact_coverage.h"
#include "test_support.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdlib>
#include <random>
#include <set>
#include <utility>

namespace {

using Pixel = std::pair<int, int>;

// The classic Bresenham algorithm with an integer decision variable, for
// every octant: step the major axis from the first end pixel to the second,
// the minor axis when d > 0 (d starts at 2·|dminor| − |dmajor|, grows by
// 2·|dminor| per step and drops by 2·|dmajor| per minor step). A tie (d == 0)
// steps only when the minor axis runs downwards, so ties always go to the
// lower minor coordinate (the kernel's convention). Both ends are drawn.
std::set<Pixel> classicBresenham(int x0, int y0, int x1, int y1)
{
  std::set<Pixel> pixels;
  const int dx = std::abs(x1 - x0), dy = std::abs(y1 - y0);
  const int sx = x1 >= x0 ? 1 : -1, sy = y1 >= y0 ? 1 : -1;
  if (dx >= dy) {
    long d = 2L * dy - dx;
    for (int i = 0, x = x0, y = y0; i <= dx; ++i, x += sx) {
      pixels.insert({x, y});
      if (d > 0 || (sy < 0 && d == 0)) {
        y += sy;
        d -= 2L * dx;
      }
      d += 2L * dy;
    }
  } else {
    long d = 2L * dx - dy;
    for (int i = 0, x = x0, y = y0; i <= dy; ++i, y += sy) {
      pixels.insert({x, y});
      if (d > 0 || (sx < 0 && d == 0)) {
        x += sx;
        d -= 2L * dy;
      }
      d += 2L * dx;
    }
  }
  return pixels;
}

LineSeg segment(int x0, int y0, int x1, int y1, float z0 = 0.5f, float z1 = 0.5f)
{
  return LineSeg{{x0, x1}, {y0, y1}, {z0, z1}, 0u, 0u};
}

// A frame with no triangle in view (shade normal: black background), ready
// for the caller's segments.
void emptyFrame(clr::Pipeline& pipeline, uint32_t width, uint32_t height, uint32_t method, uint32_t mode,
                float lineWidth = 1.0f)
{
  test::Geometry g;  // one triangle outside the view, culled
  g.addTriangle({-5, -5, 0}, {-4, -5, 0}, {-5, -4, 0});
  pipeline.uploadScene(g.mesh());
  clr::FrameSettings s = test::idSettings(width, height);
  s.shadeMode = CLR_SHADE_NORMAL;
  s.lineMethod = method;
  s.wireframe = mode;
  s.lineWidth = lineWidth;
  pipeline.beginFrame(s);
  pipeline.transform();
  pipeline.setup();
  pipeline.setupEmit();
  pipeline.raster();
  pipeline.resolve();
}

// Pixels (bottom row first) whose colour is not the background.
std::set<Pixel> drawnPixels(const std::vector<uint32_t>& rgba, uint32_t width, uint32_t height)
{
  std::set<Pixel> drawn;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      if (rgba[size_t(height - 1 - y) * width + x] != 0xFF000000u) drawn.insert({int(x), int(y)});
  return drawn;
}

std::set<Pixel> insideViewport(const std::set<Pixel>& pixels, uint32_t width, uint32_t height)
{
  std::set<Pixel> out;
  for (const Pixel& p : pixels)
    if (p.first >= 0 && p.second >= 0 && p.first < int(width) && p.second < int(height)) out.insert(p);
  return out;
}

// Draws one segment with Bresenham over a fresh background (the frame of
// emptyFrame(), resolved again); returns its pixels.
std::set<Pixel> drawBresenham(clr::Pipeline& pipeline, const LineSeg& s, uint32_t width, uint32_t height)
{
  pipeline.resolve();
  pipeline.lines({s});
  return drawnPixels(pipeline.readImage(), width, height);
}

}  // namespace

TEST_CASE("Bresenham lines match the classic algorithm in all eight octants", "[lines]")
{
  const uint32_t W = 48, H = 48;
  clr::Pipeline pipeline(test::context());
  emptyFrame(pipeline, W, H, CLR_LINE_BRESENHAM, CLR_WIREFRAME_OVERLAY);
  // Step 1: crafted segments from the centre pixel: the eight octants at
  // slopes with ties (2:1, 4:2), steep and shallow ones, the axes, the
  // diagonals, a single pixel, and one end inside a pixel's far corner.
  const int cx = 24, cy = 24;
  std::vector<std::pair<int, int>> deltas = {{0, 0},   {17, 0},   {-17, 0},  {0, 15},   {0, -15},
                                             {13, 13}, {-13, 13}, {13, -13}, {-13, -13}};
  for (int sx : {1, -1})
    for (int sy : {1, -1})
      for (auto [a, b] : {std::pair<int, int>{4, 2}, {17, 6}, {9, 8}, {16, 1}, {6, 3}}) {
        deltas.push_back({sx * a, sy * b});  // shallow octants (|dx| > |dy|)
        deltas.push_back({sx * b, sy * a});  // steep octants
      }
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> sub(0, CLR_FIXED_ONE - 1);
  for (auto [dx, dy] : deltas) {
    const int x0 = cx * CLR_FIXED_ONE + sub(rng), y0 = cy * CLR_FIXED_ONE + sub(rng);
    const int x1 = (cx + dx) * CLR_FIXED_ONE + sub(rng), y1 = (cy + dy) * CLR_FIXED_ONE + sub(rng);
    const std::set<Pixel> expected = classicBresenham(cx, cy, cx + dx, cy + dy);
    INFO("delta " << dx << "," << dy);
    CHECK(drawBresenham(pipeline, segment(x0, y0, x1, y1), W, H) == expected);
    // Step 2: the same pixels in the other direction, ends included.
    CHECK(drawBresenham(pipeline, segment(x1, y1, x0, y0), W, H) == expected);
    CHECK(expected.count({cx, cy}) == 1);
    CHECK(expected.count({cx + dx, cy + dy}) == 1);
  }
}

TEST_CASE("Bresenham lines crossing tiles and the viewport's edges match the classic algorithm", "[lines]")
{
  const uint32_t W = 80, H = 48;
  clr::Pipeline pipeline(test::context());
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> coord(-30 * CLR_FIXED_ONE, 110 * CLR_FIXED_ONE);
  // Many segments in one frame: the union of their pixels (max coverage).
  std::vector<LineSeg> segs;
  std::set<Pixel> expected;
  for (int n = 0; n < 40; ++n) {
    const int x0 = coord(rng), y0 = coord(rng) * 2 / 3, x1 = coord(rng), y1 = coord(rng) * 2 / 3;
    segs.push_back(segment(x0, y0, x1, y1));
    for (const Pixel& p : classicBresenham(x0 >> 8, y0 >> 8, x1 >> 8, y1 >> 8)) expected.insert(p);
  }
  emptyFrame(pipeline, W, H, CLR_LINE_BRESENHAM, CLR_WIREFRAME_OVERLAY);
  pipeline.lines(segs);
  const std::set<Pixel> drawn = drawnPixels(pipeline.readImage(), W, H);
  CHECK(drawn.size() > 500);
  CHECK(drawn == insideViewport(expected, W, H));
}

TEST_CASE("anti-aliased line coverage matches the exact area of the line's rectangle", "[lines]")
{
  // Lines alone are white on black, so a pixel's red channel is round(255 ·
  // coverage). Away from the ends the coverage is the exact area of the pixel
  // inside the strip (float rounding, and 0.5/255 for the 8-bit image); within
  // a pixel of an end the product approximation of lines.cl differs from the
  // exact area by at most 0.080 (measured in double over 3,000 random
  // segments of widths 0.5 to 3), so there the bound is 0.085.
  const uint32_t W = 64, H = 64;
  clr::Pipeline pipeline(test::context());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(12.0, 52.0), angle(0.0, 2.0 * M_PI), length(0.5, 30.0);
  double worstInterior = 0.0, worstEnds = 0.0;
  size_t interiorPixels = 0;
  for (int n = 0; n < 24; ++n) {
    const float width = n % 4 == 0 ? 2.5f : n % 4 == 1 ? 0.6f : 1.0f;
    // Step 1: a random segment on the subpixel grid, inside the viewport.
    const double a = angle(rng), len = length(rng);
    const int x0 = int(std::lround(pos(rng) * CLR_FIXED_ONE)), y0 = int(std::lround(pos(rng) * CLR_FIXED_ONE));
    int x1 = x0 + int(std::lround(std::cos(a) * len * CLR_FIXED_ONE)),
        y1 = y0 + int(std::lround(std::sin(a) * len * CLR_FIXED_ONE));
    x1 = std::clamp(x1, 4 * CLR_FIXED_ONE, 60 * CLR_FIXED_ONE);
    y1 = std::clamp(y1, 4 * CLR_FIXED_ONE, 60 * CLR_FIXED_ONE);
    emptyFrame(pipeline, W, H, CLR_LINE_AA, CLR_WIREFRAME_ONLY, width);
    pipeline.lines({segment(x0, y0, x1, y1)});
    const std::vector<uint32_t> rgba = pipeline.readImage();
    // Step 2: the rectangle as two triangles, and its exact coverage.
    const glm::dvec2 p0(x0 / 256.0, y0 / 256.0), p1(x1 / 256.0, y1 / 256.0);
    const double L = glm::length(p1 - p0);
    if (L == 0.0) continue;
    const glm::dvec2 t = (p1 - p0) / L, nrm(-t.y, t.x), h = nrm * (0.5 * width);
    const std::vector<double> exact = oracle::exactCoverage({p0 + h, p1 + h, p1 - h, p0 + h, p1 - h, p0 - h}, W, H);
    // Step 3: compare, pixels away from the ends and near them apart.
    const double profile = 0.5 * (std::abs(t.x) + std::abs(t.y));  // the pixel's half extent along t
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const double cover = double(rgba[size_t(H - 1 - y) * W + x] & 0xFFu) / 255.0;
        const double along = glm::dot(glm::dvec2(x + 0.5, y + 0.5) - p0, t);
        const double err = std::abs(cover - exact[size_t(y) * W + x]);
        if (along - profile >= 0.0 && along + profile <= L) {
          worstInterior = std::max(worstInterior, err);
          interiorPixels += exact[size_t(y) * W + x] > 0.0;
        } else {
          worstEnds = std::max(worstEnds, err);
        }
      }
  }
  CHECK(interiorPixels > 200);
  CHECK(worstInterior <= 0.5 / 255.0 + 1e-4);
  CHECK(worstEnds <= 0.085);
}

TEST_CASE("wireframe edges pass the depth test on top and fail it behind a triangle", "[lines]")
{
  // Identity MVP: positions are NDC, window depth z/2 + 1/2. Triangle 0 lies
  // in front (window depth 0.5); triangle 1 behind it (0.8) reaches out of it,
  // so parts of its edges are hidden and parts are not.
  const uint32_t W = 96, H = 64;
  test::Geometry g;
  g.addTriangle(test::screen(20, 10, 0, W, H), test::screen(76, 10, 0, W, H), test::screen(48, 54, 0, W, H));
  g.addTriangle(test::screen(4, 30, 0.6f, W, H), test::screen(90, 20, 0.6f, W, H), test::screen(44, 62, 0.6f, W, H));
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  clr::FrameSettings s = test::idSettings(W, H);
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, s);
  s.shadeMode = CLR_SHADE_NORMAL;
  s.wireframe = CLR_WIREFRAME_OVERLAY;
  s.lineMethod = CLR_LINE_BRESENHAM;
  std::vector<uint32_t> rgba;
  pipeline.render(s, rgba);
  const std::vector<clr::SetupRecord> setup = pipeline.readSetup();
  REQUIRE(setup.size() == 2);
  // Step 1: each triangle's edge pixels by the classic algorithm.
  std::set<Pixel> edges[2];
  for (int t = 0; t < 2; ++t)
    for (int e = 0; e < 3; ++e) {
      const clr::SetupRecord& r = setup[t];
      const int a = e, b = (e + 1) % 3;
      for (const Pixel& p : classicBresenham(r.x[a] >> 8, r.y[a] >> 8, r.x[b] >> 8, r.y[b] >> 8))
        edges[r.triId].insert(p);
    }
  auto isLine = [&](const Pixel& p) { return rgba[size_t(H - 1 - p.second) * W + p.first] == 0xFF008CFFu; };
  // Step 2: the front triangle's edges all show.
  for (const Pixel& p : insideViewport(edges[0], W, H)) CHECK(isLine(p));
  // Step 3: the back triangle's edges show outside the front one and are
  // hidden where the front triangle covers them.
  size_t hidden = 0, shown = 0;
  for (const Pixel& p : insideViewport(edges[1], W, H)) {
    if (edges[0].count(p)) continue;
    const uint32_t visible = ids[size_t(p.second) * W + p.first];
    if (visible == 0) {
      CHECK_FALSE(isLine(p));
      ++hidden;
    } else {
      CHECK(isLine(p));
      ++shown;
    }
  }
  CHECK(hidden > 20);
  CHECK(shown > 20);
}

TEST_CASE("wireframe only draws edges over the background", "[lines]")
{
  const uint32_t W = 64, H = 48;
  test::Geometry g;
  g.addTriangle(test::screen(8, 6, 0, W, H), test::screen(56, 10, 0, W, H), test::screen(30, 42, 0, W, H));
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  clr::FrameSettings s = test::idSettings(W, H);
  s.shadeMode = CLR_SHADE_NORMAL;
  s.wireframe = CLR_WIREFRAME_ONLY;
  s.lineMethod = CLR_LINE_BRESENHAM;
  std::vector<uint32_t> rgba;
  pipeline.render(s, rgba);
  const clr::SetupRecord r = pipeline.readSetup().at(0);
  std::set<Pixel> edges;
  for (int e = 0; e < 3; ++e)
    for (const Pixel& p : classicBresenham(r.x[e] >> 8, r.y[e] >> 8, r.x[(e + 1) % 3] >> 8, r.y[(e + 1) % 3] >> 8))
      edges.insert(p);
  // Every pixel is white on an edge and background elsewhere.
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x)
      CHECK(rgba[size_t(H - 1 - y) * W + x] == (edges.count({int(x), int(y)}) ? 0xFFFFFFFFu : 0xFF000000u));
}

TEST_CASE("wireframe only paints the background resolve paints in every shading mode", "[lines]")
{
  // The same triangle filled and as a wireframe alone: the pixels more than
  // 4 pixels outside its bounds (x 20-44, y 14-34), clear of it and of its
  // lines, are one colour, the same in both frames.
  const uint32_t W = 64, H = 48;
  test::Geometry g;
  g.addTriangle(test::screen(20, 14, 0, W, H), test::screen(44, 16, 0, W, H), test::screen(30, 34, 0, W, H));
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  std::set<uint32_t> backgrounds;
  for (uint32_t mode = 0; mode < CLR_NUM_SHADE_MODES; ++mode) {
    INFO("shade mode " << mode);
    clr::FrameSettings s = test::idSettings(W, H);
    s.shadeMode = mode;
    std::vector<uint32_t> filled, only;
    pipeline.render(s, filled);
    s.wireframe = CLR_WIREFRAME_ONLY;
    pipeline.render(s, only);
    const uint32_t background = filled[0];  // the top-left pixel, far from the triangle
    backgrounds.insert(background);
    size_t compared = 0, differing = 0;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const bool far = x < 16 || x >= 48 || y < 10 || y >= 38;
        if (!far) continue;
        const size_t i = size_t(H - 1 - y) * W + x;
        ++compared;
        differing += filled[i] != background || only[i] != background;
      }
    CHECK(compared > 1500);
    CHECK(differing == 0);
  }
  // Premise: the modes cover both backgrounds.
  CHECK(backgrounds == std::set<uint32_t>{CLR_BACKGROUND_LIT, CLR_BACKGROUND_UNLIT});
}

TEST_CASE("wireframe of a near-clipped triangle draws its input edges, not the fan's diagonals", "[lines]")
{
  // A ground triangle with one vertex behind the eye: the near plane cuts it
  // into a quadrilateral, fanned into two sub-triangles whose shared diagonal
  // is no input edge.
  const uint32_t W = 96, H = 64;
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 1, 0), glm::vec3(0, 0.8f, -1), glm::vec3(0, 1, 0));
  const glm::mat4 mvp = glm::perspective(glm::radians(60.0f), float(W) / H, 0.5f, 100.0f) * view;
  test::Geometry g;
  g.addTriangle({-6, 0, -60}, {6, 0, -60}, {0.5f, 0, 4});
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  clr::FrameSettings s = test::idSettings(W, H, mvp);
  s.shadeMode = CLR_SHADE_NORMAL;
  s.wireframe = CLR_WIREFRAME_ONLY;
  s.lineMethod = CLR_LINE_BRESENHAM;
  std::vector<uint32_t> rgba;
  REQUIRE(pipeline.render(s, rgba).trianglesClipped == 1);
  // Step 1: the sub-triangles' edges, kept (on an input edge) or dropped.
  const std::vector<clr::SetupRecord> setup = pipeline.readSetup();
  const std::vector<ClipBary> clip = pipeline.readClipBary();
  std::set<Pixel> kept, dropped;
  size_t subTriangles = 0;
  for (const clr::SetupRecord& r : setup) {
    if (r.flags & CLR_FLAG_DEAD) continue;
    REQUIRE(r.clipSlot != CLR_NOT_CLIPPED);
    ++subTriangles;
    for (int a = 0; a < 3; ++a) {
      const int b = (a + 1) % 3;
      bool onInput = false;
      for (int j = 0; j < 3; ++j) onInput = onInput || (clip[r.clipSlot].w[a][j] == 0 && clip[r.clipSlot].w[b][j] == 0);
      for (const Pixel& p : classicBresenham(r.x[a] >> 8, r.y[a] >> 8, r.x[b] >> 8, r.y[b] >> 8))
        (onInput ? kept : dropped).insert(p);
    }
  }
  REQUIRE(subTriangles == 2);
  // Step 2: kept edges are white, the diagonal's own pixels background.
  auto colour = [&](const Pixel& p) { return rgba[size_t(H - 1 - p.second) * W + p.first]; };
  size_t keptDrawn = 0, droppedChecked = 0;
  for (const Pixel& p : insideViewport(kept, W, H)) {
    CHECK(colour(p) == 0xFFFFFFFFu);
    ++keptDrawn;
  }
  for (const Pixel& p : insideViewport(dropped, W, H)) {
    if (kept.count(p)) continue;
    CHECK(colour(p) == 0xFF000000u);
    ++droppedChecked;
  }
  CHECK(keptDrawn > 40);
  CHECK(droppedChecked > 20);
}
