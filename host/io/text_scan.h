// text_scan.h — shared machinery of the direct text readers (fast_off.h,
// fast_stl.h, fast_ply.h, the OBJ reader): a body of text split into
// line-aligned parts that run on threads of their own, and strict,
// correctly rounded number scanning.
//
// Invariants: every part ends just after a '\n' (the last one at the end of
// the text), parts are in text order and cover it exactly; a scanner reads
// one whole word (ended by ' ', '\t', '\r', '\n' or the end of the text) or
// reads nothing and returns nullptr. Floats are correctly rounded
// (fast_float, as std::from_chars), so they equal exact_positions.h's
// reading of the same word. Nothing here throws or allocates per number.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace clr {

struct TextPart {
  const char* begin;
  const char* end;
};

// The number of parts worth running for `bytes` of text: 1 for small texts,
// else the hardware's threads (at most 16).
size_t textParts(size_t bytes);

// [begin, end) cut into at most `parts` line-aligned parts of about equal
// size (fewer when lines are long; none for an empty text).
std::vector<TextPart> splitLines(const char* begin, const char* end, size_t parts);

// Runs job(i) for i in [0, count), each on a thread of its own (the first
// on the caller's); returns when all are done. job must not throw.
void runParts(size_t count, const std::function<void(size_t)>& job);

// The number of '\n' in [begin, end).
size_t countLines(const char* begin, const char* end);

inline bool isBlank(char c)
{
  return c == ' ' || c == '\t';
}
inline bool endsWord(const char* p, const char* end)
{
  return p == end || *p == ' ' || *p == '\t' || *p == '\r' || *p == '\n';
}
inline const char* skipBlanks(const char* p, const char* end)
{
  while (p < end && isBlank(*p)) ++p;
  return p;
}

// A decimal float word at p: an optional '+' or '-', then what
// std::from_chars reads in general format (no "inf" or "nan": nullptr).
// Returns the end of the word, or nullptr.
const char* scanFloat(const char* p, const char* end, float& value);

// An unsigned decimal integer word at p: 1 to 18 digits, no sign. Returns
// the end of the word, or nullptr.
const char* scanUnsigned(const char* p, const char* end, uint64_t& value);

// The end of the line at p: the '\r' of a "\r\n", the '\n', or `end`.
// *next is set after the line end (after "\n" or "\r\n"). A '\r' not
// followed by '\n' counts as part of the line.
const char* lineEnd(const char* p, const char* end, const char** next);

}  // namespace clr
