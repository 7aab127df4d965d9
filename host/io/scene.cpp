// scene.cpp — mesh import through assimp (see scene.h for the contract).
//
// No assimp post-processing step runs that could reorder, merge or drop
// faces: polygons are fan-triangulated here, (0, k, k + 1), in file order.
#include "io/scene.h"

#include "base/error.h"
#include "io/asset_root.h"
#include "io/exact_positions.h"
#include "io/fast_gltf.h"
#include "io/fast_obj.h"
#include "io/fast_off.h"
#include "io/fast_ply.h"
#include "io/fast_stl.h"
#include "io/file_rule.h"
#include "io/import_budget.h"
#include "io/model_checks.h"
#include "io/normals.h"
#include "io/model_io.h"

#include <assimp/DefaultLogger.hpp>
#include <assimp/Importer.hpp>
#include <assimp/LogStream.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <sstream>
#include <strings.h>
#include <sys/stat.h>
#include <thread>

namespace clr {

namespace {

// The largest vertex coordinate accepted, after node transforms. Squares of
// differences of such coordinates still fit a float, so bounds, their
// extent and the framing camera stay finite.
constexpr float kMaxCoordinate = 1e18f;

// Meshes of at least this many vertices normalise their smoothed normals on two threads.
constexpr size_t kParallelVertices = 1 << 16;
// How many triangles ahead the smoothed normals' sums fetch their vertices (computeSmoothNormals).
constexpr size_t kPrefetch = 32;

std::string formatVector(const aiVector3D& v)
{
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
  return text;
}

struct ImportState {
  const std::string& path;
  const AssetRoot& root;
  const aiScene* scene;
  Mesh mesh;
  bool anyNormals = false;
  bool anyColors = false;
};

// Room for `more` elements, growing geometrically: one large mesh is
// appended without reallocating, many small ones without quadratic copies.
template <typename T>
void reserveMore(std::vector<T>& v, size_t more)
{
  if (v.size() + more > v.capacity()) v.reserve(std::max(v.size() + more, 2 * v.capacity()));
}

void appendMesh(ImportState& state, const aiMesh* src, const aiMatrix4x4& transform, unsigned meshIndex)
{
  Mesh& dst = state.mesh;
  reserveMore(dst.positions, 3 * size_t(src->mNumVertices));
  reserveMore(dst.normals, 3 * size_t(src->mNumVertices));
  reserveMore(dst.uvs, 2 * size_t(src->mNumVertices));
  reserveMore(dst.colors, 4 * size_t(src->mNumVertices));
  size_t triangles = 0;
  for (unsigned f = 0; f < src->mNumFaces; ++f)
    triangles += src->mFaces[f].mNumIndices > 2 ? src->mFaces[f].mNumIndices - 2 : 0;
  reserveMore(dst.indices, 3 * triangles);
  reserveMore(dst.triMaterial, triangles);
  const uint64_t base = dst.numVerts();
  if (base + src->mNumVertices > UINT32_MAX) throw Error(userText(state.path) + ": more than 2^32 vertices");
  // Step 1: vertices, with the node transform applied.
  aiMatrix3x3 normalMatrix(transform);
  normalMatrix.Inverse().Transpose();
  if (src->mNormals) state.anyNormals = true;
  if (src->mTextureCoords[0]) dst.facts.uvsInFile = true;
  for (unsigned v = 0; v < src->mNumVertices; ++v) {
    // Non-finite or huge coordinates would leave the bounds and the camera
    // framing overflowing; the file is rejected instead.
    const aiVector3D& q = src->mVertices[v];
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
      throw Error(userText(state.path) + ": mesh " + std::to_string(meshIndex) + " vertex " + std::to_string(v) +
                  " has a non-finite position " + formatVector(q));
    const aiVector3D p = transform * q;
    if (!(std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate && std::fabs(p.z) <= kMaxCoordinate))
      throw Error(userText(state.path) + ": mesh " + std::to_string(meshIndex) + " vertex " + std::to_string(v) +
                  " lies at " + formatVector(p) + " after node transforms, beyond the supported 1e18");
    dst.positions.insert(dst.positions.end(), {p.x, p.y, p.z});
    aiVector3D n = src->mNormals ? normalMatrix * src->mNormals[v] : aiVector3D(0, 0, 0);
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) n = aiVector3D(0, 0, 0);  // unlit
    dst.normals.insert(dst.normals.end(), {n.x, n.y, n.z});
    // Texture coordinates of the first channel, (0, 0) without one.
    const aiVector3D uv = src->mTextureCoords[0] ? src->mTextureCoords[0][v] : aiVector3D(0, 0, 0);
    dst.uvs.insert(dst.uvs.end(), {uv.x, uv.y});
    // Vertex colours of the first set, white without one.
    const aiColor4D c = src->mColors[0] ? src->mColors[0][v] : aiColor4D(1, 1, 1, 1);
    dst.colors.insert(dst.colors.end(), {c.r, c.g, c.b, c.a});
  }
  if (src->mColors[0]) state.anyColors = true;
  // Step 2: faces, validated and fan-triangulated in file order.
  for (unsigned f = 0; f < src->mNumFaces; ++f) {
    const aiFace& face = src->mFaces[f];
    for (unsigned k = 0; k < face.mNumIndices; ++k)
      if (face.mIndices[k] >= src->mNumVertices)
        throw Error(userText(state.path) + ": mesh " + std::to_string(meshIndex) + " face " + std::to_string(f) +
                    " has vertex index " + std::to_string(face.mIndices[k]) + " out of range (" +
                    std::to_string(src->mNumVertices) + " vertices)");
    // Lines and points (glTF's line and point modes, OBJ's l and p).
    if (face.mNumIndices == 2)
      dst.lines.insert(dst.lines.end(), {uint32_t(base + face.mIndices[0]), uint32_t(base + face.mIndices[1])});
    if (face.mNumIndices == 1) dst.points.push_back(uint32_t(base + face.mIndices[0]));
    for (unsigned k = 1; k + 1 < face.mNumIndices; ++k) {
      dst.indices.insert(dst.indices.end(), {uint32_t(base + face.mIndices[0]), uint32_t(base + face.mIndices[k]),
                                             uint32_t(base + face.mIndices[k + 1])});
      dst.triMaterial.push_back(src->mMaterialIndex);
    }
  }
}

void visitNode(ImportState& state, const aiNode* node, const aiMatrix4x4& parent, int depth)
{
  if (depth > 256) throw Error(userText(state.path) + ": node hierarchy deeper than 256 levels");
  const aiMatrix4x4 transform = parent * node->mTransformation;
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    const unsigned m = node->mMeshes[i];
    if (m >= state.scene->mNumMeshes || !state.scene->mMeshes[m])
      throw Error(userText(state.path) + ": node refers to missing mesh " + std::to_string(m));
    appendMesh(state, state.scene->mMeshes[m], transform, m);
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) visitNode(state, node->mChildren[c], transform, depth + 1);
}

