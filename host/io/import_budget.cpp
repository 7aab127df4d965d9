// import_budget.cpp — the import's memory budget (see import_budget.h).
#include "io/import_budget.h"

#include "base/error.h"
#include "io/file_rule.h"

#include <nlohmann/json.hpp>

#include <cstring>
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

void checkGltfBudget(const std::string& path)
{
  // Step 1: the JSON text: the whole file, or a GLB's JSON chunk.
  InputFile file(path, kModelInput);
  const std::string head = file.read(20);
  size_t first = head.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (first < head.size() && std::strchr(" \t\r\n", head[first])) ++first;
  std::string json;
  if (head.size() >= 20 && head.compare(0, 4, "glTF") == 0) {
    const uint64_t length = readU32(head, 12);
    if (length > file.size() - 20) return;  // model_checks.h reports a truncated chunk
    json = file.read(size_t(20 + length)).substr(20);
  } else if (first < head.size() && head[first] == '{') {
    json = file.read();
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
  uint64_t primitives = 0, nodes = 0;
  forEach(doc, "meshes", [&](const nlohmann::json& m) {
    if (m.is_object() && m.contains("primitives") && (m["primitives"].is_array() || m["primitives"].is_object()))
      primitives += m["primitives"].size();
  });
  forEach(doc, "nodes", [&](const nlohmann::json&) { ++nodes; });
  const long double estimate = elements * kGltfComponentBytes + (long double)(primitives)*kGltfPrimitiveBytes +
                               (long double)(nodes)*kGltfNodeBytes;
  if (estimate > (long double)kImportBudgetBytes)
    throw Error(overBudget(path,
                           "accessors declaring " + std::to_string(uint64_t(std::min<long double>(elements, 1e19L))) +
                               " components, " + std::to_string(primitives) + " primitives and " +
                               std::to_string(nodes) + " nodes need about " +
                               mib(uint64_t(std::min<long double>(estimate, 1e19L))),
                           kImportBudgetBytes));
}

}  // namespace clr
