// fast_gltf.h — a direct, strict reader for the plain GLB and glTF file.
//
// It fills a Mesh exactly as the assimp path would (scene.cpp with assimp
// 5.2's glTF2 importer): the default scene's nodes walked depth first with
// their transforms (matrix, or translation, rotation and scale) applied as
// scene.cpp applies them, each node's mesh appended primitive by primitive,
// texture coordinates with v flipped, materials in the order assimp
// retrieves them (first use in the scene's node walk, children before the
// node's own mesh) with their baseColorFactor, and assimp's default material
// last.
//
// Accepted: one binary buffer: a GLB's BIN chunk, or for a text .gltf a
// file named by a plain relative uri (opened under the model-folder rule,
// asset_root.h) or a base64 data uri; float POSITION, NORMAL and
// TEXCOORD_0 accessors, packed or interleaved; u8, u16 or u32 indices, or none;
// triangle primitives; nodes with a mesh, children and a transform;
// materials with a baseColorFactor and a baseColorTexture embedded in the
// buffer or a file named by a plain relative uri, which scene.cpp opens as
// for assimp's import (its sampler's wrap modes). Any other file (image data uris, skins, morph
// targets, cameras, extensions, sparse accessors, a JSON
// number assimp's parser could round otherwise, an index out of range)
// returns false without a word: assimp reads it, so every refusal keeps its
// wording.
#pragma once

#include "io/asset_root.h"
#include "io/scene.h"

#include <string>

namespace clr {

// Reads `bytes`, the whole GLB file at `path`, into `mesh` (empty on
// entry), its embedded textures decoded as scene.cpp decodes them under
// `root`; normals repaired (normals.h). false: not read here, `mesh` left
// empty.
bool readPlainGlb(const std::string& path, const std::string& bytes, const AssetRoot& root, Mesh& mesh);
// The same for `bytes`, the whole text glTF file at `path`; its buffer file
// read once, under `root`. A buffer it cannot open is assimp's to refuse.
bool readPlainGltf(const std::string& path, const std::string& bytes, const AssetRoot& root, Mesh& mesh);

}  // namespace clr
