// api_test.cpp — the public C++ API (include/clraster/clraster.hpp) as a
// program outside the library sees it (api_tests links only libclraster):
// rasterize's ids against the scalar oracle exactly, its outputs' layout,
// interpolate against the barycentric formula, the id encoding, the scene
// level, and that bad arguments are clraster::Errors naming them.
#include "reference_raster.h"

#include <clraster/clraster.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <random>

namespace {

clraster::Context& context()
{
  static clraster::Context ctx(std::getenv("CLRASTER_TEST_DEVICE") ? std::getenv("CLRASTER_TEST_DEVICE") : "");
  return ctx;
}

// count random clip-space triangles with w in [0.5, 3]; some cross the near
// plane or reach beyond the guard band.
void randomTriangles(uint32_t seed, size_t count, std::vector<float>& pos, std::vector<int32_t>& tri)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.3f, 1.3f), depth(-1.2f, 0.9f), w(0.5f, 3.0f);
  pos.clear();
  tri.clear();
  for (size_t v = 0; v < 3 * count; ++v) {
    const float wv = w(rng);
    const float scale = v % 17 == 0 ? 2000.0f : 1.0f;
    pos.insert(pos.end(), {unit(rng) * wv * scale, unit(rng) * wv, depth(rng) * wv, wv});
    tri.push_back(int32_t(v));
  }
}

}  // namespace

TEST_CASE("api rasterize ids equal the oracle", "[api]")
{
  for (uint32_t seed = 1; seed <= 3; ++seed) {
    std::vector<float> pos;
    std::vector<int32_t> tri;
    randomTriangles(seed, 60, pos, tri);
    const uint32_t w = 40 + 13 * seed, h = 70 - 9 * seed;
    const clraster::Raster r =
        clraster::rasterize(context(), pos.data(), pos.size() / 4, tri.data(), tri.size() / 3, w, h, true);
    REQUIRE(r.rast.size() == size_t(w) * h * 4);
    REQUIRE(r.db.size() == size_t(w) * h * 4);
    ref::Options o;
    o.width = w;
    o.height = h;
    const ref::Result expected = ref::rasterizeClip(pos, {tri.begin(), tri.end()}, o);
    size_t covered = 0;
    for (size_t p = 0; p < r.ids.size(); ++p) {
      const uint32_t want = expected.triId[p] == ref::kNone ? 0u : expected.triId[p] + 1;
      REQUIRE(r.ids[p] == want);
      REQUIRE(clraster::decodeTriangleId(r.rast[4 * p + 3]) == want);
      covered += want != 0;
      if (!want) REQUIRE((r.rast[4 * p] == 0.0f && r.rast[4 * p + 1] == 0.0f && r.rast[4 * p + 2] == 0.0f));
    }
    REQUIRE(covered > size_t(w) * h / 4);
  }
}

TEST_CASE("api interpolate follows the barycentric formula", "[api]")
{
  std::vector<float> pos;
  std::vector<int32_t> tri;
  randomTriangles(9, 30, pos, tri);
  const size_t nv = pos.size() / 4;
  const clraster::Raster r = clraster::rasterize(context(), pos.data(), nv, tri.data(), tri.size() / 3, 32, 24);
  std::vector<float> attr(2 * nv);
  for (size_t k = 0; k < attr.size(); ++k) attr[k] = float(k % 7) - 2.5f;
  const std::vector<float> out = clraster::interpolate(context(), attr.data(), nv, 2, r, tri.data());
  REQUIRE(out.size() == 32 * 24 * 2);
  for (size_t p = 0; p < r.ids.size(); ++p)
    for (size_t c = 0; c < 2; ++c) {
      float want = 0.0f;
      if (r.ids[p]) {
        const int32_t* t = &tri[3 * (r.ids[p] - 1)];
        const float u = r.rast[4 * p], v = r.rast[4 * p + 1];
        want = u * attr[2 * t[0] + c] + v * attr[2 * t[1] + c] + (1.0f - u - v) * attr[2 * t[2] + c];
      }
      REQUIRE(out[2 * p + c] == want);  // the same float operations in the same order
    }
}

