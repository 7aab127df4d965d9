// error.h — the one user-facing error type and the one way a message quotes
// a user's string. Every room of host/ reports through these two.
#pragma once

#include <clraster/error.hpp>

#include <cstddef>
#include <string>

namespace clr {

// A user-facing failure: the message is printed as is, and the CLI exits 1.
// The library's public exception type (include/clraster/error.hpp).
using Error = clraster::Error;

// A user's string (a path, a flag's value, a name from a file) as every
// message quotes it: control characters become spaces, and a string longer
// than `limit` bytes keeps its first two thirds and its last third around
// " ... ", cut at UTF-8 character boundaries. With the default limit, a
// message quoting one such string stays under 300 bytes; one quoting two
// passes a smaller limit.
inline constexpr size_t kQuoteBytes = 200;
inline std::string userText(const std::string& s, size_t limit = kQuoteBytes)
{
  auto boundary = [&](size_t i) {  // back to the start of a UTF-8 character
    while (i > 0 && i < s.size() && (static_cast<unsigned char>(s[i]) & 0xC0) == 0x80) --i;
    return i;
  };
  std::string out;
  if (s.size() <= limit) {
    out = s;
  } else {
    const size_t head = boundary(limit * 2 / 3 - 2), tail = boundary(s.size() - (limit / 3 - 3));
    out = s.substr(0, head) + " ... " + s.substr(tail);
  }
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  return out;
}

}  // namespace clr
