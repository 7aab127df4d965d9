// fast_obj.cpp — the plain OBJ reader (see fast_obj.h). Three steps: the
// text is parsed in line-aligned chunks in parallel (numbers, face corners
// with indices as written, and the statements that split meshes); the
// statements are replayed in file order as ObjFileParser keeps its state
// (objects, meshes, current material), which gives each face its mesh's
// material; the un-shared vertices are written in parallel, each chunk at
// offsets from prefix sums of the counts.
#include "io/fast_obj.h"

#include "base/error.h"
#include "io/file_rule.h"
#include "io/import_budget.h"
#include "io/mtl.h"
#include "io/normals.h"
#include "io/text_scan.h"

#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <set>
#include <unordered_map>

#include <sys/stat.h>

namespace clr {

namespace {

constexpr float kMaxCoordinate = 1e18f;             // as scene.cpp
constexpr uint32_t kNoMaterial = ~0u;               // ObjFile::Mesh::NoMaterial
constexpr size_t kMaxStatements = size_t(1) << 20;  // o, g, usemtl, mtllib: more is left to assimp's path

// Face corner forms: v, v/vt, v//vn, v/vt/vn.
enum Form { kNoForm, kV, kVT, kVN, kVTN };
bool hasUv(int form)
{
  return form == kVT || form == kVTN;
}
bool hasNormal(int form)
{
  return form == kVN || form == kVTN;
}
size_t strideOf(int form)
{
  return 1 + size_t(hasUv(form)) + size_t(hasNormal(form));
}

struct Statement {
  enum Kind { kObject, kGroup, kUseMtl, kMtlLib } kind;
  uint64_t face;  // faces of its chunk before it
  std::string name;
};

struct Chunk {
  const char *begin = nullptr, *end = nullptr;
  std::vector<float> positions, colors, uvs, normals;  // 3, 3, 2, 3 per line
  uint64_t plainVertices = 0;                          // v lines without a colour
  std::vector<int32_t> corners;                        // strideOf(form) indices per corner, 0-based
  std::vector<uint32_t> faceSizes;
  std::vector<std::pair<size_t, int>> relative;  // negative indices: (corner slot, 0 v 1 vt 2 vn), chunk-relative
  std::vector<Statement> statements;
  int form = kNoForm;
  bool uvBeforeFirstVt = false;  // a face with vt indices before the chunk's first vt line
  uint64_t triangles = 0;
  bool ok = true;
};

const char* wordEnd(const char* p, const char* e)
{
  while (p < e && !isBlank(*p)) ++p;
  return p;
}

// No character on which assimp's line reader would cut or join lines.
bool plainLine(const char* b, const char* e)
{
  for (const char* p = b; p < e; ++p)
    if (*p == '\r' || *p == '\0' || *p == '\f' || *p == '\\') return false;
  return true;
}

// A position coordinate, correctly rounded as exact_positions.h reads it.
bool position(const char* b, const char* e, float& v)
{
  return plainDecimal(b, e) && scanFloat(b, e, v) == e && std::fabs(v) <= kMaxCoordinate;
}

// Up to `max` words of [p, e) as numbers, positions first; the count, or -1.
int numbers(const char* p, const char* e, int positions, float* out, int max)
{
  int n = 0;
  for (p = skipBlanks(p, e); p < e; p = skipBlanks(p, e)) {
    const char* w = wordEnd(p, e);
    if (n == max) return -1;
    if (!(n < positions ? position(p, w, out[n]) : assimpNumber(p, w, out[n]))) return -1;
    ++n;
    p = w;
  }
  return n;
}

// One index of a corner as atoi reads it: nonzero, no leading zero or '+'.
bool index(const char*& p, const char* e, int64_t& value)
{
  const bool negative = p < e && *p == '-';
  const char* d = p + negative;
  if (d == e || *d < '1' || *d > '9') return false;
  int64_t v = 0;
  const char* q = d;
  while (q < e && *q >= '0' && *q <= '9' && q - d < 10) v = v * 10 + (*q++ - '0');
  if ((q < e && *q >= '0' && *q <= '9') || v > INT32_MAX) return false;
  value = negative ? -v : v;
  p = q;
  return true;
}

// The rest of a statement's line after its first word and blanks, as
// written (`trim`: without trailing blanks); false where assimp's line
// reader would cut it or its name buffer end it.
bool rest(const char* b, const char* e, bool trim, std::string& out)
{
  b = skipBlanks(wordEnd(b, e), e);
  while (trim && e > b && isBlank(e[-1])) --e;
  if (e - b > 500 || !plainLine(b, e)) return false;
  out.assign(b, e);
  return true;
}

bool face(Chunk& c, const char* p, const char* e, const uint64_t counts[3])
{
  uint32_t k = 0;
  for (p = skipBlanks(p, e); p < e; p = skipBlanks(p, e)) {
    int64_t v[3];
    int parts = 1, form = kV;
    if (!index(p, e, v[0])) return false;
    if (p < e && *p == '/') {
      ++p;
      if (p < e && *p == '/') {
        ++p;
        if (!index(p, e, v[parts++])) return false;
        form = kVN;
      } else {
        if (!index(p, e, v[parts++])) return false;
        form = kVT;
        if (p < e && *p == '/') {
          ++p;
          if (!index(p, e, v[parts++])) return false;
          form = kVTN;
        }
      }
    }
    if (p < e && !isBlank(*p)) return false;
    if (c.form == kNoForm) c.form = form;
    if (c.form != form) return false;
    static const int kKinds[5][3] = {{}, {0}, {0, 1}, {0, 2}, {0, 1, 2}};
    for (int j = 0; j < parts; ++j) {
      const int kind = kKinds[form][j];
      if (v[j] < 0) c.relative.emplace_back(c.corners.size(), kind);
      c.corners.push_back(int32_t(v[j] > 0 ? v[j] - 1 : int64_t(counts[kind]) + v[j]));
    }
    ++k;
  }
  if (k < 3 || k > 0x7fff) return false;  // AI_MAX_FACE_INDICES: assimp refuses a larger face
  if (hasUv(c.form) && counts[1] == 0) c.uvBeforeFirstVt = true;
  c.faceSizes.push_back(k);
  c.triangles += k - 2;
  return true;
}

// One line [b, e) of a chunk, not empty, its line end removed.
bool line(Chunk& c, const char* b, const char* e, uint64_t counts[3])
{
  const char* first = wordEnd(b, e);
  const size_t word = size_t(first - b);
  float v[7];
  std::string text;
  // Statements cost far more than their bytes: the bound holds within each part already.
  if ((*b == 'o' || *b == 'g' || *b == 'u' || *b == 'm') && c.statements.size() >= kMaxStatements) return false;
  switch (*b) {
    case 'v': {
      if (word == 1) {
        const int n = numbers(first, e, 3, v, 6);
        if (n != 3 && n != 6) return false;
        c.positions.insert(c.positions.end(), v, v + 3);
        if (n == 6)
          c.colors.insert(c.colors.end(), v + 3, v + 6);
        else
          ++c.plainVertices;
        ++counts[0];
        return true;
      }
      if (word != 2 || (b[1] != 't' && b[1] != 'n')) return false;
      const int n = numbers(first, e, 0, v, 3);
      if (b[1] == 'n') {
        if (n != 3) return false;
        c.normals.insert(c.normals.end(), v, v + 3);
        ++counts[2];
      } else {
        if (n != 2 && n != 3) return false;
        for (int k = 0; k < 2; ++k) c.uvs.push_back(std::isfinite(v[k]) ? v[k] : 0.0f);  // as assimp coerces
        ++counts[1];
      }
      return true;
    }
    case 'f': return word == 1 && face(c, first, e, counts);
    case 'o': {
      // assimp takes the second word; more words, or none, are left to it.
      const char* n = skipBlanks(first, e);
      const char* ne = wordEnd(n, e);
      if (word != 1 || n == ne || skipBlanks(ne, e) != e || !plainLine(n, ne)) return false;
      c.statements.push_back({Statement::kObject, c.faceSizes.size(), std::string(n, ne)});
      return true;
    }
    case 'g':
      if (word != 1 || !rest(b, e, false, text)) return false;
      c.statements.push_back({Statement::kGroup, c.faceSizes.size(), text});
      return true;
    case 'u':
    case 'm': {
      const bool use = word == 6 && std::memcmp(b, "usemtl", 6) == 0;
      const bool lib = word == 6 && std::memcmp(b, "mtllib", 6) == 0;
      if (!use && !lib) return plainLine(b, e);  // assimp skips the line
      if (!rest(b, e, use, text)) return false;
      if (text.empty()) return use;  // assimp ignores an empty usemtl, warns of an empty mtllib
      c.statements.push_back({use ? Statement::kUseMtl : Statement::kMtlLib, c.faceSizes.size(), text});
      return true;
    }
    case 's':
    case '#':
    case ' ':
    case '\t': return plainLine(b, e);  // assimp skips the line, an indented one too
    default: return false;
  }
}

void parseChunk(Chunk& c)
{
  uint64_t counts[3] = {0, 0, 0};  // v, vt, vn lines so far
  for (const char* p = c.begin; p < c.end;) {
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', size_t(c.end - p)));
    const char* e = nl ? nl : c.end;
    const char* b = p;
    p = nl ? nl + 1 : c.end;
    if (e > b && e[-1] == '\r') --e;
    if (b != e && !line(c, b, e, counts)) {
      c.ok = false;
      return;
    }
  }
}

// Runs f(0) ... f(n - 1) on every core (text_scan.h); false when one
// failed (out of memory: assimp's path then reports it, or reads the file).
template <typename F>
bool parallelFor(size_t n, F&& f)
{
  std::atomic<bool> failed{false};
  runParts(n, [&](size_t i) {
    try {
      f(i);
    } catch (...) {
      failed = true;
    }
  });
  return !failed;
}

// ObjFileParser's state, replayed statement by statement in file order.
class Replay {
 public:
  Replay(const std::string& path, const AssetRoot& root) : path_(path), root_(root)
  {
    MtlMaterial fallback;
    fallback.name = AI_DEFAULT_MATERIAL_NAME;
    addMaterial(fallback);
  }

