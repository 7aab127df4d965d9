// test_transform.cpp — the transform and clip stages on the device:
// transformed vertices match the oracle bit for bit, and triangles through
// the near plane are clipped (clip.h), never projected through w <= 0.
#include "test_support.h"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

using test::Geometry;

namespace {

glm::mat4 perspectiveCamera(glm::vec3 eye, glm::vec3 target, float aspect, float zNear = 0.5f, float zFar = 100.0f)
{
  return glm::perspective(glm::radians(60.0f), aspect, zNear, zFar) * glm::lookAt(eye, target, {0, 1, 0});
}

}  // namespace

TEST_CASE("transform matches the oracle bit for bit", "[transform]")
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-20.0f, 20.0f);
  Geometry g;
  for (int i = 0; i < 999; ++i) g.addVertex({coord(rng), coord(rng), coord(rng)});
  g.indices = {0, 1, 2};
  const glm::mat4 mvp = perspectiveCamera({3, 4, 30}, {0, 0, 0}, 1.5f);
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  pipeline.beginFrame(test::idSettings(64, 64, mvp));
  pipeline.transform();
  const std::vector<cl_float4> clip = pipeline.readClipPositions();
  REQUIRE(clip.size() == 999);
  for (size_t v = 0; v < clip.size(); ++v) {
    const glm::vec4 expected = ref::transformVertex(mvp, &g.positions[3 * v]);
    REQUIRE(std::memcmp(&clip[v], &expected, sizeof expected) == 0);
  }
}

TEST_CASE("near-plane clipping: no projection through w <= 0, same pixels as the oracle", "[clip]")
{
  const uint32_t W = 80, H = 60;
  const glm::mat4 mvp = perspectiveCamera({0, 1, 0}, {0, 1, -1}, float(W) / H, 0.5f, 50.0f);
  Geometry g;
  g.addTriangle({-2, 0, 3}, {2, 0, -10}, {-2, 0.5f, -10});  // one vertex behind the eye
  g.addTriangle({1, 2, 2}, {3, 2, 4}, {2, 1.5f, -8});       // two vertices behind
  g.addTriangle({-1, 0, 1}, {1, 0, 1}, {0, 1, 2});          // wholly behind: culled
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  std::vector<uint32_t> rgba;
  const clr::FrameStats stats = pipeline.render(test::keepingVis(test::idSettings(W, H, mvp)), rgba);
  CHECK(stats.trianglesClipped == 2);
  CHECK(stats.trianglesCulled == 1);
  CHECK(stats.setupTriangles == 3);
  // ClipBary rows are convex weights of the input vertices.
  size_t live = 0;
  for (const ClipBary& cb : pipeline.readClipBary()) {
    if (cb.flags & CLR_FLAG_DEAD) continue;
    ++live;
    for (int i = 0; i < 3; ++i) {
      const float sum = cb.w[i][0] + cb.w[i][1] + cb.w[i][2];
      CHECK(std::abs(sum - 1.0f) < 1e-6f);  // three float lerps of weights summing to 1
      for (int j = 0; j < 3; ++j) CHECK((cb.w[i][j] >= -1e-6f && cb.w[i][j] <= 1.0f + 1e-6f));
    }
  }
  CHECK(live == 3);  // the three setup triangles are all clipped ones
  for (const VisSample& v : pipeline.readVis())
    REQUIRE((std::isfinite(v.depth) && std::isfinite(v.b1) && std::isfinite(v.b2)));
  const std::vector<uint32_t> ids = test::renderTriIds(pipeline, test::idSettings(W, H, mvp));
  const ref::Result expected = ref::rasterize(g.positions, g.indices, mvp, {W, H, false});
  CHECK(expected.clippedTriangles == 2);
  CHECK(test::countDifferences(ids, expected.triId) == 0);
  CHECK(std::count(ids.begin(), ids.end(), 0u) > 200);
  CHECK(std::count(ids.begin(), ids.end(), 1u) > 50);
}
