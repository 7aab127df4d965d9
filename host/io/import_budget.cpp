// import_budget.cpp — the import's memory budget (see import_budget.h).
#include "io/import_budget.h"

#include "base/error.h"
#include "io/file_rule.h"

#include <nlohmann/json.hpp>

#include <cstring>
#include <map>
#include <set>
#include <unordered_set>

namespace clr {

namespace {

// Bytes an item costs an import through assimp 5.2 and the loader's mesh,
// measured with peak RSS on files of one kind of item each: an OBJ vertex
// line, a face corner (un-indexed by the reader), a group or material
// switch (a mesh and a node of its own), a material (its property list).
constexpr uint64_t kObjVertexBytes = 40, kObjCornerBytes = 150, kObjGroupBytes = 3500, kObjMaterialBytes = 36000;
// A glTF accessor component (copied to floats, then into the loader's
// arrays), a primitive (a mesh of its own), a node.
constexpr uint64_t kGltfComponentBytes = 32, kGltfPrimitiveBytes = 3500, kGltfNodeBytes = 1000;
// A vertex and an index of a node instance, in the loader's arrays (48 bytes of attributes a vertex).
constexpr uint64_t kGltfVertexBytes = 64, kGltfIndexBytes = 8;
constexpr int kMaxJsonDepth = 64;  // as model_checks.h's parser

std::string mib(uint64_t bytes)
{
  return std::to_string((bytes + (uint64_t(1) << 20) - 1) >> 20) + " MiB";
}

uint64_t readU32(const std::string& bytes, size_t at)
{
  uint64_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(bytes[at + size_t(k)]);
  return v;
}

// The members of a glTF collection: an array (glTF 2) or an object keyed by id (glTF 1).
template <typename F>
void forEach(const nlohmann::json& doc, const char* key, F&& f)
{
  const auto found = doc.find(key);
  if (found == doc.end() || !(found->is_array() || found->is_object())) return;
  for (const auto& item : *found) f(item);
}

// A glTF collection's member by reference: an index (glTF 2) or an id (glTF 1).
const nlohmann::json* member(const nlohmann::json& doc, const char* key, const nlohmann::json& ref)
{
  const auto collection = doc.find(key);
  if (collection == doc.end()) return nullptr;
  if (collection->is_array() && ref.is_number_unsigned() && ref.get<uint64_t>() < collection->size())
    return &(*collection)[ref.get<size_t>()];
  if (collection->is_object() && ref.is_string()) {
    const auto found = collection->find(ref.get<std::string>());
    return found == collection->end() ? nullptr : &*found;
  }
  return nullptr;
}

// The count an accessor reference declares, 0 without one.
long double accessorCount(const nlohmann::json& doc, const nlohmann::json* ref)
{
  const nlohmann::json* a = ref ? member(doc, "accessors", *ref) : nullptr;
  if (!a || !a->is_object() || !a->contains("count") || !(*a)["count"].is_number()) return 0;
  return std::max<long double>(0, (*a)["count"].get<long double>());
}

// The bytes the loader's copies of node instances take: each node as often
// as the scenes reach it, with its meshes' vertices and indices.
struct Instances {
  const nlohmann::json& doc;
  long double count = 0, bytes = 0;
  std::map<const nlohmann::json*, std::pair<long double, long double>> memo;  // node: (instances, bytes) below it
  std::set<const nlohmann::json*> open;                                       // on the path: a cycle ends there

