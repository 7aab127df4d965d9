// test_model_read.cpp — a model file is read once: the checks and the import
// see the same bytes (io/scene.h, io/file_rule.h), and the checks are those
// of the reader assimp chooses by content, whatever the file's extension
// (io/model_checks.h).
#include "cli_support.h"
#include "io/fast_ply.h"
#include "io/file_rule.h"
#include "io/scene.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>

namespace {

// One triangle's positions, (0,0,0) (1,0,0) (0,1,0), as a glTF data URI.
const std::string kTrianglePositions =
    "data:application/octet-stream;base64,"
    "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";

// A glTF of one triangle whose POSITION accessor has element type `type`.
std::string gltfTriangle(const std::string& type)
{
  const std::string count = type == "SCALAR" ? "9" : "3";
  return R"({"asset":{"version":"2.0"},"buffers":[{"uri":")" + kTrianglePositions +
         R"(","byteLength":36}],"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,)"
         R"("componentType":5126,"count":)" +
         count + R"(,"type":")" + type +
         R"(","min":[0,0,0],"max":[1,1,0]}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
}

// A JSON document nested `depth` arrays deep.
std::string deepJson(size_t depth)
{
  return std::string(depth, '[') + std::string(depth, ']');
}

struct Format {
  std::string name, one, two;  // a file of one triangle, and one of two
};

std::vector<Format> formats()
{
  return {
      {"obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n"},
      {"off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n"},
      {"ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n"
       "3 0 1 2\n3 1 3 2\n"},
      {"stl",
       "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
       "endsolid a\n",
       "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
       "facet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid a\n"},
      // The race of issue 50: a deep glTF put in place of a good one after the checks.
      {"gltf", gltfTriangle("VEC3"), deepJson(200000)},
  };
}

// Counts the file rule's opens of each (device, inode) while alive.
struct OpenCounter {
  std::map<std::pair<uint64_t, uint64_t>, int> opens;
  std::function<void(const std::string&)> onOpen;  // called after each open
  OpenCounter()
  {
    clr::setOpenObserver([this](const std::string& path, uint64_t device, uint64_t inode) {
      ++opens[{device, inode}];
      if (onOpen) onOpen(path);
    });
  }
  ~OpenCounter() { clr::setOpenObserver(nullptr); }
  int of(const std::string& path) const
  {
    struct stat st {};
    if (stat(path.c_str(), &st) != 0) return -1;
    const auto found = opens.find({uint64_t(st.st_dev), uint64_t(st.st_ino)});
    return found == opens.end() ? 0 : found->second;
  }
};

}  // namespace

TEST_CASE("model read: the model file is opened once and the bytes checked are imported", "[io][hostile]")
{
  for (const Format& f : formats()) {
    INFO("format " << f.name);
    const std::string path = test::writeFile("once." + f.name, f.one);
    const std::string other = test::writeFile("once-other." + f.name, f.two);
    struct stat original {};
    REQUIRE(stat(path.c_str(), &original) == 0);
    int originalOpens = 0;
    clr::Mesh mesh;
    {
      OpenCounter counter;
      // Right after the model's first open, another file takes its name: a
      // second read of the path would see two triangles (or, for glTF, a
      // document nested too deep for assimp's parser).
      counter.onOpen = [&](const std::string& opened) {
        if (opened == path) std::rename(other.c_str(), path.c_str());
      };
      mesh = clr::loadScene(path);
      originalOpens = counter.opens[{uint64_t(original.st_dev), uint64_t(original.st_ino)}];
      CHECK(counter.of(path) == 0);  // the file swapped in is never opened
    }
    CHECK(originalOpens == 1);
    CHECK(mesh.numTris() == 1);
  }
}

