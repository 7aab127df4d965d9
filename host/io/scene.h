// scene.h — triangle meshes as the pipeline consumes them.
//
// A Mesh is flat arrays: positions and normals (3 floats per vertex) and
// indices (3 per triangle; 2 per line and 1 per point of the file).
// loadScene() reads any file assimp reads,
// fan-triangulates polygons in the file's own face order, concatenates
// meshes in node order with node transforms applied, validates every index
// and every position (finite, within ±1e18), and throws clr::Error naming the
// file and the problem; model_checks.h guards assimp against hostile files
// first (docs/limits.md, "Hostile files"). Normals come from
// the file when it has them, otherwise they are smoothed over vertices that
// share a position. Vertex colours come from mColors[0]; every triangle
// keeps its mesh's material (base colour factor and base-colour texture,
// see texture.h): embedded textures ("*N" paths, GLB) are decoded from the
// file, others are read relative to the model's folder, each file once, and
// only inside the folders asset_root.h allows.
#pragma once

#include "base/warnings.h"
#include "io/texture.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

struct aiScene;

namespace clr {

class AssetRoot;

// What loading found beyond the arrays, for `clraster info` (info.h).
struct MeshFacts {
  bool normalsInFile = false;                // some mesh of the file had vertex normals
  size_t normalsRepaired = 0;                // of those, zero, NaN or missing ones recomputed (normals.h)
  bool uvsInFile = false;                    // some mesh had texture coordinates
  std::vector<std::string> missingTextures;  // texture files named but not read
  // Where the smoothed normals welded un-shared vertices: a class per vertex
  // (equal positions, -0 as +0, share one), `weldClassCount` of them; else
  // empty. Only a hint: the layout checks it before it trusts it (layout.h).
  std::vector<uint32_t> weldClasses;
  size_t weldClassCount = 0;
};

struct Mesh {
  std::vector<float> positions;       // 3 per vertex
  std::vector<float> normals;         // 3 per vertex, unit or zero
  std::vector<float> uvs;             // 2 per vertex (texture coordinates), or empty
  std::vector<uint32_t> indices;      // 3 per triangle
  std::vector<uint32_t> lines;        // 2 per line segment of the file (lines.cpp draws them)
  std::vector<uint32_t> points;       // 1 per point of the file
  std::vector<float> colors;          // 4 per vertex (RGBA in [0, 1]), or empty
  std::vector<uint32_t> triMaterial;  // 1 per triangle, index into materials; or empty
  std::vector<Material> materials;    // empty: the built-in grey albedo
  std::vector<Texture> textures;      // base-colour textures the materials name
  Warnings warnings;                  // what loading left out (a texture file it could not read), bounded
  MeshFacts facts;
  bool hasTextures() const { return !textures.empty(); }
  size_t numVerts() const { return positions.size() / 3; }
  size_t numTris() const { return indices.size() / 3; }
};

struct Bounds {
  glm::vec3 min{0.0f}, max{0.0f};
  bool empty = true;
};

// `assets` widens the folders the files a model names may lie in
// (asset_root.h): "" the model's own folder, "any", or a directory.
Mesh loadScene(const std::string& path, const std::string& assets = "");

// A model file read once, checked, and waiting for its import: the import
// reads these bytes, not the file again.
struct ModelFile {
  std::string path;
  std::shared_ptr<const std::string> bytes;  // the file's one read
  int importer = -1;                         // the assimp importer the checks were run for
  bool byExtension = false;                  // that importer was chosen by the extension
  std::string format;                        // its format, as model_checks.h names it
  double readMs = 0.0, checkMs = 0.0;        // wall time of the read, and of the checks after it
  bool direct = true;                        // a direct reader (fast_ply.h) may read it instead of assimp
};

// loadScene in two steps, so that a caller can report a bad file at once
// and import a good one while it does something else: checkSceneFile reads
// the file and runs the quick checks (a readable, non-empty regular file;
// model_checks.h), importScene the rest, on those bytes. A file moved into
// importScene lets its bytes go once the mesh no longer needs them.
ModelFile checkSceneFile(const std::string& path);
// `assets` as loadScene takes it.
Mesh importScene(ModelFile file, const std::string& assets = "");

// For direct readers (fast_obj.h): `scene`'s materials appended to
// mesh.materials (and their textures to mesh.textures) exactly as the
// assimp import converts them; `anyColors`: the file has vertex colours.
void convertMaterials(const std::string& path, const AssetRoot& root, const aiScene& scene, bool anyColors, Mesh& mesh);

// The built-in scene shipped in the binary (procedural, no file).
Mesh defaultScene();

// Where a direct reader took each vertex's position from: vertex v's
// position is positions[3 * index[v] ..] of the file's `count` positions,
// bit for bit or differing only in the sign of a zero. Welding those
// (fewer) positions gives the same classes as welding the vertices.
struct PositionIndex {
  const float* positions = nullptr;  // 3 per file position
  size_t count = 0;
  const uint32_t* index = nullptr;  // 1 per mesh vertex, each < count
};

// Area-weighted vertex normals, smoothed across vertices at equal positions
// (equal bytes once -0 is +0); `hint`, when given, only makes the weld cheaper.
void computeSmoothNormals(Mesh& mesh, const PositionIndex* hint = nullptr);

// Bounds of the finite vertex positions.
Bounds meshBounds(const Mesh& mesh);

}  // namespace clr
