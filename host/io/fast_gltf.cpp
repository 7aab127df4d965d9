// fast_gltf.cpp — the plain GLB and glTF reader (see fast_gltf.h). The JSON is read
// with nlohmann::json, which rounds numbers correctly; assimp's rapidjson
// does too for the numbers plainNumbers() lets through (at most 15
// significant digits, a decimal exponent within ±22: its exact fast path).
#include "io/fast_gltf.h"

#include "io/import_budget.h"
#include "io/normals.h"

#include <assimp/scene.h>
#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <cstring>
#include <memory>
#include <set>
#include <vector>

namespace clr {

namespace {

using Json = nlohmann::json;

constexpr float kMaxCoordinate = 1e18f;  // as scene.cpp
constexpr int kMaxDepth = 64;

// `array` (of `n` pointers) one longer.
template <typename T>
T** grow(T** array, unsigned n)
{
  T** out = new T*[n + 1];
  std::copy(array, array + n, out);
  delete[] array;
  return out;
}

uint32_t u32(const std::string& b, size_t at)
{
  uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

// The numbers of the JSON text [p, e) that reach the mesh (the arrays
// matrix, translation, rotation, scale and baseColorFactor) are ones that
// rapidjson's default parse rounds correctly, and no negative zero (which
// the two parsers type differently); no string has an escape, so each key
// is what it reads.
bool plainNumbers(const char* p, const char* e)
{
  static const std::set<std::string> kRead = {"matrix", "translation", "rotation", "scale", "baseColorFactor"};
  std::string last, key;
  int arrays = 0, checkedArray = -1;
  for (; p < e; ++p) {
    if (*p == '"') {
      const char* q = p + 1;
      while (q < e && *q != '"' && *q != '\\') ++q;
      if (q == e || *q == '\\') return false;
      last.assign(p + 1, q);
      p = q;
      continue;
    }
    if (*p == ':') key = last;
    if (*p == ',' || *p == '{') key.clear();
    if (*p == '[' && checkedArray < 0 && kRead.count(key)) checkedArray = arrays;
    arrays += (*p == '[') - (*p == ']');
    if (*p == ']' && arrays == checkedArray) checkedArray = -1;
    if (*p != '-' && (*p < '0' || *p > '9')) continue;
    const bool negative = *p == '-';
    const char* q = p + negative;
    int significant = 0, fraction = 0, exponent = 0;
    bool point = false, nonzero = false;
    for (; q < e && ((*q >= '0' && *q <= '9') || *q == '.'); ++q) {
      if (*q == '.') {
        point = true;
        continue;
      }
      nonzero = nonzero || *q != '0';
      significant += nonzero;
      fraction += point;
    }
    if (q < e && (*q == 'e' || *q == 'E')) {
      ++q;
      const bool minus = q < e && *q == '-';
      if (q < e && (*q == '-' || *q == '+')) ++q;
      int digits = 0;
      for (; q < e && *q >= '0' && *q <= '9' && digits < 4; ++q, ++digits) exponent = exponent * 10 + (*q - '0');
      if (checkedArray >= 0 && (digits == 0 || digits == 4)) return false;
      exponent = minus ? -exponent : exponent;
    }
    if (checkedArray >= 0 &&
        (significant > 15 || exponent - fraction < -22 || exponent - fraction > 22 || (negative && !nonzero)))
      return false;
    p = q - 1;
  }
  return true;
}

// `object` is an object whose keys are all in `allowed`, its name a string.
bool only(const Json& object, std::initializer_list<const char*> allowed)
{
  if (!object.is_object()) return false;
  for (const auto& item : object.items()) {
    if (item.key() == "name" && !item.value().is_string()) return false;  // assimp refuses it
    bool found = false;
    for (const char* key : allowed) found = found || item.key() == key;
    if (!found) return false;
  }
  return true;
}

bool index(const Json& object, const char* key, size_t bound, size_t& out)
{
  const auto found = object.find(key);
  if (found == object.end() || !found->is_number_unsigned() || found->get<uint64_t>() >= bound) return false;
  out = found->get<size_t>();
  return true;
}

bool floats(const Json& object, const char* key, size_t n, float* out)
{
  const auto found = object.find(key);
  if (found == object.end()) return true;
  if (!found->is_array() || found->size() != n) return false;
  for (size_t i = 0; i < n; ++i) {
    if (!(*found)[i].is_number()) return false;
    out[i] = float((*found)[i].get<double>());
  }
  return true;
}

// GetNodeTransform of assimp's glTF2 importer.
bool nodeTransform(const Json& node, aiMatrix4x4& matrix)
{
  matrix = aiMatrix4x4();
  if (node.contains("matrix")) {
    float v[16];
    if (!floats(node, "matrix", 16, v)) return false;
    matrix = aiMatrix4x4(v[0], v[4], v[8], v[12], v[1], v[5], v[9], v[13], v[2], v[6], v[10], v[14], v[3], v[7], v[11],
                         v[15]);
    return true;
  }
  if (node.contains("translation")) {
    float t[3];
    if (!floats(node, "translation", 3, t)) return false;
    aiMatrix4x4 m;
    aiMatrix4x4::Translation(aiVector3D(t[0], t[1], t[2]), m);
    matrix = matrix * m;
  }
  if (node.contains("rotation")) {
    float r[4];
    if (!floats(node, "rotation", 4, r)) return false;
    const aiQuaternion q(r[3], r[0], r[1], r[2]);
    matrix = matrix * aiMatrix4x4(q.GetMatrix());
  }
  if (node.contains("scale")) {
    float s[3];
    if (!floats(node, "scale", 3, s)) return false;
    aiMatrix4x4 m;
    aiMatrix4x4::Scaling(aiVector3D(s[0], s[1], s[2]), m);
    matrix = matrix * m;
  }
  return true;
}

size_t count(const Json& doc, const char* key)
{
  const auto found = doc.find(key);
  return found != doc.end() && found->is_array() ? found->size() : 0;
}

// A float or index accessor: its elements, `size` bytes each, `stride`
// bytes apart (interleaved only where `strided`: attributes).
const char* accessor(const Json& doc, const char* bin, uint64_t bufferLength, size_t a, int componentType,
                     const char* type, size_t size, size_t& n, size_t& stride, bool strided = false)
{
  const Json& acc = doc["accessors"][a];
  size_t view = 0;
  if (!only(acc, {"bufferView", "byteOffset", "componentType", "count", "type", "min", "max", "name", "normalized"}) ||
      !index(acc, "bufferView", count(doc, "bufferViews"), view) || acc.value("normalized", false) ||
      acc.value("componentType", 0) != componentType || acc.value("type", "") != std::string(type) ||
      !acc.contains("count") || !acc["count"].is_number_unsigned())
    return nullptr;
  const uint64_t offset = acc.contains("byteOffset") && acc["byteOffset"].is_number_unsigned()
                              ? acc["byteOffset"].get<uint64_t>()
                              : (acc.contains("byteOffset") ? UINT64_MAX : 0);
  n = acc["count"].get<size_t>();
  const Json& bv = doc["bufferViews"][view];
  if (!only(bv, {"buffer", "byteOffset", "byteLength", "byteStride", "target", "name"}) || bv.value("buffer", 1) != 0 ||
      !bv.contains("byteLength") || !bv["byteLength"].is_number_unsigned())
    return nullptr;
  stride = size;
  if (bv.contains("byteStride")) {
    if (!bv["byteStride"].is_number_unsigned()) return nullptr;
    stride = bv["byteStride"].get<size_t>();
    if ((!strided && stride != size) || stride < size || stride % 4 || stride > 252) return nullptr;
  }
  const uint64_t viewOffset = bv.value("byteOffset", uint64_t(0)), viewLength = bv["byteLength"].get<uint64_t>();
  // The last element within the view, and assimp's count * stride within it too.
  if (n == 0 || n > UINT32_MAX || offset > viewLength || viewLength - offset < size ||
      (viewLength - offset - size) / stride < n - 1 || viewLength / stride < n || viewOffset > bufferLength ||
      bufferLength - viewOffset < viewLength)
    return nullptr;
  return bin + viewOffset + offset;
}

// A uri naming a file beside the model as both readers resolve it: letters,
// digits, '.', '_', '-' and '/', relative, no ".." part (no escape to decode).
bool plainUri(const Json& uri)
{
  if (!uri.is_string()) return false;
  const std::string& s = uri.get_ref<const std::string&>();
  if (s.empty() || s[0] == '/' || s.find("..") != std::string::npos) return false;
  for (const char c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && !std::strchr("._-/", c)) return false;
  return true;
}

class Glb {
 public:
  Glb(const Json& doc, const char* bin, uint64_t bufferLength) : doc_(doc), bin_(bin), bufferLength_(bufferLength) {}

  bool read(Mesh& out)
  {
    // Step 1: what assimp retrieves, in its order: the scene's nodes, children first.
    size_t scene = 0;
    if (doc_.contains("scene") && !index(doc_, "scene", count("scenes"), scene)) return false;
    if (!doc_.contains("scenes") || !doc_["scenes"].is_array() || scene >= doc_["scenes"].size()) return false;
    const Json& s = doc_["scenes"][scene];
    if (!only(s, {"nodes", "name"}) || !s.contains("nodes") || !s["nodes"].is_array()) return false;
    std::vector<size_t> roots;
    for (const Json& r : s["nodes"]) {
      if (!r.is_number_unsigned() || r.get<uint64_t>() >= count("nodes")) return false;
      roots.push_back(r.get<size_t>());
    }
    nodeState_.assign(count("nodes"), 0);
    meshRead_.assign(count("meshes"), false);
    materialIndex_.assign(count("materials"), -1);
    for (size_t r : roots)
      if (!retrieve(r, 0)) return false;
    // Step 2: the node walk of scene.cpp, over the tree assimp builds.
    if (roots.empty()) return false;
    if (roots.size() == 1) {
      if (!visit(roots[0], aiMatrix4x4(), out)) return false;
    } else {
      const aiMatrix4x4 root = aiMatrix4x4() * aiMatrix4x4();  // assimp's "ROOT" node
      for (size_t r : roots)
        if (!visit(r, root, out)) return false;
    }
    if (out.indices.empty()) return false;
    // Step 3: the retrieved materials, then assimp's default one, as assimp's properties.
    for (const auto& [data, length] : images_) {
      auto* texture = new aiTexture;
      texture->mWidth = unsigned(length);
      texture->mHeight = 0;
      texture->pcData = new aiTexel[(length + 3) / 4];
      std::memcpy(texture->pcData, data, length);
      scene_.mTextures = grow(scene_.mTextures, scene_.mNumTextures);
      scene_.mTextures[scene_.mNumTextures++] = texture;
    }
    scene_.mMaterials = new aiMaterial*[materials_.size() + 1];
    for (size_t m = 0; m <= materials_.size(); ++m) {
      auto* mat = new aiMaterial;
      scene_.mMaterials[scene_.mNumMaterials++] = mat;
      float factor[4] = {1, 1, 1, 1};
      const Json* pbr = nullptr;
      if (m < materials_.size()) {
        const Json& material = doc_["materials"][materials_[m]];
        if (material.contains("name") && material["name"].is_string()) {
          const aiString name(material["name"].get<std::string>());
          mat->AddProperty(&name, AI_MATKEY_NAME);
        }
        if (material.contains("pbrMetallicRoughness")) pbr = &material["pbrMetallicRoughness"];
        if (pbr && !floats(*pbr, "baseColorFactor", 4, factor)) return false;
      }
      const aiColor4D colour(factor[0], factor[1], factor[2], factor[3]);
      mat->AddProperty(&colour, 1, AI_MATKEY_COLOR_DIFFUSE);
      mat->AddProperty(&colour, 1, AI_MATKEY_BASE_COLOR);
      if (pbr && pbr->contains("baseColorTexture")) {
        const Json& texture = doc_["textures"][(*pbr)["baseColorTexture"]["index"].get<size_t>()];
        // An embedded image by its index ("*N"), a file by its uri, as assimp names them.
        const size_t source = texture["source"].get<size_t>();
        aiString uri(imageIndex_[source] >= 0 ? "*" + std::to_string(imageIndex_[source])
                                              : doc_["images"][source]["uri"].get<std::string>());
        int wrap[2] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
        if (texture.contains("sampler")) {
          const Json& sampler = doc_["samplers"][texture["sampler"].get<size_t>()];
          for (int k = 0; k < 2; ++k) {
            const int mode = sampler.value(k ? "wrapT" : "wrapS", 10497);
            wrap[k] = mode == 33648   ? aiTextureMapMode_Mirror
                      : mode == 33071 ? aiTextureMapMode_Clamp
                                      : aiTextureMapMode_Wrap;
          }
        }
        for (const aiTextureType type : {aiTextureType_DIFFUSE, aiTextureType_BASE_COLOR}) {
          mat->AddProperty(&uri, AI_MATKEY_TEXTURE(type, 0));
          mat->AddProperty(&wrap[0], 1, AI_MATKEY_MAPPINGMODE_U(type, 0));
          mat->AddProperty(&wrap[1], 1, AI_MATKEY_MAPPINGMODE_V(type, 0));
        }
      }
    }
    out.colors.clear();
    return true;
  }

  const aiScene& scene() const { return scene_; }

  bool anyNormals() const { return anyNormals_; }

 private:
  size_t count(const char* key) const
  {
    const auto found = doc_.find(key);
    return found != doc_.end() && found->is_array() ? found->size() : 0;
  }

  bool retrieve(size_t n, int depth)
  {
    if (nodeState_[n] == 2) return true;
    if (nodeState_[n] == 1 || depth > kMaxDepth) return false;  // a cycle: assimp recurses without end
    nodeState_[n] = 1;
    const Json& node = doc_["nodes"][n];
    if (!only(node, {"name", "mesh", "children", "matrix", "translation", "rotation", "scale"})) return false;
    if (node.contains("matrix") &&
        (node.contains("translation") || node.contains("rotation") || node.contains("scale")))
      return false;
    if (node.contains("children")) {
      if (!node["children"].is_array()) return false;
      for (const Json& c : node["children"]) {
        if (!c.is_number_unsigned() || c.get<uint64_t>() >= count("nodes")) return false;
        if (!retrieve(c.get<size_t>(), depth + 1)) return false;
      }
    }
    size_t m = 0;
    if (node.contains("mesh")) {
      if (!index(node, "mesh", count("meshes"), m)) return false;
      if (!meshRead_[m]) {
        meshRead_[m] = true;
        const Json& mesh = doc_["meshes"][m];
        if (!only(mesh, {"name", "primitives"}) || !mesh.contains("primitives") || !mesh["primitives"].is_array() ||
            mesh["primitives"].empty())
          return false;
        for (const Json& p : mesh["primitives"]) {
          if (!only(p, {"attributes", "indices", "material", "mode"})) return false;
          if (p.contains("mode") && !(p["mode"].is_number_unsigned() && p["mode"].get<uint64_t>() == 4)) return false;
          size_t mat = 0;
          if (!p.contains("material")) continue;
          if (!index(p, "material", count("materials"), mat)) return false;
          if (materialIndex_[mat] < 0) {
            if (!only(doc_["materials"][mat],
                      {"name", "pbrMetallicRoughness", "doubleSided", "alphaMode", "alphaCutoff", "emissiveFactor"}))
              return false;
            const auto pbr = doc_["materials"][mat].find("pbrMetallicRoughness");
            if (pbr != doc_["materials"][mat].end() &&
                (!only(*pbr, {"baseColorFactor", "metallicFactor", "roughnessFactor", "baseColorTexture"}) ||
                 (pbr->contains("baseColorTexture") && !retrieveTexture((*pbr)["baseColorTexture"]))))
              return false;
            materialIndex_[mat] = long(materials_.size());
            materials_.push_back(mat);
          }
        }
      }
    }
    nodeState_[n] = 2;
    return true;
  }

  // A baseColorTexture: its image, embedded in the buffer, in assimp's order.
  bool retrieveTexture(const Json& info)
  {
    size_t t = 0, image = 0, sampler = 0;
    if (!only(info, {"index", "texCoord"}) || !index(info, "index", count("textures"), t)) return false;
    const Json& texture = doc_["textures"][t];
    if (!only(texture, {"source", "sampler", "name"}) || !index(texture, "source", count("images"), image) ||
        (texture.contains("sampler") && !index(texture, "sampler", count("samplers"), sampler)))
      return false;
    if (texture.contains("sampler") &&
        !only(doc_["samplers"][sampler], {"wrapS", "wrapT", "magFilter", "minFilter", "name"}))
      return false;
    if (imageIndex_.size() < count("images")) imageIndex_.assign(count("images"), -1);
    if (imageIndex_[image] != -1) return true;
    const Json& img = doc_["images"][image];
    if (img.contains("uri")) {
      // A file: scene.cpp opens it under the model-folder rule, as for assimp's import.
      if (!only(img, {"uri", "mimeType", "name"}) || !plainUri(img["uri"]) ||
          (img.contains("mimeType") && !img["mimeType"].is_string()))
        return false;
      imageIndex_[image] = -2;
      return true;
    }
    size_t view = 0;
    if (!only(img, {"bufferView", "mimeType", "name"}) || !index(img, "bufferView", count("bufferViews"), view) ||
        !img.contains("mimeType") || !img["mimeType"].is_string())
      return false;
    const Json& bv = doc_["bufferViews"][view];
    if (!only(bv, {"buffer", "byteOffset", "byteLength", "name"}) || bv.value("buffer", 1) != 0 ||
        !bv.contains("byteLength") || !bv["byteLength"].is_number_unsigned())
      return false;
    const uint64_t offset = bv.value("byteOffset", uint64_t(0)), length = bv["byteLength"].get<uint64_t>();
    if (length == 0 || offset > bufferLength_ || bufferLength_ - offset < length) return false;
    imageIndex_[image] = long(images_.size());
    images_.emplace_back(bin_ + offset, size_t(length));
    return true;
  }

  bool visit(size_t n, const aiMatrix4x4& parent, Mesh& out)
  {
    const Json& node = doc_["nodes"][n];
    aiMatrix4x4 own;
    if (!nodeTransform(node, own)) return false;
    const aiMatrix4x4 matrix = parent * own;
    if (node.contains("mesh"))
      for (const Json& p : doc_["meshes"][node["mesh"].get<size_t>()]["primitives"])
        if (!append(p, matrix, out)) return false;
    if (node.contains("children"))
      for (const Json& c : node["children"])
        if (!visit(c.get<size_t>(), matrix, out)) return false;
    return true;
  }

  // appendMesh of scene.cpp, for one primitive as assimp imports it.
  bool append(const Json& p, const aiMatrix4x4& transform, Mesh& out)
  {
    const auto found = p.find("attributes");
    if (found == p.end() || !only(*found, {"POSITION", "NORMAL", "TEXCOORD_0"})) return false;
    const Json& attributes = *found;
    size_t a = 0, nv = 0, nn = 0, nt = 0, sv = 0, sn = 0, st = 0, si = 0;
    if (!index(attributes, "POSITION", count("accessors"), a)) return false;
    const char* positions = accessor(doc_, bin_, bufferLength_, a, 5126, "VEC3", 12, nv, sv, true);
    const char* normals = nullptr;
    const char* uvs = nullptr;
    if (!positions) return false;
    if (attributes.contains("NORMAL")) {
      if (!index(attributes, "NORMAL", count("accessors"), a) ||
          !(normals = accessor(doc_, bin_, bufferLength_, a, 5126, "VEC3", 12, nn, sn, true)) || nn != nv)
        return false;
    }
    if (attributes.contains("TEXCOORD_0")) {
      if (!index(attributes, "TEXCOORD_0", count("accessors"), a) ||
          !(uvs = accessor(doc_, bin_, bufferLength_, a, 5126, "VEC2", 8, nt, st, true)) || nt != nv)
        return false;
    }
    const uint64_t base = out.numVerts();
    if (base + nv > UINT32_MAX) return false;
    aiMatrix3x3 normalMatrix(transform);
    normalMatrix.Inverse().Transpose();
    anyNormals_ = anyNormals_ || normals;
    out.facts.uvsInFile = out.facts.uvsInFile || uvs;
    out.positions.reserve(out.positions.size() + 3 * nv);
    out.normals.reserve(out.normals.size() + 3 * nv);
    out.uvs.reserve(out.uvs.size() + 2 * nv);
    for (size_t v = 0; v < nv; ++v) {
      aiVector3D q;
      std::memcpy(&q, positions + sv * v, 12);
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return false;
      const aiVector3D pt = transform * q;
      if (!(std::fabs(pt.x) <= kMaxCoordinate && std::fabs(pt.y) <= kMaxCoordinate &&
            std::fabs(pt.z) <= kMaxCoordinate))
        return false;
      out.positions.insert(out.positions.end(), {pt.x, pt.y, pt.z});
      aiVector3D nm(0, 0, 0);
      if (normals) {
        std::memcpy(&nm, normals + sn * v, 12);
        nm = normalMatrix * nm;
      }
      if (!std::isfinite(nm.x) || !std::isfinite(nm.y) || !std::isfinite(nm.z)) nm = aiVector3D(0, 0, 0);
      out.normals.insert(out.normals.end(), {nm.x, nm.y, nm.z});
      float uv[2] = {0, 0};
      if (uvs) {
        std::memcpy(uv, uvs + st * v, 8);
        uv[1] = 1 - uv[1];  // assimp flips v
      }
      out.uvs.insert(out.uvs.end(), uv, uv + 2);
    }
    // Faces: the indices, or the vertices in order; a partial triangle or an index out of range is assimp's to report.
    const uint32_t material =
        p.contains("material") ? uint32_t(materialIndex_[p["material"].get<size_t>()]) : uint32_t(materials_.size());
    size_t ni = nv;
    const char* indices = nullptr;
    int width = 0;
    if (p.contains("indices")) {
      if (!index(p, "indices", count("accessors"), a)) return false;
      for (const auto& [type, w] : {std::pair<int, int>{5121, 1}, {5123, 2}, {5125, 4}})
        if (!indices && doc_["accessors"][a].value("componentType", 0) == type)
          indices = accessor(doc_, bin_, bufferLength_, a, type, "SCALAR", size_t(w), ni, si), width = w;
      if (!indices) return false;
    }
    if (ni % 3 != 0) return false;
    out.indices.reserve(out.indices.size() + ni);
    for (size_t i = 0; i < ni; ++i) {
      uint32_t k = uint32_t(i);
      if (width == 1) k = static_cast<unsigned char>(indices[i]);
      if (width == 2)
        k = uint32_t(static_cast<unsigned char>(indices[2 * i])) |
            uint32_t(static_cast<unsigned char>(indices[2 * i + 1])) << 8;
      if (width == 4) std::memcpy(&k, indices + 4 * i, 4);
      if (k >= nv) return false;
      out.indices.push_back(uint32_t(base + k));
    }
    out.triMaterial.insert(out.triMaterial.end(), ni / 3, material);
    return true;
  }

  const Json& doc_;
  const char* bin_;
  uint64_t bufferLength_;       // buffer 0, within the BIN chunk
  std::vector<int> nodeState_;  // 0 unread, 1 being read, 2 read
  std::vector<bool> meshRead_;
  std::vector<long> materialIndex_;  // file index: assimp's index, -1 unused
  std::vector<size_t> materials_;    // assimp's order: file indices
  std::vector<long> imageIndex_;     // file index: assimp's embedded texture index, -1 unused, -2 a file
  std::vector<std::pair<const char*, size_t>> images_;
  aiScene scene_;  // the materials and textures as assimp's importer makes them
  bool anyNormals_ = false;
};

}  // namespace

namespace {

// Buffer 0 of `doc` from a text glTF: its file, named by a plain relative
// uri and opened as assimp's reader opens it (folder + uri, under `root`),
// or a base64 data uri. false: not read here (assimp reads or refuses it).
bool readBuffer(const std::string& path, const Json& buffer, const AssetRoot& root, std::string& out)
{
  if (!only(buffer, {"uri", "byteLength", "name"}) || !buffer.contains("uri") || !buffer["uri"].is_string() ||
      !buffer.contains("byteLength") || !buffer["byteLength"].is_number_unsigned())
    return false;
  const std::string uri = buffer["uri"].get<std::string>();
  const uint64_t length = buffer["byteLength"].get<uint64_t>();
  if (length == 0 || length > kReferencedBytes) return false;
  const std::string kData = "data:application/octet-stream;base64,";
  if (uri.compare(0, kData.size(), kData) == 0) {
    // Strict base64 only, decoding to exactly byteLength bytes, as assimp requires.
    const size_t at = kData.size(), n = uri.size() - at;
    if (n % 4 || n / 4 * 3 < length || n / 4 * 3 - length > 2) return false;
    out.clear();
    out.reserve(size_t(length) + 2);
    static const std::string kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const size_t pad = size_t(n / 4 * 3 - length);
    for (size_t i = 0; i < n; i += 4) {
      uint32_t v = 0;
      for (size_t k = 0; k < 4; ++k) {
        const bool padding = i + 4 == n && k >= 4 - pad;
        const size_t d = padding ? 0 : kAlphabet.find(uri[at + i + k]);
        if ((padding && uri[at + i + k] != '=') || d == std::string::npos) return false;
        v = v << 6 | uint32_t(d);
      }
      for (int k = 2; k >= 0; --k) out += char(v >> (8 * k));
    }
    out.resize(size_t(length));
    return true;
  }
  // A plain relative name, beside the model (a path with '\\' could resolve otherwise).
  if (!plainUri(buffer["uri"]) || path.find('\\') != std::string::npos) return false;
  const size_t slash = path.rfind('/');
  const std::string file = (slash == std::string::npos ? "" : path.substr(0, slash + 1)) + uri;
  try {
    const std::unique_ptr<InputFile> input =
        root.confined() ? root.open(file, uri, kModelInput) : std::make_unique<InputFile>(file, kModelInput);
    if (input->size() < length || input->size() > kReferencedBytes) return false;
    out = input->read(size_t(length));
  } catch (const Error&) {
    return false;  // assimp refuses it, in its words
  }
  return out.size() == length;
}

// The glTF JSON [json, json + length), its one buffer `bin` (at least the
// buffer's byteLength, checked by the caller), into `mesh`.
bool readDocument(const std::string& path, const Json& doc, const char* bin, const AssetRoot& root, Mesh& mesh)
{
  Glb glb(doc, bin, doc["buffers"][0]["byteLength"].get<uint64_t>());
  Mesh out;
  try {
    if (!glb.read(out)) return false;
  } catch (const Json::exception&) {
    return false;
  }
  convertMaterials(path, root, glb.scene(), false, out);
  repairNormals(out, path, glb.anyNormals());
  mesh = std::move(out);
  return true;
}

// The JSON text [json, json + length): its numbers within what both parsers
// read alike, no key twice, only what the reader knows at the top. false:
// not read here.
bool parseDocument(const char* json, size_t length, Json& doc)
{
  if (!plainNumbers(json, json + length)) return false;
  bool repeated = false;
  std::vector<std::set<std::string>> keys;
  try {
    doc = Json::parse(json, json + length, [&](int, Json::parse_event_t event, Json& parsed) {
      if (event == Json::parse_event_t::object_start) keys.emplace_back();
      if (event == Json::parse_event_t::object_end) keys.pop_back();
      if (event == Json::parse_event_t::key && !keys.back().insert(parsed.get<std::string>()).second) repeated = true;
      return true;
    });
  } catch (const Json::exception&) {
    return false;
  }
  if (repeated || !only(doc, {"asset", "scene", "scenes", "nodes", "meshes", "accessors", "bufferViews", "buffers",
                              "materials", "textures", "images", "samplers"}))
    return false;
  if (!doc.contains("asset") || !only(doc["asset"], {"version", "generator", "copyright"}) ||
      doc["asset"].value("version", "") != "2.0")
    return false;
  return doc.contains("buffers") && doc["buffers"].is_array() && doc["buffers"].size() == 1;
}

}  // namespace

bool readPlainGlb(const std::string& path, const std::string& bytes, const AssetRoot& root, Mesh& mesh)
{
  // Step 1: the container: header, JSON chunk, BIN chunk, nothing else.
  if (bytes.size() < 28 || bytes.compare(0, 4, "glTF") != 0 || u32(bytes, 4) != 2 || u32(bytes, 8) != bytes.size())
    return false;
  const uint64_t jsonLength = u32(bytes, 12);
  if (u32(bytes, 16) != 0x4E4F534Au || jsonLength % 4 != 0 || 20 + jsonLength + 8 > bytes.size()) return false;
  const size_t binAt = size_t(20 + jsonLength);
  const uint64_t binLength = u32(bytes, binAt);
  if (u32(bytes, binAt + 4) != 0x004E4942u || binAt + 8 + binLength != bytes.size()) return false;
  // Step 2: the JSON; its one buffer is the BIN chunk.
  Json doc;
  if (!parseDocument(bytes.data() + 20, size_t(jsonLength), doc)) return false;
  const Json& buffer = doc["buffers"][0];
  if (!only(buffer, {"byteLength", "name"}) || !buffer.contains("byteLength") ||
      !buffer["byteLength"].is_number_unsigned() || buffer["byteLength"].get<uint64_t>() > binLength)
    return false;
  // Step 3: the scene.
  return readDocument(path, doc, bytes.data() + binAt + 8, root, mesh);
}

bool readPlainGltf(const std::string& path, const std::string& bytes, const AssetRoot& root, Mesh& mesh)
{
  // Step 1: the JSON, opening with '{' (no byte order mark); its one buffer, read whole.
  const size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || bytes[first] != '{') return false;
  Json doc;
  std::string bin;
  if (!parseDocument(bytes.data(), bytes.size(), doc) || !readBuffer(path, doc["buffers"][0], root, bin)) return false;
  // Step 2: the scene.
  return readDocument(path, doc, bin.data(), root, mesh);
}

}  // namespace clr
