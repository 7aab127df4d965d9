// test_spans.cpp — span-table traversal (raster.cl): exact spans give the
// bounding-box scan's samples on real meshes in both work shapes; the
// classic float edge walk runs, and cracks a shared-edge mesh far from the
// origin where exact spans do not; the command line takes both names.
#include "test_support.h"

#include "render/camera.h"
#include "render/flags.h"
#include "cli_support.h"
#include "render/frame_request.h"
#include "render/quality.h"
#include "io/scene.h"
#include "stability_scenes.h"
#include "pipeline/pipeline.h"

#include <catch2/catch.hpp>

#include <cstring>

namespace {

// Every sample plane's triangle IDs and the image of one frame.
struct Frame {
  std::vector<std::vector<uint32_t>> ids;
  std::vector<uint32_t> rgba;
};

Frame renderFrame(clr::Pipeline& pipeline, clr::FrameSettings settings, uint32_t traversal)
{
  settings.traversal = traversal;
  Frame f;
  pipeline.render(settings, f.rgba);
  for (uint32_t k = 0; k < settings.samples; ++k) f.ids.push_back(test::readTriIds(pipeline, k));
  return f;
}

}  // namespace

TEST_CASE("spans: real meshes give the bounding-box scan's samples and image in both work shapes", "[spans]")
{
  const std::string path = GENERATE(std::string(), std::string("/usr/share/assimp/models/OFF/Wuson.off"),
                                    std::string("/usr/share/assimp/models/OBJ/spider.obj"));
  const clr::Mesh mesh = path.empty() ? clr::defaultScene() : clr::loadScene(path);
  const clr::Camera camera = clr::frameCamera({}, clr::meshBounds(mesh));
  for (int lanes : {1, 16})
    for (uint32_t samples : {1u, 4u}) {
      INFO((path.empty() ? "default scene" : path) << ", lanes " << lanes << ", samples " << samples);
      clr::ClContext ctx(test::context().info.name, lanes);
      clr::Pipeline pipeline(ctx);
      pipeline.uploadScene(mesh);
      clr::RenderArgs args;
      args.shadeMode = CLR_SHADE_LAMBERT;
      clr::FrameSettings settings = clr::makeFrameSettings(args, camera, 320, 240, clr::meshBounds(mesh));
      settings.samples = samples;
      const Frame bbox = renderFrame(pipeline, settings, CLR_TRAVERSAL_BBOX);
      const Frame spans = renderFrame(pipeline, settings, CLR_TRAVERSAL_SPANS);
      size_t covered = 0;
      for (uint32_t id : bbox.ids[0]) covered += id != ref::kNone;
      CHECK(covered > 2000);
      for (uint32_t k = 0; k < samples; ++k) CHECK(test::countDifferences(spans.ids[k], bbox.ids[k]) == 0);
      CHECK(test::countDifferences(spans.rgba, bbox.rgba) == 0);
    }
}

TEST_CASE("spans: the float edge walk cracks a far shared-edge mesh where exact spans do not", "[spans][stability]")
{
  // The band mesh (stability_scenes.h) reaching the guard band: the walk's
  // x, stepped in float from the top vertex and restarted at the split
  // point, misses or doubles samples along shared edges; the exact spans
  // of the same mesh cover every pixel once. Near the viewport both hold.
  const uint32_t W = 256, H = 256;
  clr::FrameSettings exact, walk;
  exact.width = walk.width = W;
  exact.height = walk.height = H;
  exact.traversal = CLR_TRAVERSAL_SPANS;
  walk.traversal = CLR_TRAVERSAL_SPANS_FLOAT;
  const stab::Scene far = stab::bandMesh(W, H, stab::guardBandReach(W, H, 32, 35.0), 32, 35.0, 1);
  CHECK(far.magnitude > 60000.0);
  const stab::Cracks exactFar = stab::countCracks(stab::coverageCounts(test::context(), far, exact));
  const stab::Cracks walkFar = stab::countCracks(stab::coverageCounts(test::context(), far, walk));
  INFO("walk: holes " << walkFar.holes << ", doubles " << walkFar.doubles);
  CHECK(exactFar.total() == 0);
  CHECK(walkFar.total() > 0);
  const stab::Scene near = stab::bandMesh(W, H, 256.0, 32, 35.0, 1);
  CHECK(stab::countCracks(stab::coverageCounts(test::context(), near, exact)).total() == 0);
}

TEST_CASE("spans: the command line takes both span traversals and names them in the stats", "[spans][cli]")
{
  for (const char* name : {"spans", "spans-float"}) {
    INFO(name);
    const std::string out = test::tempDir() + "/spans_" + name + ".png";
    const test::Run r = test::run(std::string("render -o ") + out + " --size 64x48 --traversal " + name + " --stats");
    CHECK(r.status == 0);
    CHECK(r.out.find(std::string("\"traversal\":\"") + name + "\"") != std::string::npos);
    CHECK(test::exists(out));
  }
  test::expectError("render -o x.png --traversal spans-exact", "--traversal");
  test::expectError("render -o x.png --edges float --traversal spans", "float edges");
}

TEST_CASE("spans: quality auto takes exact spans only as its probe frames decide and never the float walk",
          "[spans][auto]")
{
  // The choice rests on the probe frames' kernel times, which this test
  // does not judge: it checks that both methods were probed and the rule
  // applied to what was measured, and that float edges probe nothing.
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(test::randomTriangles(3, 400).mesh());
  clr::FrameSettings settings = test::idSettings(160, 120);
  const clr::AutoChoice choice = clr::chooseAutomatically(pipeline, settings, false, true);
  INFO(choice.json());
  CHECK(choice.ruleMs > 0.0);
  CHECK(choice.spansMs > 0.0);
  const bool spans = choice.spansMs < clr::kSpansMargin * choice.ruleMs;
  CHECK(choice.traversal == (spans ? CLR_TRAVERSAL_SPANS : CLR_TRAVERSAL_BBOX));
  CHECK(settings.traversal == choice.traversal);
  clr::FrameSettings floatEdges = test::idSettings(160, 120);
  floatEdges.edgeMode = CLR_EDGES_FLOAT;
  const clr::AutoChoice floatChoice = clr::chooseAutomatically(pipeline, floatEdges, false, true);
  CHECK(floatChoice.spansMs == 0.0);
  CHECK(floatEdges.traversal == CLR_TRAVERSAL_BBOX);
}
