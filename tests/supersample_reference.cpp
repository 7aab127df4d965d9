// supersample_reference.cpp — see supersample_reference.h. One tile (a run of
// pixels in one row) at a time: a sample buffer (position, depth, triangle)
// for the tile's S sample rows, the tile's triangles z-buffered into it in
// input order, then each pixel's samples shaded and averaged.
#include "supersample_reference.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace oracle {

namespace {

constexpr uint32_t kNone = 0xFFFFFFFFu;

// An edge a → b of a counter-clockwise triangle, evaluated from its
// canonical endpoint (the lexicographically smaller one) so that both
// triangles sharing it compute the same magnitude with opposite signs.
struct Edge {
  glm::dvec2 origin, delta;  // canonical endpoint, other endpoint − origin
  double sign = 1.0;         // +1 when the canonical endpoint is a
  bool inclusive = false;    // left edge or horizontal bottom edge
  glm::dvec2 a, b;           // the endpoints, for the row extents

  // Twice the signed area of (a, b, p): > 0 on the triangle's side. The y
  // term may be computed once per sample row: the result is the same.
  double yTerm(double y) const { return delta.x * (y - origin.y); }
  double at(double yTerm, double x) const { return sign * (yTerm - delta.y * (x - origin.x)); }
  double operator()(const glm::dvec2& p) const { return at(yTerm(p.y), p.x); }
  bool inside(double e) const { return e > 0.0 || (e == 0.0 && inclusive); }
};

struct Triangle {
  uint32_t id = 0;
  Edge edge[3];          // edge[k] is opposite counter-clockwise vertex k
  int original[3];       // counter-clockwise vertex k is input vertex original[k]
  bool swapped = false;  // original = {0, 2, 1}: the input was clockwise
  double z0, dz1, dz2;   // depth = z0 + (e1·dz1 + e2·dz2) / area2
  double invArea2;
  double invW[3];  // counter-clockwise order
  double minX, maxX, minY, maxY;
};

Edge makeEdge(const glm::dvec2& a, const glm::dvec2& b)
{
  Edge e;
  e.a = a;
  e.b = b;
  const bool aFirst = a.x < b.x || (a.x == b.x && a.y < b.y);
  e.origin = aFirst ? a : b;
  e.delta = aFirst ? b - a : a - b;
  e.sign = aFirst ? 1.0 : -1.0;
  const glm::dvec2 d = b - a;
  e.inclusive = d.y < 0.0 || (d.y == 0.0 && d.x > 0.0);
  return e;
}

// Step: orient counter-clockwise and precompute; false for a triangle that
// can cover no sample.
bool setup(const ScreenVertex* v, uint32_t id, Triangle& t)
{
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(v[i].xy.x) || !std::isfinite(v[i].xy.y) || !std::isfinite(v[i].z) || !std::isfinite(v[i].invW))
      return false;
  const glm::dvec2 d1 = v[1].xy - v[0].xy, d2 = v[2].xy - v[0].xy;
  double area2 = d1.x * d2.y - d1.y * d2.x;
  if (area2 == 0.0) return false;
  t.id = id;
  t.original[0] = 0;
  t.original[1] = area2 > 0.0 ? 1 : 2;
  t.original[2] = area2 > 0.0 ? 2 : 1;
  t.swapped = area2 < 0.0;
  area2 = std::fabs(area2);
  glm::dvec2 p[3];
  for (int k = 0; k < 3; ++k) {
    p[k] = v[t.original[k]].xy;
    t.invW[k] = v[t.original[k]].invW;
  }
  for (int k = 0; k < 3; ++k) t.edge[k] = makeEdge(p[(k + 1) % 3], p[(k + 2) % 3]);
  t.invArea2 = 1.0 / area2;
  t.z0 = v[t.original[0]].z;
  t.dz1 = v[t.original[1]].z - t.z0;
  t.dz2 = v[t.original[2]].z - t.z0;
  t.minX = std::min({p[0].x, p[1].x, p[2].x});
  t.maxX = std::max({p[0].x, p[1].x, p[2].x});
  t.minY = std::min({p[0].y, p[1].y, p[2].y});
  t.maxY = std::max({p[0].y, p[1].y, p[2].y});
  return true;
}

// The triangle's x extent within the strip yLo <= y <= yHi; false if none.
bool stripExtent(const Triangle& t, double yLo, double yHi, double& xLo, double& xHi)
{
  xLo = INFINITY;
  xHi = -INFINITY;
  for (const Edge& e : t.edge) {
    const double eyLo = std::min(e.a.y, e.b.y), eyHi = std::max(e.a.y, e.b.y);
    if (eyHi < yLo || eyLo > yHi) continue;
    double x[2] = {e.a.x, e.b.x};
    if (e.a.y != e.b.y) {
      // Step: the segment's ends clamped to the strip.
      for (int s = 0; s < 2; ++s) {
        const double y = std::min(eyHi, std::max(eyLo, s ? yHi : yLo));
        x[s] = e.a.x + (y - e.a.y) / (e.b.y - e.a.y) * (e.b.x - e.a.x);
      }
    }
    xLo = std::min({xLo, x[0], x[1]});
    xHi = std::max({xHi, x[0], x[1]});
  }
  return xLo <= xHi;
}

