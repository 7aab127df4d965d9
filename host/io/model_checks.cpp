// model_checks.cpp — checks before assimp reads a file (see model_checks.h).
#include "io/model_checks.h"

#include "base/error.h"

#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <set>
#include <strings.h>
#include <sstream>
#include <type_traits>
#include <utility>
#include <vector>

namespace clr {

std::string oneLine(std::string s)
{
  for (char& c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

namespace {

// The most of a file the PLY header check reads (the file rule,
// file_rule.h, opens it): far more than 10,000 header lines need.
constexpr size_t kHeaderBytes = size_t(1) << 20;

// Assimp 5.2's PLY reader loops forever on some malformed headers (an
// unknown property type, a missing end_header), drops the properties after a
// line it does not know, and it allocates what an
// element count asks for before reading any data. PLY headers are short and
// fully specified, so they are checked here before assimp sees the file: an
// element of N items needs at least N bytes.
void checkPlyHeader(const std::string& path, const std::string& bytes)
{
  const uint64_t fileSize = bytes.size();
  std::istringstream in(bytes.substr(0, kHeaderBytes));
  std::string line;
  // Step 1: the magic. Assimp skips blank lines before it and takes any case
  // ("pLy" too), and it hung (the fuzzer found it) on a magic followed by
  // more text on its line, so that is an error here.
  int magicLine = 0;
  auto trimmed = [](std::string s) {
    const size_t first = s.find_first_not_of(" \t\r\v\f");
    if (first == std::string::npos) return std::string();
    return s.substr(first, s.find_last_not_of(" \t\r\v\f") - first + 1);
  };
  std::string magic;
  while (magic.empty() && std::getline(in, line)) {
    ++magicLine;
    magic = trimmed(line);
  }
  if (magic.size() < 3 || std::tolower(static_cast<unsigned char>(magic[0])) != 'p' ||
      std::tolower(static_cast<unsigned char>(magic[1])) != 'l' ||
      std::tolower(static_cast<unsigned char>(magic[2])) != 'y')
    return;  // not PLY: assimp decides
  if (magic.size() > 3)
    throw Error(
        oneLine(userText(path) + ": PLY header line " + std::to_string(magicLine) + ": text after the magic 'ply'"));
  // Step 2: the header lines up to end_header.
  static const char* const kTypes[] = {"char", "uchar", "short", "ushort", "int",   "uint",   "float",   "double",
                                       "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  auto known = [](const std::string& t) {
    return std::find(std::begin(kTypes), std::end(kTypes), t) != std::end(kTypes);
  };
  auto typeBytes = [](const std::string& t) {  // of a known type: the table's rows are 1, 1, 2, 2, 4, 4, 4, 8
    static const uint64_t kSizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
    return kSizes[size_t(std::find(std::begin(kTypes), std::end(kTypes), t) - std::begin(kTypes)) % 8];
  };
  // A binary body holds at least each element's count times its fixed bytes (a list: its length's bytes).
  bool binary = false;
  uint64_t count = 0, itemBytes = 0, bodyBytes = 0;
  bool haveFormat = false, haveElement = false;
  int elementLine = 0, unknownLine = 0;  // the last element line, the last unknown line
  for (int lineNo = magicLine + 1; std::getline(in, line) && lineNo < 10000; ++lineNo) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key, a, b, c;
    words >> key;
    const std::string where = userText(path) + ": PLY header line " + std::to_string(lineNo) + ": ";
    if (key == "end_header") {
      if (!haveFormat || !haveElement) throw Error(oneLine(where + "end_header before format and element lines"));
      bodyBytes += count * itemBytes;
      const auto headerEnd = in.tellg();
      if (binary && headerEnd >= 0 && fileSize - uint64_t(headerEnd) < bodyBytes)
        throw Error(oneLine(userText(path) + ": PLY binary body of " + std::to_string(fileSize - uint64_t(headerEnd)) +
                            " bytes, less than its elements' " + std::to_string(bodyBytes) + " (a truncated file)"));
      return;
    }
    if (key == "comment" || key == "obj_info" || key.empty()) continue;
    if (key == "format") {
      words >> a >> b;
      if ((a != "ascii" && a != "binary_little_endian" && a != "binary_big_endian") || b != "1.0")
        throw Error(oneLine(where + "unknown format '" + userText(a + " " + b, 60) + "'"));
      haveFormat = true;
      binary = a != "ascii";
    } else if (key == "element") {
      // A name, then a count of decimal digits only: assimp read the count
      // out of a name like "4294967295roperty" (found by the fuzzer).
      std::string countText;
      words >> a >> countText;
      const bool digits = !countText.empty() && countText.size() <= 18 &&
                          std::all_of(countText.begin(), countText.end(),
                                      [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)) != 0; });
      if (a.empty() || std::isdigit(static_cast<unsigned char>(a[0])) || !digits)
        throw Error(oneLine(where + "malformed element line"));
      bodyBytes += count * itemBytes;
      count = uint64_t(std::stoll(countText));
      itemBytes = 0;
      if (count > fileSize)
        throw Error(oneLine(where + "element '" + userText(a, 60) + "' has " + std::to_string(count) +
                            " items, more than the file's " + std::to_string(fileSize) + " bytes hold"));
      haveElement = true;
      elementLine = lineNo;
    } else if (key == "property") {
      if (!haveElement) throw Error(oneLine(where + "property before any element"));
      if (unknownLine > elementLine)
        throw Error(oneLine(where + "property after the unknown header line " + std::to_string(unknownLine) +
                            " of its element (assimp would drop it)"));
      words >> a;
      if (a == "list") {
        words >> b >> c;
        if (!known(b) || !known(c))
          throw Error(oneLine(where + "unknown list property type in '" + userText(line, 60) + "'"));
        itemBytes += typeBytes(b);
      } else if (!known(a)) {
        throw Error(oneLine(where + "unknown property type '" + userText(a, 60) + "'"));
      } else {
        itemBytes += typeBytes(a);
      }
    } else {
      // Assimp skips a line it does not know (exporters write such lines:
      // Blender's "Created by ..."), but one among an element's properties
      // ends that element's list, and the properties after it would be
      // dropped, misreading the data: refused then (below).
      unknownLine = lineNo;
      continue;
    }
  }
  throw Error(userText(path) + ": PLY header has no end_header");
}

// Assimp 5.2's OFF reader allocates the vertex and face counts of the header
// before reading a line, so a 40-byte file can ask for gigabytes (and take a
// minute to fail). Every vertex and every face takes at least two bytes, so
// counts beyond half the file size are rejected here. The header is scanned
// character by character as assimp's OFFImporter::InternReadFile does: an
// optional [ST][C][N][4][n] prefix, "OFF" (its last letter may run into the
// first count: "OFF12"), a dimension after 'n', then the counts, each read
// as its leading digits; '#' starts a comment where a token may start.
void checkOffHeader(const std::string& path, const std::string& bytes)
{
  const uint64_t fileSize = bytes.size();
  const char* car = bytes.data();
  const char* const end = car + std::min<size_t>(bytes.size(), 4096);
  auto lineEnd = [](char c) { return c == '\n' || c == '\r' || c == '\f' || c == '\0'; };
  auto nextToken = [&] {
    while (car < end && (*car == ' ' || *car == '\t' || lineEnd(*car))) ++car;
    while (car < end && *car == '#') {
      while (car < end && *car != '\n' && *car != '\r') ++car;
      while (car < end && (*car == ' ' || *car == '\t' || lineEnd(*car))) ++car;
    }
  };
  auto digits = [&] {
    std::string d;
    while (car < end && *car >= '0' && *car <= '9') d += *car++;
    return d;
  };
  nextToken();
  if (end - car > 2 && car[0] == 'S' && car[1] == 'T') car += 2;
  if (end - car > 1 && car[0] == 'C') ++car;
  if (end - car > 1 && car[0] == 'N') ++car;
  if (end - car > 1 && car[0] == '4') ++car;
  const bool hasDimension = end - car > 1 && car[0] == 'n';
  if (hasDimension) ++car;
  if (end - car > 3 && car[0] == 'O' && car[1] == 'F' && car[2] == 'F') car += 3;
  nextToken();
  if (hasDimension) {
    digits();
    nextToken();
  }
  const char* const names[] = {"vertex", "face"};
  for (const char* name : names) {
    nextToken();
    const std::string count = digits();
    if (count.size() > 19 || (!count.empty() && std::stoull(count) > fileSize / 2))
      throw Error(userText(path) + ": OFF header " + name + " count " + count.substr(0, 20) +
                  " exceeds what the file's " + std::to_string(fileSize) + " bytes hold");
  }
}

// A JSON value, as much of one as the glTF checks need.
struct Json {
  enum Kind { kNull, kBool, kNumber, kString, kArray, kObject } kind = kNull;
  double number = 0.0;
  std::string text;
  std::vector<Json> items;                           // array elements
  std::vector<std::pair<std::string, Json>> fields;  // object members, in file order

