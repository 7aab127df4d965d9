// test_stability_coords.cpp — where coordinates get large or w gets small
// (project issue 4, items 1 and 2; measured boundaries in docs/limits.md).
//
// Large coordinates: band meshes (stability_scenes.h) whose vertices reach
// the guard band (fixed.h: ±65536 px) at the largest viewports (16384-pixel
// strips) stay watertight, counted from the kernels' own coverage;
// triangles at the fixed-point limits (vertices on the guard band, edges of
// 2^17 px) match the scalar oracle pixel for pixel; float edge functions
// crack on a mesh where fixed-point ones do not. Near plane and w <= 0: a
// folded sheet crossing the camera plane, with rows of vertices at w = 0
// exactly and behind the eye, is covered once per pixel, with finite
// visibility samples and clean normal and Lambert shading.
#include "stability_scenes.h"
#include "test_support.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace {

using test::Geometry;
using test::screen;

}  // namespace

TEST_CASE("stability: band meshes reaching the guard band stay watertight at 16384-pixel viewports", "[stability]")
{
  // Strips rather than 16384x16384, whose visibility buffer alone needs
  // 16 B x 2^28 = 4 GiB (docs/limits.md); each strip is 2^20 pixels.
  const uint32_t W = GENERATE(16384u, 64u);
  const uint32_t H = W == 64u ? 16384u : 64u;
  const uint32_t bands = 48;
  const double angle = GENERATE(35.0, 80.0);
  const double guard = stab::guardBandReach(W, H, bands, angle);
  SECTION("every vertex inside the guard band, none clipped")
  {
    const stab::Scene scene = stab::bandMesh(W, H, guard, bands, angle, 5);
    // Premise: the mesh reaches the guard band (2^16 px) to within 2%.
    CHECK(scene.magnitude > 0.98 * CLR_GUARD_BAND_PIXELS);
    CHECK(scene.magnitude <= CLR_GUARD_BAND_PIXELS);
    clr::FrameSettings s = test::idSettings(W, H);
    const stab::Cracks c = stab::countCracks(stab::coverageCounts(test::context(), scene, s));
    CHECK(c.holes == 0);
    CHECK(c.doubles == 0);
  }
  SECTION("vertices 4x beyond the guard band, every triangle clipped to it")
  {
    const stab::Scene scene = stab::bandMesh(W, H, 4.0 * guard, bands, angle, 6);
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(scene.mesh());
    std::vector<uint32_t> rgba;
    CHECK(pipeline.render(test::idSettings(W, H), rgba).trianglesClipped == scene.numTris());
    const stab::Cracks c = stab::countCracks(stab::coverageCounts(test::context(), scene, test::idSettings(W, H)));
    CHECK(c.holes == 0);
    CHECK(c.doubles == 0);
  }
}

// Tagged [stability] only: at 2^20 pixels a strip is too slow for Oclgrind's
// per-pixel interpretation (tests/oclgrind_check.sh); the [clip] case
// below covers the same kernel paths at 32x32.
TEST_CASE("stability: triangles at the fixed-point limits match the oracle", "[stability]")
{
  // Vertices on the guard band's corners and edges: |X| = 2^24 fixed units,
  // edge deltas up to 2^25 and edge terms near 2^50 (fixed.h); plus
  // triangles reaching 2^20 px that are clipped back to the band.
  const uint32_t W = GENERATE(16384u, 64u, 256u);
  const uint32_t H = W == 16384u ? 64u : W == 64u ? 16384u : 256u;
  const double lo_x = double(W) - CLR_GUARD_BAND_PIXELS, lo_y = double(H) - CLR_GUARD_BAND_PIXELS;
  const double hi = CLR_GUARD_BAND_PIXELS;
  const double cx = 0.5 * W, cy = 0.5 * H;
  Geometry g;
  auto at = [&](double x, double y, float z) { return screen(float(x), float(y), z, W, H); };
  // Step 1: long thin triangles between opposite guard-band corners, a wide
  // one along the band's edge, and near-degenerate ones through the centre.
  g.addTriangle(at(lo_x, lo_y, 0.5f), at(hi, hi, 0.5f), at(lo_x, hi, 0.5f));
  g.addTriangle(at(lo_x, lo_y, 0.4f), at(hi, lo_y, 0.4f), at(hi, hi, 0.4f));
  g.addTriangle(at(lo_x, lo_y, 0.3f), at(hi, hi, 0.3f), at(cx + 1.5, cy - 3.25, 0.3f));
  g.addTriangle(at(hi, lo_y, 0.2f), at(lo_x, hi, 0.2f), at(cx - 0.75, cy - 0.5, 0.2f));
  g.addTriangle(at(lo_x, cy + 0.5, 0.1f), at(hi, cy - 0.5, 0.1f), at(hi, cy + 2.0, 0.1f));
  g.addTriangle(at(cx + 0.5, lo_y, 0.05f), at(cx - 0.5, hi, 0.05f), at(cx - 3.0, hi, 0.05f));
  // Step 2: far beyond the band (clipped), sharing an edge with each other.
  const double far = 1048576.0;
  g.addTriangle(at(cx - far, cy - 30, 0.0f), at(cx + far, cy - 28, 0.0f), at(cx + far, cy - 23.5, 0.0f));
  g.addTriangle(at(cx - far, cy - 30, 0.0f), at(cx + far, cy - 23.5, 0.0f), at(cx - far, cy - 22, 0.0f));
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::idSettings(W, H));
  // Premise: the setup records reach the limits fixed.h derives.
  int maxCoord = 0;
  int64_t maxDelta = 0;
  for (const clr::SetupRecord& t : pipeline.readSetup())
    for (int v = 0; v < 3; ++v) {
      maxCoord = std::max({maxCoord, std::abs(t.x[v]), std::abs(t.y[v])});
      maxDelta = std::max(
          {maxDelta, std::abs(int64_t(t.x[v]) - t.x[(v + 1) % 3]), std::abs(int64_t(t.y[v]) - t.y[(v + 1) % 3])});
    }
  CHECK(maxCoord == CLR_GUARD_BAND_PIXELS * CLR_FIXED_ONE);
  CHECK(maxDelta >= int64_t(2 * CLR_GUARD_BAND_PIXELS - 16384) * CLR_FIXED_ONE);
  const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {W, H, false});
  CHECK(expected.clippedTriangles == 2);
  CHECK(test::countDifferences(ids, expected.triId) == 0);
  // Every triangle shows somewhere (the thin ones too).
  for (uint32_t t = 0; t < g.numTris(); ++t) CHECK(std::count(ids.begin(), ids.end(), t) > 0);
}

