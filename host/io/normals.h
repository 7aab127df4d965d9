// normals.h — repair of a loaded mesh's vertex normals.
//
// A file's normals may be absent (per mesh), zero (STL writers that leave
// the facet normal (0,0,0)) or NaN. Every such normal of a vertex that a
// triangle uses is replaced by the area-weighted normal smoothed over
// vertices at the same position (computeSmoothNormals, scene.h); good
// normals are kept as the file gives them. The flat mode needs none: it
// lights each triangle with its face normal (resolve.cl).
#pragma once

#include "io/scene.h"

#include <string>

namespace clr {

// Repairs mesh.normals in place and records the count in mesh.facts. When
// the file had normals (fileHasNormals) and some were replaced, one warning
// naming `path` and the count goes to mesh.warnings; a file with none at
// all gets smoothed normals without a warning. `hint` (scene.h) as
// computeSmoothNormals takes it.
void repairNormals(Mesh& mesh, const std::string& path, bool fileHasNormals, const PositionIndex* hint = nullptr);

}  // namespace clr
