// fast_obj.h — a direct, strict reader for the plain OBJ file, the text
// format large meshes are most often exchanged in.
//
// It fills a Mesh exactly as the assimp path would (scene.cpp with assimp
// 5.2's ObjFileImporter): meshes split where assimp splits them (o, g and
// usemtl, one mesh per object and material), vertices un-shared per face
// corner in file order, polygons fan-triangulated, positions correctly
// rounded (as exact_positions.h reads them), normals, texture coordinates
// and vertex colours as assimp's fast_atof reads them, the materials of the
// mtllib libraries (mtl.h) converted as scene.cpp converts assimp's, their
// textures read under the model-folder rule (asset_root.h). The text is
// parsed in line-aligned chunks on every core.
//
// Accepted: v (x y z, or x y z r g b on every v line), vt, vn, f of 3 or
// more corners all of one form (v, v/vt, v//vn or v/vt/vn, negative indices
// too), o, g, s, usemtl, mtllib, comments, LF or CRLF line ends. Any other
// statement (l, p, curves, a line continued with '\'), any doubt (an index
// out of range, a number assimp would read differently, a library that
// cannot be read) returns false without a word: assimp reads the file, so
// every refusal and warning keeps its wording.
#pragma once

#include "io/asset_root.h"
#include "io/scene.h"

#include <string>

namespace clr {

// Reads `bytes`, the whole OBJ file at `path`, into `mesh` (empty on
// entry), its libraries and textures under `root`; normals repaired
// (normals.h). false: not read here, `mesh` left empty. Throws what the
// assimp path would throw for the same file (a texture named "*0").
bool readPlainObj(const std::string& path, const std::string& bytes, const AssetRoot& root, Mesh& mesh);

}  // namespace clr