TEST_CASE("api triangle id encoding is exact", "[api]")
{
  for (uint32_t id : {0u, 1u, 16777215u, 16777216u, 16777217u, 16777219u, 300000001u, 889192447u})
    REQUIRE(clraster::decodeTriangleId(clraster::encodeTriangleId(id)) == id);
  REQUIRE(clraster::encodeTriangleId(16777216u) == 16777216.0f);
  REQUIRE(clraster::decodeTriangleId(std::nanf("")) == 0u);
}

TEST_CASE("api bad arguments are errors naming them", "[api]")
{
  const float pos[] = {-1, -1, 0, 1, 1, -1, 0, 1, 0, 1, 0, 1};
  const int32_t tri[] = {0, 1, 3};
  REQUIRE_THROWS_WITH(clraster::rasterize(context(), pos, 3, tri, 1, 8, 8), Catch::StartsWith("tri: vertex index 3"));
  const int32_t good[] = {0, 1, 2};
  REQUIRE_THROWS_WITH(clraster::rasterize(context(), pos, 3, good, 1, 0, 8), Catch::StartsWith("resolution"));
  REQUIRE_THROWS_WITH(clraster::rasterize(context(), pos, 3, good, 1, 8, 16385), Catch::StartsWith("resolution"));
  REQUIRE_THROWS_WITH(clraster::Context("no-such-device-xyz"), Catch::Contains("--device no-such-device-xyz"));
  REQUIRE_THROWS_WITH(clraster::RenderOptions::parse({"--shade", "glossy"}), Catch::StartsWith("--shade: unknown"));
  REQUIRE_THROWS_WITH(clraster::Scene::load("/nonexistent/model.obj"), Catch::Contains("/nonexistent/model.obj"));
  clraster::Raster r = clraster::rasterize(context(), pos, 3, good, 1, 8, 8);
  r.rast.pop_back();
  const float attr[] = {0, 1, 2};
  REQUIRE_THROWS_WITH(clraster::interpolate(context(), attr, 3, 1, r, good), Catch::StartsWith("raster: "));
}

TEST_CASE("api interpolate refuses a rast naming no triangle", "[api]")
{
  const float pos[] = {-1, -1, 0, 1, 1, -1, 0, 1, 0, 1, 0, 1};
  const int32_t tri[] = {0, 1, 2};
  const float attr[] = {0, 1, 2};
  const clraster::Raster good = clraster::rasterize(context(), pos, 3, tri, 1, 8, 8);
  REQUIRE(clraster::interpolate(context(), attr, 3, 1, good, tri).size() == 64);
  // Channel 3 of one pixel: an id beyond the one triangle, negative, NaN,
  // huge, or between two ids.
  for (float bad : {2.0f, 7.0f, -3.0f, std::nanf(""), 1e30f, 0.5f}) {
    clraster::Raster r = good;
    r.rast[4 * 5 + 3] = bad;
    REQUIRE_THROWS_WITH(clraster::interpolate(context(), attr, 3, 1, r, tri),
                        Catch::StartsWith("rast: pixel 5 holds triangle id channel") && Catch::Contains("0..1"));
  }
}

TEST_CASE("api renderer draws the built in scene", "[api]")
{
  const clraster::Scene scene = clraster::Scene::builtin();
  REQUIRE(scene.numTriangles() > 0);
  clraster::Renderer renderer(context(), scene);
  clraster::RenderOptions options = clraster::RenderOptions::parse({"--size", "64x48"});
  options.set("--shade", "id");
  clraster::FrameStats stats;
  const clraster::Image image = renderer.render(options, &stats);
  REQUIRE(image.width == 64);
  REQUIRE(image.height == 48);
  REQUIRE(stats.trianglesIn == scene.numTriangles());
  size_t drawn = 0;
  for (uint32_t px : image.rgba) {
    const uint32_t id = px & 0xFFFFFFu;
    REQUIRE(id <= scene.numTriangles());
    drawn += id != 0;
  }
  REQUIRE(drawn > 64 * 48 / 10);
}

