// default_scene.cpp — the built-in scene, generated in code so the binary
// renders something without any file: a (2,3) torus knot and an icosphere
// standing on a tiled ground plane. Deterministic: same triangles every run.
#include "io/scene.h"

#include <cmath>
#include <map>

namespace clr {

namespace {

constexpr float kPi = 3.14159265358979f;

uint32_t addVertex(Mesh& m, glm::vec3 p)
{
  m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
  return uint32_t(m.numVerts() - 1);
}

void addTri(Mesh& m, uint32_t a, uint32_t b, uint32_t c)
{
  m.indices.insert(m.indices.end(), {a, b, c});
}

void addGround(Mesh& m, float y, float half, int cells)
{
  const uint32_t base = uint32_t(m.numVerts());
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) addVertex(m, {-half + 2 * half * i / cells, y, -half + 2 * half * j / cells});
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const uint32_t v = base + j * (cells + 1) + i;
      addTri(m, v, v + cells + 1, v + 1);
      addTri(m, v + 1, v + cells + 1, v + cells + 2);
    }
}

void addTorusKnot(Mesh& m, glm::vec3 centre, float scale, int segments, int sides)
{
  auto curve = [&](float t) {
    const float r = 2.0f + std::cos(3.0f * t);
    return glm::vec3(r * std::cos(2.0f * t), std::sin(3.0f * t), r * std::sin(2.0f * t));
  };
  const uint32_t base = uint32_t(m.numVerts());
  for (int s = 0; s < segments; ++s) {
    const float t = 2.0f * kPi * s / segments;
    const glm::vec3 p = curve(t);
    const glm::vec3 tangent = glm::normalize(curve(t + 1e-3f) - curve(t - 1e-3f));
    const glm::vec3 side = glm::normalize(glm::cross(tangent, p));
    const glm::vec3 up = glm::cross(side, tangent);
    for (int k = 0; k < sides; ++k) {
      const float a = 2.0f * kPi * k / sides;
      addVertex(m, centre + scale * (p + 0.45f * (std::cos(a) * side + std::sin(a) * up)));
    }
  }
  for (int s = 0; s < segments; ++s)
    for (int k = 0; k < sides; ++k) {
      const uint32_t a = base + s * sides + k, b = base + ((s + 1) % segments) * sides + k;
      const uint32_t c = base + ((s + 1) % segments) * sides + (k + 1) % sides;
      const uint32_t d = base + s * sides + (k + 1) % sides;
      addTri(m, a, d, b);
      addTri(m, b, d, c);
    }
}

void addIcosphere(Mesh& m, glm::vec3 centre, float radius, int levels)
{
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<glm::vec3> verts = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                  {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<uint32_t> faces = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                                 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                                 6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (glm::vec3& v : verts) v = glm::normalize(v);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = midpoints.find(key);
      if (it != midpoints.end()) return it->second;
      verts.push_back(glm::normalize(verts[a] + verts[b]));
      return midpoints[key] = uint32_t(verts.size() - 1);
    };
    std::vector<uint32_t> next;
    for (size_t f = 0; f < faces.size(); f += 3) {
      const uint32_t a = faces[f], b = faces[f + 1], c = faces[f + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    faces.swap(next);
  }
  const uint32_t base = uint32_t(m.numVerts());
  for (const glm::vec3& v : verts) addVertex(m, centre + radius * v);
  for (size_t f = 0; f < faces.size(); f += 3) addTri(m, base + faces[f], base + faces[f + 1], base + faces[f + 2]);
}

}  // namespace

Mesh defaultScene()
{
  Mesh m;
  addGround(m, -1.6f, 3.6f, 24);
  addTorusKnot(m, {-0.9f, -0.35f, -0.3f}, 0.55f, 384, 24);
  addIcosphere(m, {2.2f, -0.5f, 1.2f}, 1.1f, 4);
  computeSmoothNormals(m);
  return m;
}

}  // namespace clr
