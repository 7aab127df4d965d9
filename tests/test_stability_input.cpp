// test_stability_input.cpp — degenerate input and load (project issue 4,
// items 3 and 6; measured boundaries in docs/limits.md).
//
// Degenerate input: zero-area, collinear, repeated-vertex, sub-subpixel
// sliver, NaN, Inf and huge finite triangles, interleaved with an ordinary
// scene, are culled or drawn by the fill rule and leave every other pixel
// as the ordinary scene alone draws it; every covered sample of every MSAA
// plane has finite barycentrics within [0, 1] that match the exact ratios.
// Load: 250,000 triangles in one tile and a thousand full-screen
// triangles lose nothing, device memory follows the bin counts exactly,
// and an allocation over the device's limit is a clear error, in the
// library and on the command line.
#include "cli_support.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <memory>
#include <numeric>
#include <random>

namespace {

using test::Geometry;
using test::screen;

constexpr uint32_t kW = 64, kH = 64;

// What each triangle of the mixed scene is.
enum Kind { kOrdinary, kCulled, kSliver, kHuge };

struct Mixed {
  Geometry base, mixed;
  std::vector<Kind> kind;        // per triangle of `mixed`
  std::vector<uint32_t> baseId;  // per triangle of `mixed`: its index in `base`, or ref::kNone
};

// An ordinary scene of random overlapping triangles, with a degenerate one
// before each ordinary one (cycling through the kinds), and two huge
// finite triangles behind everything.
Mixed mixedScene(uint32_t seed)
{
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::mt19937 rng(seed);
  // Ordinary triangles keep to x, y < 44, leaving background for the huge ones.
  std::uniform_int_distribution<int> coord(-8 * 256, 72 * 256), inner(-8 * 256, 44 * 256), centre(0, 63);
  std::uniform_real_distribution<float> depth(-0.9f, 0.9f);
  auto grid = [&] { return coord(rng) / 256.0f; };
  auto at = [](float x, float y, float z) { return screen(x, y, z, kW, kH); };
  Mixed m;
  auto add = [&](Kind k, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    m.mixed.addTriangle(a, b, c);
    m.kind.push_back(k);
    m.baseId.push_back(k == kOrdinary ? uint32_t(m.base.numTris()) : ref::kNone);
    if (k == kOrdinary) m.base.addTriangle(a, b, c);
  };
  for (int i = 0; i < 160; ++i) {
    const float z = depth(rng);
    const float ax = grid(), ay = grid(), bx = grid(), by = grid();
    const float cx = float(centre(rng)) + 0.5f, cy = float(centre(rng)) + 0.5f;  // a pixel centre
    switch (i % 10) {
      case 0: add(kCulled, at(ax, ay, z), at(ax, ay, z), at(ax, ay, z)); break;                    // a point
      case 1: add(kCulled, at(ax, ay, z), at(bx, by, z), at(2 * bx - ax, 2 * by - ay, z)); break;  // collinear
      case 2: add(kCulled, at(ax, ay, z), at(ax, ay, z), at(bx, by, z)); break;                    // repeated
      case 3: add(kSliver, at(ax, ay, z), at(bx, by, z), at(bx + 1 / 256.0f, by, z)); break;       // 1/256 wide
      case 4: add(kSliver, at(cx - 20, cy, z), at(cx + 20, cy, z), at(cx + 20, cy + 1 / 256.0f, z)); break;
      case 5: add(kCulled, {nan, 0, 0}, at(bx, by, z), at(ax, ay, z)); break;
      case 6: add(kCulled, at(ax, ay, z), {0, nan, 0}, at(bx, by, z)); break;
      case 7: add(kCulled, at(ax, ay, z), at(bx, by, z), {0, 0, nan}); break;
      case 8: add(kCulled, {inf, 0, 0}, at(bx, by, z), at(ax, ay, z)); break;
      default: add(kCulled, at(ax, ay, z), {0, -inf, 0}, at(bx, by, z)); break;
    }
    auto ordinary = [&] { return at(inner(rng) / 256.0f, inner(rng) / 256.0f, depth(rng)); };
    const glm::vec3 a = ordinary(), b = ordinary(), c = ordinary();
    add(kOrdinary, a, b, c);
  }
  // Huge but finite: clipped to the guard band, behind every other triangle.
  const float big = 3.0e38f;
  add(kHuge, {-big, -big, 0.99f}, {big, -big, 0.99f}, {0, big, 0.99f});
  add(kHuge, {-1e20f, 1e20f, 0.98f}, {-1e20f, -1e20f, 0.98f}, {1e20f, 0, 0.98f});
  return m;
}

// Restores test::context().maxAllocBytes when it goes out of scope.
struct AllocCap {
  size_t saved;
  explicit AllocCap(size_t bytes) : saved(test::context().maxAllocBytes) { test::context().maxAllocBytes = bytes; }
  ~AllocCap() { test::context().maxAllocBytes = saved; }
};

}  // namespace