uint32_t wrapMode(int mode)
{
  return mode == aiTextureMapMode_Mirror                                    ? CLR_WRAP_MIRROR
         : mode == aiTextureMapMode_Clamp || mode == aiTextureMapMode_Decal ? CLR_WRAP_CLAMP
                                                                            : CLR_WRAP_REPEAT;
}

// "%20" as " ", and so on; a '%' not followed by two hex digits stays.
std::string percentDecoded(const std::string& s)
{
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out += char(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

// A texture file the model names, under the model-folder rule: under it,
// every failure but the texture budget reads alike (asset_root.h).
Texture loadTexture(const AssetRoot& root, const std::string& file, const std::string& reference, TextureBudget& budget)
{
  try {
    const std::string bytes = root.open(file, reference, kTextureInput)->read();
    return decodeTexture(file, reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), budget);
  } catch (const TextureOverBudget&) {
    throw;
  } catch (const InputOverLimit&) {
    throw;
  } catch (const Error&) {
    if (!root.confined()) throw;
    throw Error(AssetRoot::refusal(reference));
  }
}

// The scene's materials: base colour factor (glTF's baseColorFactor, else
// the diffuse colour) and base-colour texture (else the diffuse texture).
// Materials assimp invents for formats without any (no name or
// AI_DEFAULT_MATERIAL_NAME, no base colour, no texture) keep the built-in grey.
void loadMaterials(ImportState& state)
{
  const aiScene* scene = state.scene;
  const std::string folder =
      state.path.find('/') == std::string::npos ? "" : state.path.substr(0, state.path.rfind('/') + 1);
  std::map<std::string, int> byPath;
  // Each texture file is read once: its warning, or its texture (copied for another wrap mode).
  std::map<std::string, std::string> failedFiles;
  std::map<std::string, int> loadedFiles;
  TextureBudget budget;  // all textures of the scene, mip chains counted
  for (unsigned m = 0; m < scene->mNumMaterials; ++m) {
    const aiMaterial* mat = scene->mMaterials[m];
    // Step 1: the colour factor.
    Material out{};
    aiColor4D colour(1, 1, 1, 1);
    const aiString matName = mat->GetName();
    const bool invented = (matName.length == 0 || matName == aiString(AI_DEFAULT_MATERIAL_NAME)) &&
                          mat->GetTextureCount(aiTextureType_DIFFUSE) == 0 &&
                          mat->GetTextureCount(aiTextureType_BASE_COLOR) == 0;
    if (mat->Get(AI_MATKEY_BASE_COLOR, colour) == AI_SUCCESS) {
      // glTF's baseColorFactor.
    } else if (invented) {
      // Invented by assimp (PLY, STL, OFF, OBJ without MTL): the built-in
      // grey, or white under the file's vertex colours.
      colour = state.anyColors ? aiColor4D(1, 1, 1, 1) : aiColor4D(0.80f, 0.78f, 0.74f, 1.0f);
    } else if (mat->Get(AI_MATKEY_COLOR_DIFFUSE, colour) != AI_SUCCESS) {
      colour = aiColor4D(1, 1, 1, 1);
    }
    out.baseColor[0] = colour.r;
    out.baseColor[1] = colour.g;
    out.baseColor[2] = colour.b;
    out.baseColor[3] = colour.a;
    out.texture = -1;
    // Step 2: the texture, decoded once per path.
    aiTextureType type = aiTextureType_BASE_COLOR;
    aiString texPath;
    if (mat->GetTexture(type, 0, &texPath) != AI_SUCCESS) {
      type = aiTextureType_DIFFUSE;
      if (mat->GetTexture(type, 0, &texPath) != AI_SUCCESS) texPath.Clear();
    }
    const std::string name = texPath.C_Str();
    if (!name.empty()) {
      int wrapU = aiTextureMapMode_Wrap, wrapV = aiTextureMapMode_Wrap;
      mat->Get(AI_MATKEY_MAPPINGMODE_U(type, 0), wrapU);
      mat->Get(AI_MATKEY_MAPPINGMODE_V(type, 0), wrapV);
      const std::string key = name + "|" + std::to_string(wrapU) + "|" + std::to_string(wrapV);
      auto found = byPath.find(key);
      if (found == byPath.end()) {
        Texture t;
        if (const aiTexture* embedded = scene->GetEmbeddedTexture(name.c_str())) {
          const std::string what = userText(state.path, 100) + ": embedded texture '" + userText(name, 60) + "'";
          try {
            if (embedded->mHeight == 0)
              t = decodeTexture(what, reinterpret_cast<const unsigned char*>(embedded->pcData), embedded->mWidth,
                                budget);
            else
              budget.claim(what, embedded->mWidth, embedded->mHeight);
          } catch (const Error& e) {  // over the budget or undecodable: as a missing file, below
            state.mesh.warnings.add("texture", userText(e.what(), 250) + "; rendered without the texture");
            state.mesh.facts.missingTextures.push_back(what);
            state.mesh.materials.push_back(out);
            continue;
          }
          if (embedded->mHeight != 0) {
            t.name = what;
            t.width = embedded->mWidth;
            t.height = embedded->mHeight;
            t.rgba.resize(size_t(t.width) * t.height);
            for (uint32_t y = 0; y < t.height; ++y)
              for (uint32_t x = 0; x < t.width; ++x) {
                const aiTexel& p = embedded->pcData[size_t(t.height - 1 - y) * t.width + x];
                t.rgba[size_t(y) * t.width + x] =
                    uint32_t(p.r) | uint32_t(p.g) << 8 | uint32_t(p.b) << 16 | uint32_t(p.a) << 24;
              }
          }
        } else if (name[0] == '*') {
          throw Error(userText(state.path, 120) + ": material " + std::to_string(m) +
                      " names missing embedded texture '" + userText(name, 100) + "'");
        } else {
          // A file beside the model ("//" is Blender's "relative to the .blend").
          std::string file = name.rfind("//", 0) == 0 ? name.substr(2) : name;
          std::replace(file.begin(), file.end(), '\\', '/');
          if (file[0] != '/') file = folder + file;
          // A glTF URI is percent-encoded ("tex%20a.png"), which assimp passes on as it is.
          const std::string decoded = percentDecoded(file);
          struct stat st;
          if (decoded != file && stat(file.c_str(), &st) != 0 && stat(decoded.c_str(), &st) == 0) file = decoded;
          const auto failed = failedFiles.find(file);
          std::string warning = failed == failedFiles.end() ? "" : failed->second;
          if (failed == failedFiles.end()) {
            try {
              const auto loaded = loadedFiles.find(file);
              if (loaded != loadedFiles.end()) {
                t = state.mesh.textures[size_t(loaded->second)];
                budget.claim(t.name, t.width, t.height);
              } else {
                t = loadTexture(state.root, file, name, budget);
                loadedFiles.emplace(file, int(state.mesh.textures.size()));
              }
            } catch (const Error& e) {
              // The model itself is sound: render the material untextured and
              // say so once, as other renderers do with a missing texture file.
              warning = userText(state.path, 60) + ": material " + std::to_string(m) + ": " + userText(e.what(), 190) +
                        "; rendered without the texture";
              failedFiles.emplace(file, warning);
              state.mesh.warnings.add("texture", warning);
              state.mesh.facts.missingTextures.push_back(file);
            }
          }
          if (!warning.empty()) {
            state.mesh.materials.push_back(out);
            continue;
          }
        }
        t.wrapS = wrapMode(wrapU);
        t.wrapT = wrapMode(wrapV);
        found = byPath.emplace(key, int(state.mesh.textures.size())).first;
        state.mesh.textures.push_back(std::move(t));
      }
      out.texture = found->second;
    }
    state.mesh.materials.push_back(out);
  }
}

// Some assimp importers repair bad input instead of failing: the OFF reader
// clamps an out-of-range vertex index, the glTF reader drops the face. Both
// say so only through the logger, so import runs with a log stream that
// records warnings and errors, and index problems among them become errors.
class ImportLog : public Assimp::LogStream {
 public:
  void write(const char* message) override
  {
    std::string m(message);
    while (!m.empty() && (m.back() == '\n' || m.back() == '\r')) m.pop_back();
    if (m.rfind("Warn", 0) == 0 || m.rfind("Error", 0) == 0) m = m.substr(std::min(m.size(), m.find(": ") + 2));
    const std::string lowered = [&] {
      std::string l = m;
      std::transform(l.begin(), l.end(), l.begin(), [](unsigned char c) { return c == '-' ? ' ' : std::tolower(c); });
      return l;
    }();
    // Not the glTF reader's "All indices for indexed attribute semantics
    // must ...": it skips that attribute (a TEXCOORD_1), not faces.
    if (firstIndexProblem.empty() && lowered.find("attribute") == std::string::npos &&
        (lowered.find("index") != std::string::npos || lowered.find("indices") != std::string::npos) &&
        (lowered.find("out of range") != std::string::npos || lowered.find("invalid") != std::string::npos))
      firstIndexProblem = m;
    // The OBJ reader goes on without a material library it cannot find.
    const std::string missingLibrary = "Unable to locate material file ";
    if (m.find(missingLibrary) != std::string::npos) {
      if (missingLibraries.empty())
        missingLibraries.push_back(m.substr(m.find(missingLibrary) + missingLibrary.size()));
      else
        ++moreMissingLibraries;  // counted only: one line names the first (base/warnings.h)
    }
  }
  std::string firstIndexProblem;
  std::vector<std::string> missingLibraries;
  size_t moreMissingLibraries = 0;
};

struct ScopedImportLog {
  ScopedImportLog()
  {
    Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);
    Assimp::DefaultLogger::get()->attachStream(&log, Assimp::Logger::Warn | Assimp::Logger::Err);
  }
  ~ScopedImportLog()
  {
    Assimp::DefaultLogger::get()->detachStream(&log, Assimp::Logger::Warn | Assimp::Logger::Err);
    Assimp::DefaultLogger::kill();
  }
  ImportLog log;
};