TEST_CASE("api moved from objects and null outputs are errors", "[api]")
{
  clraster::Context ctx(std::getenv("CLRASTER_TEST_DEVICE") ? std::getenv("CLRASTER_TEST_DEVICE") : "");
  clraster::Context moved = std::move(ctx);
  const float pos[] = {-1, -1, 0, 1, 1, -1, 0, 1, 0, 1, 0, 1};
  const int32_t tri[] = {0, 1, 2};
  REQUIRE_THROWS_WITH(clraster::rasterize(ctx, pos, 3, tri, 1, 8, 8), Catch::Contains("moved from"));
  REQUIRE_THROWS_WITH(ctx.device(), Catch::Contains("moved from"));
  clraster::Scene scene = clraster::Scene::builtin();
  clraster::Scene other = std::move(scene);
  REQUIRE_THROWS_WITH(scene.numTriangles(), Catch::Contains("clraster::Scene: used after it was moved from"));
  REQUIRE_THROWS_WITH(clraster::Renderer(moved, scene), Catch::Contains("clraster::Scene"));
  const float rast[4] = {0.3f, 0.3f, 0.5f, 1.0f}, attr[] = {1, 2, 3};
  float out[1];
  REQUIRE_THROWS_WITH(clraster::interpolateInto(attr, 3, 1, rast, 1, tri, 1, nullptr), Catch::StartsWith("out: null"));
  REQUIRE_THROWS_WITH(clraster::interpolateInto(attr, 3, 1, nullptr, 1, tri, 1, out), Catch::StartsWith("rast: null"));
  REQUIRE_THROWS_WITH(clraster::Context("99999999999999999999"), Catch::Contains("no such device index"));
}

TEST_CASE("api options name the flag at fault", "[api]")
{
  using clraster::RenderOptions;
  REQUIRE_THROWS_WITH(RenderOptions::parse({"--shade"}), Catch::Equals("--shade: missing value"));
  REQUIRE_THROWS_WITH(RenderOptions::parse({"--eye"}), Catch::Equals("--eye: missing value"));
  REQUIRE_THROWS_WITH(RenderOptions().set("--fov"), Catch::Equals("--fov: missing value"));
  REQUIRE_THROWS_WITH(RenderOptions().set("--stats", "yes"), Catch::StartsWith("--stats: takes no value"));
  REQUIRE_THROWS_WITH(RenderOptions().set("fov", "30"), Catch::Contains("'fov' is not a flag"));
  RenderOptions views = RenderOptions::parse({"--views", "v.json"});
  views.set("--shard", "1/2");  // checked against --views given before
  REQUIRE(views.viewsPath() == "v.json");
  REQUIRE(RenderOptions().set("--size", "32x16").width() == 32);
  REQUIRE_THROWS_WITH(RenderOptions::parse({"--fov", "0x2Dp0"}), Catch::StartsWith("--fov: '0x2Dp0'"));
  REQUIRE_THROWS_WITH(RenderOptions::parse({"--frames", " 2"}), Catch::StartsWith("--frames: ' 2'"));
  // The derived camera: a fov too narrow for float names --fov, not the planes it derives.
  REQUIRE_THROWS_WITH(clraster::render(context(), RenderOptions::parse({"--size", "8x8", "--fov", "1e-30"})),
                      Catch::StartsWith("--fov: too narrow"));
}

TEST_CASE("api outputs are refused where the command line refuses them", "[api]")
{
  REQUIRE_THROWS_WITH(clraster::render(context(), clraster::RenderOptions::parse({"--views", "v.json"})),
                      Catch::StartsWith("--views: render() draws one view"));
  clraster::Renderer renderer(context(), clraster::Scene::builtin());
  REQUIRE_THROWS_WITH(renderer.render(clraster::RenderOptions::parse({"--views", "v.json"})),
                      Catch::StartsWith("--views"));
  const clraster::Image image = renderer.render(clraster::RenderOptions::parse({"--size", "8x8"}));
  REQUIRE_THROWS_WITH(clraster::writePng("image.jpg", image), Catch::Contains("must be a file name ending in .png"));
  REQUIRE_THROWS_WITH(clraster::writePng("empty.png", clraster::Image{}), Catch::Contains("empty"));
  REQUIRE_THROWS_WITH(renderer.writeAov("vis.png"), Catch::Contains("ending in .exr"));
  std::unique_ptr<clraster::Context> built;
  REQUIRE_THROWS_WITH(clraster::renderCommand(clraster::RenderOptions(), built), Catch::StartsWith("missing -o"));
}

