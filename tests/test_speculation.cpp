// test_speculation.cpp — frames sized from the last frame's totals
// (Pipeline::runFrame): a sequence of cameras and settings that grows and
// shrinks every total, crosses 16-bit indices, clips, empties the view,
// changes the viewport and the sample count, renders byte for byte as
// frames that wait for their counts, with the same counts; the frames that
// could not fit ran again, and the steady ones never waited.
#include "test_support.h"

#include "render/camera.h"
#include "render/flags.h"
#include "render/frame_request.h"
#include "io/scene.h"
#include "pipeline/pipeline.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <string>
#include <vector>

namespace {

// One frame of the sequence: an eye on the direction from the model's centre
// at `distance` bounding radii (0: the CLI's framing; negative: looking
// away), and render flags.
struct Step {
  glm::vec3 direction;
  float distance, nearRadii;  // nearRadii: the near plane's distance (0: the CLI's)
  std::vector<std::string> flags;
};

}  // namespace

TEST_CASE("Frames sized from the last frame's totals render as frames that wait", "[speculation]")
{
  // Step 1: a real model of 252k triangles, so a frame can hold more than
  // 0xFFFF setup records (32-bit visibility indices) or fewer.
  const clr::Mesh mesh = clr::loadScene("/usr/share/assimp/models/BLEND/SuzanneSubdiv_252.blend");
  REQUIRE(mesh.numTris() > 200000);
  clr::Pipeline waiting(test::context()), speculating(test::context());
  waiting.setSpeculation(false);
  waiting.uploadScene(mesh);
  speculating.uploadScene(mesh);
  const clr::Bounds bounds = clr::meshBounds(mesh);
  const glm::vec3 centre = 0.5f * (bounds.min + bounds.max);
  const float radius = 0.5f * glm::length(bounds.max - bounds.min);
  const glm::vec3 front(0.1f, 0.2f, 1.0f), side(1.0f, 0.1f, 0.2f);
  const std::vector<Step> steps = {
      {front, 0, 0, {}},                           // whole model: waits (no frame before)
      {front, 0, 0, {}},                           // the same: fits
      {front, 0.9f, 0, {}},                        // closer: past 0xFFFF records, 32-bit indices
      {front, 0.9f, 0, {}},                        // steady
      {side, 4.0f, 0, {}},                         // far: fewer records, still 32-bit
      {side, 4.0f, 0, {}},                         // steady
      {front, 0, 0, {}},                           // the whole model: more records again
      {front, 0.6f, 0.3f, {}},                     // the near plane through the model: clipping
      {front, 0.6f, 0.3f, {}},                     // the last frame clipped: waits
      {front, 0.6f, 0, {}},                        // no clipping again: waits once more
      {front, 0.6f, 0, {}},                        // steady
      {front, 0, 0, {"--aa", "msaa4"}},            // four samples per pixel
      {front, 0, 0, {"--aa", "msaa4"}},            // steady
      {front, 0, 0, {"--size", "640x480"}},        // more tiles
      {front, 0, 0, {"--size", "640x480"}},        // steady
      {front, 0, 0, {"--size", "96x64"}},          // fewer tiles
      {-front, -1, 0, {}},                         // nothing in view (turned away)
      {front, 0, 0, {"--shade", "id"}},            // after an empty frame: waits
      {front, 0, 0, {"--visibility", "painter"}},  // painter's ranks
      {front, 0, 0, {"--wireframe"}},              // lines: waits
      {front, 0, 0, {"--traversal", "spans"}},     // another raster kernel
      {front, 0, 0, {"--shade", "texture"}},       // resolve's general kernel
  };

  size_t speculative = 0, missed = 0, step = 0;
  const Step* last = nullptr;
  bool lastClipped = false, lastEmpty = false;
  for (const Step& s : steps) {
    INFO("step " << step++);
    // Step 2: the camera and settings as the CLI makes them.
    clr::CameraArgs cameraArgs;
    if (s.distance != 0) {
      const glm::vec3 towards = glm::normalize(s.direction);
      cameraArgs.eye = centre + std::abs(s.distance) * radius * towards;
      cameraArgs.target = s.distance > 0 ? centre : centre + 2.0f * std::abs(s.distance) * radius * towards;
    }
    if (s.nearRadii > 0) cameraArgs.zNear = s.nearRadii * radius;
    std::vector<std::string> words = s.flags;
    words.insert(words.end(), {"-o", "x.png"});
    const clr::RenderArgs args = clr::parseRenderArgs(words);
    const clr::Camera camera = clr::frameCamera(cameraArgs, bounds);
    const clr::FrameSettings settings = clr::makeFrameSettings(args, camera, args.width == 1280 ? 320 : args.width,
                                                               args.width == 1280 ? 240 : args.height, bounds);
    // Step 3: both pipelines; the same image, ids and counts.
    std::vector<uint32_t> a, b;
    const clr::FrameStats sa = waiting.render(settings, a);
    const clr::FrameStats sb = speculating.render(settings, b);
    CHECK(!sa.speculative);
    CHECK(!sa.speculationMissed);
    CHECK(a == b);
    CHECK(test::readTriIds(waiting) == test::readTriIds(speculating));
    CHECK(sa.setupTriangles == sb.setupTriangles);
    CHECK(sa.binEntries == sb.binEntries);
    CHECK(sa.trianglesCulled == sb.trianglesCulled);
    CHECK(sa.trianglesClipped == sb.trianglesClipped);
    CHECK(waiting.readSetup().size() == speculating.readSetup().size());
    CHECK(waiting.readBinEntries().size() == speculating.readBinEntries().size());
    speculative += sb.speculative;
    missed += sb.speculationMissed;
    // Step 4: when a frame waits. After a frame that clipped or had nothing
    // in view, and with lines, always; a steady camera's frame never.
    const bool wireframe = !s.flags.empty() && s.flags[0] == "--wireframe";
    if (lastClipped || lastEmpty || wireframe) CHECK(!sb.speculative);
    if (last && !lastClipped && !lastEmpty && !wireframe && s.flags == last->flags && s.direction == last->direction &&
        s.distance == last->distance && s.nearRadii == last->nearRadii)
      CHECK(sb.speculative);
    last = &s;
    lastClipped = sa.trianglesClipped > 0;
    lastEmpty = sa.setupTriangles == 0;
  }
  // Step 5: both outcomes happened: the growths at steps 2, 7 and 11 did not fit.
  CHECK(speculative >= 8);
  CHECK(missed >= 3);
}