// Point clouds: assimp's PLY and OBJ readers return a mesh of vertices
// without faces, which its validation rejects; each vertex becomes a point
// face first. PLY has no lines or points of its own (assimp does not read
// edge elements), so a PLY face of one or two vertices is the reader's
// reading of a truncated face list: refused.
void preparePointClouds(const std::string& path, bool ply, aiScene* scene)
{
  for (unsigned m = 0; scene->mMeshes && m < scene->mNumMeshes; ++m) {
    aiMesh* mesh = scene->mMeshes[m];
    if (!mesh) continue;
    for (unsigned f = 0; ply && mesh->mFaces && f < mesh->mNumFaces; ++f)
      if (mesh->mFaces[f].mNumIndices < 3)
        throw Error(userText(path) + ": PLY faces of fewer than 3 vertices (a truncated or malformed file)");
    if (mesh->mNumFaces != 0 || mesh->mFaces || mesh->mNumVertices == 0 || !mesh->mVertices) continue;
    mesh->mFaces = new aiFace[mesh->mNumVertices];
    mesh->mNumFaces = mesh->mNumVertices;
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      mesh->mFaces[v].mNumIndices = 1;
      mesh->mFaces[v].mIndices = new unsigned[1]{v};
    }
    mesh->mPrimitiveTypes = aiPrimitiveType_POINT;
  }
}

}  // namespace