uint64_t splitmix64(uint64_t x)
{
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Sample (sx, sy) of pixel (x, y): the cell's centre or, jittered, a hashed point in it.
glm::dvec2 placeSample(const SupersampleOptions& o, uint32_t x, uint32_t y, uint32_t sx, uint32_t sy)
{
  const double S = double(o.samplesPerAxis);
  if (!o.jitter) return glm::dvec2(double(x) + (double(sx) + 0.5) / S, double(y) + (double(sy) + 0.5) / S);
  // Step: two 53-bit uniforms in [0, 1) from the seed and the sample's index.
  const uint64_t index = ((uint64_t(y) * o.width + x) * o.samplesPerAxis + sy) * o.samplesPerAxis + sx;
  const uint64_t h1 = splitmix64(o.seed ^ splitmix64(index)), h2 = splitmix64(h1);
  const double u = double(h1 >> 11) * 0x1.0p-53, v = double(h2 >> 11) * 0x1.0p-53;
  return glm::dvec2(double(x) + (double(sx) + u) / S, double(y) + (double(sy) + v) / S);
}

// One tile's samples (a run of `pixels` pixels in one pixel row): S sample
// rows of pixels·S samples each, small enough to stay in cache.
struct TileBuffer {
  std::vector<glm::dvec2> position;
  std::vector<double> depth;
  std::vector<uint32_t> triangle;
};

// Tests samples [begin, end) of one sample row against t and z-buffers the
// covered ones. kSameY: the samples share one y (unjittered).
template <bool kSameY>
void drawSpan(const Triangle& t, uint32_t ti, size_t begin, size_t end, TileBuffer& buf)
{
  double yTerm[3] = {0.0, 0.0, 0.0};
  if (kSameY)
    for (int k = 0; k < 3; ++k) yTerm[k] = t.edge[k].yTerm(buf.position[begin].y);
  for (size_t s = begin; s < end; ++s) {
    const glm::dvec2 p = buf.position[s];
    double e[3];
    for (int k = 0; k < 3; ++k) e[k] = t.edge[k].at(kSameY ? yTerm[k] : t.edge[k].yTerm(p.y), p.x);
    if (!(t.edge[0].inside(e[0]) && t.edge[1].inside(e[1]) && t.edge[2].inside(e[2]))) continue;
    const double z = t.z0 + (e[1] * t.dz1 + e[2] * t.dz2) * t.invArea2;
    if (!(z < buf.depth[s])) continue;
    buf.depth[s] = z;
    buf.triangle[s] = ti;
  }
}

// Renders pixels x0 .. x0 + pixels − 1 of row y.
void renderTile(uint32_t x0, uint32_t y, uint32_t pixels, const std::vector<Triangle>& tris,
                const std::vector<uint32_t>& tileTris, const ShadeFn& shade, const SupersampleOptions& o,
                TileBuffer& buf, SupersampleResult& r)
{
  const uint32_t S = o.samplesPerAxis;
  const size_t stride = size_t(pixels) * S;
  // Step 1: clear, and place the samples.
  buf.position.resize(stride * S);
  buf.depth.assign(stride * S, 1.0);
  buf.triangle.assign(stride * S, kNone);
  for (uint32_t sy = 0; sy < S; ++sy)
    for (uint32_t x = 0; x < pixels; ++x)
      for (uint32_t sx = 0; sx < S; ++sx) buf.position[sy * stride + x * S + sx] = placeSample(o, x0 + x, y, sx, sy);
  // Step 2: z-buffer the tile's triangles in input order, sample row by sample
  // row, each restricted to the triangle's extent in that row.
  const double firstColumn = double(x0) * S, lastColumn = firstColumn + double(stride) - 1.0;
  for (uint32_t ti : tileTris) {
    const Triangle& t = tris[ti];
    for (uint32_t sy = 0; sy < S; ++sy) {
      const double cellLo = double(y) + double(sy) / S, cellHi = double(y) + double(sy + 1) / S;
      const double yLo = o.jitter ? cellLo : buf.position[sy * stride].y, yHi = o.jitter ? cellHi : yLo;
      if (yHi < t.minY || yLo > t.maxY) continue;
      double xLo, xHi;
      if (!stripExtent(t, yLo, yHi, xLo, xHi)) continue;
      // Sample columns whose cells meet [xLo, xHi], one more each side for rounding.
      const double cLo = std::max(firstColumn, std::floor(xLo * S) - 1.0);
      const double cHi = std::min(lastColumn, std::floor(xHi * S) + 1.0);
      if (cHi < cLo) continue;
      const size_t begin = sy * stride + size_t(cLo - firstColumn), end = sy * stride + size_t(cHi - firstColumn) + 1;
      if (o.jitter)
        drawSpan<false>(t, ti, begin, end, buf);
      else
        drawSpan<true>(t, ti, begin, end, buf);
    }
  }
  // Step 3: shade each covered sample with its perspective-correct λ and average.
  const double invCount = 1.0 / (double(S) * S);
  for (uint32_t x = 0; x < pixels; ++x) {
    glm::dvec3 sum(0.0);
    uint64_t covered = 0;
    for (uint32_t sy = 0; sy < S; ++sy)
      for (uint32_t sx = 0; sx < S; ++sx) {
        const size_t s = sy * stride + x * S + sx;
        if (buf.triangle[s] == kNone) {
          sum += o.background;
          continue;
        }
        const Triangle& t = tris[buf.triangle[s]];
        const glm::dvec2 p = buf.position[s];
        double q[3], qSum = 0.0;
        for (int k = 0; k < 3; ++k) qSum += q[k] = t.edge[k](p) * t.invW[k];
        const double invSum = 1.0 / qSum;
        const glm::dvec3 lambda = invSum * (t.swapped ? glm::dvec3(q[0], q[2], q[1]) : glm::dvec3(q[0], q[1], q[2]));
        sum += shade(t.id, lambda);
        ++covered;
      }
    const size_t pixel = size_t(y) * o.width + x0 + x;
    r.color[pixel] = sum * invCount;
    r.coverage[pixel] = double(covered) * invCount;
  }
}

}  // namespace

