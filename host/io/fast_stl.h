// fast_stl.h — a direct reader for plain STL, binary and ASCII.
//
// Binary: 80 header bytes (not starting with a byte order mark), the facet
// count, exactly that many 50-byte facets, none with a colour (attribute
// bit 15). ASCII: one or more solids, each "solid [name]", then facets of
// exactly the lines "facet normal nx ny nz", "outer loop", three
// "vertex x y z", "endloop", "endfacet", then "endsolid [name]"; blanks
// before and between words, lines ending in '\n' or "\r\n", nothing after
// the last solid but white space.
//
// It fills a Mesh exactly as the assimp path would (scene.cpp with
// exact_positions.h): three unshared vertices per facet in file order,
// positions correctly rounded (ASCII) or as stored (binary), -0 as +0, the
// facet normal on its three vertices as assimp reads it (ASCII normals
// through assimp's own fast_atof, so bit for bit), non-finite normals as
// zero, texture coordinates (0, 0), no colours, the built-in grey, and
// facts.normalsInFile set. Any other file, and any doubt (a non-finite or
// huge coordinate, a line out of the grammar, a solid of no facets, a size
// that does not match), returns false without a word: assimp reads it, so
// every refusal keeps its message. ASCII bodies are parsed in line-aligned
// parts on every core (text_scan.h). Zero normals are left for the caller
// (repairNormals).
#pragma once

#include "io/scene.h"

#include <string>

namespace clr {

// Reads `bytes`, a whole .stl file, into `mesh` (empty on entry); false:
// not read here, `mesh` left empty.
bool readPlainStl(const std::string& bytes, Mesh& mesh);

}  // namespace clr