void convertMaterials(const std::string& path, const AssetRoot& root, const aiScene& scene, bool anyColors, Mesh& mesh)
{
  ImportState state{path, root, &scene, std::move(mesh)};
  state.anyColors = anyColors;
  loadMaterials(state);
  mesh = std::move(state.mesh);
}

Mesh loadScene(const std::string& path, const std::string& assets)
{
  return importScene(checkSceneFile(path), assets);
}

ModelFile checkSceneFile(const std::string& path)
{
  // Step 1: the file rule (file_rule.h), and the file's one read: a
  // non-empty regular file within the model size limit, checked without
  // blocking. The checks and the import see these bytes, never the file again.
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  ModelFile file;
  file.path = path;
  file.bytes = std::make_shared<const std::string>(readInputFile(path, kModelInput));
  const auto read = Clock::now();
  file.readMs = std::chrono::duration<double, std::milli>(read - start).count();
  // Step 2: the guards against hostile files, on the reader assimp will
  // choose. Their messages start with the whole path and may quote the
  // file's text: a long one is shortened here.
  Assimp::Importer importer;
  auto* io = new RuleIOSystem(path, "");  // the importer owns it
  importer.SetIOHandler(io);
  io->serve(path, file.bytes.get());
  try {
    const ModelReader reader = checkModelFile(path, *file.bytes, importer, *io);
    file.importer = reader.importer;
    file.byExtension = reader.byExtension;
    file.format = reader.format;
    checkGltfBudget(path, *file.bytes);
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.size() <= 300) throw;
    const size_t rest = message.rfind(path, 0) == 0 ? path.size() : 0;
    throw Error(userText(message.substr(0, rest), 120) + userText(message.substr(rest), 170));
  }
  file.checkMs = std::chrono::duration<double, std::milli>(Clock::now() - read).count();
  return file;
}