TEST_CASE("stability: degenerate and non-finite triangles are culled or drawn and disturb nothing", "[stability]")
{
  const Mixed m = mixedScene(GENERATE(1u, 2u));
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(m.mixed.mesh());
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::idSettings(kW, kH));
  const std::vector<uint32_t> alone = test::renderTriIds(m.base, test::idSettings(kW, kH));
  // Step 1: culled kinds never reach setup.
  for (const clr::SetupRecord& t : pipeline.readSetup()) REQUIRE(m.kind.at(t.triId) != kCulled);
  // Step 2: a pixel that shows an ordinary triangle shows the one the
  // ordinary scene alone shows; only slivers may cover one, and the huge
  // triangles fill exactly the pixels the ordinary scene leaves empty.
  size_t disturbed = 0, sliverPixels = 0, hugePixels = 0;
  for (size_t p = 0; p < ids.size(); ++p) {
    const uint32_t id = ids[p];
    const Kind k = id == ref::kNone ? kCulled : m.kind[id];
    if (k == kOrdinary) disturbed += m.baseId[id] != alone[p];
    if (k == kSliver) ++sliverPixels;
    if (k == kHuge) hugePixels += 1, disturbed += alone[p] != ref::kNone;
    if (id == ref::kNone) disturbed += 1;  // the huge triangles cover the viewport
  }
  CHECK(disturbed == 0);
  CHECK(sliverPixels > 0);  // premise: slivers through pixel centres are drawn
  CHECK(hugePixels > 0);
  // Step 3: the whole image is the oracle's.
  const ref::Result expected = ref::rasterize(m.mixed.positions, m.mixed.indices, glm::mat4(1.0f), {kW, kH, false});
  CHECK(test::countDifferences(ids, expected.triId) == 0);
}

TEST_CASE("stability: barycentrics of every covered sample are finite, in [0, 1] and exact to 2^-21", "[stability][aa]")
{
  // b_i = float(E_i) · float(1 / float(2·area)): four roundings of 2^-24
  // relative each, so |b_i − E_i / 2·area| <= 4·2^-24·b_i < 2^-22; the test
  // allows 2^-21 per coordinate and 2^-20 for b0 = 1 − b1 − b2.
  const double tol = std::ldexp(1.0, -21);
  const Mixed m = mixedScene(3);
  const uint32_t samples = GENERATE(1u, 16u);
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(m.mixed.mesh());
  clr::FrameSettings s = test::keepingVis(test::idSettings(kW, kH));
  s.samples = samples;
  std::vector<uint32_t> rgba;
  pipeline.render(s, rgba);
  const std::vector<clr::SetupRecord> setup = pipeline.readSetup();
  const FrameParams& params = pipeline.params();
  size_t covered = 0, bad = 0;
  double worst = 0.0;
  for (uint32_t k = 0; k < samples; ++k) {
    const std::vector<VisSample> vis = pipeline.readVis(k);
    for (uint32_t y = 0; y < kH; ++y)
      for (uint32_t x = 0; x < kW; ++x) {
        const VisSample& v = vis[size_t(y) * kW + x];
        if (v.setupIndex == CLR_NONE) continue;
        ++covered;
        const clr::SetupRecord& t = setup.at(v.setupIndex);
        // Exact barycentrics at the sample position, from the snapped record.
        const int64_t px = int64_t(x) * CLR_FIXED_ONE + CLR_FIXED_HALF + params.sampleX[k];
        const int64_t py = int64_t(y) * CLR_FIXED_ONE + CLR_FIXED_HALF + params.sampleY[k];
        auto edge = [&](int a, int b) {
          return double(int64_t(t.x[b] - t.x[a]) * (py - t.y[a]) - int64_t(t.y[b] - t.y[a]) * (px - t.x[a]));
        };
        const double area2 = edge(0, 1) * 0 + double(int64_t(t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) -
                                                     int64_t(t.x[2] - t.x[0]) * (t.y[1] - t.y[0]));
        const double e1 = edge(2, 0), e2 = edge(0, 1);
        const double b0 = 1.0 - double(v.b1) - double(v.b2);
        const bool finite = std::isfinite(v.b1) && std::isfinite(v.b2) && std::isfinite(v.depth);
        const double d1 = std::abs(v.b1 - e1 / area2), d2 = std::abs(v.b2 - e2 / area2);
        worst = std::max({worst, d1, d2});
        bad += !finite || v.b1 < 0.0f || v.b2 < 0.0f || v.b1 > 1.0 + tol || v.b2 > 1.0 + tol || b0 < -2 * tol ||
               d1 > tol || d2 > tol || std::abs(b0 - (area2 - e1 - e2) / area2) > 2 * tol;
      }
  }
  INFO("largest deviation from the exact barycentric: " << worst);
  CHECK(covered > samples * kW * kH / 2);
  CHECK(bad == 0);
}

