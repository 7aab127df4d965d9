// test_weld_hint.cpp — computeSmoothNormals with a PositionIndex hint
// (io/scene.h) against the same call without one: the normals must be the
// same bytes on meshes whose file positions repeat under different indices,
// hold -0 and +0, NaN of different payloads, and triangles of zero area.
// The layout's weld from the classes the normals leave (MeshFacts::
// weldClasses) is its weld without them, for true, stale and wrong hints.
#include "io/normals.h"
#include "io/scene.h"
#include "pipeline/layout.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace {

struct Soup {
  std::vector<float> file;       // 3 per file position
  std::vector<uint32_t> corner;  // each vertex's file position
  clr::Mesh mesh;                // one vertex per triangle corner
};

float nanWithPayload(uint32_t payload)
{
  const uint32_t bits = 0x7fc00000u | (payload & 0x3fffffu);
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

// `positions` file positions drawn from a few values (so that many repeat),
// `triangles` triangles of random file positions, each corner its own vertex;
// a vertex copies its file position, a zero's sign sometimes flipped.
Soup randomSoup(uint32_t seed, size_t positions, size_t triangles)
{
  std::mt19937 rng(seed);
  const float values[] = {0.0f, -0.0f, 1.0f, 2.5f, -1.0f, 1e-30f, nanWithPayload(1), nanWithPayload(2), 3.0f};
  Soup s;
  for (size_t i = 0; i < 3 * positions; ++i) s.file.push_back(values[rng() % 9]);
  for (size_t t = 0; t < triangles; ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t p = uint32_t(rng() % positions);
      s.corner.push_back(p);
      for (int c = 0; c < 3; ++c) {
        float x = s.file[3 * p + c];
        if (x == 0.0f && rng() % 2) x = -x;
        s.mesh.positions.push_back(x);
      }
      s.mesh.indices.push_back(uint32_t(s.mesh.indices.size()));
    }
  return s;
}

std::vector<float> smoothed(clr::Mesh mesh, const Soup* hinted)
{
  const clr::PositionIndex hint{hinted ? hinted->file.data() : nullptr, hinted ? hinted->file.size() / 3 : 0,
                                hinted ? hinted->corner.data() : nullptr};
  clr::computeSmoothNormals(mesh, hinted ? &hint : nullptr);
  return mesh.normals;
}

using test::sameBytes;

// Every array of two layouts, byte for byte.
bool sameLayout(const clr::SceneLayout& a, const clr::SceneLayout& b)
{
  auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0);
  };
  return same(a.fileTri, b.fileTri) && same(a.fileVertex, b.fileVertex) && same(a.laidVertex, b.laidVertex) &&
         same(a.mesh.positions, b.mesh.positions) && same(a.mesh.normals, b.mesh.normals) &&
         same(a.mesh.uvs, b.mesh.uvs) && same(a.mesh.colors, b.mesh.colors) && same(a.mesh.indices, b.mesh.indices);
}

}  // namespace

TEST_CASE("weld hint: hinted smooth normals are the un-hinted ones bit for bit", "[weld][direct]")
{
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    INFO("seed " << seed);
    // Few positions: most triangles are degenerate or repeat; many: mostly distinct ones.
    const Soup s = randomSoup(seed, seed % 2 ? 6 : 300, 50 + 20 * seed);
    const std::vector<float> plain = smoothed(s.mesh, nullptr);
    REQUIRE(plain.size() == s.mesh.positions.size());
    CHECK(sameBytes(plain, smoothed(s.mesh, &s)));
  }
  // Enough vertices for the two-thread halves and the per-class table.
  const Soup big = randomSoup(99, 5000, 40000);
  CHECK(sameBytes(smoothed(big.mesh, nullptr), smoothed(big.mesh, &big)));
}

TEST_CASE("weld hint: two file indices holding one position weld", "[weld][direct]")
{
  // A tent of two triangles meeting at the ridge (0,1,0)-(0,1,1), whose ridge
  // positions are each written twice in the file (indices 0, 1 and 4, 5).
  Soup s;
  s.file = {0, 1, 0, 0, 1, 1, -1, 0, 0, -1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 0, 0, 1, 0, 1};
  s.corner = {0, 2, 1, 4, 5, 6};
  for (uint32_t p : s.corner) s.mesh.positions.insert(s.mesh.positions.end(), &s.file[3 * p], &s.file[3 * p] + 3);
  s.mesh.indices = {0, 1, 2, 3, 4, 5};
  const std::vector<float> hinted = smoothed(s.mesh, &s);
  CHECK(sameBytes(hinted, smoothed(s.mesh, nullptr)));
  // The ridge vertex of each triangle gets the sum of both faces: straight up.
  for (uint32_t v : {0u, 3u}) {
    INFO("vertex " << v);
    CHECK(hinted[3 * v] == 0.0f);
    CHECK(hinted[3 * v + 1] == 1.0f);
    CHECK(hinted[3 * v + 2] == 0.0f);
  }
}

