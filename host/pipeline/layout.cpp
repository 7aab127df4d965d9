// layout.cpp — layOutScene (layout.h): the spatial order of the triangles,
// the welded vertices in first-use order, from meshoptimizer.
#include "pipeline/layout.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <future>
#include <numeric>
#include <random>

namespace clr {

// How much longer than the sorted order's the file's mean step between
// consecutive triangles may be for the file to keep its order.
constexpr double kCoherentSteps = 8.0;
// How many sorted triangles' vertices show whether welding pays (weldPays).
constexpr size_t kWeldSample = 16384;
// How many elements ahead the passes of random reads fetch what they will read.
constexpr size_t kPrefetch = 16;
// Passes over at least this many elements run on two threads (inHalves).
constexpr size_t kParallelElements = 1 << 16;

// Copies per-element arrays (`width` values per element) into the new order.
template <typename T>
static std::vector<T> gather(const std::vector<T>& from, const std::vector<uint32_t>& order, size_t width)
{
  if (from.empty()) return {};
  std::vector<T> out(order.size() * width);
  for (size_t i = 0; i < order.size(); ++i) {
    if (i + kPrefetch < order.size()) __builtin_prefetch(&from[size_t(order[i + kPrefetch]) * width]);
    for (size_t k = 0; k < width; ++k) out[i * width + k] = from[size_t(order[i]) * width + k];
  }
  return out;
}

// The vertex attributes of `ids` (positions, normals, uvs, colours), no triangles.
static Mesh gatherVertices(const Mesh& mesh, const std::vector<uint32_t>& ids)
{
  Mesh out;
  out.positions = gather(mesh.positions, ids, 3);
  out.normals = gather(mesh.normals, ids, 3);
  out.uvs = gather(mesh.uvs, ids, 2);
  out.colors = gather(mesh.colors, ids, 4);
  return out;
}

// Runs work(lo, hi) over [0, n) in two halves on two threads, where n is large enough to pay.
template <typename Work>
static void inHalves(size_t n, const Work& work)
{
  if (n < kParallelElements) {
    work(size_t(0), n);
    return;
  }
  std::future<void> other = std::async(std::launch::async, [&] { work(n / 2, n); });
  work(size_t(0), n / 2);
  other.get();
}

// The mean distance between consecutive centroids in `order` (null: the file's order).
static double meanStep(const std::vector<float>& centroids, const std::vector<uint32_t>* order)
{
  const size_t n = centroids.size() / 3;
  auto at = [&](size_t i) { return order ? size_t((*order)[i]) : i; };
  double sum = 0;
  for (size_t i = 1; i < n; ++i) {
    if (order && i + kPrefetch < n) __builtin_prefetch(&centroids[3 * at(i + kPrefetch)]);
    const float* a = &centroids[3 * at(i - 1)];
    const float* b = &centroids[3 * at(i)];
    sum += std::sqrt(double(a[0] - b[0]) * (a[0] - b[0]) + double(a[1] - b[1]) * (a[1] - b[1]) +
                     double(a[2] - b[2]) * (a[2] - b[2]));
  }
  return n > 1 ? sum / double(n - 1) : 0.0;
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

// Whether vertices a and b are equal in every attribute, bit for bit.
static bool sameVertex(const Mesh& mesh, size_t a, size_t b)
{
  auto same = [&](const std::vector<float>& array, size_t width) {
    return array.empty() || std::memcmp(&array[a * width], &array[b * width], width * sizeof(float)) == 0;
  };
  return same(mesh.positions, 3) && same(mesh.normals, 3) && same(mesh.uvs, 2) && same(mesh.colors, 4);
}

// weldVertices' result from a hint (MeshFacts::weldClasses), or false where
// the hint does not hold. Every vertex is checked equal to the first vertex
// of its class, and those first vertices, in vertex order, are welded by
// meshoptimizer: v and w weld exactly when their classes' first vertices
// are equal, that is when v and w are; the first vertex of each welded one
// is a class's first, so the numbering (first appearance) is the same too.
static bool weldByClasses(const Mesh& mesh, std::vector<uint32_t>& weld, size_t& unique)
{
  const std::vector<uint32_t>& classes = mesh.facts.weldClasses;
  const size_t verts = mesh.numVerts(), count = mesh.facts.weldClassCount;
  if (classes.size() != verts || count == 0 || count > verts) return false;
  std::vector<uint32_t> first(count, ~0u), firsts;
  for (size_t v = 0; v < verts; ++v) {
    if (classes[v] >= count) return false;
    if (first[classes[v]] == ~0u) first[classes[v]] = uint32_t(v), firsts.push_back(uint32_t(v));
  }
  std::atomic<bool> hold{true};
  inHalves(verts, [&](size_t lo, size_t hi) {
    for (size_t v = lo; v < hi && hold; ++v)
      if (!sameVertex(mesh, v, first[classes[v]])) hold = false;
  });
  if (!hold) return false;
  Mesh sample = gatherVertices(mesh, firsts);
  std::vector<uint32_t> sampleWeld;
  unique = weldVertices(sample, sampleWeld);
  for (size_t i = 0; i < firsts.size(); ++i) first[classes[firsts[i]]] = sampleWeld[i];  // class -> welded
  weld.resize(verts);
  for (size_t v = 0; v < verts; ++v) weld[v] = first[classes[v]];
  return true;
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
  Mesh sample = gatherVertices(file, ids);
  std::vector<uint32_t> weld;
  return weldVertices(sample, weld) < ids.size() - ids.size() / 64;
}

// Frees an array of the mesh the layout owns (a no-op for a borrowed one):
// once its laid-out copy exists, the file's is not read again.
template <typename T>
static void release(Mesh* owned, std::vector<T> Mesh::*array)
{
  if (owned) std::vector<T>().swap(owned->*array);
}

// layOutScene's two forms: `file` borrowed (owned null), or owned (owned == &file), its arrays freed as they are laid
// out.
static SceneLayout layOut(const Mesh& file, Mesh* owned, bool enabled)
{
  // Texture coordinates that are all +0 read as absent ones do (device_scene.h): an owned mesh's are not laid out.
  if (owned && std::all_of(owned->uvs.begin(), owned->uvs.end(), [](float c) { return c == 0.0f && !std::signbit(c); }))
    std::vector<float>().swap(owned->uvs);
  SceneLayout out;
  const size_t tris = file.numTris(), verts = file.numVerts();
  // An index past the vertices (the loader rejects such files) keeps the
  // file's order: meshoptimizer may not see it.
  for (uint32_t i : file.indices) enabled = enabled && i < verts;
  if (!enabled || tris < 2) {
    out.mesh = owned ? std::move(*owned) : file;
    out.fileTri.resize(tris);
    std::iota(out.fileTri.begin(), out.fileTri.end(), 0u);
    out.fileVertex.resize(verts);
    std::iota(out.fileVertex.begin(), out.fileVertex.end(), 0u);
    out.laidVertex = out.fileVertex;
    return out;
  }
  // Step 1: the triangles by the Morton order of their centroids (a
  // centroid that is not finite sorts as the origin).
  std::vector<float> centroids(3 * tris);
  inHalves(tris, [&](size_t lo, size_t hi) {
    for (size_t t = lo; t < hi; ++t) {
      if (t + kPrefetch < hi)
        for (int v = 0; v < 3; ++v)
          __builtin_prefetch(&file.positions[3 * size_t(file.indices[3 * (t + kPrefetch) + v])]);
      for (int a = 0; a < 3; ++a) {
        float sum = 0.0f;
        for (int v = 0; v < 3; ++v) sum += file.positions[3 * size_t(file.indices[3 * t + v]) + a];
        centroids[3 * t + a] = std::isfinite(sum) ? sum / 3.0f : 0.0f;
      }
    }
  });
  // A file whose triangles already step between near neighbours keeps its
  // order (docs/architecture.md, "Scene layout and locality": the sort
  // slowed raster on such a file, whose order also served the depth skip).
  // The file's mean step is measured while the sort runs.
  // (Futures, not threads: an exception on either side reaches the caller once both are done.)
  std::future<double> fileStep = std::async(std::launch::async, [&] { return meanStep(centroids, nullptr); });
  std::vector<uint32_t> sorted;  // laid-out triangle -> file's
  {
    std::vector<uint32_t> newTri(tris);  // file triangle -> laid-out
    meshopt_spatialSortRemap(newTri.data(), centroids.data(), tris, 3 * sizeof(float));
    sorted.resize(tris);
    for (size_t t = 0; t < tris; ++t) sorted[newTri[t]] = uint32_t(t);
  }
  const double sortedStep = meanStep(centroids, &sorted);
  const bool keepFileOrder = fileStep.get() <= kCoherentSteps * sortedStep;
  std::vector<float>().swap(centroids);  // (v = {} would keep the capacity)
  if (!keepFileOrder) {
    out.fileTri = std::move(sorted);
  } else {
    out.fileTri.resize(tris);
    std::iota(out.fileTri.begin(), out.fileTri.end(), 0u);
  }
  std::vector<uint32_t>().swap(sorted);
  std::vector<uint32_t> sortedIndices = gather(file.indices, out.fileTri, 3);
  release(owned, &Mesh::indices);
  // Step 2: vertices equal in every attribute become one, where that pays (weldPays).
  std::vector<uint32_t> weld;  // file vertex -> welded; empty: none welded
  size_t unique = verts;
  if (weldPays(file, sortedIndices)) {
    if (!weldByClasses(file, weld, unique)) unique = weldVertices(file, weld);
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
  std::vector<uint32_t>().swap(weld);
  // Step 4: the copy, field by field (a copy of the whole mesh first would also copy, and page in, the arrays
  // replaced here), the triangles' arrays on a second thread.
  static_assert(sizeof(Mesh) == 10 * sizeof(std::vector<float>) + sizeof(Warnings) + sizeof(MeshFacts),
                "a new Mesh field must be copied or reordered here");
  Mesh& m = out.mesh;
  std::future<void> triangles = std::async(std::launch::async, [&] {
    for (uint32_t& i : sortedIndices) i = newVertex[i];
    m.indices = std::move(sortedIndices);
    m.triMaterial = gather(file.triMaterial, out.fileTri, 1);
    release(owned, &Mesh::triMaterial);
  });
  m.positions = gather(file.positions, out.fileVertex, 3);
  release(owned, &Mesh::positions);
  m.normals = gather(file.normals, out.fileVertex, 3);
  release(owned, &Mesh::normals);
  m.uvs = gather(file.uvs, out.fileVertex, 2);
  release(owned, &Mesh::uvs);
  m.colors = gather(file.colors, out.fileVertex, 4);
  release(owned, &Mesh::colors);
  triangles.get();
  if (owned) {
    m.lines = std::move(owned->lines);
    m.points = std::move(owned->points);
    m.materials = std::move(owned->materials);
    m.textures = std::move(owned->textures);
    m.warnings = std::move(owned->warnings);
    m.facts = std::move(owned->facts);
  } else {
    m.lines = file.lines;
    m.points = file.points;
    m.materials = file.materials;
    m.textures = file.textures;
    m.warnings = file.warnings;
    m.facts = file.facts;
  }
  m.facts.weldClasses = {}, m.facts.weldClassCount = 0;  // (of the file's vertices, not of these)
  for (uint32_t& v : m.lines) v = out.laidVertex[v];     // a file's own lines and points name vertices too
  for (uint32_t& v : m.points) v = out.laidVertex[v];
  return out;
}

SceneLayout layOutScene(const Mesh& file, bool enabled)
{
  return layOut(file, nullptr, enabled);
}

SceneLayout layOutScene(Mesh&& file, bool enabled)
{
  return layOut(file, &file, enabled);
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
