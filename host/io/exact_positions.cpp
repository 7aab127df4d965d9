// exact_positions.cpp — correctly rounded positions for text models (see
// exact_positions.h). Each scanner walks its format as assimp 5.2 does
// (ObjFileParser, OFFImporter, PLY::DOM, STLImporter::LoadASCIIFile).
#include "io/exact_positions.h"

#include "base/error.h"

#include <assimp/Importer.hpp>
#include <assimp/scene.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <cstring>

namespace clr {

namespace {

// Vertex number i is written as x = i mod 2^20, y = i / 2^20 and
// z = kMagic + x: integers below 2^24, exact in float. A coordinate that
// assimp read from the file itself fails z == kMagic + x.
constexpr uint32_t kLowBits = 20;
constexpr uint32_t kLowMask = (1u << kLowBits) - 1;
constexpr uint32_t kMagic = 7340033;  // 7·2^20 + 1: z stays at most 2^23

bool isLineEnd(char c)
{
  return c == '\r' || c == '\n' || c == '\0' || c == '\f';
}
bool isSpace(char c)
{
  return c == ' ' || c == '\t';
}

// A whole word as a correctly rounded float: an optional sign, then what
// std::from_chars reads in general format, and nothing after it. Out of
// float's range, strtof's correctly rounded infinity, zero or subnormal.
bool parseCoordinate(const char* begin, const char* end, float& value)
{
  const char* p = begin;
  if (p < end && *p == '+') ++p;
  if (p < end && (*p == '+' || *p == '-') && p != begin) return false;
  const auto [stop, ec] = std::from_chars(p, end, value, std::chars_format::general);
  if (stop != end || p == end) return false;
  if (ec == std::errc::result_out_of_range) {
    value = std::strtof(std::string(begin, end).c_str(), nullptr);
    return true;
  }
  return ec == std::errc();
}

// The file's text, rewritten piece by piece, and the positions read so far.
class Rewriter {
 public:
  Rewriter(const std::string& path, const std::string& format, const std::string& src, size_t start = 0)
      : path_(path), format_(format), src_(src), copied_(start)
  {
    out_.reserve(src.size() + src.size() / 8);
  }

  const std::string& src() const { return src_; }

  // The vertex whose coordinate words are [b[k], e[k]) for k < 3, and, when
  // w is set, its homogeneous w at [w[0], w[1]) (rewritten to 1, divided
  // out here as assimp divides).
  void vertex(const size_t* b, const size_t* e, const size_t* w = nullptr)
  {
    const size_t at = b[0];
    float xyz[3];
    for (int k = 0; k < 3; ++k) xyz[k] = number(b[k], e[k]);
    if (w) {
      const float wv = number(w[0], w[1]);
      if (wv == 0.0f) fail(at, "homogeneous w is 0");
      for (float& c : xyz) c /= wv;
    }
    const uint64_t i = positions_.size() / 3;
    if (i >= (uint64_t(1) << 44)) fail(at, "too many vertices");
    const uint32_t low = uint32_t(i & kLowMask);
    const std::string code[3] = {std::to_string(low), std::to_string(i >> kLowBits), std::to_string(kMagic + low)};
    // In text order (a PLY may list y before x).
    std::vector<std::pair<size_t, std::pair<size_t, std::string>>> edits;
    for (int k = 0; k < 3; ++k) edits.push_back({b[k], {e[k], code[k]}});
    if (w) edits.push_back({w[0], {w[1], "1"}});
    std::sort(edits.begin(), edits.end());
    for (const auto& [begin, edit] : edits) replace(begin, edit.first, edit.second);
    positions_.insert(positions_.end(), xyz, xyz + 3);
  }

  // The word [b, e) as `text` for assimp; after every earlier rewrite.
  void rewrite(size_t b, size_t e, const std::string& text) { replace(b, e, text); }

  // An error at byte `offset` of the text, named by its line.
  [[noreturn]] void fail(size_t offset, const std::string& what) const
  {
    const size_t line =
        size_t(std::count(src_.begin(), src_.begin() + ptrdiff_t(std::min(offset, src_.size())), '\n')) + 1;
    throw Error(userText(path_) + ": " + format_ + " line " + std::to_string(line) + ": " + what +
                " (positions are read exactly, not guessed)");
  }

