// stability_scenes.cpp — see stability_scenes.h.
#include "stability_scenes.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace stab {

clr::Mesh Scene::mesh() const
{
  clr::Mesh m;
  m.positions = positions;
  m.indices = indices;
  clr::computeSmoothNormals(m);
  return m;
}

void addScreenVertex(Scene& scene, double sx, double sy, uint32_t width, uint32_t height)
{
  const double hw = 0.5 * width, hh = 0.5 * height;
  scene.positions.insert(scene.positions.end(), {float((sx - hw) / hw), float((sy - hh) / hh), 0.0f});
  scene.magnitude = std::max({scene.magnitude, std::fabs(sx), std::fabs(sy)});
}

namespace {

// The band layout: direction u along the bands, v across them, the
// viewport's half extents along each, the band spacing and the jitter.
struct Layout {
  double ux, uy, vx, vy;
  double halfU, halfV;  // the viewport's half extent along u and along v
  double first, spacing, jitter;
};

Layout layout(uint32_t width, uint32_t height, uint32_t bands, double angleDeg)
{
  Layout l;
  const double a = angleDeg * M_PI / 180.0;
  l.ux = std::cos(a), l.uy = std::sin(a), l.vx = -l.uy, l.vy = l.ux;
  l.halfU = 0.5 * width * std::fabs(l.ux) + 0.5 * height * std::fabs(l.uy);
  l.halfV = 0.5 * width * std::fabs(l.vx) + 0.5 * height * std::fabs(l.vy);
  const double margin = 2.0;  // the outermost lines stay 2 px outside the viewport
  l.first = -l.halfV - margin;
  l.spacing = 2.0 * (l.halfV + margin) / bands;
  l.jitter = l.spacing / 4.0;  // neighbouring lines stay >= spacing/2 apart at both ends
  return l;
}

double snap(double v)
{
  return std::nearbyint(v * 256.0) / 256.0;
}

}  // namespace

Scene bandMesh(uint32_t width, uint32_t height, double reach, uint32_t bands, double angleDeg, uint32_t seed)
{
  // Step 1: the band lines' ends, on the 1/256 grid; the outermost lines are
  // not jittered, so the bands always cover the viewport.
  const Layout l = layout(width, height, bands, angleDeg);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-l.jitter, l.jitter);
  const double cx = 0.5 * width, cy = 0.5 * height;
  Scene s;
  for (uint32_t k = 0; k <= bands; ++k)
    for (int end = -1; end <= 1; end += 2) {
      const double o = l.first + l.spacing * k + (k == 0 || k == bands ? 0.0 : jitter(rng));
      addScreenVertex(s, snap(cx + end * reach * l.ux + o * l.vx), snap(cy + end * reach * l.uy + o * l.vy), width,
                      height);
    }
  // Step 2: two triangles per band (vertices 2k, 2k + 1 are line k's ends),
  // counter-clockwise; classes by band parity and half.
  for (uint32_t i = 0; i < bands; ++i) {
    const uint32_t l0 = 2 * i, r0 = 2 * i + 1, l1 = 2 * i + 2, r1 = 2 * i + 3;
    s.indices.insert(s.indices.end(), {l0, r0, r1, l0, r1, l1});
    s.cls.push_back(uint8_t((i % 2) * 2));
    s.cls.push_back(uint8_t((i % 2) * 2 + 1));
  }
  s.numClasses = 4;
  return s;
}

double guardBandReach(uint32_t width, uint32_t height, uint32_t bands, double angleDeg)
{
  // A vertex lies at the centre ± reach·u + o·v with |o| <= halfV + margin +
  // jitter; each coordinate may move 2^16 − size/2 from the centre (fixed.h).
  const Layout l = layout(width, height, bands, angleDeg);
  const double o = -l.first + l.jitter + 1.0 / 256.0;
  double reach = 1e300;
  if (std::fabs(l.ux) > 1e-9)
    reach = std::min(reach, (CLR_GUARD_BAND_PIXELS - 0.5 * width - o * std::fabs(l.vx)) / std::fabs(l.ux));
  if (std::fabs(l.uy) > 1e-9)
    reach = std::min(reach, (CLR_GUARD_BAND_PIXELS - 0.5 * height - o * std::fabs(l.vy)) / std::fabs(l.uy));
  return std::floor(reach - 1.0);
}

std::vector<uint8_t> coverageCounts(clr::ClContext& cl, const Scene& scene, clr::FrameSettings settings)
{
  settings.shadeMode = CLR_SHADE_ID;
  settings.samples = 1;
  settings.mvp = glm::mat4(1.0f);
  std::vector<uint8_t> counts(size_t(settings.width) * settings.height, 0);
  clr::Pipeline pipeline(cl);
  const clr::Mesh full = scene.mesh();
  for (uint32_t c = 0; c < scene.numClasses; ++c) {
    // Step 1: the class alone (shared vertex positions, so identical snapping).
    clr::Mesh part = full;
    part.indices.clear();
    for (size_t t = 0; t < scene.numTris(); ++t)
      if (scene.cls[t] == c) part.indices.insert(part.indices.end(), &scene.indices[3 * t], &scene.indices[3 * t + 3]);
    if (part.indices.empty()) continue;
    pipeline.uploadScene(part);
    // Step 2: its hits.
    std::vector<uint32_t> rgba;
    pipeline.render(settings, rgba);
    const std::vector<VisSample> vis = pipeline.readVis(0);
    for (size_t p = 0; p < vis.size(); ++p) counts[p] += vis[p].setupIndex != CLR_NONE;
  }
  return counts;
}

Cracks countCracks(const std::vector<uint8_t>& counts)
{
  Cracks c;
  for (uint8_t n : counts) c.holes += n == 0, c.doubles += n > 1;
  return c;
}

}  // namespace stab