TEST_CASE("model read: guards run for the reader assimp chooses by content", "[io][hostile][cli][rlimit]")
{
  // An OFF of a billion vertices named .txt: refused from its header, not
  // allocated (the memory limit turns an allocation into a failure).
  const std::string off = test::writeFile("content-off.txt", "OFF\n1000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const test::Run big = test::runShell(
      std::string("ulimit -v 4000000; timeout 60 '") + CLRASTER_BIN + "' info '" + off + "' 2>'" + off + ".err'",
      off + ".err");
  CHECK(big.status == 1);
  CHECK_THAT(big.err, Catch::Matchers::Contains("OFF header vertex count 1000000000 exceeds"));
  // A JSON nested 200,000 deep under names assimp reads by content.
  for (const char* name : {"deep.vrm", "deep.txt", "deep"}) {
    const std::string path = test::writeFile(name, deepJson(200000));
    test::expectError("info '" + path + "'", "nested deeper than 64 levels");
  }
  // A SCALAR POSITION is refused whatever the file is called.
  for (const char* name : {"scalar.gltf", "scalar.vrm", "scalar.bin"}) {
    const std::string path = test::writeFile(name, gltfTriangle("SCALAR"));
    test::expectError("info '" + path + "'", "attribute POSITION uses an accessor of type SCALAR");
  }
}

TEST_CASE("smooth normals: vertices at the same position weld and -0 equals +0", "[io]")
{
  // Two triangles at right angles, sharing the origin (once written -0) and
  // (0,1,0) through separate vertices: each shared corner gets the sum of
  // both face normals, (1, 0, 1) normalised; unwelded it would be a face's.
  clr::Mesh mesh;
  mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, -0.0f, 0, 0, 0, 1, 0, 0, 0, 1};
  mesh.indices = {0, 1, 2, 3, 4, 5};
  clr::computeSmoothNormals(mesh);
  REQUIRE(mesh.normals.size() == 18);
  const float r = 0.70710678f;  // 1/sqrt(2); tolerance: float rounding of a double normalisation
  for (int v : {0, 3}) {
    CHECK(mesh.normals[3 * v] == Approx(r).margin(1e-6));
    CHECK(mesh.normals[3 * v + 1] == Approx(0.0f).margin(1e-6));
    CHECK(mesh.normals[3 * v + 2] == Approx(r).margin(1e-6));
  }
  for (int k = 0; k < 3; ++k) CHECK(mesh.normals[3 * 2 + k] == mesh.normals[3 * 4 + k]);
}

TEST_CASE("smooth normals: a large mesh gets a plain one-thread weld's bits", "[io]")
{
  // 200,000 triangles of a shuffled height field whose vertices repeat
  // (each quad has corners of its own, a zero height written -0 in every
  // other quad), far above the prefetch distance and the two-thread bound:
  // the result equals, bit for bit, this plain one-thread weld by position
  // bytes with the double sums taken in triangle order.
  const uint32_t side = 317;  // (side - 1)^2 quads, 2 triangles each
  clr::Mesh mesh;
  std::mt19937 random(46);
  for (uint32_t y = 0; y + 1 < side; ++y)
    for (uint32_t x = 0; x + 1 < side; ++x) {
      const uint32_t base = uint32_t(mesh.numVerts());
      for (uint32_t c = 0; c < 4; ++c) {
        const uint32_t gx = x + (c & 1), gy = y + (c >> 1);
        const float height = float((7 * gx + 3 * gy) % 5) * 0.25f;
        mesh.positions.insert(mesh.positions.end(),
                              {float(gx), float(gy), height == 0.0f && (x + y) % 2 ? -0.0f : height});
      }
      mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base + 2, base + 1, base + 3});
    }
  REQUIRE(mesh.numTris() > 65536 * 2);
  std::vector<uint32_t> order(mesh.numTris());
  for (uint32_t t = 0; t < order.size(); ++t) order[t] = t;
  std::shuffle(order.begin(), order.end(), random);
  std::vector<uint32_t> shuffled;
  for (uint32_t t : order) shuffled.insert(shuffled.end(), &mesh.indices[3 * t], &mesh.indices[3 * t] + 3);
  mesh.indices = shuffled;
  // The reference.
  std::map<std::vector<float>, glm::dvec3> sums;
  auto key = [&](uint32_t v) {
    return std::vector<float>{mesh.positions[3 * v] + 0.0f, mesh.positions[3 * v + 1] + 0.0f,
                              mesh.positions[3 * v + 2] + 0.0f};
  };
  auto pos = [&](uint32_t v) {
    return glm::dvec3(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
  };
  for (size_t t = 0; t < mesh.numTris(); ++t) {
    const uint32_t* tri = &mesh.indices[3 * t];
    const glm::dvec3 n = glm::cross(pos(tri[1]) - pos(tri[0]), pos(tri[2]) - pos(tri[0]));
    for (int k = 0; k < 3; ++k) sums[key(tri[k])] += n;
  }
  clr::computeSmoothNormals(mesh);
  size_t differing = 0;
  for (uint32_t v = 0; v < mesh.numVerts(); ++v) {
    const glm::dvec3 s = sums[key(v)];
    const double len = glm::length(s);
    for (int k = 0; k < 3; ++k) differing += mesh.normals[3 * v + k] != (len > 0.0 ? float(s[k] / len) : 0.0f);
  }
  CHECK(differing == 0);
}