  void add(const nlohmann::json& node)
  {
    const auto [n, b] = visit(node);
    count += n;
    bytes += b;
  }
  std::pair<long double, long double> visit(const nlohmann::json& node)
  {
    if (!node.is_object() || open.count(&node)) return {0, 0};
    const auto known = memo.find(&node);
    if (known != memo.end()) return known->second;
    open.insert(&node);
    std::pair<long double, long double> sum{1, kGltfNodeBytes};
    auto addMesh = [&](const nlohmann::json& ref) {
      const nlohmann::json* mesh = member(doc, "meshes", ref);
      if (!mesh) return;
      forEach(*mesh, "primitives", [&](const nlohmann::json& p) {
        if (!p.is_object()) return;
        const auto attributes = p.find("attributes");
        if (attributes != p.end() && attributes->is_object() && attributes->contains("POSITION"))
          sum.second += accessorCount(doc, &(*attributes)["POSITION"]) * kGltfVertexBytes;
        if (p.contains("indices")) sum.second += accessorCount(doc, &p["indices"]) * kGltfIndexBytes;
      });
    };
    if (node.contains("mesh")) addMesh(node["mesh"]);                           // glTF 2
    forEach(node, "meshes", [&](const nlohmann::json& ref) { addMesh(ref); });  // glTF 1
    forEach(node, "children", [&](const nlohmann::json& ref) {
      if (const nlohmann::json* child = member(doc, "nodes", ref)) {
        const auto [n, b] = visit(*child);
        sum.first += n;
        sum.second += b;
      }
    });
    open.erase(&node);
    return memo[&node] = sum;
  }
};

uint64_t components(const std::string& type)
{
  return type == "SCALAR"                   ? 1
         : type == "VEC2"                   ? 2
         : type == "VEC3"                   ? 3
         : type == "VEC4" || type == "MAT2" ? 4
         : type == "MAT3"                   ? 9
                                            : 16;
}

}  // namespace

std::string overBudget(const std::string& path, const std::string& what, uint64_t limitBytes)
{
  return userText(path, 120) + ": " + what + ", over the import budget of " + mib(limitBytes) + " (docs/limits.md)";
}

void checkObjBudget(const std::string& path, const std::string& text)
{
  uint64_t vertices = 0, corners = 0, groups = 0;
  std::unordered_set<std::string> materials;
  const char* p = text.data();
  const char* const end = p + text.size();
  while (p < end) {
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', size_t(end - p)));
    if (!eol) eol = end;
    while (p < eol && (*p == ' ' || *p == '\t')) ++p;
    const char* word = p;
    while (p < eol && *p != ' ' && *p != '\t' && *p != '\r') ++p;
    const std::string key(word, p);
    if (key == "v") {
      ++vertices;
    } else if (key == "f") {
      for (bool inToken = false; p < eol; ++p) {  // one corner a token
        const bool space = *p == ' ' || *p == '\t' || *p == '\r';
        if (!space && !inToken) ++corners;
        inToken = !space;
      }
    } else if (key == "o" || key == "g") {
      ++groups;
    } else if (key == "usemtl") {
      ++groups;
      while (p < eol && (*p == ' ' || *p == '\t')) ++p;
      const char* name = p;
      const char* last = eol;
      while (last > name && (last[-1] == ' ' || last[-1] == '\t' || last[-1] == '\r')) --last;
      if (materials.emplace(name, last).second && materials.size() > kMaxMaterials)
        throw Error(userText(path, 120) + ": more than " + std::to_string(kMaxMaterials) +
                    " distinct usemtl names, the limit for one OBJ (docs/limits.md)");
    }
    p = eol + 1;
  }
  const uint64_t estimate = vertices * kObjVertexBytes + corners * kObjCornerBytes + groups * kObjGroupBytes +
                            uint64_t(materials.size()) * kObjMaterialBytes;
  if (estimate > kImportBudgetBytes)
    throw Error(overBudget(path,
                           "importing " + std::to_string(vertices) + " vertices, " + std::to_string(corners) +
                               " face corners and " + std::to_string(groups) + " groups needs about " + mib(estimate),
                           kImportBudgetBytes));
}

uint64_t countMaterials(const std::string& text)
{
  uint64_t n = 0;
  for (size_t at = 0; (at = text.find("newmtl", at)) != std::string::npos; at += 6) {
    size_t start = text.rfind('\n', at);
    start = start == std::string::npos ? 0 : start + 1;
    while (start < at && (text[start] == ' ' || text[start] == '\t')) ++start;
    if (start == at) ++n;  // at a line's start
  }
  return n;
}

void checkGltfBudget(const std::string& path, const std::string& bytes)
{
  // Step 1: the JSON text: the whole file, or a GLB's JSON chunk.
  const std::string head = bytes.substr(0, 20);
  size_t first = head.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (first < head.size() && std::strchr(" \t\r\n", head[first])) ++first;
  std::string json;
  if (head.size() >= 20 && head.compare(0, 4, "glTF") == 0) {
    const uint64_t length = readU32(head, 12);
    if (length > bytes.size() - 20) return;  // model_checks.h reports a truncated chunk
    json = bytes.substr(20, size_t(length));
  } else if (first < head.size() && head[first] == '{') {
    json = bytes;
  } else {
    return;  // not glTF
  }
  // Step 2: parse, no deeper than the checks allow; a malformed file is for them and assimp to report.
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(json, [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
      if (depth > kMaxJsonDepth) throw Error("nested too deep");
      return true;
    });
  } catch (const std::exception&) {
    return;
  }
  if (!doc.is_object()) return;
  // Step 3: the declared elements and structure.
  long double elements = 0;  // every accessor's count times its components, as declared
  forEach(doc, "accessors", [&](const nlohmann::json& a) {
    if (!a.is_object()) return;
    const auto count = a.find("count");
    const auto type = a.find("type");
    if (count == a.end() || !count->is_number() || type == a.end() || !type->is_string()) return;
    elements += std::max<long double>(0, count->get<long double>()) * components(type->get<std::string>());
  });
  uint64_t primitives = 0;
  forEach(doc, "meshes",
          [&](const nlohmann::json& m) { forEach(m, "primitives", [&](const auto&) { ++primitives; }); });
  // Step 4: the node instances the loader copies meshes into (a node two
  // parents name is imported twice: nodes shared level by level double).
  Instances instances{doc};
  const auto scenes = doc.find("scenes");
  if (scenes != doc.end() && !scenes->empty()) {
    forEach(doc, "scenes", [&](const nlohmann::json& scene) {
      forEach(scene, "nodes", [&](const nlohmann::json& ref) {
        if (const nlohmann::json* node = member(doc, "nodes", ref)) instances.add(*node);
      });
    });
  } else {
    forEach(doc, "nodes", [&](const nlohmann::json& node) { instances.add(node); });
  }
  const long double estimate =
      elements * kGltfComponentBytes + (long double)(primitives)*kGltfPrimitiveBytes + instances.bytes;
  auto text = [](long double v) { return std::to_string(uint64_t(std::min<long double>(v, 1e19L))); };
  if (estimate > (long double)kImportBudgetBytes)
    throw Error(overBudget(path,
                           "accessors declaring " + text(elements) + " components, " + std::to_string(primitives) +
                               " primitives and " + text(instances.count) + " node instances need about " +
                               mib(uint64_t(std::min<long double>(estimate, 1e19L))),
                           kImportBudgetBytes));
}

}  // namespace clr
