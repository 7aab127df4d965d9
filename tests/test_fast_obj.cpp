// test_fast_obj.cpp — the direct OBJ reader (io/fast_obj.h) against its
// oracle, assimp's path: for every OBJ of assimp's test models and for
// generated stress files, a file the direct reader takes must give a Mesh
// byte for byte the same as the one assimp's path gives (forced with
// ModelFile::direct = false), and one it leaves must load, or fail, as before.
#include "io/asset_root.h"
#include "io/fast_obj.h"
#include "io/file_rule.h"
#include "io/import_budget.h"
#include "io/mtl.h"
#include "io/scene.h"
#include "test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <dirent.h>
#include <fstream>
#include <iterator>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <sys/stat.h>

namespace {

void writeFile(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  REQUIRE(out.good());
}

// An uncompressed w×h TGA of one colour.
std::string tga(int w, int h)
{
  std::string t(18, '\0');
  t[2] = 2;
  t[12] = char(w), t[14] = char(h), t[16] = 24;
  for (int i = 0; i < w * h; ++i) t += std::string("\x20\x60\xa0", 3);
  return t;
}

// Loads `path` through importScene, directly if it may; the error text on failure.
std::string load(const std::string& path, bool direct, clr::Mesh& mesh)
{
  try {
    clr::ModelFile file = clr::checkSceneFile(path);
    file.direct = direct;
    mesh = clr::importScene(file);
    return "";
  } catch (const clr::Error& e) {
    return e.what();
  }
}

// Whether the direct reader takes `path`.
bool directTakes(const std::string& path)
{
  clr::Mesh mesh;
  const clr::AssetRoot root(path, "");
  return clr::readPlainObj(path, clr::readInputFile(path, clr::kModelInput), root, mesh);
}

// Checks one file both ways; true when the direct reader took it.
bool checkBothWays(const std::string& path)
{
  INFO(path);
  clr::Mesh direct, assimp;
  const std::string directError = load(path, true, direct);
  const std::string assimpError = load(path, false, assimp);
  REQUIRE(directError == assimpError);
  if (!directError.empty()) return false;
  REQUIRE(test::meshDifference(direct, assimp) == "");
  return directTakes(path);
}

// A number of 7 to 9 significant digits in one of the forms writers use.
std::string number(std::mt19937& rng)
{
  const int form = int(rng() % 12);
  if (form == 0) return "-0";
  if (form == 1) return "0";
  if (form == 2) return std::to_string(int(rng() % 2001) - 1000);
  const int digits = 7 + int(rng() % 3);
  const int exponent = int(rng() % 13) - 6;
  const double mantissa = std::uniform_real_distribution<double>(-1.0, 1.0)(rng);
  char text[64];
  const char* format = form == 3 ? "%.*e" : form == 4 ? "%.*E" : "%.*g";
  std::snprintf(text, sizeof text, format, digits - 1, mantissa * std::pow(10.0, exponent));
  std::string s = text;
  if (form == 5 && s[0] != '-') s = "+" + s;
  return s;
}

// The model fuzz_load.cpp loads for an MTL seed.
const char* const kLibraryModel =
    "mtllib input.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nf 1/1 2/2 3/1\n"
    "usemtl a\nf 3/1 2/2 1/1\nusemtl z\nf 1/2 3/1 2/2\n";

struct Generated {
  std::string obj, mtl;
};

// A random OBJ (and its library) that uses what the direct reader accepts.
Generated generate(uint32_t seed)
{
  std::mt19937 rng(seed);
  const std::string eol = rng() % 3 == 0 ? "\r\n" : "\n";
  const int form = int(rng() % 4);  // v, v/vt, v//vn, v/vt/vn
  const bool colours = rng() % 4 == 0;
  const int vertices = 4 + int(rng() % 60), uvs = 3 + int(rng() % 20), normals = 3 + int(rng() % 20);
  Generated g;
  // The library: materials with colours, some with a texture, one missing.
  std::vector<std::string> names = {"unknown_" + std::to_string(seed % 3)};
  const int materials = int(rng() % 4);
  for (int m = 0; m < materials; ++m) {
    const std::string name = "mat " + std::to_string(m);
    names.push_back(name);
    g.mtl += "newmtl " + name + eol + (rng() % 2 ? "\t" : "") + "Kd " + number(rng) + " " + number(rng) + " " +
             number(rng) + eol;
    g.mtl += "Ka 0.1 0.2 0.3" + eol + "Ns 96.078431" + eol + "d 1.000000" + eol + "illum 2" + eol + "# note" + eol;
    if (m % 2) g.mtl += std::string("map_Kd ") + (m == 3 ? "missing.tga" : "tex.tga") + eol;
    if (m == 2) g.mtl += "map_Bump bump.png" + eol;
  }
  // The model: vertices in two halves, faces between and after them.
  const bool library = materials > 0 && rng() % 5 != 0;
  if (!library) names.resize(1);  // a late library would redefine names used before it: assimp's path only
  if (library) g.obj += "# generated" + eol + "mtllib in.mtl" + eol;
  int emittedV = 0, emittedT = 0, emittedN = 0;
  auto emit = [&](int v, int t, int n) {
    for (; emittedV < v; ++emittedV) {
      g.obj += "v " + number(rng) + " " + number(rng) + " " + number(rng);
      if (colours) g.obj += " 0.5 " + number(rng) + " 1";
      g.obj += eol;
    }
    for (; emittedT < t; ++emittedT) g.obj += "vt " + number(rng) + " " + number(rng) + (rng() % 2 ? " 0" : "") + eol;
    for (; emittedN < n; ++emittedN) g.obj += "vn " + number(rng) + " " + number(rng) + " " + number(rng) + eol;
  };
  auto index = [&](int emitted, int total) {
    const int i = int(rng() % uint32_t(rng() % 3 == 0 ? emitted : total));
    return rng() % 3 == 0 && i < emitted ? std::to_string(i - emitted) : std::to_string(i + 1);
  };
  int objects = 0;
  for (int half = 1; half <= 2; ++half) {
    emit(vertices * half / 2, form % 2 ? uvs * half / 2 : 0, form >= 2 ? normals * half / 2 : 0);
    const int faces = 1 + int(rng() % 30);
    for (int f = 0; f < faces; ++f) {
      switch (rng() % 10) {
        case 0: g.obj += "o object" + std::to_string(objects++) + eol; break;
        case 1: g.obj += "g group" + std::to_string(rng() % 3) + eol; break;
        case 2:
        case 3: g.obj += "usemtl " + names[rng() % names.size()] + eol; break;
        case 4: g.obj += (rng() % 2 ? "s 1" : "s off") + eol; break;
        case 5: g.obj += "# a comment" + eol + eol; break;
        default: break;
      }
      const int corners = rng() % 4 == 0 ? 3 + int(rng() % 6) : 3 + int(rng() % 2);
      g.obj += "f";
      for (int k = 0; k < corners; ++k) {
        g.obj += " " + index(emittedV, vertices);
        if (form == 1) g.obj += "/" + index(emittedT, uvs);
        if (form == 2) g.obj += "//" + index(emittedN, normals);
        if (form == 3) g.obj += "/" + index(emittedT, uvs) + "/" + index(emittedN, normals);
      }
      g.obj += (rng() % 5 == 0 ? " " : "") + eol;
    }
  }
  if (materials > 0 && !library) g.obj += "mtllib in.mtl" + eol;  // late: it recolours the last mesh
  return g;
}

}  // namespace