namespace {

// A plain binary PLY (fast_ply.h): `positions` as floats, faces as given.
std::string plainPly(const std::vector<float>& positions, const std::vector<std::vector<int32_t>>& faces)
{
  std::string s = "ply\nformat binary_little_endian 1.0\ncomment made by a test\nelement vertex " +
                  std::to_string(positions.size() / 3) +
                  "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                  std::to_string(faces.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  s.append(reinterpret_cast<const char*>(positions.data()), positions.size() * sizeof(float));
  for (const auto& face : faces) {
    s += char(face.size());
    s.append(reinterpret_cast<const char*>(face.data()), face.size() * sizeof(int32_t));
  }
  return s;
}

// Bit for bit: -0 and +0 differ.
template <typename T>
bool sameBytes(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

void requireSameMesh(const clr::Mesh& a, const clr::Mesh& b)
{
  CHECK(sameBytes(a.positions, b.positions));
  CHECK(sameBytes(a.normals, b.normals));
  CHECK(sameBytes(a.uvs, b.uvs));
  CHECK(a.indices == b.indices);
  CHECK(a.lines == b.lines);
  CHECK(a.points == b.points);
  CHECK(sameBytes(a.colors, b.colors));
  CHECK(a.triMaterial == b.triMaterial);
  REQUIRE(a.materials.size() == b.materials.size());
  for (size_t m = 0; m < a.materials.size(); ++m)
    CHECK(std::memcmp(&a.materials[m], &b.materials[m], sizeof(Material)) == 0);
  CHECK(a.textures.size() == b.textures.size());
  CHECK(a.warnings.lines() == b.warnings.lines());
  CHECK(a.facts.normalsInFile == b.facts.normalsInFile);
  CHECK(a.facts.normalsRepaired == b.facts.normalsRepaired);
  CHECK(a.facts.uvsInFile == b.facts.uvsInFile);
}

}  // namespace

TEST_CASE("model read: the direct binary PLY reader gives assimp's mesh", "[io][models]")
{
  std::vector<std::string> paths;
  // A quad, a -0 coordinate, a vertex no face uses; the corpus's PLY files.
  const std::string plain =
      plainPly({-0.0f, 0, 0, 1, 0, 0, 1, 1, -0.0f, 0, 1, 0, 5, 5, 5, 2, 0, 1}, {{0, 1, 2, 3}, {1, 5, 2}});
  clr::Mesh direct;
  REQUIRE(clr::readPlainBinaryPly(plain, direct));
  paths.push_back(test::writeFile("plain.ply", plain));
  // Refused by assimp's path: an index out of range, a NaN; read by neither.
  paths.push_back(test::writeFile("plain-range.ply", plainPly({0, 0, 0, 1, 0, 0, 0, 1, 0}, {{0, 1, 3}})));
  paths.push_back(test::writeFile("plain-nan.ply", plainPly({0, 0, 0, 1, 0, 0, 0, NAN, 0}, {{0, 1, 2}})));
  for (const char* name :
       {"cube.ply", "cube_binary.ply", "Wuson.ply", "points.ply", "cube_uv.ply", "float-color.ply", "issue623.ply"})
    paths.push_back(std::string("/usr/share/assimp/models/PLY/") + name);
  for (const std::string& path : paths) {
    INFO(path);
    clr::ModelFile viaAssimp = clr::checkSceneFile(path);
    viaAssimp.direct = false;
    std::string assimpError, directError;
    clr::Mesh a, b;
    try {
      a = clr::importScene(viaAssimp);
    } catch (const clr::Error& e) {
      assimpError = e.what();
    }
    try {
      b = clr::importScene(clr::checkSceneFile(path));
    } catch (const clr::Error& e) {
      directError = e.what();
    }
    CHECK(assimpError == directError);
    requireSameMesh(a, b);
  }
}