TEST_CASE("stability: 250,000 triangles in one tile, none dropped", "[stability][load]")
{
  // 10 million is the bench case (bench/stability.sh, docs/limits.md); a
  // quarter million keeps this test to a few seconds, under ASan too.
  const uint32_t n = 250000, W = 128, H = 128;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> in(16 * 256 + 64, 32 * 256 - 64);  // inside tile (1, 1)
  Geometry g;
  g.positions.reserve(9 * size_t(n));
  g.indices.reserve(3 * size_t(n));
  for (uint32_t t = 0; t < n; ++t) {
    const float z = 1.0f - 2.0f * float(t + 1) / float(n + 2);  // later triangles nearer
    g.addTriangle(screen(in(rng) / 256.0f, in(rng) / 256.0f, z, W, H),
                  screen(in(rng) / 256.0f, in(rng) / 256.0f, z, W, H),
                  screen(in(rng) / 256.0f, in(rng) / 256.0f, z, W, H));
  }
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  std::vector<uint32_t> rgba;
  const clr::FrameStats stats = pipeline.render(test::allBinned(test::idSettings(W, H)), rgba);
  // Every setup triangle is in the one tile's bin exactly once.
  const uint32_t tile = 1 * (W / CLR_TILE_SIZE) + 1;
  const std::vector<uint32_t> offsets = pipeline.readTileOffsets();
  CHECK(stats.binEntries == stats.setupTriangles);
  CHECK(offsets[tile + 1] - offsets[tile] == stats.setupTriangles);
  std::vector<uint32_t> bin = pipeline.readBinEntries();
  std::sort(bin.begin(), bin.end());
  std::vector<uint32_t> all(stats.setupTriangles);
  std::iota(all.begin(), all.end(), 0u);
  CHECK(bin == all);
  CHECK(stats.setupTriangles + stats.trianglesCulled == n);
  CHECK(stats.setupTriangles > n * 9 / 10);  // premise: most cover a pixel centre
  const ref::Result expected = ref::rasterize(g.positions, g.indices, glm::mat4(1.0f), {W, H, false});
  CHECK(test::countDifferences(test::readTriIds(pipeline), expected.triId) == 0);
}

namespace {

// n triangles that each cover the whole viewport, at distinct depths with
// the nearest (a tie of two) in the middle of the list; or n copies of one
// triangle inside tile (0, 0) at the same depths.
Geometry stackedTriangles(uint32_t n, bool fullScreen)
{
  Geometry g;
  for (uint32_t t = 0; t < n; ++t) {
    const uint32_t nearest = n / 2;
    const float z = t == nearest || t == nearest + 1 ? -0.95f : 0.9f * std::cos(float(t));
    if (fullScreen)
      g.addTriangle({-1, -1, z}, {3, -1, z}, {-1, 3, z});
    else
      g.addTriangle({-0.999f, -0.999f, z}, {-0.99f, -0.999f, z}, {-0.999f, -0.99f, z});
  }
  return g;
}

}  // namespace

