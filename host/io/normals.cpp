// normals.cpp — vertex normal repair (see normals.h).
#include "io/normals.h"

#include <cmath>

namespace clr {

namespace {

// A normal the shading can use: finite and of non-zero length.
bool usable(const float* n)
{
  const float len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  return std::isfinite(len2) && len2 > 0.0f;
}

}  // namespace

void repairNormals(Mesh& mesh, const std::string& path, bool fileHasNormals)
{
  mesh.facts.normalsInFile = fileHasNormals;
  mesh.facts.normalsRepaired = 0;
  // Step 1: the vertices triangles use whose normal is unusable.
  const size_t n = mesh.numVerts();
  std::vector<bool> used(n, false);
  for (uint32_t i : mesh.indices) used[i] = true;
  mesh.normals.resize(3 * n, 0.0f);
  std::vector<size_t> broken;
  for (size_t v = 0; v < n; ++v)
    if (used[v] && !usable(&mesh.normals[3 * v])) broken.push_back(v);
  if (broken.empty()) return;
  // Step 2: smoothed normals for all, kept only where the file's failed.
  std::vector<float> fromFile = mesh.normals;
  computeSmoothNormals(mesh);
  std::swap(fromFile, mesh.normals);
  size_t replaced = 0;
  for (size_t v : broken) {
    for (int k = 0; k < 3; ++k) mesh.normals[3 * v + k] = fromFile[3 * v + k];
    if (usable(&mesh.normals[3 * v])) ++replaced;
  }
  if (!fileHasNormals || replaced == 0) return;
  mesh.facts.normalsRepaired = replaced;
  mesh.warnings.add("normals", userText(path) + ": " + std::to_string(replaced) + " of " + std::to_string(n) +
                                   " vertex normals were zero, NaN or missing; recomputed from the geometry");
}

}  // namespace clr
