// fast_stl.cpp — the plain STL reader (see fast_stl.h). The checks follow
// assimp 5.2's STLImporter: IsBinarySTL decides by size first.
#include "io/fast_stl.h"

#include "io/fast_ply.h"
#include "io/text_scan.h"

#include <assimp/fast_atof.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>

namespace clr {

namespace {

constexpr float kMaxCoordinate = 1e18f;  // scene.cpp's limit

bool usablePosition(float& c)
{
  if (!(std::fabs(c) <= kMaxCoordinate)) return false;
  c += 0.0f;  // -0 as +0, as the identity node transform leaves it
  return true;
}

// A facet normal as scene.cpp's appendMesh transforms it under the identity
// node: the same matrix and arithmetic, so the same zero signs.
void putNormal(const aiVector3D& n, float* out)
{
  static const aiMatrix3x3 normalMatrix = [] {
    aiMatrix3x3 m{aiMatrix4x4()};
    m.Inverse().Transpose();
    return m;
  }();
  aiVector3D t = normalMatrix * n;
  if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z)) t = aiVector3D(0, 0, 0);
  for (int v = 0; v < 3; ++v) out[3 * v] = t.x, out[3 * v + 1] = t.y, out[3 * v + 2] = t.z;
}

// IsBinarySTL of assimp: the size the facet count asks for, modulo 2^32.
bool sizedAsBinary(const char* s, size_t size)
{
  if (size < 84) return false;
  uint32_t faces = 0;
  std::memcpy(&faces, s + 80, 4);
  return uint32_t(faces * 50u + 84u) == uint32_t(size);
}

bool readBinary(const std::string& bytes, Mesh& out)
{
  // TextFileToBuffer converts a file that starts with a byte order mark.
  for (const char* mark : {"\xEF\xBB\xBF", "\xFF\xFE", "\xFE\xFF"})
    if (bytes.compare(0, std::strlen(mark), mark) == 0) return false;
  if (bytes.compare(0, 4, std::string("\0\0\xFE\xFF", 4)) == 0) return false;
  uint32_t faces = 0;
  std::memcpy(&faces, bytes.data() + 80, 4);
  if (faces == 0 || 84 + 50 * uint64_t(faces) != bytes.size()) return false;
  const size_t n = 3 * size_t(faces);
  out.positions.resize(3 * n);
  out.normals.resize(3 * n);
  out.indices.resize(n);
  // Facets in ranges, one per core: each range checks and copies its own.
  const size_t parts = textParts(bytes.size());
  std::vector<char> ok(parts, 0);
  runParts(parts, [&](size_t part) {
    const size_t first = faces * part / parts, last = faces * (part + 1) / parts;
    const char* p = bytes.data() + 84 + 50 * first;
    for (size_t f = first; f < last; ++f, p += 50) {
      uint16_t attribute = 0;
      std::memcpy(&attribute, p + 48, 2);
      if (attribute & 0x8000u) return;  // a facet colour: assimp's vertex colours
      float* xyz = &out.positions[9 * f];
      std::memcpy(xyz, p + 12, 36);
      for (int k = 0; k < 9; ++k)
        if (!usablePosition(xyz[k])) return;
      float normal[3];
      std::memcpy(normal, p, 12);
      putNormal(aiVector3D(normal[0], normal[1], normal[2]), &out.normals[9 * f]);
      for (size_t i = 3 * f; i < 3 * f + 3; ++i) out.indices[i] = uint32_t(i);
    }
    ok[part] = 1;
  });
  return std::find(ok.begin(), ok.end(), 0) == ok.end();
}

// The kinds of line of an ASCII solid.
enum Line : uint8_t { kSolid, kFacet, kOuterLoop, kVertex, kEndLoop, kEndFacet, kEndSolid };

struct AsciiPart {
  TextPart text;
  std::vector<uint8_t> lines;
  std::vector<const char*> solids;  // where each "solid" word starts
  std::vector<float> positions, normals;
  bool ok = false;
};

bool isWord(const char* p, const char* e, const char* word)
{
  const size_t n = std::strlen(word);
  return size_t(e - p) >= n && std::memcmp(p, word, n) == 0 && endsWord(p + n, e);
}

// What fast_atoreal_move throws here on a word it cannot read (assimp's own
// exception type is not exported by its shared library).
struct UnreadNumber {
  template <typename... Args>
  explicit UnreadNumber(Args&&...)
  {
  }
};

// A word through assimp's fast_atoreal_move, which must read all of it.
const char* assimpFloat(const char* p, const char* e, float& value)
{
  const char* w = p;
  while (w < e && !isBlank(*w)) ++w;
  char word[64];
  if (w == p || w - p >= ptrdiff_t(sizeof word)) return nullptr;
  std::memcpy(word, p, size_t(w - p));
  word[w - p] = '\0';
  try {
    if (Assimp::fast_atoreal_move<float, UnreadNumber>(word, value) != word + (w - p)) return nullptr;
  } catch (const UnreadNumber&) {
    return nullptr;
  }
  return w;
}

// At most one word (a solid's name) and blanks after p.
bool nameOnly(const char* p, const char* e)
{
  p = skipBlanks(p, e);
  const char* start = p;
  while (p < e && !isBlank(*p)) ++p;
  return p - start < 200 && skipBlanks(p, e) == e;
}