  ExactPositions finish(int importer)
  {
    out_.append(src_, copied_, std::string::npos);
    // A last line without its line end: assimp's line reader drops it where it crosses a 16 MiB block.
    if (!out_.empty() && out_.back() != '\n') out_ += '\n';
    ExactPositions r;
    r.importer = importer;
    r.checked = true;
    r.format = format_;
    r.text = std::move(out_);
    r.positions = std::move(positions_);
    return r;
  }

 private:
  float number(size_t b, size_t e) const
  {
    float v = 0.0f;
    if (!parseCoordinate(src_.data() + b, src_.data() + e, v))
      fail(b, "coordinate '" + userText(src_.substr(b, std::min<size_t>(e - b, 40))) + "' is not a decimal number");
    return v;
  }
  void replace(size_t b, size_t e, const std::string& text)
  {
    out_.append(src_, copied_, b - copied_);
    // A word that assimp's reader began inside (OFF's edge count takes the
    // digits before a vertex line's '.') stays a word of its own.
    if (b > 0 && !isSpace(src_[b - 1]) && !isLineEnd(src_[b - 1])) out_ += ' ';
    out_ += text;
    copied_ = e;
  }

  const std::string& path_;
  std::string format_;
  const std::string& src_;
  size_t copied_;
  std::string out_;
  std::vector<float> positions_;
};

// Words of [b, e) split at spaces and tabs: begin and end offsets.
std::vector<std::pair<size_t, size_t>> words(const std::string& s, size_t b, size_t e)
{
  std::vector<std::pair<size_t, size_t>> out;
  for (size_t i = b; i < e;) {
    while (i < e && isSpace(s[i])) ++i;
    const size_t start = i;
    while (i < e && !isSpace(s[i])) ++i;
    if (i > start) out.emplace_back(start, i);
  }
  return out;
}

// OBJ: logical lines as IOStreamBuffer::getNextDataLine cuts them ('\\'
// before a line end joins the next line); a line "v" + blank whose numeric
// words (a digit, '+' or '-' first, or nan/inf) number 3, 4 or 6 is a
// vertex, its first three words the position (and the fourth w, with 4).
void scanObj(Rewriter& r)
{
  const std::string& s = r.src();
  const size_t n = s.size();
  bool insideCstype = false;
  size_t pos = 0;
  auto firstWord = [&](size_t b, size_t e) {
    size_t i = b;
    while (i < e && !isSpace(s[i])) ++i;
    return s.substr(b, i - b);
  };
  while (pos < n) {
    const size_t b = pos;
    bool continued = false;
    while (pos < n && !isLineEnd(s[pos])) {
      if (s[pos] == '\\' && pos + 1 < n && isLineEnd(s[pos + 1])) {
        continued = true;
        const size_t nl = s.find('\n', pos);
        pos = nl == std::string::npos ? n : nl + 1;
        continue;
      }
      ++pos;
    }
    const size_t e = pos;
    if (pos < n) ++pos;
    if (e == b) continue;
    if (insideCstype) {
      if (s[b] == 'e' && firstWord(b, e) == "end") insideCstype = false;
      continue;
    }
    if (s[b] == 'c' && firstWord(b, e) == "cstype") {
      insideCstype = true;
      continue;
    }
    if (e - b < 2 || s[b] != 'v' || !isSpace(s[b + 1])) continue;
    if (continued) r.fail(b, "a vertex line continued with '\\'");
    // The numbers: the words assimp counts, and those it skips a line for, a leading '.' (".5"), rewritten.
    const auto w = words(s, b + 1, e);
    size_t numeric = 0;
    for (const auto& [wb, we] : w) {
      const char c = s[wb];
      const std::string head = s.substr(wb, std::min<size_t>(3, we - wb));
      const bool nanOrInf = strncasecmp(head.c_str(), "nan", 3) == 0 || strncasecmp(head.c_str(), "inf", 3) == 0;
      const bool dot = c == '.' && we - wb > 1 && s[wb + 1] >= '0' && s[wb + 1] <= '9';
      if ((c >= '0' && c <= '9') || c == '+' || c == '-' || nanOrInf || dot) ++numeric;
    }
    // assimp reads x y z, x y z w or x y z r g b, and skips any other line, which would shift every later index.
    if (numeric != 3 && numeric != 4 && numeric != 6 && numeric != 7)
      r.fail(b, "a vertex line of " + std::to_string(numeric) + " numbers (x y z, x y z w, or x y z r g b [a])");
    const size_t wb[3] = {w[0].first, w[1].first, w[2].first}, we[3] = {w[0].second, w[1].second, w[2].second};
    if (numeric == 4) {
      const size_t hw[2] = {w[3].first, w[3].second};
      r.vertex(wb, we, hw);
    } else {
      r.vertex(wb, we);
    }
    // Colours: ".5" as "0.5"; an alpha (the 7th) dropped, as assimp reads r g b.
    for (size_t k = 3; numeric >= 6 && k < numeric; ++k) {
      const auto [cb, ce] = w[k];
      if (k == 6)
        r.rewrite(cb, ce, "");
      else if (s[cb] == '.')
        r.rewrite(cb, ce, "0" + s.substr(cb, ce - cb));
    }
  }
}

// OFF: the header as OFFImporter reads it, then one GetNextLine line per
// vertex (blank lines skipped, at most 4095 bytes) with its coordinates
// first.
void scanOff(Rewriter& r, size_t start)
{
  const std::string& s = r.src();
  const size_t n = s.size();
  auto at = [&](size_t i) { return i < n ? s[i] : '\0'; };
  size_t car = start;
  auto skipSpacesAndLineEnd = [&] {
    while (at(car) == ' ' || at(car) == '\t' || at(car) == '\r' || at(car) == '\n') ++car;
  };
  auto nextToken = [&] {
    skipSpacesAndLineEnd();
    while (car < n && (s[car] == '#' || s[car] == '\n' || s[car] == '\r')) {
      while (at(car) != '\r' && at(car) != '\n' && at(car) != '\0') ++car;
      while (at(car) == '\r' || at(car) == '\n') ++car;
      skipSpacesAndLineEnd();
    }
  };
  auto strtoul10 = [&] {
    uint64_t v = 0;
    while (at(car) >= '0' && at(car) <= '9') v = (v * 10 + uint64_t(at(car++) - '0')) & 0xFFFFFFFFu;
    return v;
  };
  nextToken();
  if (car + 2 < n && s[car] == 'S' && s[car + 1] == 'T') car += 2;
  if (car + 1 < n && s[car] == 'C') ++car;
  if (car + 1 < n && s[car] == 'N') ++car;
  bool homogeneous = false, hasDimension = false;
  if (car + 1 < n && s[car] == '4') homogeneous = true, ++car;
  if (car + 1 < n && s[car] == 'n') hasDimension = true, ++car;
  uint64_t dimensions = 3;
  if (car + 3 < n && s.compare(car, 3, "OFF") == 0) {
    car += 3;
    nextToken();
  } else {
    homogeneous = false;
    nextToken();
  }
  if (hasDimension) {
    dimensions = strtoul10();
    nextToken();
  }
  if (dimensions != 3) r.fail(car, "vertices of " + std::to_string(dimensions) + " coordinates");
  nextToken();
  const uint64_t numVertices = strtoul10();
  nextToken();
  const uint64_t numFaces = strtoul10();
  nextToken();
  strtoul10();  // edges
  nextToken();
  size_t buffer = car;
  for (uint64_t v = 0; v < numVertices; ++v) {
    if (at(buffer) == '\0') break;  // assimp reports the short file
    const size_t b = buffer;
    while (!isLineEnd(at(buffer))) ++buffer;
    const size_t e = buffer;
    if (e - b > 4095) r.fail(b, "a vertex line longer than 4095 bytes");
    while (isLineEnd(at(buffer)) && at(buffer) != '\0') ++buffer;
    const auto w = words(s, b, e);
    if (w.size() < (homogeneous ? 4u : 3u)) r.fail(b, "a vertex line with too few coordinates");
    const size_t wb[3] = {w[0].first, w[1].first, w[2].first}, we[3] = {w[0].second, w[1].second, w[2].second};
    if (homogeneous) {
      const size_t hw[2] = {w[3].first, w[3].second};
      r.vertex(wb, we, hw);
    } else {
      r.vertex(wb, we);
    }
  }
  // The faces' indices: assimp's strtoul10 reads "-2" or "x" as 0, silently another vertex. A line whose
  // count it reads (wrapping at 2^32) as 0 or above 9 it skips, reading on, yet counts the faces down:
  // more such lines than the faces left unread drop the last faces, or wrap the count (a crash).
  uint64_t read = 0, skipped = 0;
  size_t firstSkipped = 0;
  while (read < numFaces && at(buffer) != '\0') {
    const size_t b = buffer;
    while (!isLineEnd(at(buffer))) ++buffer;
    const size_t e = buffer;
    while (isLineEnd(at(buffer)) && at(buffer) != '\0') ++buffer;
    const auto w = words(s, b, e);
    uint32_t corners = 0;
    for (size_t i = w.empty() ? e : w[0].first; i < e && s[i] >= '0' && s[i] <= '9'; ++i)
      corners = corners * 10u + uint32_t(s[i] - '0');
    if (corners == 0 || corners > 9) {
      if (skipped++ == 0) firstSkipped = b;
    } else {
      ++read;
    }
    if (w.empty()) continue;
    const uint64_t count = std::strtoull(s.substr(w[0].first, w[0].second - w[0].first).c_str(), nullptr, 10);
    for (size_t k = 1; k <= count && k < w.size(); ++k) {
      const std::string index = s.substr(w[k].first, w[k].second - w[k].first);
      if (index.find_first_not_of("0123456789") != std::string::npos)
        r.fail(w[k].first, "vertex index '" + userText(index, 40) + "' is not a non-negative integer");
    }
  }
  if (skipped > numFaces - read)
    r.fail(firstSkipped, "face lines whose vertex count is not 1 to 9 would drop later faces");
}

// IOStreamBuffer::getNextLine over the whole text: a line end where the
// last line stopped is skipped through its '\n' first.
bool nextPlyLine(const std::string& s, size_t& pos, size_t& b, size_t& e)
{
  const size_t n = s.size();
  if (pos >= n) return false;
  if (isLineEnd(s[pos])) {
    while (pos < n && s[pos] != '\n') ++pos;
    if (++pos >= n) return false;
  }
  b = pos;
  while (pos < n && !isLineEnd(s[pos])) ++pos;
  e = pos++;
  return true;
}

struct PlyProperty {
  std::string name;
  bool list = false, integer = false;
};
struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

// PLY: the header's elements, then one line per element instance; in the
// element "vertex", the words of x, y and z (list properties take a count
// word and that many more).
bool scanPly(Rewriter& r)
{
  const std::string& s = r.src();
  size_t pos = 0, b = 0, e = 0;
  std::vector<PlyElement> elements;
  bool ascii = false, ended = false;
  auto isInteger = [](const std::string& t) {
    return t != "float" && t != "double" && t != "float32" && t != "float64";
  };
  while (nextPlyLine(s, pos, b, e)) {
    const auto w = words(s, b, e);
    if (w.empty()) continue;
    auto word = [&](size_t k) { return k < w.size() ? s.substr(w[k].first, w[k].second - w[k].first) : std::string(); };
    const std::string key = word(0);
    if (key == "end_header") {
      ended = true;
      break;
    }
    if (key == "format") ascii = word(1) == "ascii";
    if (key == "element") {
      PlyElement el;
      el.name = word(1);
      el.count = std::strtoull(word(2).c_str(), nullptr, 10);
      elements.push_back(el);
    }
    if (key == "property" && !elements.empty()) {
      PlyProperty p;
      p.list = word(1) == "list";
      p.name = word(p.list ? 4 : 2);
      p.integer = isInteger(word(p.list ? 3 : 1));
      elements.back().properties.push_back(p);
    }
  }
  if (!ascii || !ended) return false;  // binary (exact already), or left to assimp's error
  for (const PlyElement& el : elements) {
    int slot[3] = {-1, -1, -1};
    for (size_t k = 0; k < el.properties.size(); ++k)
      for (int c = 0; c < 3; ++c)
        if (!el.properties[k].list && el.properties[k].name == std::string(1, char('x' + c))) slot[c] = int(k);
    const bool isVertex = el.name == "vertex";
    if (isVertex && (slot[0] < 0 || slot[1] < 0 || slot[2] < 0))
      r.fail(pos, "the vertex element lacks a scalar x, y or z");
    for (uint64_t i = 0; i < el.count; ++i) {
      if (!nextPlyLine(s, pos, b, e)) return true;  // assimp reports the short file
      if (!isVertex) continue;
      const auto w = words(s, b, e);
      size_t wb[3] = {0, 0, 0}, we[3] = {0, 0, 0}, at = 0;
      int found = 0;
      for (size_t k = 0; k < el.properties.size() && at < w.size(); ++k) {
        const PlyProperty& p = el.properties[k];
        if (p.list) {
          at += 1 + size_t(std::strtoull(s.substr(w[at].first, w[at].second - w[at].first).c_str(), nullptr, 10));
          continue;
        }
        for (int c = 0; c < 3; ++c)
          if (slot[c] == int(k)) {
            found |= 1 << c;
            wb[c] = w[at].first;
            we[c] = w[at].second;
            const std::string text = s.substr(wb[c], we[c] - wb[c]);
            if (p.integer && text.find_first_not_of("+-0123456789") != std::string::npos)
              r.fail(b, "integer property " + p.name + " holds '" + userText(text, 40) + "'");
          }
        ++at;
      }
      if (found != 7) r.fail(b, "a vertex line with too few values");
      r.vertex(wb, we);
    }
  }
  return true;
}

bool isBinaryStl(const std::string& s, size_t at, uint64_t size)
{
  if (size < 84 || at + 84 > s.size()) return false;
  uint32_t faces = 0;
  std::memcpy(&faces, s.data() + at + 80, 4);
  return uint32_t(faces * 50u + 84u) == uint32_t(size);
}

// Whether the text from `at` starts an ASCII solid as IsAsciiSTL decides.
bool isAsciiStl(const std::string& s, size_t at, uint64_t size)
{
  if (isBinaryStl(s, at, size)) return false;
  while (at < s.size() && isSpace(s[at])) ++at;
  if (at >= s.size() || isLineEnd(s[at]) || at + 5 >= s.size()) return false;
  return s.compare(at, 5, "solid") == 0;
}

// ASCII STL: LoadASCIIFile's token walk; the three numbers after each of
// a facet's first three "vertex" keywords.
void scanStl(Rewriter& r, size_t start)
{
  const std::string& s = r.src();
  const size_t n = s.size();
  auto at = [&](size_t i) { return i < n ? s[i] : '\0'; };
  auto spaceOrNewLine = [&](size_t i) { return isSpace(at(i)) || isLineEnd(at(i)); };
  size_t sz = start;
  auto skipSpaces = [&] {
    while (isSpace(at(sz))) ++sz;
  };
  auto word = [&] {
    skipSpaces();
    const size_t b = sz;
    while (!spaceOrNewLine(sz)) ++sz;
    return b;
  };
  while (isAsciiStl(s, sz, n - sz)) {
    skipSpaces();
    sz += 5;
    word();  // the solid's name
    unsigned corner = 3;
    for (;;) {
      while (at(sz) == ' ' || at(sz) == '\t' || at(sz) == '\r' || at(sz) == '\n') ++sz;
      if (at(sz) == '\0') break;
      if (s.compare(sz, 5, "facet") == 0 && spaceOrNewLine(sz + 5) && at(sz + 5) != '\0') {
        corner = 0;
        sz += 6;
        skipSpaces();
        if (s.compare(sz, 6, "normal") == 0 && at(sz + 6) != '\0') {
          sz += 7;
          for (int k = 0; k < 3; ++k) word();
        }
      } else if (s.compare(sz, 6, "vertex") == 0 && spaceOrNewLine(sz + 6)) {
        if (corner >= 3 || at(sz + 6) == '\0') {
          ++sz;
          continue;
        }
        sz += 7;
        size_t b[3], e[3];
        for (int k = 0; k < 3; ++k) {
          b[k] = word();
          e[k] = sz;
        }
        r.vertex(b, e);
        ++corner;
      } else if (s.compare(sz, 8, "endsolid") == 0) {
        do ++sz;
        while (!isLineEnd(at(sz)));
        while (at(sz) == ' ' || at(sz) == '\t' || at(sz) == '\r' || at(sz) == '\n') ++sz;
        break;
      } else {
        do ++sz;
        while (!spaceOrNewLine(sz));
      }
    }
  }
}

int importerFor(const Assimp::Importer& importer, const char* ext)
{
  const size_t index = importer.GetImporterIndex(ext);
  return index == size_t(-1) ? -2 : int(index);  // -2 matches no importer index
}

}  // namespace

ExactPositions prepareExactPositions(const std::string& path, const std::string& bytes, const std::string& format,
                                     bool byExtension, const Assimp::Importer& importer)
{
  const bool obj = format == "obj", off = format == "off", ply = format == "ply", stl = format == "stl";
  if (!obj && !off && !ply && !stl) return {};
  if (!byExtension)
    throw Error(userText(path) + ": assimp reads it as ." + format + " by its content; name it so, and its positions" +
                " are read exactly");
  ExactPositions binary;
  binary.checked = true;  // binary PLY or STL: float positions, exact already
  // OFF and STL text goes through assimp's TextFileToBuffer, which drops a
  // UTF-8 byte order mark and converts UTF-16 and UTF-32.
  const bool utf8Mark = bytes.compare(0, 3, "\xEF\xBB\xBF") == 0;
  const bool wideMark = bytes.compare(0, 2, "\xFF\xFE") == 0 || bytes.compare(0, 2, "\xFE\xFF") == 0 ||
                        bytes.compare(0, 4, std::string("\0\0\xFE\xFF", 4)) == 0;
  if ((off || stl) && wideMark)
    throw Error(userText(path) + ": UTF-16 and UTF-32 text are not read (positions are read exactly, not guessed)");
  if (obj) {
    Rewriter r(path, "OBJ", bytes);
    scanObj(r);
    return r.finish(importerFor(importer, "obj"));
  }
  if (off) {
    Rewriter r(path, "OFF", bytes, utf8Mark ? 3 : 0);
    scanOff(r, utf8Mark ? 3 : 0);
    return r.finish(importerFor(importer, "off"));
  }
  if (ply) {
    Rewriter r(path, "PLY", bytes);
    return scanPly(r) ? r.finish(importerFor(importer, "ply")) : binary;
  }
  const size_t start = utf8Mark ? 3 : 0;
  if (isBinaryStl(bytes, start, bytes.size()) || !isAsciiStl(bytes, start, bytes.size())) return binary;
  Rewriter r(path, "STL", bytes, start);
  scanStl(r, start);
  return r.finish(importerFor(importer, "stl"));
}

void applyExactPositions(const std::string& path, const ExactPositions& exact, const Assimp::Importer& importer,
                         const aiScene& scene)
{
  const int used = importer.GetPropertyInteger("importerIndex", -1);
  if (exact.importer == -1 && exact.checked) return;
  if (exact.importer == -1) {
    // Not prepared: assimp must not have read the text formats by content.
    for (const char* ext : {"obj", "off", "ply", "stl"})
      if (used == importerFor(importer, ext))
        throw Error(userText(path) + ": assimp reads it as ." + ext + " by its content; name it so, and its positions" +
                    " are read exactly");
    return;
  }
  if (used != exact.importer)
    throw Error(userText(path) + ": prepared as " + exact.format + " but assimp read it with another importer");
  const uint64_t count = exact.positions.size() / 3;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    aiMesh* mesh = scene.mMeshes[m];
    if (!mesh || !mesh->mVertices) continue;
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      aiVector3D& p = mesh->mVertices[v];
      const bool integral = p.x >= 0.0f && p.x <= float(kLowMask) && p.x == float(uint32_t(p.x)) && p.y >= 0.0f &&
                            p.y < 16777216.0f && p.y == float(uint32_t(p.y));
      const uint64_t index = integral ? (uint64_t(p.y) << kLowBits) | uint32_t(p.x) : count;
      if (!integral || p.z != float(kMagic + uint32_t(p.x)) || index >= count)
        throw Error(userText(path) + ": " + exact.format + ": mesh " + std::to_string(m) + " vertex " +
                    std::to_string(v) + " holds a position clraster did not re-read; positions are never mixed");
      p = aiVector3D(exact.positions[3 * index], exact.positions[3 * index + 1], exact.positions[3 * index + 2]);
    }
  }
}

}  // namespace clr