glm::dvec2 samplePosition(const SupersampleOptions& o, uint32_t x, uint32_t y, uint32_t sx, uint32_t sy)
{
  return placeSample(o, x, y, sx, sy);
}

SupersampleResult supersampleRender(const std::vector<ScreenVertex>& verts, const ShadeFn& shade,
                                    const SupersampleOptions& o)
{
  if (o.samplesPerAxis == 0) throw std::invalid_argument("supersampleRender: samplesPerAxis must be positive");
  SupersampleResult r;
  r.width = o.width;
  r.height = o.height;
  r.color.assign(size_t(o.width) * o.height, o.background);
  r.coverage.assign(size_t(o.width) * o.height, 0.0);
  if (o.width == 0 || o.height == 0) return r;
  // Step 1: set up the triangles and bin them into tiles: runs of pixels in a
  // row holding about 32k samples.
  const uint32_t tileW = std::max(1u, std::min(o.width, 32768u / std::max(1u, o.samplesPerAxis * o.samplesPerAxis)));
  const uint32_t tilesX = (o.width + tileW - 1) / tileW;
  std::vector<Triangle> tris;
  std::vector<std::vector<uint32_t>> tiles(size_t(tilesX) * o.height);
  for (size_t i = 0; i + 2 < verts.size(); i += 3) {
    Triangle t;
    if (!setup(&verts[i], uint32_t(i / 3), t)) continue;
    if (t.maxX < 0.0 || t.minX > double(o.width) || t.maxY < 0.0 || t.minY > double(o.height)) continue;
    const double y0 = std::max(0.0, std::floor(t.minY)), y1 = std::min(double(o.height) - 1.0, std::floor(t.maxY));
    const double x0 = std::max(0.0, std::floor(t.minX)), x1 = std::min(double(o.width) - 1.0, std::floor(t.maxX));
    for (size_t y = size_t(y0); double(y) <= y1; ++y)
      for (size_t tx = size_t(x0) / tileW; tx <= size_t(x1) / tileW; ++tx)
        tiles[y * tilesX + tx].push_back(uint32_t(tris.size()));
    tris.push_back(t);
  }
  // Step 2: tiles shared out among the threads.
  std::atomic<size_t> next{0};
  const auto worker = [&]() {
    TileBuffer buf;
    for (size_t tile; (tile = next.fetch_add(1)) < tiles.size();) {
      const uint32_t x0 = uint32_t(tile % tilesX) * tileW, y = uint32_t(tile / tilesX);
      renderTile(x0, y, std::min(tileW, o.width - x0), tris, tiles[tile], shade, o, buf, r);
    }
  };
  unsigned threads = o.threads ? o.threads : std::max(1u, std::thread::hardware_concurrency());
  threads = unsigned(std::min(size_t(threads), tiles.size()));
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread& th : pool) th.join();
  return r;
}

}  // namespace oracle