void parseAsciiPart(AsciiPart& part)
{
  const char* p = part.text.begin;
  const char* const end = part.text.end;
  const size_t guess = size_t(end - p) / 24;
  part.lines.reserve(guess / 8);
  part.positions.reserve(guess);
  while (p < end) {
    const char* next = nullptr;
    const char* const e = lineEnd(p, end, &next);
    const char* q = skipBlanks(p, e);
    Line kind;
    if (isWord(q, e, "vertex")) {
      kind = kVertex;
      q += 6;
      for (int k = 0; k < 3; ++k) {
        float c = 0.0f;
        q = scanFloat(skipBlanks(q, e), e, c);
        if (!q || !usablePosition(c)) return;
        part.positions.push_back(c);
      }
    } else if (isWord(q, e, "facet")) {
      kind = kFacet;
      q = skipBlanks(q + 5, e);
      if (!isWord(q, e, "normal")) return;
      q += 6;
      for (int k = 0; k < 3; ++k) {
        float c = 0.0f;
        q = assimpFloat(skipBlanks(q, e), e, c);
        if (!q) return;
        part.normals.push_back(c);
      }
    } else if (isWord(q, e, "outer")) {
      kind = kOuterLoop;
      q = skipBlanks(q + 5, e);
      if (!isWord(q, e, "loop")) return;
      q += 4;
    } else if (isWord(q, e, "endloop")) {
      kind = kEndLoop;
      q += 7;
    } else if (isWord(q, e, "endfacet")) {
      kind = kEndFacet;
      q += 8;
    } else if (isWord(q, e, "solid") || isWord(q, e, "endsolid")) {
      kind = *q == 's' ? kSolid : kEndSolid;
      if (kind == kSolid) part.solids.push_back(q);
      if (!nameOnly(q + (kind == kSolid ? 5 : 8), e)) return;
      q = e;
    } else {
      return;
    }
    if (skipBlanks(q, e) != e) return;
    part.lines.push_back(kind);
    p = next;
  }
  part.ok = true;
}

// The lines in order: (solid (facet outer vertex vertex vertex endloop endfacet)+ endsolid)+.
bool validSequence(const std::vector<AsciiPart>& parts)
{
  static const Line kFacetLines[] = {kFacet, kOuterLoop, kVertex, kVertex, kVertex, kEndLoop, kEndFacet};
  int state = -1;  // -1: a solid next; 0..6: kFacetLines[state] next; 7: a facet or endsolid next; 8: solid or end
  for (const AsciiPart& part : parts)
    for (uint8_t kind : part.lines) {
      if (state == -1 || state == 8) {
        if (kind != kSolid) return false;
        state = 0;
      } else if (state == 7 && kind == kEndSolid) {
        state = 8;
      } else {
        if (kind != kFacetLines[state % 7]) return false;
        state = state % 7 + 1;
      }
    }
  return state == 8;
}

bool readAscii(const std::string& bytes, Mesh& out)
{
  const char* const begin = bytes.data();
  const char* end = begin + bytes.size();
  if (bytes.compare(0, 5, "solid") != 0) return false;
  while (end > begin && (isBlank(end[-1]) || end[-1] == '\r' || end[-1] == '\n')) --end;
  std::vector<AsciiPart> parts;
  for (const TextPart& t : splitLines(begin, end, textParts(size_t(end - begin)))) parts.emplace_back().text = t;
  runParts(parts.size(), [&](size_t i) {
    try {
      parseAsciiPart(parts[i]);
    } catch (const std::bad_alloc&) {
      parts[i].ok = false;  // assimp's path decides, as for any doubt
    }
  });
  for (const AsciiPart& part : parts)
    if (!part.ok) return false;
  if (!validSequence(parts)) return false;
  // A later solid is read only where assimp's IsAsciiSTL, on the rest of the file, does not take it as binary.
  for (const AsciiPart& part : parts)
    for (const char* solid : part.solids)
      if (solid != begin && sizedAsBinary(solid, size_t(begin + bytes.size() - solid))) return false;
  size_t floats = 0;
  for (const AsciiPart& part : parts) floats += part.positions.size();
  if (floats == 0 || floats / 3 > UINT32_MAX) return false;
  out.positions.reserve(floats);
  out.normals.resize(floats);
  size_t facet = 0;
  for (AsciiPart& part : parts) {
    out.positions.insert(out.positions.end(), part.positions.begin(), part.positions.end());
    for (size_t k = 0; k < part.normals.size(); k += 3, ++facet)
      putNormal(aiVector3D(part.normals[k], part.normals[k + 1], part.normals[k + 2]), &out.normals[9 * facet]);
    part = AsciiPart{};
  }
  out.indices.resize(floats / 3);
  for (size_t i = 0; i < out.indices.size(); ++i) out.indices[i] = uint32_t(i);
  return true;
}

}  // namespace

bool readPlainStl(const std::string& bytes, Mesh& mesh)
{
  Mesh out;
  const bool binary = sizedAsBinary(bytes.data(), bytes.size());
  if (!(binary ? readBinary(bytes, out) : readAscii(bytes, out))) return false;
  addImportDefaults(out);
  out.facts.normalsInFile = true;
  mesh = std::move(out);
  return true;
}

}  // namespace clr