  // Faces up to `face` (global) go to the current mesh.
  void facesUpTo(uint64_t face)
  {
    if (face == faces_) return;
    if (!haveObject_) createObject("defaultobject");
    Mesh& m = meshes_[size_t(current_)];
    if (m.faces == 0) m.first = faces_;
    m.faces += face - faces_;
    faces_ = face;
  }

  bool apply(const Statement& s)
  {
    switch (s.kind) {
      case Statement::kObject:
        if (objects_.count(s.name)) return false;  // assimp re-selects it: not plain
        createObject(s.name);
        return true;
      case Statement::kGroup:
        if (activeGroup_ != s.name) createObject(s.name);
        activeGroup_ = s.name;
        return true;
      case Statement::kUseMtl:
        useMaterial(s.name);
        return materials_.size() <= kMaxMaterials;  // more: assimp's path applies its limit
      case Statement::kMtlLib: return readLibrary(s.name);
    }
    return false;
  }

  // Each mesh with faces, in order: (first face, material index).
  bool runs(std::vector<std::pair<uint64_t, uint32_t>>& out) const
  {
    uint64_t next = 0;
    for (const Mesh& m : meshes_) {
      if (m.faces == 0) continue;
      if (m.first != next) return false;
      out.emplace_back(m.first, m.material == kNoMaterial ? 0 : m.material);
      next += m.faces;
    }
    return next == faces_;
  }