TEST_CASE("stability: a thousand full-screen triangles at 1920x1080, none dropped, memory from the counts",
          "[stability][load]")
{
  const uint32_t n = 1000, W = 1920, H = 1080;
  const uint64_t tiles = uint64_t((W + 15) / 16) * ((H + 15) / 16);
  clr::Pipeline full(test::context());
  full.uploadScene(stackedTriangles(n, true).mesh());
  std::vector<uint32_t> rgba;
  const clr::FrameStats stats = full.render(test::idSettings(W, H), rgba);
  const std::vector<uint32_t> ids = test::readTriIds(full);
  // Step 1: every tile's bin holds every triangle once; the nearest (the
  // earlier of the tied pair) wins every pixel.
  CHECK(stats.setupTriangles == n);
  CHECK(stats.binEntries == n * tiles);
  const std::vector<uint32_t> offsets = full.readTileOffsets();
  const std::vector<uint32_t> bins = full.readBinEntries();
  size_t badTiles = 0;
  std::vector<uint32_t> all(n);
  std::iota(all.begin(), all.end(), 0u);
  for (uint64_t t = 0; t < tiles; ++t) {
    std::vector<uint32_t> bin(bins.begin() + offsets[t], bins.begin() + offsets[t + 1]);
    std::sort(bin.begin(), bin.end());
    badTiles += bin != all;
  }
  CHECK(badTiles == 0);
  CHECK(size_t(std::count(ids.begin(), ids.end(), n / 2)) == ids.size());
  // Step 2: the same number of triangles in one tile: every buffer but the
  // bins and the visibility buffer (a block per covered tile, shared.h) has
  // the same size, so the device bytes differ by those alone. The visibility
  // buffer is the setup-index plane (no depth and barycentric planes), of
  // 16-bit entries (fewer than 0xFFFF setup records), two per 32-bit word.
  // Each pipeline's first frame allocates what it needs, without growth
  // slack (buffer.h).
  clr::Pipeline small(test::context());
  small.uploadScene(stackedTriangles(n, false).mesh());
  const clr::FrameStats smallStats = small.render(test::idSettings(W, H), rgba);
  CHECK(smallStats.binEntries == n);
  const uint64_t fullVis = tiles * 256, smallVis = 256;  // entries per sample plane
  CHECK(full.params().visIndexBits == 16u);
  CHECK(full.deviceBytes() - small.deviceBytes() == 4 * stats.binEntries - 4 * n + 2 * fullVis - 2 * smallVis);
}

TEST_CASE("stability: bins larger than the device's largest allocation are a clear error", "[stability][load]")
{
  const uint32_t n = 1000, W = 1920, H = 1080;
  // The bins need 4 B x 1000 x 8160 = 32.6 MB; every other buffer < 25 MB.
  const AllocCap cap(30000000);
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(stackedTriangles(n, true).mesh());
  std::vector<uint32_t> rgba;
  std::string message;
  try {
    pipeline.render(test::idSettings(W, H), rgba);
  } catch (const clr::Error& e) {
    message = e.what();
  }
  INFO(message);
  CHECK(message.find("32640000 bytes for bin entries") != std::string::npos);
  CHECK(message.find("largest allocation (30000000 bytes)") != std::string::npos);
  // The pipeline stays usable: a scene that fits renders correctly.
  pipeline.uploadScene(stackedTriangles(n, false).mesh());
  CHECK(test::renderTriIds(pipeline, test::idSettings(W, H))[W + 1] == n / 2);  // pixel (1, 1)
}

TEST_CASE("stability: CLRASTER_MAX_ALLOC_BYTES makes the command line report the allocation it cannot make",
          "[stability][cli]")
{
  const std::string png = test::tempDir() + "/alloc.png";
  std::remove(png.c_str());
  // 1920x1080 needs 8.3 MB for the visibility buffer's triangle plane alone.
  setenv("CLRASTER_MAX_ALLOC_BYTES", "4000000", 1);
  test::expectError("render -o '" + png + "' --size 1920x1080", "more than the device's largest allocation");
  CHECK(!test::exists(png));
  setenv("CLRASTER_MAX_ALLOC_BYTES", "lots", 1);
  test::expectError("render -o '" + png + "' --size 64x64", "CLRASTER_MAX_ALLOC_BYTES must be a positive number");
  unsetenv("CLRASTER_MAX_ALLOC_BYTES");
  CHECK(!test::exists(png));
}

