// layout.h — the scene's memory layout on the device, made once at upload.
//
// Real meshes often store their triangles in no spatial order (scans, files
// rewritten by tools), and then every stage's loads miss the caches
// (docs/architecture.md, "Scene layout and locality"). layOutScene returns a
// copy of a mesh with its triangles in spatial order (meshoptimizer's Morton
// sort of the centroids, meshopt_spatialSortRemap, as
// meshopt_spatialSortTriangles does) and its vertices welded (weldVertices,
// where that pays: see layOutScene) and in first-use order
// (meshopt_optimizeVertexFetchRemap; vertices no triangle uses follow, so
// none is dropped). fileTri maps each laid-out triangle to its index in the
// file, laidVertex each file vertex to the laid-out one: what a user sees
// (--shade id, the triangle_id AOV, depth ties, read-backs) speaks of the
// file's order through them. The same geometry, attributes and materials,
// bit for bit, only reordered and shared; an identity layout when `enabled`
// is false.
#pragma once

#include "io/scene.h"

#include <cstdint>
#include <vector>

namespace clr {

struct SceneLayout {
  Mesh mesh;                         // the laid-out copy
  std::vector<uint32_t> fileTri;     // laid-out triangle -> the file's triangle
  std::vector<uint32_t> fileVertex;  // laid-out vertex -> the first file vertex it stands for
  std::vector<uint32_t> laidVertex;  // file vertex -> laid-out vertex
};

SceneLayout layOutScene(const Mesh& file, bool enabled = true);
// The same from a mesh the layout may consume: each of its arrays is freed
// once laid out, so that the two copies of the scene never coexist whole;
// texture coordinates that are all +0 are dropped (an absent array reads
// as zeros).
SceneLayout layOutScene(Mesh&& file, bool enabled = true);

// Vertices equal in every attribute (position, normal, texture coordinates,
// colour), bit for bit, as one (meshopt_generateVertexRemapMulti): assimp
// gives each face of an OBJ, STL or Blender file vertices of its own, which
// a frame would otherwise hold and gather two or three times over. Sets
// weld[file vertex] = its distinct vertex, numbered in order of first
// appearance, and returns how many there are. The layout's weld starts from
// a mesh's MeshFacts::weldClasses where every vertex proves equal to its
// class's first, welding only those first vertices: the same result.
size_t weldVertices(const Mesh& mesh, std::vector<uint32_t>& weld);

// A copy of a mesh with its triangles in a random order (a Fisher-Yates
// shuffle from mt19937(seed), the same on every platform) and each
// triangle's vertices as they were: a file in no spatial order, for the
// bench and the tests.
Mesh shuffledTriangles(const Mesh& mesh, uint32_t seed);

}  // namespace clr