TEST_CASE("fast obj: every file the direct reader takes loads byte for byte as through assimp", "[fast_obj]")
{
  size_t files = 0, taken = 0;
  // Step 1: assimp's own OBJ test models.
  std::function<void(const std::string&)> walk = [&](const std::string& dir) {
    DIR* d = opendir(dir.c_str());
    if (!d) return;
    std::vector<std::string> entries;
    while (dirent* e = readdir(d)) entries.push_back(e->d_name);
    closedir(d);
    std::sort(entries.begin(), entries.end());
    for (const std::string& name : entries) {
      if (name == "." || name == "..") continue;
      const std::string path = dir + "/" + name;
      if (name.size() > 4 && name.compare(name.size() - 4, 4, ".obj") == 0) {
        ++files;
        taken += checkBothWays(path);
      } else {
        walk(path);
      }
    }
  };
  walk("/usr/share/assimp/models");
  // Step 2: generated stress files, with a texture beside them.
  const std::string dir = test::tempDir() + "/fast_obj";
  mkdir(dir.c_str(), 0755);
  writeFile(dir + "/tex.tga", tga(3, 2));
  for (uint32_t seed = 1; seed <= 60; ++seed) {
    const Generated g = generate(seed);
    writeFile(dir + "/in.mtl", g.mtl.empty() ? "# empty\n" : g.mtl);
    writeFile(dir + "/in.obj", g.obj);
    ++files;
    INFO("seed " << seed);
    taken += checkBothWays(dir + "/in.obj");
  }
  // Step 3: the fuzz seeds of OBJ ('o') and MTL ('m'), beside fuzz_load.cpp's library and texture.
  writeFile(dir + "/in.mtl", "newmtl m\nKd 1 0 0\nmap_Kd in.png\n");
  writeFile(dir + "/in.png", tga(1, 1));
  const std::string list = CLRASTER_CORPUS_LIST;
  const std::string seeds = list.substr(0, list.rfind('/')) + "/fuzz_corpus";
  DIR* d = opendir(seeds.c_str());
  REQUIRE(d);
  std::vector<std::string> names;
  while (const dirent* e = readdir(d))
    if (e->d_type == DT_REG) names.push_back(e->d_name);
  closedir(d);
  size_t seedFiles = 0;
  for (const std::string& name : names) {
    std::ifstream in(seeds + "/" + name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.empty() || (bytes[0] != 'o' && bytes[0] != 'm')) continue;
    INFO("seed " << name);
    if (bytes[0] == 'm') writeFile(dir + "/input.mtl", bytes.substr(1));
    writeFile(dir + "/seed.obj", bytes[0] == 'm' ? std::string(kLibraryModel) : bytes.substr(1));
    ++seedFiles, ++files;
    taken += checkBothWays(dir + "/seed.obj");
  }
  CHECK(seedFiles >= 20);
  INFO(taken << " of " << files << " files taken");
  CHECK(files > 60);
  CHECK(taken >= 60);  // every generated file, and some of assimp's
}