Mesh importScene(ModelFile file, const std::string& assets)
{
  const std::string& path = file.path;
  const AssetRoot root(path, assets);
  // The plainest PLY, OFF and STL files, read directly (fast_ply.h, fast_off.h, fast_stl.h): the same mesh.
  Mesh direct;
  if (file.direct && file.byExtension &&
      ((file.format == "ply" && (readPlainBinaryPly(*file.bytes, direct) || readPlainAsciiPly(*file.bytes, direct))) ||
       (file.format == "off" && readPlainOff(*file.bytes, direct)) ||
       (file.format == "stl" && readPlainStl(*file.bytes, direct)))) {
    file.bytes.reset();  // the last reference, unless the caller kept one
    repairNormals(direct, path, direct.facts.normalsInFile);
    return direct;
  }
  // The plain OBJ, GLB and glTF, read directly (fast_obj.h, fast_gltf.h): the same mesh.
  if (file.direct && file.format == "obj" && file.byExtension && readPlainObj(path, *file.bytes, root, direct))
    return direct;
  if (file.direct && file.format == "gltf" && path.size() > 4 &&
      ((strcasecmp(path.c_str() + path.size() - 4, ".glb") == 0 && readPlainGlb(path, *file.bytes, root, direct)) ||
       (path.size() > 5 && strcasecmp(path.c_str() + path.size() - 5, ".gltf") == 0 &&
        readPlainGltf(path, *file.bytes, root, direct))))
    return direct;
  // Step 1: import without reordering post-processing, from the bytes checked.
  Assimp::Importer importer;
  auto* io = new RuleIOSystem(path, assets);  // every file the import opens, under the file rules; the importer owns it
  importer.SetIOHandler(io);
  // Text formats: positions re-read correctly rounded (exact_positions.h).
  const ExactPositions exact = prepareExactPositions(path, *file.bytes, file.format, file.byExtension, importer);
  io->serve(path, exact.importer != -1 ? &exact.text : file.bytes.get());
  if (exact.format == "OBJ") {
    checkObjBudget(path, exact.text);
    io->countMaterialLibraries();
  }
  ScopedImportLog importLog;
  const aiScene* scene = nullptr;
  try {
    // Validated once point clouds have faces (preparePointClouds).
    scene = importer.ReadFile(path, 0);
    if (scene) {
      if (importer.GetPropertyInteger("importerIndex", -1) != file.importer)
        throw Error(userText(path, 100) + ": assimp chose another reader than the one checked");
      preparePointClouds(path, file.format == "ply", const_cast<aiScene*>(scene));
      scene = importer.ApplyPostProcessing(aiProcess_ValidateDataStructure);
    }
  } catch (const Error&) {
    throw;  // ours, already one line naming the file
  } catch (const std::exception& e) {
    throw Error(userText(path, 100) + ": cannot import (" + userText(e.what(), 160) + ")");
  }
  if (!io->overBudget().empty()) throw Error(io->overBudget());
  if (!importLog.log.firstIndexProblem.empty())
    throw Error(userText(path, 100) + ": " + userText(importLog.log.firstIndexProblem, 180));
  if (!scene && !io->refusals().empty())
    throw Error(userText(path, 80) + ": cannot import (" + userText(io->refusals().front(), 160) + ")");
  if (!scene) throw Error(userText(path, 100) + ": cannot import (" + userText(importer.GetErrorString(), 160) + ")");
  if (!scene->mRootNode || scene->mNumMeshes == 0) throw Error(userText(path) + ": no meshes in file");
  applyExactPositions(path, exact, importer, *scene);
  // Step 2: walk the nodes, concatenating meshes.
  ImportState state{path, root, scene, {}};
  for (const std::string& refused : io->refusals())
    state.mesh.warnings.add("refused", userText(path, 80) + ": " + userText(refused, 160) + "; imported without it");
  if (io->refusals().empty())  // (a refused library is warned of above)
    for (const std::string& library : importLog.log.missingLibraries)
      state.mesh.warnings.add("library", userText(path, 80) + ": material library '" + userText(library, 100) +
                                             "' not found; rendered with default materials");
  if (io->refusals().empty() && importLog.log.moreMissingLibraries)
    state.mesh.warnings.add("library", "", importLog.log.moreMissingLibraries);
  visitNode(state, scene->mRootNode, aiMatrix4x4(), 0);
  // Some readers leave a mesh out of every node (assimp's AC reader, a point
  // list without surfaces): where the nodes give nothing, the meshes are drawn as they are.
  if (state.mesh.indices.empty() && state.mesh.lines.empty() && state.mesh.points.empty())
    for (unsigned m = 0; m < scene->mNumMeshes; ++m)
      if (scene->mMeshes[m]) appendMesh(state, scene->mMeshes[m], aiMatrix4x4(), m);
  if (state.mesh.indices.empty() && state.mesh.lines.empty() && state.mesh.points.empty())
    throw Error(userText(path) + ": no triangles, lines or points in file");
  if (!state.anyColors) state.mesh.colors.clear();
  // Step 3: materials and their textures.
  loadMaterials(state);
  for (uint32_t& m : state.mesh.triMaterial)
    if (m >= state.mesh.materials.size())
      throw Error(userText(path) + ": mesh refers to missing material " + std::to_string(m));
  if (meshBounds(state.mesh).empty) throw Error(userText(path) + ": no vertex has finite coordinates");
  repairNormals(state.mesh, path, state.anyNormals);
  return std::move(state.mesh);
}

