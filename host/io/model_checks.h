// model_checks.h — checks that run on a model file before assimp reads it.
//
// The checks follow the reader assimp will actually choose, found by the
// same rule as Importer::ReadFile (extension, then content), not by the
// file's extension alone. Assimp 5.2 trusts some fields of a file it should not: a PLY reader that
// loops forever on a malformed header, counts allocated before any data is
// read (OFF, PLY), glTF accessors copied into fixed-size vectors whatever
// their declared type (an overflow or uninitialised coordinates), and a
// recursive JSON parser. Each check reads only the file's header or JSON and
// throws clr::Error naming the file and the problem; a file that passes is
// left to assimp. docs/limits.md, "Hostile files", lists what is guarded.
#pragma once

#include <cstdint>
#include <string>

namespace Assimp {
class Importer;
class IOSystem;
}  // namespace Assimp

namespace clr {

// The reader assimp will choose for a file, chosen as assimp chooses it:
// by the file's extension where one importer lists it, else by content.
struct ModelReader {
  int importer = -1;         // assimp's importer index; -1: none reads it
  bool byExtension = false;  // chosen by the extension alone
  std::string format;        // "ply", "off", "obj", "stl", "gltf" (glTF 1 or 2, GLB too), or "" for any other
};

// Runs the checks of the reader assimp will choose for `bytes`, the one
// read of the file at `path`; `io` must serve those bytes for `path`.
ModelReader checkModelFile(const std::string& path, const std::string& bytes, const Assimp::Importer& importer,
                           Assimp::IOSystem& io);

// `s` with control characters (newlines included) replaced by spaces and
// trailing spaces removed: text from a file or from assimp, made fit for a
// one-line message.
std::string oneLine(std::string s);

}  // namespace clr
