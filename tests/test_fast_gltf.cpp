// test_fast_gltf.cpp — the direct GLB and glTF reader (io/fast_gltf.h)
// against its oracle, assimp's path: for every GLB and glTF 2 file of
// assimp's test models and for
// generated scenes (node trees with matrices and TRS transforms, shared
// nodes, several primitives, u8/u16/u32 or no indices, normals, texture
// coordinates, used and unused materials), a file the direct reader takes
// must give a Mesh byte for byte the same as assimp's path gives, and a
// buffer file outside the model's folder is refused in assimp's words.
#include "io/asset_root.h"
#include "io/fast_gltf.h"
#include "io/file_rule.h"
#include "io/scene.h"
#include "test_support.h"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

namespace {

using Json = nlohmann::json;

std::string load(const std::string& path, bool direct, clr::Mesh& mesh, const std::string& assets = "")
{
  try {
    clr::ModelFile file = clr::checkSceneFile(path);
    file.direct = direct;
    mesh = clr::importScene(file, assets);
    return "";
  } catch (const clr::Error& e) {
    return e.what();
  }
}

// Checks one file both ways; true when the direct reader took it.
bool checkBothWays(const std::string& path, const std::string& assets = "")
{
  INFO(path);
  clr::Mesh direct, assimp;
  const std::string directError = load(path, true, direct, assets);
  REQUIRE(directError == load(path, false, assimp, assets));
  if (!directError.empty()) return false;
  REQUIRE(test::meshDifference(direct, assimp) == "");
  clr::Mesh mesh;
  const clr::AssetRoot root(path, assets);
  const std::string bytes = clr::readInputFile(path, clr::kModelInput);
  return path.size() > 5 && path.compare(path.size() - 5, 5, ".gltf") == 0 ? clr::readPlainGltf(path, bytes, root, mesh)
                                                                           : clr::readPlainGlb(path, bytes, root, mesh);
}

// A GLB under construction: one buffer, a tightly packed view per accessor.
struct GlbWriter {
  Json doc = {{"asset", {{"version", "2.0"}}}, {"bufferViews", Json::array()}, {"accessors", Json::array()}};
  std::string bin;

  size_t accessor(const void* data, size_t bytes, int componentType, size_t count, const char* type)
  {
    while (bin.size() % 4) bin += '\0';
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}});
    bin.append(static_cast<const char*>(data), bytes);
    doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                                {"componentType", componentType},
                                {"count", count},
                                {"type", type}});
    return doc["accessors"].size() - 1;
  }

  // Position, normal and texture coordinates interleaved in one view: their three accessors.
  std::vector<size_t> interleaved(const std::vector<float>& pos, const std::vector<float>& nor,
                                  const std::vector<float>& uv, size_t n)
  {
    while (bin.size() % 4) bin += '\0';
    const size_t at = bin.size();
    for (size_t v = 0; v < n; ++v) {
      bin.append(reinterpret_cast<const char*>(&pos[3 * v]), 12);
      bin.append(reinterpret_cast<const char*>(&nor[3 * v]), 12);
      bin.append(reinterpret_cast<const char*>(&uv[2 * v]), 8);
    }
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", 32 * n}, {"byteStride", 32}});
    std::vector<size_t> out;
    for (const auto& [offset, type] : {std::pair<int, const char*>{0, "VEC3"}, {12, "VEC3"}, {24, "VEC2"}}) {
      doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                                  {"byteOffset", offset},
                                  {"componentType", 5126},
                                  {"count", n},
                                  {"type", type}});
      out.push_back(doc["accessors"].size() - 1);
    }
    return out;
  }

  // The text glTF: its buffer named `uri`, or embedded as a base64 data uri when `uri` is empty.
  std::string finishText(const std::string& uri)
  {
    while (bin.size() % 4) bin += '\0';
    std::string data = uri;
    if (uri.empty()) {
      static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
      data = "data:application/octet-stream;base64,";
      for (size_t i = 0; i < bin.size(); i += 3) {
        uint32_t v = 0;
        for (size_t k = 0; k < 3; ++k) v = v << 8 | (i + k < bin.size() ? uint8_t(bin[i + k]) : 0u);
        for (size_t k = 0; k < 4; ++k) data += k <= bin.size() - i ? kAlphabet[(v >> (18 - 6 * k)) & 63] : '=';
      }
    }
    doc["buffers"] = Json::array({{{"byteLength", bin.size()}, {"uri", data}}});
    return doc.dump(1);
  }

  std::string finish()
  {
    while (bin.size() % 4) bin += '\0';
    doc["buffers"] = Json::array({{{"byteLength", bin.size()}}});
    std::string json = doc.dump();
    while (json.size() % 4) json += ' ';
    auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
    return "glTF" + u32(2) + u32(uint32_t(28 + json.size() + bin.size())) + u32(uint32_t(json.size())) +
           u32(0x4E4F534Au) + json + u32(uint32_t(bin.size())) + u32(0x004E4942u) + bin;
  }
};

