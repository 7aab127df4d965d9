// test_micro.cpp — the micro-triangle path (kernels/micro.h) changes no
// output: frames with it (FrameSettings.microMax above 0) and without it (0)
// give bit-identical images and visibility planes (setup index, depth and
// barycentrics of every sample) at 1, 4 and 16 samples, for small random
// triangles some through the near plane, a jittered grid with vertices on
// pixel centres (the fill rule decides shared edges) and coplanar scenes in
// which every sample is a depth tie (the earlier triangle in the file wins),
// in the file's order and shuffled, and assimp's test models through the
// render command's settings at every limit. Each frame with the path also
// shows it took triangles out of the bins.
#include "test_support.h"

#include "io/scene.h"
#include "pipeline/layout.h"
#include "pipeline/pipeline.h"
#include "render/flags.h"
#include "render/frame_request.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cstring>
#include <random>

namespace {

// A frame's outputs: the image and every sample plane of the visibility buffer.
struct Frame {
  std::vector<uint32_t> rgba;
  std::vector<std::vector<VisSample>> vis;
  uint64_t binEntries = 0;
  uint32_t microMax = 0;  // the limit the frame took (FrameStats)
};

Frame renderFrame(const clr::Mesh& mesh, clr::FrameSettings settings, int32_t microMax)
{
  settings.microMax = microMax;
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(mesh);
  Frame f;
  const clr::FrameStats stats = pipeline.render(settings, f.rgba);
  f.binEntries = stats.binEntries;
  f.microMax = stats.microMax;
  for (uint32_t k = 0; k < settings.samples; ++k) f.vis.push_back(pipeline.readVis(k));
  return f;
}

// Renders with and without the path at 1, 4 and 16 samples, in the shade
// modes and depth formats given, with and without the depth and barycentric
// planes, and requires the same bytes.
void compareMicro(const clr::Mesh& mesh, const glm::mat4& mvp, uint32_t width, uint32_t height,
                  std::initializer_list<uint32_t> shadeModes, std::initializer_list<uint32_t> depthModes,
                  uint32_t traversal = CLR_TRAVERSAL_BBOX)
{
  for (uint32_t samples : {1u, 4u, 16u})
    for (uint32_t shade : shadeModes)
      for (uint32_t depth : depthModes)
        for (bool keepVis : {false, true}) {
          clr::FrameSettings s = test::idSettings(width, height, mvp);
          s.samples = samples;
          s.shadeMode = shade;
          s.depthMode = depth;
          s.keepVisAttributes = keepVis;
          s.traversal = traversal;
          INFO("traversal " << traversal << ", "
                            << "samples " << samples << ", shade " << shade << ", depth " << depth << ", planes "
                            << keepVis);
          const Frame off = renderFrame(mesh, s, 0);
          const Frame on = renderFrame(mesh, s, CLR_TILE_SIZE * CLR_TILE_SIZE);
          CHECK(on.binEntries < off.binEntries);  // the path took triangles
          CHECK(off.microMax == 0);
          CHECK(on.microMax == CLR_TILE_SIZE * CLR_TILE_SIZE);
          REQUIRE(on.rgba == off.rgba);
          size_t covered = 0, differing = 0;
          for (uint32_t k = 0; k < samples; ++k) {
            REQUIRE(on.vis[k].size() == off.vis[k].size());
            for (size_t p = 0; p < on.vis[k].size(); ++p) {
              covered += off.vis[k][p].setupIndex != CLR_NONE;
              differing += std::memcmp(&on.vis[k][p], &off.vis[k][p], sizeof(VisSample)) != 0;
            }
          }
          CHECK(differing == 0);
          CHECK(covered > 0);
        }
}

// A screen-space grid of n×n cells over W×H pixels at depth z, its vertices
// jittered on the subpixel grid and many on pixel centres (as test_watertight).
void addGrid(test::Geometry& g, uint32_t width, uint32_t height, int n, float z, uint32_t seed)
{
  std::mt19937 rng(seed);
  std::vector<glm::vec3> grid;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const glm::vec2 p = test::jitterVertex(float(width) * i / n, float(height) * j / n, 40, rng);
      grid.push_back(test::screen(p.x, p.y, z, width, height));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const glm::vec3 v = grid[j * (n + 1) + i], r = grid[j * (n + 1) + i + 1];
      const glm::vec3 u = grid[(j + 1) * (n + 1) + i], ur = grid[(j + 1) * (n + 1) + i + 1];
      g.addTriangle(v, r, ur);
      g.addTriangle(v, ur, u);
    }
}

}  // namespace

