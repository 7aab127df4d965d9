// fast_ply.cpp — the plain binary PLY reader (see fast_ply.h).
#include "io/fast_ply.h"

#include "io/fast_off.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <vector>

namespace clr {

namespace {

// The largest coordinate scene.cpp accepts (kMaxCoordinate there).
constexpr float kMaxCoordinate = 1e18f;

struct Layout {
  uint64_t vertices = 0, faces = 0;
  size_t bodyStart = 0;
};

// The header, if it is the plain layout in `format` (its "format" line).
bool plainHeader(const std::string& bytes, const char* format, Layout& layout)
{
  const size_t end = bytes.find("\nend_header\n");
  if (end == std::string::npos || end > (size_t(1) << 20)) return false;
  layout.bodyStart = end + 12;
  std::istringstream in(bytes.substr(0, end + 1));
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) {
    if (line.rfind("comment", 0) == 0 && (line.size() == 7 || line[7] == ' ')) continue;
    lines.push_back(line);
  }
  const char* const kExpected[] = {"ply",   format, nullptr, "property float x", "property float y", "property float z",
                                   nullptr, nullptr};
  if (lines.size() != 8) return false;
  for (size_t i = 0; i < 8; ++i)
    if (kExpected[i] && lines[i] != kExpected[i]) return false;
  auto count = [](const std::string& l, const char* prefix, uint64_t& n) {
    const size_t p = std::strlen(prefix);
    if (l.compare(0, p, prefix) != 0 || l.size() == p || l.size() > p + 10) return false;
    n = 0;
    for (size_t i = p; i < l.size(); ++i) {
      if (l[i] < '0' || l[i] > '9') return false;
      n = n * 10 + uint64_t(l[i] - '0');
    }
    return true;
  };
  if (!count(lines[2], "element vertex ", layout.vertices) || !count(lines[6], "element face ", layout.faces))
    return false;
  const std::string& list = lines[7];
  for (const char* c : {"uchar ", "uint8 "})
    for (const char* i : {"int ", "int32 ", "uint ", "uint32 "})
      for (const char* name : {"vertex_indices", "vertex_index"})
        if (list == std::string("property list ") + c + i + name) return layout.vertices > 0 && layout.faces > 0;
  return false;
}

}  // namespace

bool readPlainBinaryPly(const std::string& bytes, Mesh& mesh)
{
  Layout layout;
  if (!plainHeader(bytes, "format binary_little_endian 1.0", layout)) return false;
  const uint64_t n = layout.vertices;
  if (n > UINT32_MAX || (bytes.size() - layout.bodyStart) / 12 < n) return false;
  Mesh out;
  // Step 1: positions, checked as scene.cpp checks them.
  out.positions.resize(3 * n);
  std::memcpy(out.positions.data(), bytes.data() + layout.bodyStart, 12 * n);
  for (float& c : out.positions) {
    if (!(std::fabs(c) <= kMaxCoordinate)) return false;  // NaN too: assimp's path names it
    c += 0.0f;                                            // as the identity transform leaves it
  }
  // Step 2: faces, the body exactly as long as they need.
  const unsigned char* p = reinterpret_cast<const unsigned char*>(bytes.data()) + layout.bodyStart + 12 * n;
  const unsigned char* const end = reinterpret_cast<const unsigned char*>(bytes.data()) + bytes.size();
  // Each face takes at least 13 bytes: the count is bounded by the body before anything is reserved.
  if (layout.faces > uint64_t(end - p) / 13) return false;
  // Triangles are written in place; a polygon's fan grows the array.
  out.indices.resize(3 * layout.faces);
  size_t written = 0;
  for (uint64_t f = 0; f < layout.faces; ++f) {
    if (p == end) return false;
    const unsigned k = *p++;
    if (k < 3 || size_t(end - p) < 4 * size_t(k)) return false;
    if (written + 3 * size_t(k - 2) > out.indices.size())
      out.indices.resize(std::max(2 * out.indices.size(), written + 3 * size_t(k - 2)));
    uint32_t* to = out.indices.data() + written;
    uint32_t first = 0, previous = 0;
    for (unsigned j = 0; j < k; ++j, p += 4) {
      uint32_t index;
      std::memcpy(&index, p, 4);
      if (index >= n) return false;
      if (j == 0) first = index;
      if (j >= 2) {
        to[0] = first;
        to[1] = previous;
        to[2] = index;
        to += 3;
      }
      previous = index;
    }
    written += 3 * size_t(k - 2);
  }
  out.indices.resize(written);
  if (out.indices.capacity() > written + written / 4) out.indices.shrink_to_fit();
  if (p != end) return false;
  addImportDefaults(out);
  mesh = std::move(out);
  return true;
}

bool readPlainAsciiPly(const std::string& bytes, Mesh& mesh)
{
  Layout layout;
  Mesh out;
  // A face's count is a uchar: at most 255 corners.
  if (!plainHeader(bytes, "format ascii 1.0", layout) ||
      !readVertexFaceLines(bytes.data() + layout.bodyStart, bytes.data() + bytes.size(), layout.vertices, layout.faces,
                           255, out))
    return false;
  addImportDefaults(out);
  mesh = std::move(out);
  return true;
}

void addImportDefaults(Mesh& mesh)
{
  const size_t n = mesh.numVerts();
  if (mesh.normals.empty()) mesh.normals.assign(3 * n, 0.0f);
  mesh.uvs.assign(2 * n, 0.0f);
  mesh.triMaterial.assign(mesh.numTris(), 0);
  Material grey{};
  grey.baseColor[0] = 0.80f;
  grey.baseColor[1] = 0.78f;
  grey.baseColor[2] = 0.74f;
  grey.baseColor[3] = 1.0f;
  grey.texture = -1;
  mesh.materials.assign(1, grey);
}

}  // namespace clr