TEST_CASE(
    "stability: a buffer's first allocation is what the frame needs and growing again adds 1/8 slack up to its bound",
    "[stability]")
{
  clr::DeviceMemory memory;
  memory.context = test::context().context;
  memory.queue = test::context().queue;
  memory.maxAllocBytes = test::context().maxAllocBytes;
  clr::DeviceBuffer<uint32_t> buffer(memory, "test buffer");
  buffer.reserve(1);  // the placeholder of a buffer a frame does not use
  CHECK(buffer.capacity() == 1);
  buffer.reserve(800);  // first use: exact
  CHECK(buffer.capacity() == 800);
  CHECK(memory.bytesAllocated == 4 * 800);
  buffer.reserve(700);  // room enough: kept
  CHECK(buffer.capacity() == 800);
  buffer.reserve(900);  // growing again: 1/8 slack
  CHECK(buffer.capacity() == 900 + 900 / 8);
  buffer.reserve(1000);
  CHECK(buffer.capacity() == 900 + 900 / 8);
  buffer.reserve(2000, false, 2100);  // the slack stops at the bound
  CHECK(buffer.capacity() == 2100);
  buffer.reserve(3000, true);  // exact buffers never take slack
  CHECK(buffer.capacity() == 3000);
  CHECK(memory.bytesAllocated == 4 * 3000);
}

TEST_CASE("memory: a setup triangle costs a 36-byte record and a source word and an input triangle a one-byte count",
          "[stability][load]")
{
  // Three scenes of a few small triangles over pixel (2, 2) of a 64×64
  // viewport: `base` of them; the same and m more outside the viewport
  // (setup's count pass culls them); the same and m more over the pixel.
  // Fewer than 64 triangles in all keep the scans' chunk counts (scan.cpp)
  // the same, and the visibility buffer is tile (0, 0)'s block in each, so
  // the device bytes differ by what each triangle costs (shared.h): its
  // vertices (three positions of 12 bytes; ID frames upload no normals),
  // its indices (12) and its count (1) (the scenes keep the file's order, so
  // the layout binds no map, layout.h); and for a setup triangle its record
  // (36), its source word (4) and its bin entry (4). Each pipeline's first
  // frame allocates exactly what it needs (buffer.h).
  const uint32_t W = 64, H = 64, base = 16, m = 32;
  auto render = [&](uint32_t outside, uint32_t inside) {
    Geometry g;
    for (uint32_t t = 0; t < base + inside; ++t) {
      const float z = -0.5f + 0.01f * float(t);
      g.addTriangle({-0.95f, -0.95f, z}, {-0.85f, -0.95f, z}, {-0.95f, -0.85f, z});
    }
    for (uint32_t t = 0; t < outside; ++t) {  // each its own vertices (equal ones are welded, layout.h)
      const float x = 2.0f + 0.01f * float(t);
      g.addTriangle({x, 0.0f, 0.0f}, {x + 1.0f, 0.0f, 0.0f}, {x, 1.0f, 0.0f});
    }
    auto pipeline = std::make_unique<clr::Pipeline>(test::context());
    pipeline->uploadScene(g.mesh());
    std::vector<uint32_t> rgba;
    const clr::FrameStats stats = pipeline->render(test::allBinned(test::idSettings(W, H)), rgba);
    CHECK(stats.setupTriangles == base + inside);
    CHECK(stats.binEntries == base + inside);
    CHECK(stats.trianglesCulled == outside);
    return pipeline->deviceBytes();
  };
  const size_t bytesBase = render(0, 0), bytesCulled = render(m, 0), bytesKept = render(0, m);
  CHECK(bytesCulled - bytesBase == m * (36 + 12 + 1));
  CHECK(bytesKept - bytesBase == m * (36 + 12 + 1 + 36 + 4 + 4));
}
