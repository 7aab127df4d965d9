// test_support.cpp — see test_support.h.
#include "test_support.h"

#include <cmath>
#include <cstdlib>
#include <random>

#include <sys/stat.h>

namespace test {

std::string deviceSelector()
{
  const char* selector = std::getenv("CLRASTER_TEST_DEVICE");
  return selector ? selector : "";
}

clr::ClContext& context()
{
  // Never destroyed: releasing OpenCL objects from a static destructor races
  // the ICD's own teardown at exit (Oclgrind's runtime crashes on it).
  static clr::ClContext* ctx = new clr::ClContext(deviceSelector());
  return *ctx;
}

bool underOclgrind()
{
  return context().info.platformName.find("Oclgrind") != std::string::npos;
}

uint32_t Geometry::addVertex(glm::vec3 p)
{
  positions.insert(positions.end(), {p.x, p.y, p.z});
  return uint32_t(positions.size() / 3 - 1);
}

void Geometry::addTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c)
{
  const uint32_t ia = addVertex(a), ib = addVertex(b), ic = addVertex(c);
  indices.insert(indices.end(), {ia, ib, ic});
}

clr::Mesh Geometry::mesh() const
{
  clr::Mesh m;
  m.positions = positions;
  m.indices = indices;
  clr::computeSmoothNormals(m);
  return m;
}

Geometry randomTriangles(uint32_t seed, int count)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coord(-1.2f, 1.2f), depth(-0.9f, 0.9f);
  Geometry g;
  for (int t = 0; t < count; ++t)
    g.addTriangle({coord(rng), coord(rng), depth(rng)}, {coord(rng), coord(rng), depth(rng)},
                  {coord(rng), coord(rng), depth(rng)});
  return g;
}

glm::vec3 screen(float sx, float sy, float z, uint32_t width, uint32_t height)
{
  const float hw = 0.5f * float(width), hh = 0.5f * float(height);
  return {(sx - hw) / hw, (sy - hh) / hh, z};
}

clr::FrameSettings idSettings(uint32_t width, uint32_t height, const glm::mat4& mvp, bool cullBack)
{
  clr::FrameSettings s;
  s.width = width;
  s.height = height;
  s.mvp = mvp;
  s.cullBack = cullBack;
  s.shadeMode = CLR_SHADE_ID;
  return s;
}

std::vector<uint32_t> renderTriIds(clr::Pipeline& pipeline, const clr::FrameSettings& settings)
{
  std::vector<uint32_t> rgba;
  pipeline.render(settings, rgba);
  return readTriIds(pipeline);
}

std::vector<uint32_t> readTriIds(const clr::Pipeline& pipeline, uint32_t sample)
{
  const std::vector<VisSample> vis = pipeline.readVis(sample);
  const std::vector<clr::SetupRecord> setup = pipeline.readSetup();
  std::vector<uint32_t> ids(vis.size(), ref::kNone);
  for (size_t i = 0; i < vis.size(); ++i)
    if (vis[i].setupIndex != CLR_NONE) ids[i] = setup.at(vis[i].setupIndex).triId;
  return ids;
}

std::vector<uint32_t> renderTriIds(const Geometry& geometry, const clr::FrameSettings& settings)
{
  clr::Pipeline pipeline(context());
  pipeline.uploadScene(geometry.mesh());
  return renderTriIds(pipeline, settings);
}

std::string tempDir()
{
  mkdir(CLRASTER_TEST_TMP, 0755);
  return CLRASTER_TEST_TMP;
}

size_t countDifferences(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b)
{
  size_t n = 0;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) n += a[i] != b[i];
  return n + (a.size() > b.size() ? a.size() - b.size() : b.size() - a.size());
}

std::string meshDifference(const clr::Mesh& a, const clr::Mesh& b)
{
  if (!sameBytes(a.positions, b.positions)) return "positions";
  if (!sameBytes(a.normals, b.normals)) return "normals";
  if (!sameBytes(a.uvs, b.uvs)) return "uvs";
  if (!sameBytes(a.indices, b.indices)) return "indices";
  if (!sameBytes(a.lines, b.lines) || !sameBytes(a.points, b.points)) return "lines or points";
  if (!sameBytes(a.colors, b.colors)) return "colors";
  if (!sameBytes(a.triMaterial, b.triMaterial)) return "triMaterial";
  if (!sameBytes(a.materials, b.materials)) return "materials";
  if (a.textures.size() != b.textures.size()) return "texture count";
  for (size_t t = 0; t < a.textures.size(); ++t) {
    const clr::Texture &x = a.textures[t], &y = b.textures[t];
    if (x.name != y.name || x.width != y.width || x.height != y.height || x.wrapS != y.wrapS || x.wrapT != y.wrapT ||
        !sameBytes(x.rgba, y.rgba))
      return "texture " + std::to_string(t);
  }
  if (a.warnings.lines() != b.warnings.lines()) return "warnings";
  if (a.facts.normalsInFile != b.facts.normalsInFile || a.facts.normalsRepaired != b.facts.normalsRepaired ||
      a.facts.uvsInFile != b.facts.uvsInFile || a.facts.missingTextures != b.facts.missingTextures)
    return "facts";
  return "";
}

glm::vec2 jitterVertex(float x, float y, int jitter, std::mt19937& rng)
{
  std::uniform_int_distribution<int> sub(-jitter, jitter), pick(0, 3);
  x = std::round(x * 256.0f + sub(rng)) / 256.0f;
  y = std::round(y * 256.0f + sub(rng)) / 256.0f;
  const int mode = pick(rng);
  if (mode == 1 || mode == 3) x = std::floor(x) + 0.5f;
  if (mode == 2 || mode == 3) y = std::floor(y) + 0.5f;
  return {x, y};
}

std::vector<clr::Camera> modelViews(const clr::Bounds& bounds)
{
  const glm::vec3 centre = 0.5f * (bounds.min + bounds.max);
  const float radius = 0.5f * glm::length(bounds.max - bounds.min);
  std::vector<clr::Camera> views;
  for (int view = 0; view < 3; ++view) {
    clr::CameraArgs args;
    if (view > 0) {
      args.target = centre;
      args.eye = centre + radius * (view == 1 ? glm::vec3(0.21f, 0.13f, 0.31f) : glm::vec3(1.3f, 0.05f, 0.02f));
    }
    views.push_back(clr::frameCamera(args, bounds));
  }
  return views;
}

}  // namespace test