TEST_CASE("api calls past the memory limit are refused naming the size", "[api]")
{
  clraster::Context ctx(std::getenv("CLRASTER_TEST_DEVICE") ? std::getenv("CLRASTER_TEST_DEVICE") : "");
  const float pos[] = {-1, -1, 0, 1, 1, -1, 0, 1, 0, 1, 0, 1};
  const int32_t tri[] = {0, 1, 2};
  ctx.setMemoryLimit(1 << 20);
  REQUIRE(ctx.memoryLimit() == 1u << 20);
  REQUIRE_THROWS_WITH(clraster::rasterize(ctx, pos, 3, tri, 1, 512, 512),
                      Catch::StartsWith("rasterize at 512x512 needs ") && Catch::Contains("more than the limit of"));
  std::vector<float> rast(4 * 512 * 512);
  REQUIRE_THROWS_WITH(clraster::rasterizeInto(ctx, pos, 3, tri, 1, 512, 512, rast.data(), nullptr),
                      Catch::Contains("bytes"));
  REQUIRE(clraster::rasterize(ctx, pos, 3, tri, 1, 16, 16).ids[16 * 8 + 8] == 1);
  // Huge sizes: refused by the limit, the device's memory or the host's, never an abort.
  ctx.setMemoryLimit(0);
  for (uint32_t side : {16384u, 12000u, 1u})
    for (uint64_t outputs : {uint64_t(1) << 50, ~uint64_t(0) / 2}) {
      try {
        clraster::checkRasterizeMemory(ctx, side, 16384, outputs);
        FAIL("outputs of " << outputs << " bytes at " << side << "x16384 were not refused");
      } catch (const clraster::Error& e) {
        CHECK_THAT(e.what(), Catch::Contains(" bytes ("));
      }
    }
  REQUIRE_THROWS_WITH(clraster::checkRasterizeMemory(ctx, 0, 8, 0), Catch::StartsWith("resolution"));
  // release() frees what calls kept; the next call allocates again.
  ctx.release();
  REQUIRE(clraster::rasterize(ctx, pos, 3, tri, 1, 16, 16).ids[16 * 8 + 8] == 1);
}

TEST_CASE("api scenes reach only their folder unless assets widens it", "[api][assets]")
{
  // A glTF in DIR/model whose buffer is DIR/secret.bin (issue: its bytes came out as vertex data).
  char dirTemplate[] = "/tmp/clraster-api-assets-XXXXXX";
  REQUIRE(mkdtemp(dirTemplate));
  const std::string dir = dirTemplate;
  REQUIRE(std::system(("mkdir '" + dir + "/model'").c_str()) == 0);
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  FILE* bin = std::fopen((dir + "/secret.bin").c_str(), "wb");
  REQUIRE(bin);
  std::fwrite(positions, sizeof positions, 1, bin);
  std::fclose(bin);
  const std::string model = dir + "/model/up.gltf";
  FILE* gltf = std::fopen(model.c_str(), "w");
  REQUIRE(gltf);
  std::fputs(R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "../secret.bin", "byteLength": 36}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}], "accessors": [{"bufferView": 0, "componentType": 5126,
    "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}], "meshes": [{"primitives": [{"attributes":
    {"POSITION": 0}}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})",
             gltf);
  std::fclose(gltf);
  CHECK_THROWS_WITH(clraster::Scene::load(model), Catch::Contains("cannot use '../secret.bin'"));
  const auto options = clraster::RenderOptions::parse({model, "--size", "8x8"});
  CHECK_THROWS_WITH(clraster::render(context(), options), Catch::Contains("cannot use '../secret.bin'"));
  CHECK(clraster::Scene::load(model, dir).numTriangles() == 1);
  CHECK(clraster::Scene::load(model, "any").numTriangles() == 1);
  const auto widened = clraster::RenderOptions::parse({model, "--size", "8x8", "--assets", dir});
  CHECK(clraster::render(context(), widened).width == 8);
  REQUIRE(std::system(("rm -rf '" + dir + "'").c_str()) == 0);
}
