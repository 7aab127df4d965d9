// import_budget.h — one memory budget for a scene's import, counted from
// what the files declare before any reader allocates it.
//
// A small file can ask assimp for gigabytes: a glTF accessor's declared
// count (a sparse one needs no bytes behind it), many buffers naming one
// large file, thousands of materials or groups, each of which costs tens of
// kilobytes whatever its triangles. Each check here estimates the import's
// memory from counts read off the file (per-item costs measured on assimp
// 5.2, the loader's own copies included) and throws a clr::Error naming the
// file and the limit when the estimate is over kImportBudgetBytes, or a
// count over its own limit. docs/limits.md, "Import memory budget", lists
// the limits and the costs.
#pragma once

#include <cstdint>
#include <string>

namespace clr {

inline constexpr uint64_t kImportBudgetBytes = uint64_t(4) << 30;  // an import's estimated peak
inline constexpr uint64_t kReferencedBytes = uint64_t(1) << 30;    // the files a model names, together
inline constexpr uint64_t kMaxMaterials = 4096;                    // assimp's OBJ materials cost time quadratically

// An OBJ's text: vertices, face corners, groups (o, g, usemtl switches) and
// distinct usemtl names, against the budget and kMaxMaterials.
void checkObjBudget(const std::string& path, const std::string& text);
// The number of materials (newmtl lines) in an OBJ material library's text.
uint64_t countMaterials(const std::string& text);
// A glTF or GLB file's bytes (by content; anything else passes): every
// accessor's declared elements, sparse or not, and the meshes, primitives
// and nodes. `path` names the file in the error.
void checkGltfBudget(const std::string& path, const std::string& bytes);

// "PATH: WHAT, over the import budget of N MiB (docs/limits.md)".
std::string overBudget(const std::string& path, const std::string& what, uint64_t limitBytes);

}  // namespace clr