// A number of up to 3 decimals in [-range, range], as exporters write them (never -0).
double shortNumber(std::mt19937& rng, int range)
{
  return double(int64_t(rng() % uint32_t(2000 * range + 1)) - 1000 * range) / 1000.0;
}

// A random scene: the GLB, or with `uri` set the text glTF, the files it
// names (its buffer as `*uri`, unless that is empty: a data uri; some
// images) in `files`, names and bytes.
using Files = std::vector<std::pair<std::string, std::string>>;
std::string generate(uint32_t seed, const std::string* uri = nullptr, Files* files = nullptr)
{
  std::mt19937 rng(seed);
  GlbWriter w;
  // Embedded images (uncompressed TGA), textures of them with and without samplers.
  const int images = int(rng() % 3), textures = images ? 1 + int(rng() % 3) : 0;
  for (int i = 0; i < images; ++i) {
    std::string tga(18, '\0');
    tga[2] = 2, tga[12] = char(1 + i), tga[14] = 2, tga[16] = 24;
    for (int t = 0; t < 2 * (1 + i); ++t) tga += std::string{char(rng()), char(rng()), char(rng())};
    if (files && i % 2) {  // a file beside the model
      const std::string name = "image-" + std::to_string(seed) + "-" + std::to_string(i) + ".tga";
      files->emplace_back(name, tga);
      w.doc["images"].push_back({{"uri", name}});
      continue;
    }
    w.accessor(tga.data(), tga.size(), 5121, tga.size(), "SCALAR");  // its view; the accessor stays unused
    w.doc["images"].push_back({{"bufferView", w.doc["bufferViews"].size() - 1}, {"mimeType", "image/png"}});
  }
  for (int t = 0; t < textures; ++t) {
    Json texture = {{"source", rng() % uint32_t(images)}};
    if (rng() % 2) {
      static const int kWraps[] = {33071, 33648, 10497};
      w.doc["samplers"].push_back({{"wrapS", kWraps[rng() % 3]}, {"wrapT", kWraps[rng() % 3]}});
      texture["sampler"] = w.doc["samplers"].size() - 1;
    }
    w.doc["textures"].push_back(texture);
  }
  // Materials, some never used.
  const int materials = int(rng() % 4);
  for (int m = 0; m < materials; ++m) {
    Json mat = {{"name", "m" + std::to_string(m)}};
    if (rng() % 3)
      mat["pbrMetallicRoughness"] = {
          {"baseColorFactor",
           {double(rng() % 1001) / 1000, double(rng() % 1001) / 1000, double(rng() % 1001) / 1000, 1.0}},
          {"metallicFactor", 0.5}};
    if (textures && rng() % 2)
      mat["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", rng() % uint32_t(textures)}};
    w.doc["materials"].push_back(mat);
  }
  // Meshes of 1 to 3 primitives.
  const int meshes = 1 + int(rng() % 3);
  for (int m = 0; m < meshes; ++m) {
    Json primitives = Json::array();
    const int count = 1 + int(rng() % 3);
    for (int p = 0; p < count; ++p) {
      const size_t nv = 3 + rng() % 30;
      std::vector<float> pos, nor, uv;
      for (size_t v = 0; v < nv; ++v) {
        for (int k = 0; k < 3; ++k) pos.push_back(float(shortNumber(rng, 10)));
        for (int k = 0; k < 3; ++k) nor.push_back(float(shortNumber(rng, 1)));
        for (int k = 0; k < 2; ++k) uv.push_back(float(shortNumber(rng, 2)));
      }
      Json prim;
      if (rng() % 3 == 0) {
        const std::vector<size_t> a = w.interleaved(pos, nor, uv, nv);
        prim = {{"attributes", {{"POSITION", a[0]}, {"NORMAL", a[1]}, {"TEXCOORD_0", a[2]}}}};
      } else {
        prim = {{"attributes", {{"POSITION", w.accessor(pos.data(), 4 * pos.size(), 5126, nv, "VEC3")}}}};
        if (rng() % 2) prim["attributes"]["NORMAL"] = w.accessor(nor.data(), 4 * nor.size(), 5126, nv, "VEC3");
        if (rng() % 2) prim["attributes"]["TEXCOORD_0"] = w.accessor(uv.data(), 4 * uv.size(), 5126, nv, "VEC2");
      }
      const int width = int(rng() % 4);  // none, u8, u16, u32
      if (width) {
        const size_t ni = 3 * (1 + rng() % 20);
        std::vector<uint8_t> i8;
        std::vector<uint16_t> i16;
        std::vector<uint32_t> i32;
        for (size_t i = 0; i < ni; ++i) {
          const uint32_t k = uint32_t(rng() % nv);
          i8.push_back(uint8_t(k)), i16.push_back(uint16_t(k)), i32.push_back(k);
        }
        prim["indices"] = width == 1   ? w.accessor(i8.data(), ni, 5121, ni, "SCALAR")
                          : width == 2 ? w.accessor(i16.data(), 2 * ni, 5123, ni, "SCALAR")
                                       : w.accessor(i32.data(), 4 * ni, 5125, ni, "SCALAR");
      } else if (nv % 3) {
        prim["indices"] = w.accessor(std::vector<uint32_t>{0, 1, 2}.data(), 12, 5125, 3, "SCALAR");
      }
      if (materials && rng() % 3) prim["material"] = rng() % materials;
      if (rng() % 4 == 0) prim["mode"] = 4;
      primitives.push_back(prim);
    }
    w.doc["meshes"].push_back({{"primitives", primitives}});
  }
  // Nodes: a tree (children after their parent), transforms of each kind, one node shared at times.
  const int nodes = 1 + int(rng() % 6);
  std::vector<Json> list(size_t(nodes), Json::object());
  std::vector<int> roots;
  for (int n = 0; n < nodes; ++n) {
    Json& node = list[size_t(n)];
    if (rng() % 4) node["mesh"] = rng() % uint32_t(meshes);
    const int kind = int(rng() % 4);
    if (kind == 1) {
      Json m = Json::array();
      for (int k = 0; k < 16; ++k) m.push_back(k == 15 ? 1.0 : shortNumber(rng, 2));
      node["matrix"] = m;
    } else if (kind >= 2) {
      if (rng() % 2) node["translation"] = {shortNumber(rng, 5), shortNumber(rng, 5), shortNumber(rng, 5)};
      if (rng() % 2) node["rotation"] = {shortNumber(rng, 1), shortNumber(rng, 1), shortNumber(rng, 1), 0.5};
      if (rng() % 2) node["scale"] = {shortNumber(rng, 3), 2.0, 0.5};
    }
    if (n == 0 || rng() % 3 == 0)
      roots.push_back(n);
    else
      list[rng() % uint32_t(n)]["children"].push_back(n);
  }
  if (nodes > 2 && rng() % 3 == 0) list[0]["children"].push_back(nodes - 1);  // shared: imported twice
  w.doc["nodes"] = list;
  w.doc["scenes"] = Json::array({{{"nodes", roots}}});
  w.doc["scene"] = 0;
  if (!uri) return w.finish();
  const std::string text = w.finishText(*uri);
  if (!uri->empty()) files->emplace_back(*uri, w.bin);
  return text;
}

}  // namespace