  const std::vector<MtlMaterial>& materials() const { return materials_; }

 private:
  struct Mesh {
    uint32_t material = kNoMaterial;
    uint64_t first = 0, faces = 0;
  };

  uint32_t addMaterial(const MtlMaterial& m)
  {
    byName_.emplace(m.name, uint32_t(materials_.size()));
    materials_.push_back(m);
    return uint32_t(materials_.size() - 1);
  }
  void createMesh()
  {
    meshes_.emplace_back();
    current_ = long(meshes_.size()) - 1;
  }
  void createObject(const std::string& name)
  {
    objects_.insert(name);
    haveObject_ = true;
    createMesh();
    if (material_ >= 0) meshes_.back().material = uint32_t(material_);
  }
  void useMaterial(const std::string& name)
  {
    if (material_ >= 0 && materials_[size_t(material_)].name == name) return;
    const auto found = byName_.find(name);
    uint32_t m = 0;
    if (found != byName_.end()) {
      m = found->second;
    } else {
      MtlMaterial unknown;  // a name no library defines: assimp's default colour
      unknown.name = name;
      m = addMaterial(unknown);
    }
    material_ = long(m);
    const bool split = current_ < 0 || (meshes_[size_t(current_)].material != kNoMaterial &&
                                        meshes_[size_t(current_)].material != m && meshes_[size_t(current_)].faces);
    if (split) createMesh();
    meshes_[size_t(current_)].material = m;
  }
  bool readLibrary(const std::string& name)
  {
    // The name as ObjFileParser::getMaterialLib opens it, under the rule RuleIOSystem keeps.
    const size_t slash = path_.find_last_of("\\/");
    if (path_.find('\\') != std::string::npos || slash == 0) return false;
    const std::string file = slash == std::string::npos ? name : path_.substr(0, slash + 1) + name;
    const std::string reference = slash == std::string::npos ? name : file.substr(slash + 1);
    std::string text;
    try {
      if (root_.confined()) {
        text = root_.open(file, reference, kModelInput)->read();
      } else {
        struct stat st;
        if (stat(file.c_str(), &st) != 0) return false;
        text = InputFile(file, kModelInput).read();
      }
    } catch (const Error&) {
      return false;  // assimp warns of it, or refuses it
    }
    referencedBytes_ += text.size();
    libraryMaterials_ += countMaterials(text);
    if (referencedBytes_ > kReferencedBytes || libraryMaterials_ > kMaxMaterials) return false;
    std::vector<MtlMaterial> found;
    if (!readPlainMtl(text, found)) return false;
    for (const MtlMaterial& m : found) {
      if (byName_.count(m.name)) return false;  // assimp reuses the earlier one: not plain
      material_ = long(addMaterial(m));
      if (current_ >= 0) meshes_[size_t(current_)].material = uint32_t(material_);
    }
    return true;
  }

