// layout.cpp — layOutScene (layout.h): the spatial order of the triangles,
// the welded vertices in first-use order, from meshoptimizer.
#include "pipeline/layout.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace clr {

// How much longer than the sorted order's the file's mean step between
// consecutive triangles may be for the file to keep its order.
constexpr double kCoherentSteps = 8.0;
// How many sorted triangles' vertices show whether welding pays (weldPays).
constexpr size_t kWeldSample = 16384;

// Copies per-element arrays (`width` values per element) into the new order.
template <typename T>
static std::vector<T> gather(const std::vector<T>& from, const std::vector<uint32_t>& order, size_t width)
{
  if (from.empty()) return {};
  std::vector<T> out(order.size() * width);
  for (size_t i = 0; i < order.size(); ++i)
    for (size_t k = 0; k < width; ++k) out[i * width + k] = from[size_t(order[i]) * width + k];
  return out;
}

// The mean distance between consecutive centroids in `order`.
static double meanStep(const std::vector<float>& centroids, const std::vector<uint32_t>& order)
{
  double sum = 0;
  for (size_t i = 1; i < order.size(); ++i) {
    const float* a = &centroids[3 * size_t(order[i - 1])];
    const float* b = &centroids[3 * size_t(order[i])];
    sum += std::sqrt(double(a[0] - b[0]) * (a[0] - b[0]) + double(a[1] - b[1]) * (a[1] - b[1]) +
                     double(a[2] - b[2]) * (a[2] - b[2]));
  }
  return order.size() > 1 ? sum / double(order.size() - 1) : 0.0;
}

size_t weldVertices(const Mesh& mesh, std::vector<uint32_t>& weld)
{
  const size_t verts = mesh.numVerts();
  std::vector<meshopt_Stream> streams = {{mesh.positions.data(), 3 * sizeof(float), 3 * sizeof(float)}};
  if (!mesh.normals.empty()) streams.push_back({mesh.normals.data(), 3 * sizeof(float), 3 * sizeof(float)});
  if (!mesh.uvs.empty()) streams.push_back({mesh.uvs.data(), 2 * sizeof(float), 2 * sizeof(float)});
  if (!mesh.colors.empty()) streams.push_back({mesh.colors.data(), 4 * sizeof(float), 4 * sizeof(float)});
  // Each vertex once, padded with vertex 0 to whole triangles (meshoptimizer asks for them), so the welded
  // vertices follow the first of each in the file's order and none is dropped.
  std::vector<uint32_t> every(verts + 2, 0);
  std::iota(every.begin(), every.begin() + verts, 0u);
  weld.assign(verts, 0);
  if (verts == 0) return 0;
  return meshopt_generateVertexRemapMulti(weld.data(), every.data(), verts + 2 - (verts + 2) % 3, verts, streams.data(),
                                          streams.size());
}

// Whether welding pays: in a mesh of more vertices than triangles (faces with vertices of their own have two or three
// per triangle, a shared mesh about half of one), whose vertices of the first kWeldSample sorted triangles (neighbours
// in space, whatever the file's order) weld by at least a 64th (an STL file's facet normals keep its vertices apart).
// The weld's pass over every vertex would otherwise cost a large upload a third more for nothing.
static bool weldPays(const Mesh& file, const std::vector<uint32_t>& sortedIndices)
{
  if (file.numVerts() <= file.numTris()) return false;
  std::vector<uint32_t> ids(sortedIndices.begin(),
                            sortedIndices.begin() + std::min(sortedIndices.size(), 3 * kWeldSample));
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  Mesh sample;
  sample.positions = gather(file.positions, ids, 3);
  sample.normals = gather(file.normals, ids, 3);
  sample.uvs = gather(file.uvs, ids, 2);
  sample.colors = gather(file.colors, ids, 4);
  std::vector<uint32_t> weld;
  return weldVertices(sample, weld) < ids.size() - ids.size() / 64;
}

