// test_resolve.cpp — the resolve kernel's perspective-correct interpolation
// (the 1/w rule) against the analytic value on a tilted plane, unclipped and
// clipped by the near plane, wound either way, whole and cut small; the image's orientation, the mapped ImageView,
// the background over tiles without triangles, edge tiles included; and the
// choice of resolve's prefetch: its rule, its timed turns, and frames with
// and without it giving the same pixels.
#include "io/image_io.h"
#include "test_support.h"

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#include <stb/stb_image.h>

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace {

// The colour --shade normal gives a unit vector, per channel.
glm::dvec3 normalColour(glm::dvec3 n)
{
  return glm::clamp((glm::normalize(n) * 0.5 + 0.5) * 255.0, 0.0, 255.0);
}

// World barycentrics of p in triangle (a, b, c), all on one plane.
glm::dvec3 worldBarycentrics(glm::dvec3 p, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c)
{
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double area = glm::dot(n, n);
  return {glm::dot(glm::cross(c - b, p - b), n) / area, glm::dot(glm::cross(a - c, p - c), n) / area,
          glm::dot(glm::cross(b - a, p - a), n) / area};
}

// Writes rgba (width x height, top row first) with clr::writePng to a file
// named `name` in the temporary folder and decodes it back with stb_image:
// RGB, top row first, R in the low byte.
std::vector<uint32_t> pngRoundTrip(const std::string& name, uint32_t width, uint32_t height,
                                   const std::vector<uint32_t>& rgba)
{
  const std::string path = test::tempDir() + "/" + name;
  clr::writePng(path, width, height, rgba);
  int w = 0, h = 0, channels = 0;
  unsigned char* png = stbi_load(path.c_str(), &w, &h, &channels, 3);
  REQUIRE(png);
  const bool sized = w == int(width) && h == int(height);
  std::vector<uint32_t> decoded(sized ? size_t(width) * height : 0);
  for (size_t i = 0; i < decoded.size(); ++i) decoded[i] = png[3 * i] | (png[3 * i + 1] << 8) | (png[3 * i + 2] << 16);
  stbi_image_free(png);
  REQUIRE(sized);
  return decoded;
}

}  // namespace

