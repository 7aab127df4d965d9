// device_scene.cpp — a scene on the device (see device_scene.h).
#include "pipeline/device_scene.h"

#include "pipeline/layout.h"
#include "io/texture.h"

#include <algorithm>
#include <cmath>

namespace clr {

DeviceScene::DeviceScene(ClContext& cl)
    : cl_(cl),
      memory_(deviceMemoryOf(cl)),
      positions_(memory_, "vertex positions"),
      normals_(memory_, "vertex normals"),
      uvs_(memory_, "vertex texture coordinates"),
      colors_(memory_, "vertex colours"),
      clusterBounds_(memory_, "cluster bounds"),
      clusterCount_(memory_, "cluster counts"),
      indices_(memory_, "triangle indices"),
      triMaterial_(memory_, "triangle materials"),
      fileTri_(memory_, "triangles' file order"),
      materials_(memory_, "materials"),
      texDescs_(memory_, "texture descriptors"),
      texels_(memory_, "texels")
{
  // Attributes a frame does not read are bound as 1-element dummies.
  normals_.reserve(1);
  uvs_.reserve(1);
  colors_.reserve(1);
  triMaterial_.reserve(1);
  materials_.reserve(1);
  texDescs_.reserve(1);
  texels_.reserve(1);
}

// The bounds of each cluster of CLR_CLUSTER_TRIS consecutive triangles
// (shared.h), NaN where a vertex is not finite: the count pass then neither
// skips the cluster nor takes it as inside the view, and setup_classify
// culls the non-finite triangles.
static std::vector<float> clusterBounds(const Mesh& mesh)
{
  const size_t clusters = (mesh.numTris() + CLR_CLUSTER_TRIS - 1) / CLR_CLUSTER_TRIS;
  std::vector<float> bounds(6 * clusters);
  for (size_t c = 0; c < clusters; ++c) {
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    bool finite = true;
    const size_t end = std::min<size_t>(3 * (c + 1) * CLR_CLUSTER_TRIS, mesh.indices.size());
    for (size_t k = 3 * c * CLR_CLUSTER_TRIS; k < end; ++k) {
      if (mesh.indices[k] >= mesh.numVerts()) continue;  // (scene.cpp rejects such files)
      const float* p = &mesh.positions[3 * size_t(mesh.indices[k])];
      finite = finite && std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
      }
    }
    const bool any = finite && lo[0] <= hi[0];
    for (int a = 0; a < 3; ++a) {
      bounds[6 * c + a] = any ? lo[a] : NAN;
      bounds[6 * c + 3 + a] = any ? hi[a] : NAN;
    }
  }
  return bounds;
}

void DeviceScene::placeScene(const Mesh& fileMesh)
{
  placeLaidOut(layOutScene(fileMesh, layoutOn_));
}

void DeviceScene::placeScene(Mesh&& fileMesh)
{
  placeLaidOut(layOutScene(std::move(fileMesh), layoutOn_));
}

void DeviceScene::placeLaidOut(SceneLayout&& layout)
{
  scene_ = std::move(layout.mesh);
  fileTriHost_ = std::move(layout.fileTri);
  laidVertex_ = std::move(layout.laidVertex);
  std::vector<uint32_t>().swap(layout.fileVertex);  // not kept
  oneMaterial_ = std::all_of(scene_.triMaterial.begin(), scene_.triMaterial.end(),
                             [&](uint32_t m) { return m == scene_.triMaterial[0]; });
  triMaterials_ = !scene_.triMaterial.empty();
  firstMaterial_ = triMaterials_ ? scene_.triMaterial[0] : 0;
  if (oneMaterial_) std::vector<uint32_t>().swap(scene_.triMaterial);  // firstMaterial_ says it all
  ++sceneUploads_;
  resident_ = 0;
  fileOrder_ = true;
  for (uint32_t t = 0; t < fileTriHost_.size() && fileOrder_; ++t) fileOrder_ = fileTriHost_[t] == t;
  if (fileOrder_)
    fileTri_.reserve(1);  // FrameParams.fileOrder: no reader takes it
  else
    fileTri_.upload(fileTriHost_);
  // The cluster bounds first, then each array uploaded and freed in turn
  // (the host keeps the positions only for the file's own lines and
  // points, file_primitives.cpp): host and device hold one array twice at most.
  const std::vector<float> bounds = cl_.lanes > 1 ? clusterBounds(scene_) : std::vector<float>(6, NAN);
  clusterBounds_.upload(bounds);
  clusterCount_.reserve(std::max<size_t>(1, bounds.size() / 6), true);
  sceneVerts_ = scene_.numVerts();
  sceneTris_ = scene_.numTris();
  indices_.upload(scene_.indices);
  std::vector<uint32_t>().swap(scene_.indices);  // (v = {} would keep the capacity)
  positions_.uploadPadded(scene_.positions, 1);  // setup reads x, y, z of a vertex as one float4 (setup.cl)
  if (scene_.lines.empty() && scene_.points.empty()) std::vector<float>().swap(scene_.positions);
  sceneMin_ = glm::vec3(INFINITY);
  sceneMax_ = glm::vec3(-INFINITY);
  for (size_t c = 0; c + 5 < bounds.size(); c += 6)
    if (!std::isnan(bounds[c])) {
      sceneMin_ = glm::min(sceneMin_, glm::vec3(bounds[c], bounds[c + 1], bounds[c + 2]));
      sceneMax_ = glm::max(sceneMax_, glm::vec3(bounds[c + 3], bounds[c + 4], bounds[c + 5]));
    }
}