TEST_CASE("stability: huge finite vertices are clipped to the guard band exactly", "[stability][clip]")
{
  // Triangles with vertices at 1e20 and 3e38 contain the whole guard band.
  // Without clip.h's intersections exactly on the plane and its halved
  // overflowing differences, the first covers half of the viewport
  // (rounding at 1e20 is 2^43) and the second nothing (6e38 overflows).
  const uint32_t W = 32, H = 32;
  const float big = GENERATE(1e6f, 1e20f, 3e38f);
  Geometry g;
  g.addTriangle({-big, -big, 0.5f}, {big, -big, 0.5f}, {0, big, 0.5f});
  g.addTriangle({-big, big, 0.0f}, {-big, -big, 0.0f}, {big, 0.25f, 0.0f});  // nearer, shares no edge
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  std::vector<uint32_t> rgba;
  const clr::FrameStats stats = pipeline.render(test::keepingVis(test::idSettings(W, H)), rgba);
  CHECK(stats.trianglesClipped == 2);
  // The guard band is the square |x_s|, |y_s| <= 2^16 around the viewport;
  // both triangles contain it, so each clips to it: two sub-triangles each.
  CHECK(stats.setupTriangles == 4);
  for (const clr::SetupRecord& t : pipeline.readSetup()) {
    if (t.flags & CLR_FLAG_DEAD) continue;
    for (int v = 0; v < 3; ++v) {
      CHECK((t.x[v] == (int(W) - CLR_GUARD_BAND_PIXELS) * CLR_FIXED_ONE ||
             t.x[v] == CLR_GUARD_BAND_PIXELS * CLR_FIXED_ONE));
      CHECK((t.y[v] == (int(H) - CLR_GUARD_BAND_PIXELS) * CLR_FIXED_ONE ||
             t.y[v] == CLR_GUARD_BAND_PIXELS * CLR_FIXED_ONE));
    }
  }
  const std::vector<uint32_t> ids = test::readTriIds(pipeline);
  CHECK(size_t(std::count(ids.begin(), ids.end(), 1u)) == ids.size());
  for (const VisSample& v : pipeline.readVis())
    REQUIRE((std::isfinite(v.depth) && std::isfinite(v.b1) && std::isfinite(v.b2)));
  const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {W, H, false});
  CHECK(test::countDifferences(ids, expected.triId) == 0);
}