TEST_CASE("micro: small random triangles some through the near plane match the binned path", "[micro][differential]")
{
  std::mt19937 rng(48);
  std::uniform_real_distribution<float> coord(-3.0f, 3.0f), depth(-8.0f, 5.5f), size(0.005f, 0.12f);
  test::Geometry g;
  for (int t = 0; t < 3000; ++t) {
    const glm::vec3 c(coord(rng), coord(rng), depth(rng));
    const float r = t % 50 == 0 ? 2.0f : size(rng);  // a few large ones, binned, among them
    std::uniform_real_distribution<float> off(-r, r);
    g.addTriangle(c + glm::vec3(off(rng), off(rng), off(rng)), c + glm::vec3(off(rng), off(rng), off(rng)),
                  c + glm::vec3(off(rng), off(rng), off(rng)));
  }
  const uint32_t width = 200, height = 150;  // not a multiple of the tile size
  const glm::mat4 mvp = glm::perspective(glm::radians(50.0f), float(width) / height, 0.25f, 40.0f) *
                        glm::lookAt(glm::vec3(0.3f, 0.8f, 6.0f), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0));
  compareMicro(g.mesh(), mvp, width, height, {CLR_SHADE_ID, CLR_SHADE_LAMBERT}, {CLR_DEPTH_FLOAT32, CLR_DEPTH_UNORM24});
}

TEST_CASE("micro: a jittered pixel-centre grid matches the binned path", "[micro][watertight]")
{
  // Cells of about 1.5 px: most triangles hold one to four pixel centres, and
  // many edges run through centres, where only the fill rule decides.
  test::Geometry g;
  addGrid(g, 128, 128, 84, 0.25f, 5);
  // Every exact traversal merges the path's fragments (raster.cl's variants).
  const uint32_t traversal = GENERATE(CLR_TRAVERSAL_BBOX, CLR_TRAVERSAL_HIERARCHICAL, CLR_TRAVERSAL_SPANS);
  compareMicro(g.mesh(), glm::mat4(1.0f), 128, 128, {CLR_SHADE_ID, CLR_SHADE_DEPTH}, {CLR_DEPTH_FLOAT32}, traversal);
}

TEST_CASE("micro: depth ties go to the earlier triangle in the file", "[micro][depth]")
{
  // Everything at one depth, so every covered sample is a tie: two copies
  // of a fine grid (micro triangles tie with micro triangles) over a large
  // quad (binned ones tie with micro ones), in the file's order and
  // shuffled (the ties then follow the file's ranks, not the layout's).
  test::Geometry g;
  const uint32_t W = 128, H = 128;
  addGrid(g, W, H, 70, 0.0f, 9);
  g.addTriangle(test::screen(-4, -4, 0, W, H), test::screen(W + 4.0f, -4, 0, W, H),
                test::screen(W + 4.0f, H + 4.0f, 0, W, H));
  g.addTriangle(test::screen(-4, -4, 0, W, H), test::screen(W + 4.0f, H + 4.0f, 0, W, H),
                test::screen(-4, H + 4.0f, 0, W, H));
  addGrid(g, W, H, 70, 0.0f, 9);
  const clr::Mesh inOrder = g.mesh();
  const bool shuffled = GENERATE(false, true);
  INFO("shuffled " << shuffled);
  compareMicro(shuffled ? clr::shuffledTriangles(inOrder, 31) : inOrder, glm::mat4(1.0f), W, H, {CLR_SHADE_ID},
               {CLR_DEPTH_FLOAT32});
}

TEST_CASE("micro: a speculative frame with too few micro slots is redone and matches", "[micro][speculation]")
{
  // Frame 1 sees the grid from afar (few tiles, few micro slots); frame 2
  // fills the view, needing more slots than frame 1 sized, so it is redone
  // waiting; frame 3 repeats frame 2 speculatively. Each matches a frame
  // without the path.
  test::Geometry g;
  addGrid(g, 128, 128, 84, 0.25f, 6);
  const clr::Mesh mesh = clr::shuffledTriangles(g.mesh(), 3);
  const glm::mat4 far = glm::scale(glm::mat4(1.0f), glm::vec3(0.2f, 0.2f, 1.0f));
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(mesh);
  std::vector<uint32_t> rgba;
  clr::FrameSettings first = test::idSettings(128, 128, far), full = test::idSettings(128, 128);
  first.microMax = full.microMax = CLR_TILE_SIZE * CLR_TILE_SIZE;
  pipeline.render(first, rgba);
  const Frame off = renderFrame(mesh, full, 0);
  const clr::FrameStats missed = pipeline.render(full, rgba);
  CHECK(missed.speculationMissed);
  CHECK(rgba == off.rgba);
  const clr::FrameStats again = pipeline.render(full, rgba);
  CHECK(again.speculative);
  CHECK(!again.speculationMissed);
  CHECK(again.binEntries < off.binEntries);
  CHECK(rgba == off.rgba);
}