void computeSmoothNormals(Mesh& mesh, const PositionIndex* hint)
{
  // Step 1: weld vertices by equal position (meshoptimizer compares bytes:
  // -0 becomes +0 first, as the two compare equal; a copy only where one
  // occurs). With a hint the file's positions are welded instead and vertex
  // v takes the class of its position index[v]: v's key is that position's
  // key, so key(v) = key(w) exactly when their positions' classes agree.
  const size_t n = mesh.numVerts();
  const float* source = hint ? hint->positions : mesh.positions.data();
  const size_t keyCount = hint ? hint->count : n;
  std::vector<float> keys;
  if (std::any_of(source, source + 3 * keyCount, [](float c) { return c == 0.0f && std::signbit(c); })) {
    keys.resize(3 * keyCount);
    for (size_t i = 0; i < keys.size(); ++i) keys[i] = source[i] + 0.0f;
  }
  const float* weldKeys = keys.empty() ? source : keys.data();
  std::vector<uint32_t> weld(n);
  std::vector<uint32_t> keyWeld(hint ? keyCount : 0);
  uint32_t* remap = hint ? keyWeld.data() : weld.data();
  const size_t welded =
      keyCount == 0 ? 0 : meshopt_generateVertexRemap(remap, nullptr, keyCount, weldKeys, keyCount, 3 * sizeof(float));
  std::vector<float>().swap(keys);  // (v = {} would keep the capacity)
  if (hint)
    for (size_t v = 0; v < n; ++v) weld[v] = keyWeld[hint->index[v]];
  std::vector<uint32_t>().swap(keyWeld);
  // Step 2: accumulate area-weighted face normals per welded vertex, in
  // triangle order (whatever the classes' numbers, each sum adds the same
  // terms in the same order). The loads are random in a large mesh (a
  // scan's faces are in no spatial order): the vertices of the triangle
  // kPrefetch ahead and their welded ids are fetched early, and the sums
  // they add to half that far ahead, so that the misses overlap.
  std::vector<glm::dvec3> sum(welded, glm::dvec3(0.0));
  auto pos = [&](uint32_t v) {
    return glm::dvec3(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
  };
  const size_t tris = mesh.numTris();
  const uint32_t* indices = mesh.indices.data();
  for (size_t t = 0; t < tris; ++t) {
    if (t + kPrefetch < tris)
      for (const uint32_t* v = indices + 3 * (t + kPrefetch); v < indices + 3 * (t + kPrefetch + 1); ++v) {
        __builtin_prefetch(&weld[*v]);
        __builtin_prefetch(&mesh.positions[3 * size_t(*v)]);
      }
    if (t + kPrefetch / 2 < tris)
      for (const uint32_t* v = indices + 3 * (t + kPrefetch / 2); v < indices + 3 * (t + kPrefetch / 2 + 1); ++v)
        __builtin_prefetch(&sum[weld[*v]], 1);
    const uint32_t* tri = indices + 3 * t;
    const glm::dvec3 faceNormal = glm::cross(pos(tri[1]) - pos(tri[0]), pos(tri[2]) - pos(tri[0]));
    if (!std::isfinite(faceNormal.x + faceNormal.y + faceNormal.z)) continue;
    for (int k = 0; k < 3; ++k) sum[weld[tri[k]]] += faceNormal;
  }
  // Step 3: normalise, a large mesh's halves on two threads. Where the
  // vertices outnumber the classes twice over (un-shared vertices), each
  // class is normalised once and copied: the same operations, the same bits.
  auto unit = [](const glm::dvec3& s, float* out) {
    const double len = glm::length(s);
    for (int k = 0; k < 3; ++k) out[k] = len > 0.0 ? float(s[k] / len) : 0.0f;
  };
  std::vector<float> table(2 * welded <= n ? 3 * welded : 0);
  auto tabulate = [&](size_t lo, size_t hi) {
    for (size_t w = lo; w < hi; ++w) unit(sum[w], &table[3 * w]);
  };
  mesh.normals.resize(3 * n);
  auto normalise = [&](size_t lo, size_t hi) {
    if (table.empty())
      for (size_t v = lo; v < hi; ++v) unit(sum[weld[v]], &mesh.normals[3 * v]);
    else
      for (size_t v = lo; v < hi; ++v) std::copy_n(&table[3 * size_t(weld[v])], 3, &mesh.normals[3 * v]);
  };
  auto halves = [](size_t count, const auto& work) {
    if (count < kParallelVertices) return work(0, count);
    std::thread other([&] { work(count / 2, count); });
    work(0, count / 2);
    other.join();
  };
  if (!table.empty()) halves(welded, tabulate);
  halves(n, normalise);
  // Un-shared vertices: the classes are the layout's weld hint.
  mesh.facts.weldClassCount = table.empty() ? 0 : welded;
  mesh.facts.weldClasses = table.empty() ? std::vector<uint32_t>() : std::move(weld);
}

Bounds meshBounds(const Mesh& mesh)
{
  Bounds b;
  for (size_t v = 0; v < mesh.numVerts(); ++v) {
    const glm::vec3 p(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    b.min = b.empty ? p : glm::min(b.min, p);
    b.max = b.empty ? p : glm::max(b.max, p);
    b.empty = false;
  }
  return b;
}

}  // namespace clr
