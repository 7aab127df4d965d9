// model_checks.h — checks that run on a model file before assimp reads it.
//
// Assimp 5.2 trusts some fields of a file it should not: a PLY reader that
// loops forever on a malformed header, counts allocated before any data is
// read (OFF, PLY), glTF accessors copied into fixed-size vectors whatever
// their declared type (an overflow or uninitialised coordinates), and a
// recursive JSON parser. Each check reads only the file's header or JSON and
// throws clr::Error naming the file and the problem; a file that passes is
// left to assimp. docs/limits.md, "Hostile files", lists what is guarded.
#pragma once

#include <cstdint>
#include <string>

namespace clr {

// Runs the checks that apply to the file's extension or content.
void checkModelFile(const std::string& path, uint64_t fileSize);

// `s` with control characters (newlines included) replaced by spaces and
// trailing spaces removed: text from a file or from assimp, made fit for a
// one-line message.
std::string oneLine(std::string s);

}  // namespace clr
