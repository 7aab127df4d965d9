// test_bin.cpp — binning on the device (bin.cl): every triangle reaches
// every tile its pixel bounds touch, however many share a tile, and no other.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

using test::Geometry;
using test::screen;

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
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::allBinned(test::idSettings(W, H)));
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
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::allBinned(test::idSettings(W, H)));
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