TEST_CASE("stability: float edge functions crack where fixed-point edges do not", "[stability]")
{
  // Measured with bench/stability.sh (docs/limits.md): at 512x512, 64 bands,
  // 3 seeds, float edges give no crack at reach 362 (magnitude 758 px), the
  // first at 881 px and 374 (181 holes, 193 double hits) at the guard band;
  // fixed-point edges none anywhere. Seed 1 alone: 68 holes and 53 doubles
  // at the guard band.
  const uint32_t W = 512, H = 512, bands = 64;
  const double angle = 35.0;
  clr::FrameSettings fixedEdges = test::idSettings(W, H), floatEdges = fixedEdges;
  floatEdges.edgeMode = CLR_EDGES_FLOAT;
  SECTION("at the guard band: fixed-point clean, float cracked")
  {
    const stab::Scene scene = stab::bandMesh(W, H, stab::guardBandReach(W, H, bands, angle), bands, angle, 1);
    CHECK(scene.magnitude > 65000.0);
    const stab::Cracks fixedCracks = stab::countCracks(stab::coverageCounts(test::context(), scene, fixedEdges));
    const stab::Cracks floatCracks = stab::countCracks(stab::coverageCounts(test::context(), scene, floatEdges));
    CHECK(fixedCracks.holes == 0);
    CHECK(fixedCracks.doubles == 0);
    INFO("float edges: " << floatCracks.holes << " holes, " << floatCracks.doubles << " double hits");
    CHECK(floatCracks.holes > 0);
    CHECK(floatCracks.doubles > 0);
  }
  SECTION("at 758 px both are clean")
  {
    const stab::Scene scene = stab::bandMesh(W, H, 362.0, bands, angle, 1);
    CHECK(scene.magnitude < 800.0);
    CHECK(stab::countCracks(stab::coverageCounts(test::context(), scene, fixedEdges)).total() == 0);
    CHECK(stab::countCracks(stab::coverageCounts(test::context(), scene, floatEdges)).total() == 0);
  }
}

namespace {

// A sheet folded along x = 1.5, y = −1: floor (y = −1) left of the fold, a
// wall (x = 1.5) above it. Seen from the eye at the origin, inside the
// convex region y >= −1, x <= 1.5, every ray meets the sheet at most once.
// `along` lists the rows' z: behind the eye (z > 0) or on the camera plane
// (z = 0, so w = 0 exactly under a perspective matrix), then ahead, so the
// first visible cells cross the camera plane inside the view.
struct Sheet {
  std::vector<glm::vec3> grid;
  int ni = 0, nj = 0;
};

Sheet foldedSheet(const std::vector<float>& along)
{
  const std::vector<float> across = {-20, -8, -3, -1, -0.3f, 0, 0.4f, 1, 1.5f};  // floor x, then the fold
  const std::vector<float> up = {-0.5f, 0, 0.7f, 2, 5};                          // wall y above the fold
  Sheet s;
  s.ni = int(across.size() + up.size()) - 1;
  s.nj = int(along.size()) - 1;
  for (float z : along) {
    for (float x : across) s.grid.push_back({x, -1.0f, z});
    for (float y : up) s.grid.push_back({1.5f, y, z});
  }
  return s;
}

// The sheet's cells as triangles; class c only (18 classes whose members
// never touch, as in test_watertight.cpp), or all with c < 0.
Geometry sheetGeometry(const Sheet& s, int c)
{
  Geometry g;
  for (int j = 0; j < s.nj; ++j)
    for (int i = 0; i < s.ni; ++i) {
      const int base = ((i % 3) * 3 + j % 3) * 2;
      const glm::vec3 v = s.grid[j * (s.ni + 1) + i], r = s.grid[j * (s.ni + 1) + i + 1];
      const glm::vec3 u = s.grid[(j + 1) * (s.ni + 1) + i], ur = s.grid[(j + 1) * (s.ni + 1) + i + 1];
      if (c < 0 || c == base) g.addTriangle(v, r, ur);
      if (c < 0 || c == base + 1) g.addTriangle(v, ur, u);
    }
  return g;
}

}  // namespace

