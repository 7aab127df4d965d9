// test_import_budget.cpp — one memory budget for a scene's import
// (import_budget.h): tiny files that declare gigabytes (a sparse glTF
// accessor, buffers naming one large file many times, thousands of OBJ
// materials or groups) are refused with one line naming the file and the
// limit. The CLI runs under an address-space limit (ulimit -v), so a check
// that fails shows as another error or a crash, never as an exhausted machine.
#include "cli_support.h"
#include "io/import_budget.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

using Catch::Matchers::Contains;

namespace {

// The address-space limit of each run: 3 GiB, far below what the refused
// files would take, above what clraster itself maps for `info`.
constexpr const char* kLimitKb = "3145728";

// `clraster info FILE` under the limit and a 60 s timeout.
test::Run infoLimited(const std::string& file)
{
  const std::string errPath = test::tempDir() + "/budget-err-" + std::to_string(getpid()) + ".txt";
  return test::runShell(std::string("ulimit -v ") + kLimitKb + "; timeout 60 '" + CLRASTER_BIN + "' info '" + file +
                            "' 2>'" + errPath + "'",
                        errPath);
}

void expectRefused(const std::string& file, const std::string& needle)
{
  const test::Run r = infoLimited(file);
  INFO(file << ": " << r.err);
  CHECK(r.status == 1);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_THAT(r.err, Contains(needle));
}

std::string write(const std::string& name, const std::string& text)
{
  return test::writeFile(name, text);
}

const char* const kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

// A glTF whose one accessor declares `count` VEC3 positions, three of them
// given by a sparse block in a data URI (595 bytes for count 1e8).
std::string sparseGltf(const std::string& count)
{
  return R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "data:application/octet-stream;base64,)"
         R"(AAAAAAEAAAACAAAAAAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA", "byteLength": 48}],
  "bufferViews": [{"buffer": 0, "byteLength": 12}, {"buffer": 0, "byteOffset": 12, "byteLength": 36}],
  "accessors": [{"componentType": 5126, "count": )" +
         count + R"(, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0], "sparse": {"count": 3,
    "indices": {"bufferView": 0, "componentType": 5125}, "values": {"bufferView": 1}}}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 0}]}], "nodes": [{"mesh": 0}],
  "scenes": [{"nodes": [0]}], "scene": 0})";
}

}  // namespace

TEST_CASE("import budget: a sparse glTF accessor is counted from its declared size", "[budget][cli][rlimit]")
{
  const test::Run small = infoLimited(write("budget-sparse-small.gltf", sparseGltf("1000")));
  INFO(small.err);
  CHECK(small.status == 0);
  CHECK_THAT(small.out, Contains("points     1000"));
  expectRefused(write("budget-sparse.gltf", sparseGltf("100000000")),
                "budget-sparse.gltf: accessors declaring 300000000 components, 1 primitives and 1 node instances need "
                "about 15259 MiB, over the import budget of 4096 MiB");
}

TEST_CASE("import budget: the files a glTF names count each time it names them", "[budget][cli][rlimit]")
{
  // 80 buffers naming one 16 MiB file (sparse on disk): 1,280 MiB together.
  const std::string big = test::tempDir() + "/budget-big.bin";
  FILE* f = std::fopen(big.c_str(), "wb");
  REQUIRE(f);
  std::fclose(f);
  REQUIRE(truncate(big.c_str(), 16 << 20) == 0);
  std::string buffers, views, accessors, attributes;
  for (int i = 0; i < 80; ++i) {
    const std::string n = std::to_string(i), sep = i ? ", " : "";
    buffers += sep + R"({"uri": "budget-big.bin", "byteLength": 16777216})";
    views += sep + R"({"buffer": )" + n + R"(, "byteLength": 36})";
    accessors += sep + R"({"bufferView": )" + n +
                 R"(, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]})";
    attributes += sep + R"({"attributes": {"POSITION": )" + n + "}}";
  }
  const std::string gltf = R"({"asset": {"version": "2.0"}, "buffers": [)" + buffers + R"(], "bufferViews": [)" +
                           views + R"(], "accessors": [)" + accessors + R"(], "meshes": [{"primitives": [)" +
                           attributes + R"(]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
  expectRefused(write("budget-buffers.gltf", gltf),
                "budget-buffers.gltf: the files it names take more than 1024 MiB together, the limit for one import");
}

TEST_CASE("import budget: OBJ materials and groups are limited by name", "[budget][cli][rlimit]")
{
  // Step 1: distinct undefined usemtl names, and newmtl lines in a library.
  std::string obj = kTriangle;
  for (int i = 0; i < 5000; ++i) obj += "usemtl m" + std::to_string(i) + "\nf 1 2 3\n";
  expectRefused(write("budget-usemtl.obj", obj),
                "budget-usemtl.obj: more than 4096 distinct usemtl names, the limit for one OBJ");
  std::string mtl;
  for (int i = 0; i < 5000; ++i) mtl += "newmtl m" + std::to_string(i) + "\nKd 1 1 1\n";
  write("budget-lib.mtl", mtl);
  expectRefused(write("budget-newmtl.obj", "mtllib budget-lib.mtl\nusemtl m1\n" + std::string(kTriangle)),
                "budget-newmtl.obj: more than 4096 materials in its material libraries, the limit for one OBJ");
  // Step 2: 1.3 million groups in 2.6 MB: memory would follow the groups, not the one triangle.
  std::string groups = kTriangle;
  for (int i = 0; i < 1300000; ++i) groups += "g\n";
  expectRefused(write("budget-groups.obj", groups),
                "budget-groups.obj: importing 3 vertices, 3 face corners and 1300000 groups needs about");
  CHECK_NOTHROW(clr::checkObjBudget("ok.obj", std::string(kTriangle) + "usemtl a\nusemtl b\ng x\n"));
  CHECK(clr::countMaterials("newmtl a\n  newmtl b\n# newmtl c\nxnewmtl d\n") == 2);
}

TEST_CASE("import budget: glTF nodes count as often as the scene reaches them", "[budget][cli][rlimit]")
{
  // 24 levels of two nodes, each naming both nodes of the next level as
  // children: 1.4 kB that assimp imports as 2^24 - 1 node instances.
  std::string nodes;
  for (int level = 0; level < 24; ++level)
    for (int j = 0; j < 2; ++j) {
      nodes += level || j ? ", " : "";
      nodes += level + 1 < 24
                   ? "{\"children\": [" + std::to_string(2 * level + 2) + ", " + std::to_string(2 * level + 3) + "]}"
                   : std::string("{\"mesh\": 0}");
    }
  const std::string gltf = sparseGltf("3");
  const std::string dag = gltf.substr(0, gltf.find("\"nodes\": [")) + "\"nodes\": [" + nodes +
                          "], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0}";
  expectRefused(write("budget-dag.gltf", dag),
                "budget-dag.gltf: accessors declaring 9 components, 1 primitives and "
                "16777215 node instances need about");
}
