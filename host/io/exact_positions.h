// exact_positions.h — vertex positions of text models read correctly
// rounded.
//
// Assimp's OBJ, OFF, ASCII PLY and ASCII STL readers parse numbers with
// fast_atof, which is not correctly rounded (about one coordinate in six of
// a 7-decimal grid comes out one ulp off). So clraster reads the position
// coordinates of such a file itself, with std::from_chars, and hands assimp
// the file's text with each vertex's coordinates replaced by integers that
// encode the vertex's number in the file (exact in float): assimp does
// everything else (faces, groups, materials, texture coordinates, normals),
// and afterwards every mesh vertex's encoded number is swapped for the
// position read here. A mesh vertex that does not carry a valid number, or
// an import by another importer than the one the text was prepared for, is
// a clr::Error: the two readers are never mixed. The scanners follow assimp
// 5.2's own tokenisation of each format, so each rewrites exactly the
// numbers assimp reads as positions; a coordinate that is not a whole
// decimal number is an error rather than a guess at assimp's prefix parse.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

struct aiScene;
namespace Assimp {
class Importer;
}

namespace clr {

struct ExactPositions {
  bool checked = false;          // the extension names a text format
  int importer = -1;             // assimp's importer index for the format; -1: nothing prepared
  std::string format;            // "OBJ", "OFF", "PLY", "STL"
  std::string text;              // what assimp reads instead of the file
  std::vector<float> positions;  // 3 per file vertex, correctly rounded
};

// Prepares `bytes`, the model at `path`, when assimp reads it with one of
// the four text formats' importers (`format`, model_checks.h; for PLY and
// STL, when the file is ASCII); otherwise returns an empty one. A file that
// assimp reads with one of them by its content, not its extension, is
// refused before the import.
ExactPositions prepareExactPositions(const std::string& path, const std::string& bytes, const std::string& format,
                                     bool byExtension, const Assimp::Importer& importer);

// After the import: puts the positions in place of the encoded numbers.
// Also refuses a file that assimp read with one of the four text importers
// although it was not prepared for it (another extension).
void applyExactPositions(const std::string& path, const ExactPositions& exact, const Assimp::Importer& importer,
                         const aiScene& scene);

}  // namespace clr