void DeviceScene::placeClipScene(const float* positions, size_t numVerts, const uint32_t* indices, size_t numTris)
{
  ++sceneUploads_;
  positions_.upload(std::vector<float>(positions, positions + 4 * numVerts));
  indices_.upload(std::vector<uint32_t>(indices, indices + 3 * numTris));
  // No layout: the caller's order is the file's (FrameParams.fileOrder; raster's ties by setup index).
  fileTriHost_.clear();
  laidVertex_.clear();
  fileOrder_ = true;
  fileTri_.reserve(1);
  // No cluster test (setup.cl compiles it out): empty bounds, margin 0.
  clusterBounds_.upload(std::vector<float>(6, NAN));
  clusterCount_.reserve(1);
  sceneMin_ = glm::vec3(INFINITY);
  sceneMax_ = glm::vec3(-INFINITY);
  scene_ = Mesh{};
  triMaterials_ = false;
  sceneVerts_ = numVerts;
  sceneTris_ = numTris;
  resident_ = 0;
}

uint32_t DeviceScene::bindAttributes(const FrameSettings& settings)
{
  const uint32_t mode = settings.shadeMode;
  const bool albedo = CLR_USES_ALBEDO(mode);
  const bool materials = albedo && !scene_.materials.empty() && triMaterials_;
  const bool textures = materials && scene_.hasTextures();
  const bool colors = CLR_NEEDS_COLORS(mode) && !scene_.colors.empty();
  // Step 1: upload what is missing, once.
  if (CLR_NEEDS_NORMALS(mode) && !(resident_ & kResidentNormals)) {
    normals_.upload(scene_.normals);
    std::vector<float>().swap(scene_.normals);  // read only by this upload
    resident_ |= kResidentNormals;
  }
  if ((CLR_NEEDS_UVS(mode) || textures) && !(resident_ & kResidentUvs)) {
    // Meshes without texture coordinates read (0, 0).
    uvs_.upload(scene_.uvs.empty() ? std::vector<float>(2 * sceneVerts_, 0.0f) : scene_.uvs);
    resident_ |= kResidentUvs;
  }
  if (colors && !(resident_ & kResidentColors)) {
    colors_.upload(scene_.colors);
    resident_ |= kResidentColors;
  }
  // One material for every triangle (assimp gives a file without materials one): no per-triangle buffer.
  const bool oneMaterial = materials && oneMaterial_;
  if (materials && !(resident_ & kResidentMaterials)) {
    if (oneMaterial) {
      materials_.upload({scene_.materials[firstMaterial_]});
    } else {
      triMaterial_.upload(scene_.triMaterial);
      materials_.upload(scene_.materials);
    }
    resident_ |= kResidentMaterials;
  }
  if (textures && !(resident_ & kResidentTextures)) {
    const TexturePack pack = packTextures(scene_.textures);
    texDescs_.upload(pack.descs);
    texels_.upload(pack.texels);
    resident_ |= kResidentTextures;
  }
  // Step 2: the flags resolve follows.
  return (colors ? CLR_SCENE_COLORS : 0u) | (materials ? CLR_SCENE_MATERIALS : 0u) |
         (materials && !oneMaterial ? CLR_SCENE_TRI_MATERIALS : 0u) | (textures ? CLR_SCENE_TEXTURES : 0u);
}

float DeviceScene::clusterMargin(const glm::mat4& mvp) const
{
  // M (setup_cluster_place): the largest sum of term magnitudes of a corner
  // of the scene's box, which bounds every vertex's and every cluster's.
  if (sceneMin_.x > sceneMax_.x) return 0.0f;
  float largest = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p(corner & 1 ? sceneMax_.x : sceneMin_.x, corner & 2 ? sceneMax_.y : sceneMin_.y,
                      corner & 4 ? sceneMax_.z : sceneMin_.z);
    float sum = 0.0f;
    for (int row = 0; row < 4; ++row)
      sum += std::abs(mvp[0][row] * p.x) + std::abs(mvp[1][row] * p.y) + std::abs(mvp[2][row] * p.z) +
             std::abs(mvp[3][row]);
    largest = std::max(largest, sum);
  }
  // The margin, 2^-16 M.
  return std::isfinite(largest) ? largest / 65536.0f : 0.0f;
}

}  // namespace clr