TEST_CASE("fast gltf: every GLB the direct reader takes loads byte for byte as through assimp", "[fast_gltf]")
{
  size_t files = 0, taken = 0;
  const std::string models = "/usr/share/assimp/models/";
  for (const char* name :
       {"glTF/BoxTextured-glTF-Binary/BoxTextured.glb", "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
        "glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb",
        "glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb"}) {
    const std::string path = models + name;
    std::ifstream probe(path);
    if (!probe) continue;
    ++files;
    taken += checkBothWays(path);
  }
  for (uint32_t seed = 1; seed <= 80; ++seed) {
    INFO("seed " << seed);
    ++files;
    const std::string path = test::tempDir() + "/fast_gltf.glb";
    std::ofstream(path, std::ios::binary | std::ios::trunc) << generate(seed);
    taken += checkBothWays(path);
  }
  // The fuzz seeds of GLB ('b': one selector byte, then the file; fuzz_load.cpp).
  const std::string list = CLRASTER_CORPUS_LIST;
  const std::string seeds = list.substr(0, list.rfind('/')) + "/fuzz_corpus";
  size_t seedsTaken = 0;
  for (const char* name : {"glb_direct_plain", "glb_direct_truncated", "glb_direct_count_huge", "glb_direct_index_out",
                           "glb_direct_long_numbers", "glb_direct_cycle", "glb_direct_shared_roots", "glb_basic"}) {
    INFO("seed " << name);
    std::ifstream in(seeds + "/" + name, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    REQUIRE(bytes.size() > 1);
    const std::string path = test::tempDir() + "/fast_gltf_seed.glb";
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(1);
    ++files;
    seedsTaken += checkBothWays(path);
  }
  CHECK(seedsTaken >= 2);
  INFO(taken << " of " << files << " files taken");
  CHECK(files == 93);
  CHECK(taken >= 70);
}

TEST_CASE("fast gltf: every glTF the direct reader takes loads byte for byte as through assimp", "[fast_gltf]")
{
  size_t files = 0, taken = 0, corpusTaken = 0;
  std::vector<std::string> corpus;
  const std::string models = "/usr/share/assimp/models/glTF2";
  if (std::filesystem::is_directory(models))
    for (const auto& entry : std::filesystem::recursive_directory_iterator(models))
      if (entry.path().extension() == ".gltf") corpus.push_back(entry.path().string());
  std::sort(corpus.begin(), corpus.end());
  for (const std::string& path : corpus) {
    ++files;
    corpusTaken += checkBothWays(path);
  }
  // Generated scenes: the buffer a file beside it (in a subfolder at times), or a data uri.
  const std::string dir = test::tempDir() + "/fast_gltf_text";
  std::filesystem::create_directories(dir + "/buffers");
  for (uint32_t seed = 1; seed <= 60; ++seed) {
    INFO("seed " << seed);
    const std::string uri = seed % 3 == 0   ? ""
                            : seed % 3 == 1 ? "scene.bin"
                                            : "buffers/scene-" + std::to_string(seed) + ".bin";
    Files named;
    const std::string text = generate(seed, &uri, &named);
    for (const auto& [name, bytes] : named)
      std::ofstream(dir + "/" + name, std::ios::binary | std::ios::trunc) << bytes;
    std::ofstream(dir + "/scene.gltf", std::ios::binary | std::ios::trunc) << text;
    ++files;
    taken += checkBothWays(dir + "/scene.gltf");
  }
  INFO(corpusTaken << " of " << corpus.size() << " corpus files taken, " << taken << " generated");
  CHECK(corpusTaken >= 3);
  CHECK(taken >= 45);
}

TEST_CASE("fast gltf: a buffer file outside the model folder is refused as through assimp", "[fast_gltf]")
{
  // The buffer reached through a link in the model's folder to a folder beside it.
  const std::string dir = test::tempDir() + "/fast_gltf_outside";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/model");
  std::filesystem::create_directories(dir + "/elsewhere");
  const std::string uri = "linked/scene.bin";
  Files named;
  const std::string text = generate(7, &uri, &named);
  for (const auto& [name, bytes] : named)
    std::ofstream(dir + (name == uri ? "/elsewhere/scene.bin" : "/model/" + name), std::ios::binary) << bytes;
  REQUIRE(symlink((dir + "/elsewhere").c_str(), (dir + "/model/linked").c_str()) == 0);
  const std::string path = dir + "/model/scene.gltf";
  std::ofstream(path, std::ios::binary) << text;
  clr::Mesh direct, assimp;
  const std::string error = load(path, true, direct);
  CHECK(error.find(clr::AssetRoot::refusal(uri)) != std::string::npos);
  CHECK(error == load(path, false, assimp));
  clr::Mesh mesh;
  CHECK_FALSE(clr::readPlainGltf(path, text, clr::AssetRoot(path, ""), mesh));
  // --assets any or the folder: read, and by the direct reader.
  CHECK(checkBothWays(path, clr::kAnyAssets));
  CHECK(checkBothWays(path, dir + "/elsewhere"));
  CHECK(clr::readPlainGltf(path, text, clr::AssetRoot(path, clr::kAnyAssets), mesh));
}