TEST_CASE("resolve interpolates perspective-correctly (1/w rule)", "[resolve]")
{
  const uint32_t W = 128, H = 96;
  // A ground plane seen at a grazing angle; nearZ > 0 puts its near edge
  // behind the eye so the near plane clips it. Records hold no 1/w
  // (shared.h): resolve recomputes it per setup vertex, so the plane is also
  // wound clockwise (setup swaps vertices 1 and 2) and cut into triangles of
  // a few pixels, whose rows of many runs resolve gathers lane by lane.
  const float nearZ = GENERATE(-1.0f, 4.0f);
  const bool clockwise = GENERATE(false, true);
  const int cuts = GENERATE(1, 40);
  const glm::mat4 view = glm::lookAt(glm::vec3(0, 1, 0), glm::vec3(0, 0.8f, -1), glm::vec3(0, 1, 0));
  const glm::mat4 proj = glm::perspective(glm::radians(60.0f), float(W) / H, 0.5f, 100.0f);
  const glm::mat4 mvp = proj * view;
  const glm::dvec3 v[3] = {{-6, 0, nearZ}, {6, 0, nearZ}, {6, 0, -60}};
  // Normals used as an attribute that varies strongly across the triangle.
  const glm::dvec3 n[3] = {{1, 0.05, 0}, {0, 1, 0.05}, {0.05, 0, 1}};

  // The triangle cut into cuts² triangles, each vertex's normal the corners'
  // blended by its barycentrics, so the interpolated normal is the same
  // linear function of the hit point.
  clr::Mesh mesh;
  auto vertexAt = [&](int i, int j) { return uint32_t(i * (cuts + 1) + j); };
  for (int i = 0; i <= cuts; ++i)
    for (int j = 0; j <= cuts; ++j) {
      const double b1 = double(j) / cuts * (1.0 - double(i) / cuts), b2 = double(i) / cuts, b0 = 1.0 - b1 - b2;
      const glm::dvec3 p = b0 * v[0] + b1 * v[1] + b2 * v[2], q = b0 * n[0] + b1 * n[1] + b2 * n[2];
      mesh.positions.insert(mesh.positions.end(), {float(p.x), float(p.y), float(p.z)});
      mesh.normals.insert(mesh.normals.end(), {float(q.x), float(q.y), float(q.z)});
    }
  auto addTriangle = [&](uint32_t a, uint32_t b, uint32_t c) {
    mesh.indices.insert(mesh.indices.end(), {a, clockwise ? c : b, clockwise ? b : c});
  };
  for (int i = 0; i < cuts; ++i)
    for (int j = 0; j < cuts; ++j) {
      addTriangle(vertexAt(i, j), vertexAt(i, j + 1), vertexAt(i + 1, j + 1));
      if (j + 1 < cuts) addTriangle(vertexAt(i + 1, j + 1), vertexAt(i + 1, j), vertexAt(i, j));
    }
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(mesh);
  clr::FrameSettings settings = test::idSettings(W, H, mvp);
  settings.shadeMode = CLR_SHADE_NORMAL;
  std::vector<uint32_t> rgba;
  const clr::FrameStats stats = pipeline.render(settings, rgba);
  if (cuts == 1) CHECK(stats.trianglesClipped == (nearZ > 0 ? 1u : 0u));

  // Step 1: per covered pixel, the analytic attribute at the ray's hit point.
  const glm::dmat4 inv = glm::inverse(glm::dmat4(mvp));
  double worstCorrect = 0, worstAffine = 0;
  size_t covered = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const uint32_t c = rgba[size_t(H - 1 - y) * W + x];
      if (c == 0xFF000000u) continue;
      ++covered;
      const glm::dvec2 ndc((x + 0.5) / W * 2 - 1, (y + 0.5) / H * 2 - 1);
      glm::dvec4 a = inv * glm::dvec4(ndc, -1, 1), b = inv * glm::dvec4(ndc, 1, 1);
      const glm::dvec3 from = glm::dvec3(a) / a.w, to = glm::dvec3(b) / b.w;
      const glm::dvec3 hit = from + (to - from) * (-from.y / (to.y - from.y));
      const glm::dvec3 mu = worldBarycentrics(hit, v[0], v[1], v[2]);
      // (A clockwise face is a back face, whose normal resolve flips.)
      const double sign = clockwise ? -1.0 : 1.0;
      const glm::dvec3 expected = normalColour(sign * (mu.x * n[0] + mu.y * n[1] + mu.z * n[2]));
      // Step 2: what affine (screen-space) interpolation would give.
      glm::dvec2 s[3];
      for (int i = 0; i < 3; ++i) {
        const glm::dvec4 clip = glm::dmat4(mvp) * glm::dvec4(v[i], 1);
        s[i] = glm::dvec2(clip) / clip.w;
      }
      const double area = (s[1].x - s[0].x) * (s[2].y - s[0].y) - (s[2].x - s[0].x) * (s[1].y - s[0].y);
      auto e = [&](glm::dvec2 p, glm::dvec2 q) { return (q.x - p.x) * (ndc.y - p.y) - (q.y - p.y) * (ndc.x - p.x); };
      const glm::dvec3 b3(e(s[1], s[2]) / area, e(s[2], s[0]) / area, e(s[0], s[1]) / area);
      const glm::dvec3 affine = normalColour(sign * (b3.x * n[0] + b3.y * n[1] + b3.z * n[2]));
      for (int k = 0; k < 3; ++k) {
        const double got = double((c >> (8 * k)) & 0xFF);
        worstCorrect = std::max(worstCorrect, std::abs(got - expected[k]));
        worstAffine = std::max(worstAffine, std::abs(got - affine[k]));
      }
    }
  INFO("near z " << nearZ << ", clockwise " << clockwise << ", cuts " << cuts << ", covered " << covered);
  CHECK(covered > 2000);
  // Tolerance: 8-bit output rounds to within 0.5 level; float interpolation
  // adds < 0.05 level. Behind-the-eye vertices make screen-space (affine)
  // barycentrics meaningless, so the affine comparison only runs unclipped.
  CHECK(worstCorrect <= 0.55);
  if (nearZ < 0) CHECK(worstAffine > 20.0);
}

TEST_CASE("screen space is y-up and the PNG is written top row first", "[resolve]")
{
  // A triangle in the lower-left corner of screen space (origin bottom-left).
  const uint32_t W = 32, H = 16;
  test::Geometry g;
  g.addTriangle(test::screen(0, 0, 0, W, H), test::screen(8, 0, 0, W, H), test::screen(0, 4, 0, W, H));
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  std::vector<uint32_t> rgba;
  pipeline.render(test::idSettings(W, H), rgba);
  const std::vector<uint32_t> png = pngRoundTrip("orientation.png", W, H, rgba);
  auto idAt = [&](int x, int yUp) {  // PNG row 0 is the top: y-up row yUp is PNG row H-1-yUp
    return png[size_t(H - 1 - yUp) * W + x];
  };
  CHECK(idAt(1, 1) == 1);           // triangle index 0 is written as 1
  CHECK(idAt(1, int(H) - 2) == 0);  // top-left: background
  CHECK(idAt(int(W) - 2, 1) == 0);  // bottom-right: background
}