TEST_CASE("weld hint: repairNormals passes the hint and keeps the file's good normals", "[weld][direct]")
{
  Soup s = randomSoup(7, 40, 300);
  s.mesh.normals.assign(s.mesh.positions.size(), 0.0f);
  for (size_t v = 0; v < s.mesh.numVerts(); v += 3) s.mesh.normals[3 * v + 2] = 1.0f;  // some kept
  clr::Mesh plain = s.mesh, hinted = s.mesh;
  const clr::PositionIndex hint{s.file.data(), s.file.size() / 3, s.corner.data()};
  clr::repairNormals(plain, "a.obj", true);
  clr::repairNormals(hinted, "a.obj", true, &hint);
  CHECK(sameBytes(plain.normals, hinted.normals));
  CHECK(plain.facts.normalsRepaired == hinted.facts.normalsRepaired);
  CHECK(plain.facts.normalsRepaired > 0);
  CHECK(hinted.facts.weldClasses.empty());  // kept file normals: no class hint for the layout
}

TEST_CASE("weld hint: the layout welds the same with a true a stale or a wrong class hint", "[weld][layout]")
{
  // Un-shared corners of a few hundred finite positions, -0 among them: the
  // normals' classes (-0 as +0) are coarser than the layout's bitwise weld.
  Soup s = randomSoup(3, 200, 3000);
  for (float& c : s.mesh.positions)
    if (std::isnan(c)) c = 0.5f;
  clr::computeSmoothNormals(s.mesh);
  REQUIRE(s.mesh.facts.weldClasses.size() == s.mesh.numVerts());
  clr::Mesh plain = s.mesh;
  plain.facts.weldClasses.clear(), plain.facts.weldClassCount = 0;
  const clr::SceneLayout expected = clr::layOutScene(plain);
  REQUIRE(expected.mesh.numVerts() < s.mesh.numVerts() / 2);  // welded
  const size_t n = s.mesh.numVerts();
  auto withHint = [&](std::vector<uint32_t> classes, size_t count) {
    clr::Mesh m = plain;
    m.facts.weldClasses = std::move(classes), m.facts.weldClassCount = count;
    return clr::layOutScene(m);
  };
  // The normals' own classes, where no -0 occurs, and where it does (coarser).
  CHECK(sameLayout(expected, clr::layOutScene(s.mesh)));
  clr::Mesh noNegativeZero = plain;
  for (float& c : noNegativeZero.positions) c += 0.0f;
  clr::computeSmoothNormals(noNegativeZero);
  clr::Mesh bare = noNegativeZero;
  bare.facts.weldClasses.clear(), bare.facts.weldClassCount = 0;
  CHECK(sameLayout(clr::layOutScene(bare), clr::layOutScene(noNegativeZero)));
  // Every vertex one class; classes renumbered backwards; all in one class
  // (wrong); a class past the count; a hint of another mesh's size.
  std::vector<uint32_t> own(n);
  std::iota(own.begin(), own.end(), 0u);
  CHECK(sameLayout(expected, withHint(own, n)));
  std::vector<uint32_t> backwards = s.mesh.facts.weldClasses;
  for (uint32_t& c : backwards) c = uint32_t(s.mesh.facts.weldClassCount - 1 - c);
  CHECK(sameLayout(expected, withHint(backwards, s.mesh.facts.weldClassCount)));
  CHECK(sameLayout(expected, withHint(std::vector<uint32_t>(n, 0), 1)));
  std::vector<uint32_t> past = own;
  past.back() = uint32_t(n);
  CHECK(sameLayout(expected, withHint(past, n)));
  CHECK(sameLayout(expected, withHint(std::vector<uint32_t>(n - 1, 0), 1)));
  // The right classes, but one vertex's normal changed after they were made (stale).
  clr::Mesh stale = s.mesh;
  stale.normals[3 * (n / 2)] += 1.0f;
  clr::Mesh staleBare = stale;
  staleBare.facts.weldClasses.clear(), staleBare.facts.weldClassCount = 0;
  CHECK(sameLayout(clr::layOutScene(staleBare), clr::layOutScene(stale)));
  // The laid-out mesh keeps no hint: its vertices are not the file's.
  CHECK(clr::layOutScene(s.mesh).mesh.facts.weldClasses.empty());
}