TEST_CASE("A speculative frame that does not fit writes within its buffers and runs again", "[setup][speculation]")
{
  // Small enough for Oclgrind (oclgrind_check.sh, geometry), which checks
  // that a frame past its capacities stays inside every buffer: random
  // triangles under a scale that grows and shrinks the records and bins,
  // one that pushes vertices behind the eye (clipping), and one out of view.
  // Under Oclgrind a quarter of the pixels: the counts below still show
  // frames that fit and frames that did not.
  const test::Geometry g = test::randomTriangles(5, 300);
  const uint32_t width = test::underOclgrind() ? 32 : 64, height = test::underOclgrind() ? 24 : 48;
  clr::Pipeline waiting(test::context()), speculating(test::context());
  waiting.setSpeculation(false);
  waiting.uploadScene(g.mesh());
  speculating.uploadScene(g.mesh());
  const auto scaled = [](float s, float z) {
    return glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, z)) * glm::scale(glm::mat4(1.0f), glm::vec3(s));
  };
  const std::vector<glm::mat4> mvps = {scaled(0.3f, 0), scaled(0.3f, 0), scaled(1.0f, 0),    scaled(1.0f, 0),
                                       scaled(3.0f, 0), scaled(3.0f, 0), scaled(0.5f, 0),    scaled(1.0f, 1.5f),
                                       scaled(1.0f, 0), scaled(1.0f, 0), scaled(0.3f, 9.0f), scaled(0.3f, 0)};
  size_t speculative = 0, missed = 0;
  for (size_t i = 0; i < mvps.size(); ++i) {
    INFO("frame " << i);
    clr::FrameSettings settings = test::idSettings(width, height, mvps[i]);
    std::vector<uint32_t> a, b;
    const clr::FrameStats sa = waiting.render(settings, a);
    const clr::FrameStats sb = speculating.render(settings, b);
    CHECK(a == b);
    CHECK(test::readTriIds(waiting) == test::readTriIds(speculating));
    CHECK(sa.setupTriangles == sb.setupTriangles);
    CHECK(sa.binEntries == sb.binEntries);
    CHECK(sa.trianglesClipped == sb.trianglesClipped);
    speculative += sb.speculative;
    missed += sb.speculationMissed;
  }
  CAPTURE(width, height);
  CHECK(speculative >= 3);
  CHECK(missed >= 2);
}
