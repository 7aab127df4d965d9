// procedural.cpp — generated benchmark scenes and views (see procedural.h).
#include "procedural.h"

#include "pipeline/cl.h"

#include <algorithm>
#include <cmath>

namespace clr::bench {

namespace {

// Radius of the displaced sphere in the unit direction d: 1 plus smooth bumps
// of a few wavelengths, at most 0.1 in all.
float displacedRadius(const glm::vec3& d)
{
  return 1.0f + 0.06f * std::sin(9.0f * d.x + 1.0f) * std::sin(7.0f * d.y + 2.0f) * std::sin(8.0f * d.z + 3.0f) +
         0.04f * std::sin(23.0f * d.x + 17.0f * d.y) * std::sin(19.0f * d.z + 0.5f);
}

glm::vec3 surfacePoint(const glm::vec3& direction)
{
  const glm::vec3 d = glm::normalize(direction);
  return d * displacedRadius(d);
}

// Outward normal of the displaced surface at unit direction d, by central
// differences along two tangents t1, t2 with t1 x t2 = d.
glm::vec3 surfaceNormal(const glm::vec3& d)
{
  const glm::vec3 axis = std::abs(d.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 t1 = glm::normalize(glm::cross(d, axis));
  const glm::vec3 t2 = glm::cross(d, t1);
  const float h = 1e-3f;
  const glm::vec3 du = surfacePoint(d + h * t1) - surfacePoint(d - h * t1);
  const glm::vec3 dv = surfacePoint(d + h * t2) - surfacePoint(d - h * t2);
  return glm::normalize(glm::cross(du, dv));
}

}  // namespace

BenchScene displacedSphere(size_t targetTriangles)
{
  // Step 1: grid resolution per cube face.
  const uint32_t n = std::max<uint32_t>(1, uint32_t(std::lround(std::sqrt(double(targetTriangles) / 12.0))));
  // Face frames (normal, u, v) with u x v = normal, so (i, j) -> (i+1, j) ->
  // (i+1, j+1) winds counter-clockwise seen from outside.
  const glm::vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  const glm::vec3 faces[6][3] = {{x, y, z}, {-x, z, y}, {y, z, x}, {-y, x, z}, {z, x, y}, {-z, y, x}};
  // Equal-angle coordinates, exactly -1 and 1 at the face edges so that seam
  // vertices of neighbouring faces are bit-identical.
  std::vector<float> coord(n + 1);
  for (uint32_t i = 0; i <= n; ++i)
    coord[i] = i == 0 ? -1.0f : i == n ? 1.0f : std::tan((2.0f * float(i) / float(n) - 1.0f) * 0.78539816f);

  // Step 2: vertices, with the analytic normals.
  BenchScene scene;
  Mesh& mesh = scene.mesh;
  const size_t perFace = size_t(n + 1) * (n + 1);
  mesh.positions.reserve(6 * perFace * 3);
  mesh.normals.reserve(6 * perFace * 3);
  for (const auto& face : faces)
    for (uint32_t j = 0; j <= n; ++j)
      for (uint32_t i = 0; i <= n; ++i) {
        const glm::vec3 d = glm::normalize(face[0] + coord[i] * face[1] + coord[j] * face[2]);
        const glm::vec3 p = d * displacedRadius(d), nrm = surfaceNormal(d);
        mesh.positions.insert(mesh.positions.end(), {p.x, p.y, p.z});
        mesh.normals.insert(mesh.normals.end(), {nrm.x, nrm.y, nrm.z});
      }

  // Step 3: two triangles per grid cell.
  mesh.indices.reserve(size_t(12) * n * n);
  for (uint32_t f = 0; f < 6; ++f)
    for (uint32_t j = 0; j < n; ++j)
      for (uint32_t i = 0; i < n; ++i) {
        const uint32_t a = uint32_t(f * perFace + size_t(j) * (n + 1) + i), b = a + 1, c = a + n + 2, d = a + n + 1;
        mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
      }
  scene.focus = meshBounds(mesh);
  return scene;
}

BenchScene instancedGrid(const Mesh& mesh, uint32_t copiesPerSide)
{
  // Step 1: spacing from the mesh's extent.
  const Bounds b = meshBounds(mesh);
  if (b.empty) throw Error("--grid: the mesh has no finite vertex");
  const glm::vec3 extent = b.max - b.min;
  const float spacing = 1.5f * std::max({extent.x, extent.y, extent.z, 1e-6f});
  const uint64_t copies = uint64_t(copiesPerSide) * copiesPerSide;
  if (copies * mesh.numVerts() > UINT32_MAX) throw Error("--grid: too many vertices for 32-bit indices");

  // Step 2: copies in row-major order, indices offset per copy.
  BenchScene scene;
  Mesh& out = scene.mesh;
  out.positions.reserve(copies * mesh.positions.size());
  out.normals.reserve(copies * mesh.normals.size());
  out.indices.reserve(copies * mesh.indices.size());
  const float half = 0.5f * float(copiesPerSide - 1);
  for (uint32_t row = 0; row < copiesPerSide; ++row)
    for (uint32_t col = 0; col < copiesPerSide; ++col) {
      const glm::vec3 offset((float(col) - half) * spacing, 0.0f, (float(row) - half) * spacing);
      const uint32_t base = uint32_t(out.numVerts());
      for (size_t v = 0; v < mesh.numVerts(); ++v)
        for (int k = 0; k < 3; ++k) out.positions.push_back(mesh.positions[3 * v + k] + offset[k]);
      out.normals.insert(out.normals.end(), mesh.normals.begin(), mesh.normals.end());
      for (uint32_t i : mesh.indices) out.indices.push_back(base + i);
    }

  // Step 3: the focus is the copy nearest the centre.
  const uint32_t centre = copiesPerSide / 2;
  const glm::vec3 offset((float(centre) - half) * spacing, 0.0f, (float(centre) - half) * spacing);
  scene.focus.min = b.min + offset;
  scene.focus.max = b.max + offset;
  scene.focus.empty = false;
  return scene;
}

Camera benchCamera(const BenchScene& scene, const std::string& view, uint32_t width, uint32_t height)
{
  const Bounds all = meshBounds(scene.mesh);
  if (view == "far") return frameCamera(CameraArgs{}, all);
  if (view == "away") {
    // The far camera turned round: the whole scene behind the eye, nothing in view.
    const Camera far = frameCamera(CameraArgs{}, all);
    CameraArgs args;
    args.eye = far.eye;
    args.target = far.eye + (far.eye - far.target);
    args.zNear = far.zNear;
    args.zFar = far.zFar;
    return frameCamera(args, all);
  }
  if (view == "fill") {
    // The far camera moved along its line of sight until the vertices'
    // projection reaches 90% of the way to the viewport's nearest border
    // from its centre: projected size goes roughly as 1/distance, so a few
    // steps of distance · reach / 0.9 settle it.
    Camera camera = frameCamera(CameraArgs{}, all);
    for (int step = 0; step < 5; ++step) {
      const glm::mat4 mvp = camera.viewProjection(width, height);
      float reach = 0.0f;
      for (size_t v = 0; v + 2 < scene.mesh.positions.size(); v += 3) {
        const glm::vec4 c =
            mvp * glm::vec4(scene.mesh.positions[v], scene.mesh.positions[v + 1], scene.mesh.positions[v + 2], 1.0f);
        if (c.w > 0.0f) reach = std::max(reach, std::max(std::abs(c.x), std::abs(c.y)) / c.w);
      }
      if (!(reach > 0.0f)) break;
      CameraArgs args;
      args.target = camera.target;
      args.eye = camera.target + (camera.eye - camera.target) * (reach / 0.9f);
      camera = frameCamera(args, all);
    }
    return camera;
  }
  if (view != "near") throw Error("--view: '" + view + "' is not far, fill, near or away");
  // The eye 0.75 focus radii from the focus centre, on the CLI's default
  // viewing diagonal; near and far planes from the whole scene's extent.
  const glm::vec3 centre = 0.5f * (scene.focus.min + scene.focus.max);
  const float radius = std::max(0.5f * glm::length(scene.focus.max - scene.focus.min), 1e-6f);
  const float sceneRadius = std::max(0.5f * glm::length(all.max - all.min), radius);
  CameraArgs args;
  args.target = centre;
  args.eye = centre + 0.75f * radius * glm::normalize(glm::vec3(0.55f, 0.45f, 1.0f));
  args.zNear = 0.01f * radius;
  args.zFar = glm::length(0.5f * (all.min + all.max) - *args.eye) + 1.5f * sceneRadius;
  return frameCamera(args, all);
}

}  // namespace clr::bench