TEST_CASE("micro: a small shuffled grid matches the binned path (Oclgrind size)", "[micro][raster]")
{
  // The raster part of tests/oclgrind_check.sh runs this one: both kernels
  // of the path (setup's claims and fragments, raster's merge) on 32 x 32
  // pixels, ties by paint rank (shuffled), 1 and 4 samples.
  test::Geometry g;
  addGrid(g, 32, 32, 20, 0.0f, 7);
  addGrid(g, 32, 32, 20, 0.0f, 7);
  const clr::Mesh mesh = clr::shuffledTriangles(g.mesh(), 5);
  for (uint32_t samples : {1u, 4u}) {
    clr::FrameSettings s = test::keepingVis(test::idSettings(32, 32));
    s.samples = samples;
    const Frame off = renderFrame(mesh, s, 0), on = renderFrame(mesh, s, 8);
    CHECK(on.binEntries < off.binEntries);
    CHECK(on.rgba == off.rgba);
    for (uint32_t k = 0; k < samples; ++k)
      CHECK(std::memcmp(on.vis[k].data(), off.vis[k].data(), on.vis[k].size() * sizeof(VisSample)) == 0);
  }
}

TEST_CASE("micro: corpus models in both orders match the binned path at every limit", "[micro][layout]")
{
  // Real meshes (a dense subdivision surface, a scan, a textured model, one
  // of many parts), in the file's order and shuffled, through the render
  // command's settings: the CLI's framing, an eye inside the model (near-
  // plane clipping) and one grazing its side. One pipeline switches limits
  // frame by frame; each frame's image, visibility planes and AOVs must be
  // those of the frame without the path.
  const std::string models = "/usr/share/assimp/models/";
  const std::string file = GENERATE(as<std::string>{}, "BLEND/SuzanneSubdiv_252.blend", "OFF/Wuson.off",
                                    "OBJ/spider.obj", "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  const bool shuffle = GENERATE(false, true);
  INFO(file << (shuffle ? ", shuffled" : ""));
  const clr::Mesh loaded = clr::loadScene(models + file);
  const clr::Mesh mesh = shuffle ? clr::shuffledTriangles(loaded, 11) : loaded;
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(mesh);
  const clr::Bounds bounds = clr::meshBounds(mesh);
  const std::vector<std::vector<std::string>> methods = {
      {}, {"--shade", "id"}, {"--aa", "msaa4", "--shade", "phong"}, {"--aa", "ssaa16"}, {"--depth", "unorm24"}};
  size_t fewerBins = 0;  // frames in which the path took triangles out of the bins
  const std::vector<clr::Camera> views = test::modelViews(bounds);
  for (size_t view = 0; view < views.size(); ++view) {
    const clr::Camera& camera = views[view];
    for (std::vector<std::string> words : methods) {
      words.insert(words.end(), {"-o", "x.png"});
      const clr::FrameSettings base =
          test::keepingVis(clr::makeFrameSettings(clr::parseRenderArgs(words), camera, 192, 144, bounds));
      std::vector<uint32_t> offImage, onImage;
      std::vector<float> offAov;
      std::vector<std::vector<VisSample>> offVis;
      uint64_t offBins = 0;
      for (int32_t limit : {0, 1, 4, 16, 256}) {
        INFO("view " << view << ", method " << words.front() << ", limit " << limit);
        clr::FrameSettings s = base;
        s.microMax = limit;
        std::vector<uint32_t>& image = limit == 0 ? offImage : onImage;
        const clr::FrameStats stats = pipeline.render(s, image);
        CHECK(stats.microMax == uint32_t(limit));
        pipeline.aov();
        const std::vector<float> aov = pipeline.readAov();
        if (limit == 0) {
          offAov = aov;
          offBins = stats.binEntries;
          for (uint32_t k = 0; k < s.samples; ++k) offVis.push_back(pipeline.readVis(k));
          continue;
        }
        fewerBins += stats.binEntries < offBins;
        REQUIRE(onImage == offImage);
        CHECK(test::sameBytes(aov, offAov));
        for (uint32_t k = 0; k < s.samples; ++k) {
          const std::vector<VisSample> vis = pipeline.readVis(k);
          REQUIRE(vis.size() == offVis[k].size());
          CHECK(std::memcmp(vis.data(), offVis[k].data(), vis.size() * sizeof(VisSample)) == 0);
        }
      }
    }
  }
  CHECK(fewerBins > 0);
}
