// fast_ply.h — direct readers for the plainest PLY, the format large scans
// come in. Binary: little-endian, one element "vertex" of float x, y, z
// and nothing else, one element "face" of one list (uchar or uint8 count,
// int, int32, uint or uint32 indices) named vertex_indices or
// vertex_index, header lines ending in '\n'.
//
// It fills a Mesh exactly as the assimp path would (scene.cpp): positions
// as the identity node transform leaves them (-0 as +0), polygons
// fan-triangulated in file order, texture coordinates (0, 0), no colours,
// one material of the built-in grey. Any other file, and any file with a
// doubt (a face of fewer than 3 vertices, an index out of range, a
// non-finite or huge coordinate, a body not exactly the header's size),
// returns false without a word: assimp reads it, so every refusal keeps its
// message. Normals are left empty for the caller (repairNormals).
#pragma once

#include "io/scene.h"

#include <string>

namespace clr {

// Reads `bytes`, a whole file, into `mesh` (empty on entry); false: not
// read here, `mesh` left empty.
bool readPlainBinaryPly(const std::string& bytes, Mesh& mesh);

// The same header with "format ascii 1.0", and a body of one line per
// vertex (three decimal coordinates, correctly rounded) and per face
// ("k i1 .. ik", 3 <= k <= 255), lines ending in '\n' or "\r\n", read as
// fast_off.h reads OFF's body (line-aligned parts on every core); the same
// mesh and the same refusals as the binary reader.
bool readPlainAsciiPly(const std::string& bytes, Mesh& mesh);

// What the assimp path adds to a mesh of positions and triangles from a
// file without texture coordinates, colours or materials (PLY, OFF, STL):
// normals zero where `mesh` has none, texture coordinates (0, 0), every
// triangle of material 0, the built-in grey. The direct readers share it.
void addImportDefaults(Mesh& mesh);

}  // namespace clr