TEST_CASE("fast obj: a file the direct reader takes is not held to assimp's import estimate", "[fast_obj][budget]")
{
  // 1,048,000 groups and 4,344,000 face corners: assimp's path is estimated at 4120 MiB and refuses the file.
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  for (int i = 0; i < 524000; ++i) obj += "g a\nf 1 2 3\ng b\nf 1 3 2\n";
  for (int i = 0; i < 400000; ++i) obj += "f 2 3 1\n";
  const std::string path = test::tempDir() + "/fast_obj_groups.obj";
  writeFile(path, obj);
  REQUIRE_THROWS_WITH(clr::checkObjBudget(path, obj), Catch::Contains("4344000 face corners and 1048000 groups"));
  clr::Mesh mesh;
  const clr::AssetRoot root(path, "");
  REQUIRE(clr::readPlainObj(path, obj, root, mesh));
  CHECK(mesh.numTris() == 1448000);
  CHECK(mesh.numVerts() == 4344000);
  CHECK(mesh.indices.back() == 4343999);           // the last face, 2 3 1, un-shared
  CHECK(mesh.positions[3 * 4343998 + 1] == 1.0f);  // its second corner, vertex 3
  CHECK(clr::loadScene(path).numTris() == 1448000);
}

TEST_CASE("fast obj: a library with a texture statement before any newmtl is refused and not read", "[fast_obj]")
{
  // assimp 5.2 writes such a statement to a null material; the direct reader leaves the file to assimp's path.
  const std::string dir = test::tempDir() + "/fast_obj";
  mkdir(dir.c_str(), 0755);
  writeFile(dir + "/early.mtl", "map_Kd in.png\nnewmtl m\nKd 1 0 0\n");
  writeFile(dir + "/early.obj", "mtllib early.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK_FALSE(directTakes(dir + "/early.obj"));
  const clr::Mesh mesh = clr::loadScene(dir + "/early.obj");
  CHECK(mesh.numTris() == 1);
  REQUIRE(mesh.warnings.lines().size() == 1);
  CHECK_THAT(mesh.warnings.lines()[0], Catch::Contains("early.mtl: a map, bump, refl, norm, disp or anisotropy") &&
                                           Catch::Contains("imported without it"));
  CHECK(clr::mtlReadableByAssimp("# note\n  Kd 1 1 1\nnewmtl a\nmap_Kd a.png\n"));
  CHECK_FALSE(clr::mtlReadableByAssimp("Ka 0 0 0\r\n\tnorm n.png\r\nnewmtl a\n"));
}