TEST_CASE("a written PNG decodes to the rendered pixels", "[resolve]")
{
  // Lambert random triangles at an odd size: many distinct values and row
  // lengths not a multiple of anything, through zlib and the Sub filter.
  const uint32_t W = 97, H = 61;
  const test::Geometry g = test::randomTriangles(11, 300);
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  clr::FrameSettings settings = test::idSettings(W, H);
  settings.shadeMode = CLR_SHADE_LAMBERT;
  std::vector<uint32_t> rgba;
  pipeline.render(settings, rgba);
  const std::vector<uint32_t> png = pngRoundTrip("roundtrip.png", W, H, rgba);
  size_t differing = 0;
  std::set<uint32_t> values;
  for (size_t i = 0; i < png.size(); ++i) {
    differing += png[i] != (rgba[i] & 0xFFFFFFu);
    values.insert(png[i]);
  }
  CHECK(differing == 0);
  CHECK(values.size() > 50);  // a picture that is not trivially compressible
}

TEST_CASE("an ImageView shows render()'s pixels until the next frame begins", "[resolve]")
{
  // Random triangles, lambert: a picture with background, shading and edges.
  const test::Geometry g = test::randomTriangles(5, 40);
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(g.mesh());
  auto settings = [](uint32_t w, uint32_t h) {
    clr::FrameSettings s = test::idSettings(w, h);
    s.shadeMode = CLR_SHADE_LAMBERT;
    return s;
  };
  std::vector<uint32_t> copied;
  clr::ImageView view;
  // Step 1: a view, then a copy of the same frame, then a view of another size.
  for (const auto& [w, h] : {std::pair<uint32_t, uint32_t>{64, 48}, {40, 72}}) {
    INFO(w << "x" << h);
    pipeline.render(settings(w, h), view);
    REQUIRE((view.width == w && view.height == h));
    const std::vector<uint32_t> viewed(view.pixels, view.pixels + size_t(w) * h);
    pipeline.render(settings(w, h), copied);  // unmaps the view before its kernels run
    CHECK(viewed == copied);
    size_t background = 0;
    for (uint32_t p : copied) background += p == copied[0];
    CHECK((background > 0 && background < copied.size()));  // premise: the picture is not uniform
  }
}

TEST_CASE("resolve paints every pixel no triangle covers with the background in partial edge tiles too", "[resolve]")
{
  // A 37x35 viewport: 3x3 tiles, the right column 5 pixels wide and the top
  // row 3 high. A first frame covers the whole image; the second draws one
  // small triangle in the middle tile, so eight tiles have no bin entries and
  // resolve paints them (its empty-tile path in the CPU shape) over the first
  // frame's pixels. Every pixel the oracle leaves uncovered must be the
  // mode's background, every covered one not.
  const uint32_t W = 37, H = 35;
  test::Geometry cover, small;
  cover.addTriangle(test::screen(-1, -1, 0.5f, W, H), test::screen(2 * W + 1, -1, 0.5f, W, H),
                    test::screen(-1, 2 * H + 1, 0.5f, W, H));
  small.addTriangle(test::screen(17, 17, 0, W, H), test::screen(30, 19, 0, W, H), test::screen(20, 29, 0, W, H));
  const ref::Result reference = ref::rasterize(small.positions, small.indices, glm::mat4(1.0f), {W, H, false});
  // Lambert (resolve_lambert), a lit mode and an unlit one (the general resolve).
  for (const auto& [mode, background] : {std::pair<uint32_t, uint32_t>{CLR_SHADE_LAMBERT, 0xFF261F1Au},
                                         {CLR_SHADE_GOURAUD, 0xFF261F1Au},
                                         {CLR_SHADE_NORMAL, 0xFF000000u}}) {
    INFO("shade mode " << mode);
    clr::Pipeline pipeline(test::context());
    clr::FrameSettings settings = test::idSettings(W, H);
    settings.shadeMode = mode;
    std::vector<uint32_t> rgba;
    pipeline.uploadScene(cover.mesh());
    pipeline.render(settings, rgba);
    size_t firstBackground = 0;
    for (uint32_t p : rgba) firstBackground += p == background;
    REQUIRE(firstBackground == 0);  // premise: the first frame leaves no background pixel
    pipeline.uploadScene(small.mesh());
    pipeline.render(settings, rgba);
    REQUIRE(rgba.size() == size_t(W) * H);
    size_t wrong = 0, covered = 0;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const bool isCovered = reference.triId[size_t(y) * W + x] != ref::kNone;
        const uint32_t pixel = rgba[size_t(H - 1 - y) * W + x];  // the image's top row first
        covered += isCovered;
        wrong += isCovered == (pixel == background);
      }
    CHECK(covered > 20);  // premise: the triangle covers pixels, in one tile
    CHECK(wrong == 0);
  }
}

