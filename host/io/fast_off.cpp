// fast_off.cpp — the plain OFF reader (see fast_off.h).
#include "io/fast_off.h"

#include "io/fast_ply.h"
#include "io/text_scan.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <new>

namespace clr {

namespace {

constexpr float kMaxCoordinate = 1e18f;  // scene.cpp's limit
// assimp reads a line into 4096 bytes; longer lines are never read here.
constexpr ptrdiff_t kMaxLine = 4000;

bool blankOrComment(const char* p, const char* e)
{
  p = skipBlanks(p, e);
  return p == e || *p == '#';
}

// The header: "OFF", comments, "V F E", comments; `body` set to the first vertex line.
bool readHeader(const char* p, const char* end, uint64_t counts[3], const char*& body)
{
  const char* next = nullptr;
  const char* e = lineEnd(p, end, &next);
  if (skipBlanks(p + std::min<ptrdiff_t>(3, e - p), e) != e || e - p < 3 || std::memcmp(p, "OFF", 3) != 0) return false;
  for (p = next; p < end && blankOrComment(p, lineEnd(p, end, &next)); p = next) {
  }
  e = lineEnd(p, end, &next);
  for (int k = 0; k < 3; ++k) {
    p = scanUnsigned(skipBlanks(p, e), e, counts[k]);
    if (!p) return false;
  }
  if (skipBlanks(p, e) != e) return false;
  for (p = next; p < end && blankOrComment(p, lineEnd(p, end, &next)); p = next) {
  }
  body = p;
  return true;
}

// One part of the body: its lines, numbered from `firstLine`.
struct Part {
  TextPart text;
  uint64_t firstLine = 0, lines = 0;
  std::vector<uint32_t> indices;
  bool ok = false;
};

void parsePart(Part& part, uint64_t vertices, uint64_t maxCorners, float* positions)
{
  const char* p = part.text.begin;
  const char* const end = part.text.end;
  uint64_t line = part.firstLine;
  const uint64_t faceLines =
      part.firstLine + part.lines > vertices ? part.firstLine + part.lines - std::max(part.firstLine, vertices) : 0;
  part.indices.reserve(3 * faceLines);
  while (p < end) {
    const char* next = nullptr;
    const char* const e = lineEnd(p, end, &next);
    if (e - p > kMaxLine) return;
    const char* q = skipBlanks(p, e);
    if (line < vertices) {
      float* xyz = positions + 3 * line;
      for (int k = 0; k < 3; ++k) {
        if (k > 0) q = skipBlanks(q, e);
        q = scanFloat(q, e, xyz[k]);
        if (!q || !(std::fabs(xyz[k]) <= kMaxCoordinate)) return;
        xyz[k] += 0.0f;  // -0 as +0, as the identity node transform leaves it
      }
    } else {
      uint64_t k = 0, first = 0, previous = 0;
      q = scanUnsigned(q, e, k);
      if (!q || k < 3 || k > maxCorners) return;
      for (uint64_t j = 0; j < k; ++j) {
        uint64_t index = 0;
        q = scanUnsigned(skipBlanks(q, e), e, index);
        if (!q || index >= vertices) return;
        if (j == 0) first = index;
        if (j >= 2) {
          part.indices.push_back(uint32_t(first));
          part.indices.push_back(uint32_t(previous));
          part.indices.push_back(uint32_t(index));
        }
        previous = index;
      }
    }
    if (skipBlanks(q, e) != e) return;
    ++line;
    p = next;
  }
  part.ok = true;
}

}  // namespace

bool readVertexFaceLines(const char* body, const char* end, uint64_t vertices, uint64_t faces, uint64_t maxCorners,
                         Mesh& out)
{
  if (vertices == 0 || faces == 0 || vertices > UINT32_MAX) return false;
  // White space after the last face line is not a line.
  while (end > body && (isBlank(end[-1]) || end[-1] == '\r' || end[-1] == '\n')) --end;
  if (body == end) return false;
  // Step 1: line counts per part, so each part knows its lines' numbers.
  std::vector<Part> parts;
  for (const TextPart& t : splitLines(body, end, textParts(size_t(end - body)))) parts.emplace_back().text = t;
  runParts(parts.size(), [&](size_t i) { parts[i].lines = countLines(parts[i].text.begin, parts[i].text.end); });
  ++parts.back().lines;  // the last line has no '\n'
  uint64_t total = 0;
  for (Part& part : parts) {
    part.firstLine = total;
    total += part.lines;
  }
  if (total != vertices + faces) return false;  // also bounds the counts by the file's size
  // Step 2: every part parsed on its own thread.
  out.positions.resize(3 * vertices);
  runParts(parts.size(), [&](size_t i) {
    try {
      parsePart(parts[i], vertices, maxCorners, out.positions.data());
    } catch (const std::bad_alloc&) {
      parts[i].ok = false;  // assimp's path decides, as for any doubt
    }
  });
  size_t indices = 0;
  for (const Part& part : parts) {
    if (!part.ok) return false;
    indices += part.indices.size();
  }
  out.indices.reserve(indices);
  for (Part& part : parts) {
    out.indices.insert(out.indices.end(), part.indices.begin(), part.indices.end());
    part.indices = {};
  }
  return true;
}

bool readPlainOff(const std::string& bytes, Mesh& mesh)
{
  uint64_t counts[3] = {0, 0, 0};
  const char* body = nullptr;
  Mesh out;
  if (!readHeader(bytes.data(), bytes.data() + bytes.size(), counts, body) ||
      !readVertexFaceLines(body, bytes.data() + bytes.size(), counts[0], counts[1], 9, out))
    return false;
  addImportDefaults(out);
  mesh = std::move(out);
  return true;
}

}  // namespace clr