  const std::string& path_;
  const AssetRoot& root_;
  std::vector<MtlMaterial> materials_;
  std::unordered_map<std::string, uint32_t> byName_;
  std::set<std::string> objects_;
  std::vector<Mesh> meshes_;
  std::string activeGroup_;
  bool haveObject_ = false;
  long current_ = -1, material_ = -1;
  uint64_t faces_ = 0, referencedBytes_ = 0, libraryMaterials_ = 0;
};

// Line-aligned chunks, about one per core.
std::vector<Chunk> split(const std::string& bytes)
{
  const std::vector<TextPart> parts = splitLines(bytes.data(), bytes.data() + bytes.size(), textParts(bytes.size()));
  std::vector<Chunk> chunks(parts.size());
  for (size_t i = 0; i < parts.size(); ++i) chunks[i].begin = parts[i].begin, chunks[i].end = parts[i].end;
  return chunks;
}

}  // namespace

bool readPlainObj(const std::string& path, const std::string& bytes, const AssetRoot& root, Mesh& mesh)
{
  if (bytes.size() < 16) return false;  // assimp's "OBJ-file is too small"
  // Step 1: the chunks, parsed in parallel.
  std::vector<Chunk> chunks = split(bytes);
  if (!parallelFor(chunks.size(), [&](size_t i) { parseChunk(chunks[i]); })) return false;
  // Step 2: counts, their prefix sums, and what must agree across chunks.
  const size_t n = chunks.size();
  std::vector<uint64_t> vBase(n + 1), tBase(n + 1), nBase(n + 1), faceBase(n + 1), cornerBase(n + 1), triBase(n + 1);
  int form = kNoForm;
  uint64_t colored = 0, plain = 0, statements = 0;
  for (size_t i = 0; i < n; ++i) {
    const Chunk& c = chunks[i];
    if (!c.ok) return false;
    if (c.form != kNoForm && form != kNoForm && c.form != form) return false;
    if (c.form != kNoForm) form = c.form;
    vBase[i + 1] = vBase[i] + c.positions.size() / 3;
    tBase[i + 1] = tBase[i] + c.uvs.size() / 2;
    nBase[i + 1] = nBase[i] + c.normals.size() / 3;
    faceBase[i + 1] = faceBase[i] + c.faceSizes.size();
    cornerBase[i + 1] = cornerBase[i] + (c.form == kNoForm ? 0 : c.corners.size() / strideOf(c.form));
    triBase[i + 1] = triBase[i] + c.triangles;
    colored += c.colors.size() / 3;
    plain += c.plainVertices;
    statements += c.statements.size();
    // A vt index before any vt line: assimp may read it as a normal's.
    if (c.uvBeforeFirstVt && tBase[i] == 0) return false;
  }
  // Colours on some v lines only shift assimp's colour indices; faces: assimp makes a point cloud.
  if ((colored && plain) || form == kNoForm || statements > kMaxStatements) return false;
  const uint64_t corners = cornerBase[n], triangles = triBase[n];
  // The mesh's own arrays (AI_MAX_VERTICES for assimp), and their memory within the import budget.
  const uint64_t cornerBytes = 12 + 12 + 8 + (colored ? 16 : 0) + 16, triangleBytes = 16;
  if (corners > INT32_MAX || corners * cornerBytes + triangles * triangleBytes > kImportBudgetBytes) return false;
  // Step 3: the statements, in file order.
  Replay replay(path, root);
  for (size_t i = 0; i < n; ++i)
    for (const Statement& s : chunks[i].statements) {
      replay.facesUpTo(faceBase[i] + s.face);
      if (!replay.apply(s)) return false;
    }
  replay.facesUpTo(faceBase[n]);
  std::vector<std::pair<uint64_t, uint32_t>> runs;
  if (!replay.runs(runs)) return false;
  // Step 4: the file's vertices, texture coordinates and normals, whole.
  std::vector<float> positions(3 * vBase[n]), uvs(2 * tBase[n]), normals(3 * nBase[n]), colors(3 * colored);
  const bool gathered = parallelFor(n, [&](size_t i) {
    Chunk& c = chunks[i];
    for (size_t k = 0; k < c.positions.size(); ++k) positions[3 * vBase[i] + k] = c.positions[k] + 0.0f;
    std::copy(c.uvs.begin(), c.uvs.end(), uvs.begin() + ptrdiff_t(2 * tBase[i]));
    std::copy(c.normals.begin(), c.normals.end(), normals.begin() + ptrdiff_t(3 * nBase[i]));
    if (colored) std::copy(c.colors.begin(), c.colors.end(), colors.begin() + ptrdiff_t(3 * vBase[i]));
    const uint64_t bases[3] = {vBase[i], tBase[i], nBase[i]};
    for (const auto& [slot, kind] : c.relative) c.corners[slot] = int32_t(c.corners[slot] + int64_t(bases[kind]));
    c.positions = {}, c.uvs = {}, c.normals = {}, c.colors = {};
  });
  // Step 5: the un-shared vertices and triangles, each chunk at its offsets.
  Mesh out;
  out.positions.resize(3 * corners);
  out.normals.resize(3 * corners);
  out.uvs.resize(2 * corners);
  if (colored) out.colors.resize(4 * corners);
  out.indices.resize(3 * triangles);
  out.triMaterial.resize(triangles);
  std::vector<uint32_t> positionIndex(corners);  // each corner's v, for the weld (repairNormals)
  aiMatrix3x3 normalMatrix{aiMatrix4x4()};       // as scene.cpp transforms normals
  normalMatrix.Inverse().Transpose();
  const size_t stride = strideOf(form);
  std::atomic<bool> inRange{true};
  if (!gathered) return false;
  const bool written = parallelFor(n, [&](size_t i) {
    const Chunk& c = chunks[i];
    uint64_t corner = cornerBase[i], tri = triBase[i], f = faceBase[i];
    size_t run = size_t(std::upper_bound(runs.begin(), runs.end(), std::make_pair(f, ~0u)) - runs.begin()) - 1;
    const int32_t* src = c.corners.data();
    for (uint32_t k : c.faceSizes) {
      while (run + 1 < runs.size() && runs[run + 1].first <= f) ++run;
      const uint64_t first = corner;
      for (uint32_t j = 0; j < k; ++j, src += stride, ++corner) {
        const int64_t v = src[0];
        if (v < 0 || uint64_t(v) >= vBase[n]) return void(inRange = false);
        std::copy_n(&positions[3 * size_t(v)], 3, &out.positions[3 * corner]);
        positionIndex[corner] = uint32_t(v);
        if (colored) {
          std::copy_n(&colors[3 * size_t(v)], 3, &out.colors[4 * corner]);
          out.colors[4 * corner + 3] = 1.0f;
        }
        if (hasUv(form)) {
          const int64_t t = src[1];
          if (t < 0 || uint64_t(t) >= tBase[n]) return void(inRange = false);
          std::copy_n(&uvs[2 * size_t(t)], 2, &out.uvs[2 * corner]);
        }
        if (hasNormal(form)) {
          const int64_t m = src[stride - 1];
          if (m < 0 || uint64_t(m) >= nBase[n]) return void(inRange = false);
          aiVector3D q = normalMatrix * aiVector3D(normals[3 * m], normals[3 * m + 1], normals[3 * m + 2]);
          if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) q = aiVector3D(0, 0, 0);
          out.normals[3 * corner] = q.x, out.normals[3 * corner + 1] = q.y, out.normals[3 * corner + 2] = q.z;
        }
      }
      for (uint32_t j = 1; j + 1 < k; ++j, ++tri) {
        out.indices[3 * tri] = uint32_t(first);
        out.indices[3 * tri + 1] = uint32_t(first + j);
        out.indices[3 * tri + 2] = uint32_t(first + j + 1);
        out.triMaterial[tri] = runs[run].second;
      }
      ++f;
    }
  });
  if (!written || !inRange) return false;
  chunks = {};
  out.facts.uvsInFile = hasUv(form);
  // Step 6: the materials, converted as scene.cpp converts assimp's.
  aiScene scene;
  const auto& materials = replay.materials();
  scene.mMaterials = new aiMaterial*[materials.size()];
  for (const MtlMaterial& m : materials) {
    auto* mat = new aiMaterial;
    const aiString name(m.name);
    mat->AddProperty(&name, AI_MATKEY_NAME);
    const aiColor3D diffuse(m.diffuse[0], m.diffuse[1], m.diffuse[2]);
    mat->AddProperty(&diffuse, 1, AI_MATKEY_COLOR_DIFFUSE);
    if (!m.texture.empty()) {
      const aiString texture(m.texture);
      mat->AddProperty(&texture, AI_MATKEY_TEXTURE_DIFFUSE(0));
    }
    scene.mMaterials[scene.mNumMaterials++] = mat;
  }
  convertMaterials(path, root, scene, colored != 0, out);
  const PositionIndex hint{positions.data(), vBase[n], positionIndex.data()};
  repairNormals(out, path, hasNormal(form), &hint);
  mesh = std::move(out);
  return true;
}

}  // namespace clr