SceneLayout layOutScene(const Mesh& file, bool enabled)
{
  SceneLayout out;
  const size_t tris = file.numTris(), verts = file.numVerts();
  out.fileTri.resize(tris);
  std::iota(out.fileTri.begin(), out.fileTri.end(), 0u);
  // An index past the vertices (the loader rejects such files) keeps the
  // file's order: meshoptimizer may not see it.
  for (uint32_t i : file.indices) enabled = enabled && i < verts;
  if (!enabled || tris < 2) {
    out.mesh = file;
    out.fileVertex.resize(verts);
    std::iota(out.fileVertex.begin(), out.fileVertex.end(), 0u);
    out.laidVertex = out.fileVertex;
    return out;
  }
  // Step 1: the triangles by the Morton order of their centroids (a
  // centroid that is not finite sorts as the origin).
  std::vector<float> centroids(3 * tris);
  for (size_t t = 0; t < tris; ++t)
    for (int a = 0; a < 3; ++a) {
      float sum = 0.0f;
      for (int v = 0; v < 3; ++v) sum += file.positions[3 * size_t(file.indices[3 * t + v]) + a];
      centroids[3 * t + a] = std::isfinite(sum) ? sum / 3.0f : 0.0f;
    }
  std::vector<uint32_t> newTri(tris);  // file triangle -> laid-out
  meshopt_spatialSortRemap(newTri.data(), centroids.data(), tris, 3 * sizeof(float));
  std::vector<uint32_t> sorted(tris);
  for (size_t t = 0; t < tris; ++t) sorted[newTri[t]] = uint32_t(t);
  // A file whose triangles already step between near neighbours keeps its
  // order (docs/architecture.md, "Scene layout and locality": the sort
  // slowed raster on such a file, whose order also served the depth skip).
  const double fileStep = meanStep(centroids, out.fileTri), sortedStep = meanStep(centroids, sorted);
  if (!(fileStep <= kCoherentSteps * sortedStep)) out.fileTri = std::move(sorted);
  std::vector<uint32_t> sortedIndices = gather(file.indices, out.fileTri, 3);
  // Step 2: vertices equal in every attribute become one, where that pays (weldPays).
  std::vector<uint32_t> weld;  // file vertex -> welded; empty: none welded
  size_t unique = verts;
  if (weldPays(file, sortedIndices)) {
    unique = weldVertices(file, weld);
    for (uint32_t& i : sortedIndices) i = weld[i];
  }
  // Step 3: the welded vertices in the order the sorted triangles first use them, then the unused ones.
  std::vector<uint32_t> newVertex(unique);  // welded vertex -> laid-out, ~0u unused
  size_t used = meshopt_optimizeVertexFetchRemap(newVertex.data(), sortedIndices.data(), sortedIndices.size(), unique);
  for (size_t v = 0; v < unique; ++v)
    if (newVertex[v] == ~0u) newVertex[v] = uint32_t(used++);
  out.fileVertex.resize(unique);
  out.laidVertex.resize(verts);
  for (size_t v = verts; v-- > 0;) {  // the first file vertex of each laid-out one
    out.laidVertex[v] = newVertex[weld.empty() ? v : weld[v]];
    out.fileVertex[out.laidVertex[v]] = uint32_t(v);
  }
  for (uint32_t& i : sortedIndices) i = newVertex[i];
  // Step 4: the copy, field by field: a copy of the whole mesh first would also copy (and page in) the arrays
  // replaced here, a quarter of a 10M-triangle upload's time.
  static_assert(sizeof(Mesh) == 10 * sizeof(std::vector<float>) + sizeof(Warnings) + sizeof(MeshFacts),
                "a new Mesh field must be copied or reordered here");
  Mesh& m = out.mesh;
  m.lines = file.lines;
  m.points = file.points;
  m.materials = file.materials;
  m.textures = file.textures;
  m.warnings = file.warnings;
  m.facts = file.facts;
  m.indices = std::move(sortedIndices);
  m.positions = gather(file.positions, out.fileVertex, 3);
  m.normals = gather(file.normals, out.fileVertex, 3);
  m.uvs = gather(file.uvs, out.fileVertex, 2);
  m.colors = gather(file.colors, out.fileVertex, 4);
  m.triMaterial = gather(file.triMaterial, out.fileTri, 1);
  for (uint32_t& v : m.lines) v = out.laidVertex[v];  // a file's own lines and points name vertices too
  for (uint32_t& v : m.points) v = out.laidVertex[v];
  return out;
}

Mesh shuffledTriangles(const Mesh& mesh, uint32_t seed)
{
  std::vector<uint32_t> order(mesh.numTris());
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937 random(seed);
  for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[random() % i]);
  Mesh out = mesh;
  out.indices = gather(mesh.indices, order, 3);
  out.triMaterial = gather(mesh.triMaterial, order, 1);
  return out;
}

}  // namespace clr
