// procedural.h — the benchmark suite's generated scenes and its two views.
//
// displacedSphere(T) is a cube-sphere (six n x n grids, equal-angle mapping, n = round(sqrt(T / 12)), so 12 n^2
// triangles, within 1% of T for T >= 10^4) whose radius is displaced by a smooth sum of sines; normals are the analytic
// surface's, by central differences, so copies of a seam vertex get the same normal. instancedGrid(mesh, n) places n x
// n copies of a mesh on the x-z plane, 1.5 extents apart. Both return the scene with a focus: the bounds a "near" view
// looks at (the whole sphere, the central copy).
//
// Views: "far" frames the whole scene as the CLI does (mostly small triangles; an elongated mesh covers a few percent
// of the screen); "fill" moves that camera closer until the scene's projection reaches 90% of the way to the viewport's
// nearest border (the mesh fills a good part of the screen); "near" puts the eye at 0.75 focus radii from the focus
// centre (mostly large triangles, the near plane clips some).
#pragma once

#include "render/camera.h"
#include "io/scene.h"

#include <string>

namespace clr::bench {

struct BenchScene {
  Mesh mesh;
  Bounds focus;  // what the near view looks at
};

BenchScene displacedSphere(size_t targetTriangles);

BenchScene instancedGrid(const Mesh& mesh, uint32_t copiesPerSide);

// view: "far", "fill" or "near" (fill frames for a width x height
// viewport); anything else is a clr::Error.
Camera benchCamera(const BenchScene& scene, const std::string& view, uint32_t width, uint32_t height);

}  // namespace clr::bench