  const Json* get(const std::string& key) const
  {
    for (const auto& [k, v] : fields)
      if (k == key) return &v;
    return nullptr;
  }
  // Element `ref` of a collection: an array indexed by number (glTF 2) or an
  // object keyed by id (glTF 1).
  const Json* at(const Json& ref) const
  {
    if (kind == kArray && ref.kind == kNumber && ref.number >= 0 && ref.number < double(items.size()))
      return &items[size_t(ref.number)];
    if (kind == kObject && ref.kind == kString) return get(ref.text);
    return nullptr;
  }
  std::vector<const Json*> elements() const
  {
    std::vector<const Json*> out;
    for (const Json& v : items) out.push_back(&v);
    for (const auto& f : fields) out.push_back(&f.second);
    return out;
  }
};

// Strict JSON (RFC 8259), nesting at most kMaxDepth deep: assimp's parser
// recurses once per level, so a deep file would overflow its stack.
class JsonParser {
 public:
  static constexpr int kMaxDepth = 64;
  JsonParser(const std::string& where, const char* begin, const char* end) : where_(where), p_(begin), end_(end) {}

  Json document()
  {
    Json v = value(0);
    skipSpace();
    if (p_ != end_ && *p_ != '\0') fail("text after the JSON document");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const
  {
    throw Error(where_ + "invalid JSON: " + what + " at byte " + std::to_string(p_ - begin_));
  }
  void skipSpace()
  {
    while (p_ != end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\n' || *p_ == '\r')) ++p_;
  }
  bool literal(const char* word)
  {
    const size_t n = std::strlen(word);
    if (size_t(end_ - p_) < n || std::memcmp(p_, word, n) != 0) return false;
    p_ += n;
    return true;
  }
  std::string string()
  {
    std::string s;
    ++p_;  // the opening quote
    while (true) {
      if (p_ == end_) fail("unterminated string");
      const char c = *p_++;
      if (c == '"') return s;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
      if (c != '\\') {
        s += c;
        continue;
      }
      if (p_ == end_) fail("unterminated string");
      const char e = *p_++;
      if (e == 'u') {
        for (int k = 0; k < 4; ++k, ++p_)
          if (p_ == end_ || !std::isxdigit(static_cast<unsigned char>(*p_))) fail("bad \\u escape");
        s += '?';  // the checks compare only ASCII names
      } else if (std::strchr("\"\\/bfnrt", e)) {
        s += e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e == 'b' ? '\b' : e == 'f' ? '\f' : e;
      } else {
        fail("bad escape");
      }
    }
  }
  double number()
  {
    const char* start = p_;
    auto digits = [&] {
      const char* d = p_;
      while (p_ != end_ && *p_ >= '0' && *p_ <= '9') ++p_;
      return p_ != d;
    };
    if (p_ != end_ && *p_ == '-') ++p_;
    if (!digits()) fail("bad number");
    if (p_ != end_ && *p_ == '.') {
      ++p_;
      if (!digits()) fail("bad number");
    }
    if (p_ != end_ && (*p_ == 'e' || *p_ == 'E')) {
      ++p_;
      if (p_ != end_ && (*p_ == '+' || *p_ == '-')) ++p_;
      if (!digits()) fail("bad number");
    }
    return std::strtod(std::string(start, p_).c_str(), nullptr);
  }
  Json value(int depth)
  {
    if (depth > kMaxDepth) fail("nested deeper than " + std::to_string(kMaxDepth) + " levels");
    skipSpace();
    if (p_ == end_) fail("unexpected end");
    Json v;
    const char c = *p_;
    if (c == '{' || c == '[') {
      v.kind = c == '{' ? Json::kObject : Json::kArray;
      ++p_;
      skipSpace();
      const char close = c == '{' ? '}' : ']';
      if (p_ != end_ && *p_ == close) {
        ++p_;
        return v;
      }
      while (true) {
        skipSpace();
        if (v.kind == Json::kObject) {
          if (p_ == end_ || *p_ != '"') fail("expected a member name");
          std::string key = string();
          skipSpace();
          if (p_ == end_ || *p_ != ':') fail("expected ':'");
          ++p_;
          v.fields.emplace_back(std::move(key), value(depth + 1));
        } else {
          v.items.push_back(value(depth + 1));
        }
        skipSpace();
        if (p_ != end_ && *p_ == ',') {
          ++p_;
        } else if (p_ != end_ && *p_ == close) {
          ++p_;
          return v;
        } else {
          fail(std::string("expected ',' or '") + close + "'");
        }
      }
    }
    if (c == '"') {
      v.kind = Json::kString;
      v.text = string();
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      v.kind = Json::kNumber;
      v.number = number();
    } else if (literal("true") || literal("false")) {
      v.kind = Json::kBool;
    } else if (literal("null")) {
      v.kind = Json::kNull;
    } else {
      fail("unexpected character");
    }
    return v;
  }

  std::string where_;
  const char* p_;
  const char* begin_ = p_;
  const char* end_;
};

// glTF component types (GL enums) and element types.
constexpr int kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125, kFloat = 5126;

// What a use of an accessor allows: element types and component types.
struct AccessorRule {
  std::vector<std::string> types;
  std::vector<int> components;
};

// Assimp copies each element of an accessor into a fixed-size vector of
// its use (aiVector3D for a position) with the accessor's declared element
// size, unchecked: a larger one overflows the vector, a smaller one leaves
// the rest uninitialised. So every use must have the type the glTF
// specification requires of it.
AccessorRule attributeRule(const std::string& name)
{
  auto starts = [&](const char* prefix) { return name.rfind(prefix, 0) == 0; };
  if (name == "POSITION" || name == "NORMAL") return {{"VEC3"}, {kFloat}};
  if (name == "TANGENT") return {{"VEC4"}, {kFloat}};
  if (starts("TEXCOORD")) return {{"VEC2"}, {kFloat, kUByte, kUShort}};
  if (starts("COLOR")) return {{"VEC3", "VEC4"}, {kFloat, kUByte, kUShort}};
  if (starts("JOINT")) return {{"VEC4"}, {kUByte, kUShort, kFloat}};  // glTF 1 stores joints as float
  if (starts("WEIGHT")) return {{"VEC4"}, {kFloat, kUByte, kUShort}};
  return {};  // any other attribute is not read
}

class GltfCheck {
 public:
  GltfCheck(const std::string& path, const Json& doc) : path_(path), doc_(doc) {}

  void run()
  {
    if (doc_.kind != Json::kObject) fail("the document is not a JSON object");
    // Every accessor: known component and element types, a sane count.
    if (const Json* accessors = doc_.get("accessors")) {
      for (const Json* a : accessors->elements()) {
        const Json* component = a->get("componentType");
        const Json* type = a->get("type");
        if (!isOneOf(enumValue(component), {kByte, kUByte, kShort, kUShort, kUInt, kFloat}))
          fail("an accessor has no valid componentType");
        if (!type || type->kind != Json::kString ||
            !isOneOf(type->text, {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}))
          fail("an accessor has no valid type");
        if (const Json* sparse = a->get("sparse"))
          if (const Json* indices = sparse->get("indices")) {
            if (!isOneOf(enumValue(indices->get("componentType")), {kUByte, kUShort, kUInt}))
              fail("a sparse accessor has invalid index componentType");
          }
      }
    }
    // Every use of an accessor.
    if (const Json* meshes = doc_.get("meshes"))
      for (const Json* mesh : meshes->elements())
        if (const Json* primitives = mesh->get("primitives"))
          for (const Json* primitive : primitives->elements()) {
            if (const Json* mode = primitive->get("mode"))
              if (!isOneOf(enumValue(mode), {0, 1, 2, 3, 4, 5, 6})) fail("a primitive has no valid mode (0..6)");
            if (const Json* attributes = primitive->get("attributes"))
              for (const auto& [name, ref] : attributes->fields) use(ref, "attribute " + name, attributeRule(name));
            if (const Json* indices = primitive->get("indices"))
              use(*indices, "indices", {{"SCALAR"}, {kUByte, kUShort, kUInt}});
            if (const Json* targets = primitive->get("targets"))
              for (const Json* target : targets->elements())
                for (const auto& [name, ref] : target->fields) use(ref, "morph target " + name, {{"VEC3"}, {kFloat}});
          }
    if (const Json* skins = doc_.get("skins"))
      for (const Json* skin : skins->elements())
        if (const Json* matrices = skin->get("inverseBindMatrices"))
          use(*matrices, "skin inverseBindMatrices", {{"MAT4"}, {kFloat}});
    if (const Json* animations = doc_.get("animations"))
      for (const Json* animation : animations->elements()) {
        const Json* samplers = animation->get("samplers");
        const Json* channels = animation->get("channels");
        if (!samplers || !channels) continue;
        for (const Json* channel : channels->elements()) {
          const Json* samplerRef = channel->get("sampler");
          const Json* target = channel->get("target");
          const Json* pathName = target ? target->get("path") : nullptr;
          const Json* sampler = samplerRef ? samplers->at(*samplerRef) : nullptr;
          if (!sampler) continue;
          if (const Json* input = sampler->get("input")) use(*input, "animation input", {{"SCALAR"}, {kFloat}});
          const std::string p = pathName && pathName->kind == Json::kString ? pathName->text : "";
          AccessorRule rule{{"SCALAR"}, {kFloat, kByte, kUByte, kShort, kUShort}};  // weights
          if (p == "translation" || p == "scale") rule = {{"VEC3"}, {kFloat}};
          if (p == "rotation") rule = {{"VEC4"}, {kFloat, kByte, kUByte, kShort, kUShort}};
          if (const Json* output = sampler->get("output")) use(*output, "animation output", rule);
        }
      }
  }

 private:
  [[noreturn]] void fail(const std::string& what) const
  {
    throw Error(userText(path_) + ": glTF: " + userText(what, 90));
  }

  // A whole number that fits an int, else -1 (no glTF enum).
  static int enumValue(const Json* v)
  {
    if (!v || v->kind != Json::kNumber || !(v->number >= 0.0 && v->number <= 1e9) ||
        v->number != double(int(v->number)))
      return -1;
    return int(v->number);
  }

  template <typename T>
  static bool isOneOf(const T& value, std::initializer_list<std::common_type_t<T>> allowed)
  {
    return std::find(allowed.begin(), allowed.end(), value) != allowed.end();
  }

  void use(const Json& ref, const std::string& what, const AccessorRule& rule) const
  {
    const Json* accessors = doc_.get("accessors");
    const Json* a = accessors ? accessors->at(ref) : nullptr;
    if (!a) return;  // a missing accessor: assimp reports it
    const std::string type = a->get("type")->text;
    const int component = enumValue(a->get("componentType"));
    if (!rule.types.empty() && std::find(rule.types.begin(), rule.types.end(), type) == rule.types.end())
      fail(what + " uses an accessor of type " + type);
    if (!rule.components.empty() &&
        std::find(rule.components.begin(), rule.components.end(), component) == rule.components.end())
      fail(what + " uses an accessor of componentType " + std::to_string(component));
    inView(*a, what);
  }

  // An accessor's elements lie inside its bufferView: assimp reads past its end, into the next view's bytes.
  void inView(const Json& a, const std::string& what) const
  {
    const Json* views = doc_.get("bufferViews");
    const Json* viewRef = a.get("bufferView");
    const Json* view = views && viewRef ? views->at(*viewRef) : nullptr;
    const double count = number(a.get("count"), 0.0);
    if (!view || count <= 0.0) return;  // no view (sparse, or assimp's own error), or nothing to read
    const std::string& type = a.get("type")->text;
    const int component = enumValue(a.get("componentType"));
    const double components = type == "SCALAR" ? 1
                              : type == "VEC2" ? 2
                              : type == "VEC3" ? 3
                              : type == "VEC4" ? 4
                              : type == "MAT2" ? 4
                              : type == "MAT3" ? 9
                                               : 16;
    const double element = components * (component == kByte || component == kUByte     ? 1
                                         : component == kShort || component == kUShort ? 2
                                                                                       : 4);
    const double stride = std::max(number(view->get("byteStride"), 0.0), element);
    const double end = number(a.get("byteOffset"), 0.0) + (count - 1.0) * stride + element;
    if (end > number(view->get("byteLength"), 0.0))
      fail(what + " reads " + std::to_string(uint64_t(end)) + " bytes of a bufferView of " +
           std::to_string(uint64_t(number(view->get("byteLength"), 0.0))));
  }

  // A JSON number, or fallback when absent or not a number.
  static double number(const Json* v, double fallback) { return v && v->kind == Json::kNumber ? v->number : fallback; }

  const std::string& path_;
  const Json& doc_;
};

uint32_t readU32(const std::string& bytes, size_t at)
{
  uint32_t v = 0;
  for (int k = 3; k >= 0; --k) v = (v << 8) | static_cast<unsigned char>(bytes[at + size_t(k)]);
  return v;
}

// A .gltf (JSON) or .glb (binary container, versions 1 and 2) file; with
// `full` false, only its container and JSON syntax (depth included).
void checkGltf(const std::string& path, const std::string& bytes, bool full = true)
{
  const size_t bom = bytes.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  const char* json = bytes.data() + bom;
  size_t jsonSize = bytes.size() - bom;
  if (bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0) {
    if (bytes.size() < 20) throw Error(userText(path) + ": GLB header truncated");
    const uint32_t version = readU32(bytes, 4);
    const uint32_t chunkLength = readU32(bytes, 12);
    if (version != 1 && version != 2)
      throw Error(userText(path) + ": GLB version " + std::to_string(version) + " unknown");
    if (version == 2 && readU32(bytes, 16) != 0x4E4F534Au)
      throw Error(userText(path) + ": GLB first chunk is not JSON");
    if (version == 2 && readU32(bytes, 8) > bytes.size())  // a truncated file (glTF 1 exporters wrote loose lengths)
      throw Error(userText(path) + ": GLB header states " + std::to_string(readU32(bytes, 8)) +
                  " bytes, the file has " + std::to_string(bytes.size()));
    if (chunkLength > bytes.size() - 20) throw Error(userText(path) + ": GLB JSON chunk truncated");
    json = bytes.data() + 20;
    jsonSize = chunkLength;
  }
  const Json doc = JsonParser(userText(path) + ": ", json, json + jsonSize).document();
  if (full) GltfCheck(path, doc).run();
}

// Whether assimp's signature checks may parse the bytes as glTF JSON or GLB.
bool looksLikeGltf(const std::string& bytes)
{
  size_t at = bytes.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  if (bytes.compare(0, 4, "glTF") == 0) return true;
  while (at < bytes.size() && std::strchr(" \t\r\n", bytes[at]) && bytes[at] != '\0') ++at;
  return at < bytes.size() && (bytes[at] == '{' || bytes[at] == '[');
}

// Whether importer `index` lists extension `ext`.
bool lists(const Assimp::Importer& importer, size_t index, const char* ext)
{
  std::set<std::string> extensions;
  importer.GetImporter(index)->GetExtensionList(extensions);
  return extensions.count(ext) != 0;
}

}  // namespace

ModelReader checkModelFile(const std::string& path, const std::string& bytes, const Assimp::Importer& importer,
                           Assimp::IOSystem& io)
{
  checkPlyHeader(path, bytes);  // by content: a first line "ply"
  // Step 1: assimp's choice, as Importer::ReadFile makes it: the one
  // importer that lists the file's extension; else, among those that list
  // it (or all), the first whose signature check accepts the file.
  std::vector<size_t> candidates;
  for (size_t i = 0; i < importer.GetImporterCount(); ++i) {
    std::set<std::string> extensions;
    importer.GetImporter(i)->GetExtensionList(extensions);
    for (const std::string& ext : extensions)
      if (ext.size() < path.size() && strcasecmp(path.c_str() + path.size() - ext.size(), ext.c_str()) == 0 &&
          path[path.size() - ext.size() - 1] == '.') {
        candidates.push_back(i);
        break;
      }
  }
  ModelReader reader;
  reader.byExtension = candidates.size() == 1;
  if (reader.byExtension) {
    reader.importer = int(candidates.front());
  } else {
    // The glTF readers' signature checks parse the JSON recursively.
    if (looksLikeGltf(bytes)) checkGltf(path, bytes, false);
    for (size_t pass = 0; pass < 2 && reader.importer < 0; ++pass) {
      const size_t count = pass == 0 ? candidates.size() : importer.GetImporterCount();
      for (size_t k = 0; k < count && reader.importer < 0; ++k) {
        const size_t i = pass == 0 ? candidates[k] : k;
        if (importer.GetImporter(i)->CanRead(path, &io, true)) reader.importer = int(i);
      }
    }
  }
  if (reader.importer < 0) return reader;  // assimp reports no suitable reader
  // Step 2: the checks of that reader.
  const size_t chosen = size_t(reader.importer);
  for (const char* ext : {"ply", "off", "obj", "stl", "gltf"})
    if (lists(importer, chosen, ext)) reader.format = ext;
  if (reader.format == "off") checkOffHeader(path, bytes);
  if (reader.format == "gltf") checkGltf(path, bytes);
  return reader;
}

}  // namespace clr