TEST_CASE("the prefetch chooser times both settings in turns and keeps the faster", "[resolve]")
{
  // A case's first frame prefetches untimed; then on, off, off, on.
  clr::PrefetchChooser chooser;
  const auto play = [&](uint64_t scene, std::vector<double> ms) {
    std::vector<bool> answers;
    for (double t : ms) {
      answers.push_back(chooser.next({scene, 1920, 1080, CLR_SHADE_LAMBERT, 1, true}));
      chooser.report(t);
    }
    return answers;
  };
  // Off faster (3 against 5): the first frame's 100 ms, which pays the
  // buffers' first touch, does not count.
  CHECK(play(1, {100, 5, 3, 3, 5}) == std::vector<bool>{true, true, false, false, true});
  CHECK(play(1, {9, 9}) == std::vector<bool>{false, false});
  // A new case times again; on faster, and one slow "on" frame (the
  // machine's hiccup) does not outweigh its other one: each setting's fastest counts.
  CHECK(play(2, {1, 4, 5, 5, 20}) == std::vector<bool>{true, true, false, false, true});
  CHECK(play(2, {1}) == std::vector<bool>{true});
  // Back to case 1: its earlier choice is gone, it is timed anew.
  CHECK(play(1, {1, 2, 1, 1, 2, 0}) == std::vector<bool>{true, true, false, false, true, false});
  // Any other part of the case starts the turns again too.
  CHECK(chooser.next({1, 1920, 1080, CLR_SHADE_LAMBERT, 1, true}) == false);
  chooser.report(1);
  CHECK(chooser.next({1, 1920, 1080, CLR_SHADE_PHONG, 1, false}) == true);
  chooser.report(1);
  CHECK(chooser.next({1, 1920, 1080, CLR_SHADE_PHONG, 1, false}) == true);
}

TEST_CASE("resolve may prefetch only for small triangles beyond 2 MB of gathers", "[resolve]")
{
  // Gathered: 40 bytes per setup triangle (record and source word), 12 per
  // input triangle (indices), 12 per vertex (positions) and 12 more where
  // the mode reads normals.
  FrameParams params{};
  params.shadeMode = CLR_SHADE_LAMBERT;
  params.numTris = 40000;   // 480,000 bytes of indices
  params.numVerts = 20000;  // 240,000 bytes of positions, as many of normals
  const uint32_t limit = 2u << 20;
  const uint32_t setupAtLimit = (limit - 480000 - 2 * 240000) / 40;  // 28,428: 2,097,120 bytes of 2,097,152
  CHECK_FALSE(clr::resolveMayPrefetch(params, setupAtLimit, setupAtLimit));
  CHECK(clr::resolveMayPrefetch(params, setupAtLimit + 4, setupAtLimit + 4));
  // Two bin entries a triangle at most.
  CHECK(clr::resolveMayPrefetch(params, setupAtLimit + 4, 2 * uint64_t(setupAtLimit + 4)));
  CHECK_FALSE(clr::resolveMayPrefetch(params, setupAtLimit + 4, 2 * uint64_t(setupAtLimit + 4) + 1));
  // A mode without normals gathers 240,000 bytes less.
  params.shadeMode = CLR_SHADE_ID;
  CHECK_FALSE(clr::resolveMayPrefetch(params, setupAtLimit + 4, setupAtLimit + 4));
}

TEST_CASE("frames with and without resolve's prefetch give the same pixels", "[resolve][prefetch]")
{
  // A bumpy grid of 125,000 triangles of about a pixel each in a 384x384
  // viewport (about 220 bin entries a tile, 8 MB of gathers): a case the
  // chooser times, so its first frames run with and without the prefetch.
  const uint32_t W = 384, H = 384;
  const int N = 250;
  test::Geometry grid;
  const auto at = [&](int i, int j) {
    const float x = -1.0f + 2.0f * i / N, y = -1.0f + 2.0f * j / N;
    return glm::vec3(x, y, 0.3f * std::sin(9.0f * x) * std::cos(7.0f * y));
  };
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      grid.addTriangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      grid.addTriangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  clr::Pipeline pipeline(test::context());
  pipeline.uploadScene(grid.mesh());
  clr::FrameSettings settings = test::idSettings(W, H);
  settings.shadeMode = CLR_SHADE_LAMBERT;
  std::vector<uint32_t> first, rgba;
  std::set<bool> prefetched;
  for (int frame = 0; frame < 6; ++frame) {
    const clr::FrameStats stats = pipeline.render(settings, frame ? rgba : first);
    prefetched.insert(stats.resolvePrefetch);
    if (frame) CHECK(test::countDifferences(first, rgba) == 0);
  }
  // Premise: where the device's build prefetches (PoCL, 16 lanes), both settings ran.
  if (test::context().prefetch && test::context().lanes > 1) CHECK(prefetched == std::set<bool>{false, true});
}
