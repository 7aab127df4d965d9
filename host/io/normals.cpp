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

void repairNormals(Mesh& mesh, const std::string& path, bool fileHasNormals, const PositionIndex* hint)
{
  mesh.facts.normalsInFile = fileHasNormals;
  mesh.facts.normalsRepaired = 0;
  // Step 1: the vertices triangles use, and how many of them have an unusable normal.
  const size_t n = mesh.numVerts();
  std::vector<bool> used(n, false);
  for (uint32_t i : mesh.indices) used[i] = true;
  mesh.normals.resize(3 * n, 0.0f);
  size_t usedCount = 0, brokenCount = 0;
  for (size_t v = 0; v < n; ++v)
    if (used[v]) {
      ++usedCount;
      if (!usable(&mesh.normals[3 * v])) ++brokenCount;
    }
  if (brokenCount == 0) return;
  // Step 2: smoothed normals for all, kept only where the file's failed:
  // the file's normals of the other vertices are set aside and put back.
  std::vector<uint32_t> kept;
  std::vector<float> keptNormals;
  for (size_t v = 0; v < n; ++v)
    if (!used[v] || usable(&mesh.normals[3 * v])) {
      kept.push_back(uint32_t(v));
      keptNormals.insert(keptNormals.end(), &mesh.normals[3 * v], &mesh.normals[3 * v] + 3);
    }
  computeSmoothNormals(mesh, hint);
  for (size_t i = 0; i < kept.size(); ++i)
    for (int k = 0; k < 3; ++k) mesh.normals[3 * size_t(kept[i]) + k] = keptNormals[3 * i + k];
  // A kept normal may differ from its class's: the layout would check the classes in vain.
  if (!kept.empty()) mesh.facts.weldClasses = {}, mesh.facts.weldClassCount = 0;
  size_t replaced = 0;
  for (size_t v = 0; v < n; ++v)
    if (used[v] && usable(&mesh.normals[3 * v])) ++replaced;
  replaced -= usedCount - brokenCount;  // the used vertices whose file normal was kept
  if (!fileHasNormals || replaced == 0) return;
  mesh.facts.normalsRepaired = replaced;
  mesh.warnings.add("normals", userText(path) + ": " + std::to_string(replaced) + " of " + std::to_string(n) +
                                   " vertex normals were zero, NaN or missing; recomputed from the geometry");
}

}  // namespace clr