TEST_CASE("stability: triangles through the camera plane and behind the eye clip without seams or NaN", "[stability]")
{
  const uint32_t W = 160, H = 120;
  // View = identity: w = −z_eye exactly, so the z = 0 rows have w = 0.
  const glm::mat4 mvp = glm::perspective(glm::radians(70.0f), float(W) / H, 0.1f, 100.0f);
  // Rows at w = 0 exactly, or behind the eye, then cells reaching ahead.
  const bool onCameraPlane = GENERATE(true, false);
  const Sheet sheet =
      foldedSheet(onCameraPlane ? std::vector<float>{0, -3, -12, -40} : std::vector<float>{5, -2.5f, -12, -40});
  const Geometry all = sheetGeometry(sheet, -1);
  // Premise: vertices at w = 0 exactly, or behind the eye.
  size_t zeroW = 0, behind = 0;
  for (size_t v = 0; v < all.positions.size() / 3; ++v) {
    const glm::vec4 c = ref::transformVertex(mvp, &all.positions[3 * v]);
    zeroW += c.w == 0.0f;
    behind += c.w < 0.0f;
  }
  CHECK((onCameraPlane ? zeroW : behind) > 0);

  SECTION("every pixel whose neighbourhood sees the sheet is covered exactly once")
  {
    std::vector<int> counts(size_t(W) * H, 0);
    for (int c = 0; c < 18; ++c) {
      const Geometry g = sheetGeometry(sheet, c);
      if (g.numTris() == 0) continue;
      const std::vector<uint32_t> ids = test::renderTriIds(g, test::idSettings(W, H, mvp));
      for (size_t p = 0; p < ids.size(); ++p) counts[p] += ids[p] != ref::kNone;
    }
    // Analytic: the ray through (x, y) meets the sheet inside its extent,
    // away from the outer borders (the fold is interior).
    const float ty = std::tan(glm::radians(35.0f)), tx = ty * float(W) / H;
    auto sees = [&](float px, float py) {
      const float dx = (2.0f * px / W - 1.0f) * tx, dy = (2.0f * py / H - 1.0f) * ty;
      const float tFloor = dy < 0.0f ? -1.0f / dy : INFINITY, tWall = dx > 0.0f ? 1.5f / dx : INFINITY;
      const float t = std::min(tFloor, tWall);
      if (!std::isfinite(t)) return false;
      const float x = t * dx, y = t * dy, z = -t;
      return z > -40.0f && x > -20.0f && y < 5.0f;
    };
    size_t holes = 0, doubles = 0, interior = 0;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const int c = counts[size_t(y) * W + x];
        doubles += c > 1;
        bool inside = true;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) inside = inside && sees(x + 0.5f + dx, y + 0.5f + dy);
        if (!inside) continue;
        ++interior;
        holes += c == 0;
      }
    CHECK(interior > W * H / 2);  // premise: most of the screen is checked
    CHECK(holes == 0);
    CHECK(doubles == 0);
  }
  SECTION("finite samples, the oracle's pixels, clean normal and Lambert shading")
  {
    clr::Pipeline pipeline(test::context());
    pipeline.uploadScene(all.mesh());
    std::vector<uint32_t> rgba;
    const clr::FrameStats stats = pipeline.render(test::keepingVis(test::idSettings(W, H, mvp)), rgba);
    const std::vector<uint32_t> ids = test::readTriIds(pipeline);
    CHECK(stats.trianglesClipped > 0);
    CHECK(pipeline.readClipBary().size() > 0);
    size_t covered = 0;
    for (const VisSample& v : pipeline.readVis()) {
      if (v.setupIndex == CLR_NONE) continue;
      ++covered;
      REQUIRE((std::isfinite(v.depth) && std::isfinite(v.b1) && std::isfinite(v.b2)));
      REQUIRE((v.depth >= 0.0f && v.depth <= 1.0f));
    }
    CHECK(covered > W * H / 2);
    const ref::Result expected = ref::rasterize(all.positions, all.indices, mvp, {W, H, false});
    CHECK(test::countDifferences(ids, expected.triId) == 0);
    // Normal shading: the floor's normal is (0, 1, 0), the wall's (−1, 0, 0),
    // the fold's smooth normal between them, so every covered pixel has
    // blue 128 and (red, green) on the unit circle mapped to [0, 255]; a NaN
    // would clamp to 0 or 255. Tolerance: 2/255 per channel from rounding.
    clr::FrameSettings s = test::idSettings(W, H, mvp);
    s.shadeMode = CLR_SHADE_NORMAL;
    pipeline.render(s, rgba);
    size_t badNormal = 0, badLambert = 0;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        if (ids[size_t(y) * W + x] == ref::kNone) continue;
        const uint32_t c = rgba[size_t(H - 1 - y) * W + x];  // image rows are top first
        const float r = (c & 0xFF) / 127.5f - 1.0f, g = ((c >> 8) & 0xFF) / 127.5f - 1.0f;
        const int b = (c >> 16) & 0xFF;
        badNormal += b != 128 || r > 0.01f || g < -0.01f || std::abs(r * r + g * g - 1.0f) > 0.03f;
      }
    // Lambert with the light along (−1, 1, 0): floor and wall both get
    // n·l = 0.707, the fold up to 1, so grey 0.12 + 0.88·n·l times the
    // albedo (0.80, 0.78, 0.74): red in [0.80·0.742, 0.80]·255 = [151, 204].
    s.shadeMode = CLR_SHADE_LAMBERT;
    s.lightDir = glm::vec3(-1.0f, 1.0f, 0.0f);
    pipeline.render(s, rgba);
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        if (ids[size_t(y) * W + x] == ref::kNone) continue;
        const int r = rgba[size_t(H - 1 - y) * W + x] & 0xFF;
        badLambert += r < 150 || r > 205;
      }
    CHECK(badNormal == 0);
    CHECK(badLambert == 0);
  }
}
