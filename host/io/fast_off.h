// fast_off.h — a direct reader for plain OFF text, as large meshes come:
// a first line "OFF", then blank or '#' comment lines, a line of exactly
// three counts (vertices, faces, edges), blank or comment lines, then one
// line of exactly three decimal coordinates per vertex and one line
// "k i1 .. ik" (3 <= k <= 9, indices in range) per face, nothing after the
// faces but white space; lines end in '\n' or "\r\n".
//
// It fills a Mesh exactly as the assimp path would (scene.cpp with
// exact_positions.h): positions correctly rounded (-0 as +0), vertices as
// the file lists them, polygons fan-triangulated in file order, texture
// coordinates (0, 0), no colours, one material of the built-in grey. Any
// other file, and any doubt (a blank line inside the body, a coordinate
// that is not a whole decimal number, non-finite or beyond 1e18, an index
// out of range, counts that do not match the lines), returns false without
// a word: assimp reads it, so every refusal keeps its message. The body is
// parsed in line-aligned parts on every core (text_scan.h). Normals are
// left for the caller (repairNormals).
#pragma once

#include "io/scene.h"

#include <string>

namespace clr {

// Reads `bytes`, a whole .off file, into `mesh` (empty on entry); false:
// not read here, `mesh` left empty.
bool readPlainOff(const std::string& bytes, Mesh& mesh);

// The body shared with ASCII PLY (fast_ply.h): from `body` to `end`,
// exactly `vertices` lines of three coordinates, then `faces` lines
// "k i1 .. ik" (3 <= k <= maxCorners), then white space, checked and
// read as above into out.positions and out.indices (fan-triangulated);
// false: not read, `out` to be discarded.
bool readVertexFaceLines(const char* body, const char* end, uint64_t vertices, uint64_t faces, uint64_t maxCorners,
                         Mesh& out);

}  // namespace clr
