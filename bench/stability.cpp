// stability.cpp — clraster_stability: where the methods fail.
//
//   clraster_stability coords [--size WxH] [--bands N] [--seeds N] [--reach PX|guard] [--csv FILE]
//   clraster_stability walk [--size WxH] [--seeds N] [--csv FILE]
//   clraster_stability load [--tris N] [--fullscreen N] [--size WxH]
//
// coords renders a band mesh (tests/stability_scenes.h: a shared-edge mesh
// whose vertices lie `reach` pixels from the viewport's centre) at growing
// reach with each coverage method (fixed-point and float edge functions,
// exact spans, the float edge walk), counts cracked pixels (holes and
// double hits, from the kernels' own coverage) and writes one CSV row per
// magnitude and method. walk counts them, per method, on the cases where
// the edge walk of span tables fails: slivers (band meshes of more and
// thinner bands at a fixed reach), flat-top and flat-bottom triangles (a
// strip mesh whose every triangle has a level edge, some on sample rows),
// and triangles made degenerate by the split (the same mesh with its rows'
// vertices moved up and down by a few 1/256 px, so that one half of each
// triangle is that thin). Reaches past the guard band (fixed.h) are
// clipped to it. --reach renders one reach only ("guard": the largest
// inside the guard band), for one-off checks of large viewports. load renders N small triangles inside one tile and M
// triangles that each cover the whole viewport, and prints one JSON line
// per scene with the frame time, the bin entries against the expected
// count, the pixels that differ from the oracle (one tile) or from the
// nearest triangle (full screen) and the device memory. Times are wall-clock on whatever else the
// machine runs; the counts are exact.
#include "render/flags.h"
#include "pipeline/device.h"
#include "pipeline/pipeline.h"
#include "reference_raster.h"
#include "stability_scenes.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace clr;

namespace {

struct Args {
  std::string mode;
  uint32_t width = 512, height = 512, bands = 64, seeds = 3;
  uint64_t tris = 10000000, fullscreen = 4000;
  std::string csv;
  std::string reach;  // empty: the whole sweep
};

Args parse(int argc, char** argv)
{
  Args a;
  if (argc < 2) throw Error("usage: clraster_stability coords|load [options] (see bench/stability.cpp)");
  a.mode = argv[1];
  bool sizeGiven = false;
  for (int i = 2; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) throw Error(flag + ": missing value");
    const std::string value = argv[++i];
    if (flag == "--size") {
      parseSize(flag, value, a.width, a.height);
      sizeGiven = true;
    } else if (flag == "--bands")
      a.bands = parseUnsigned(flag, value, 1, 100000);
    else if (flag == "--seeds")
      a.seeds = parseUnsigned(flag, value, 1, 1000);
    else if (flag == "--tris")
      a.tris = parseUnsigned(flag, value, 1, 100000000);
    else if (flag == "--fullscreen")
      a.fullscreen = parseUnsigned(flag, value, 1, 1000000);
    else if (flag == "--csv")
      a.csv = value;
    else if (flag == "--reach")
      a.reach = value;
    else
      throw Error("unknown flag " + flag);
  }
  if (a.mode == "load" && !sizeGiven) a.width = 1920, a.height = 1080;
  if (a.mode != "coords" && a.mode != "walk" && a.mode != "load")
    throw Error("unknown mode '" + a.mode + "' (coords, walk, load)");
  return a;
}

// The coverage methods compared: name, edge mode, traversal.
struct Method {
  const char* name;
  uint32_t edges, traversal;
};
const Method kMethods[] = {{"fixed", CLR_EDGES_FIXED, CLR_TRAVERSAL_BBOX},
                           {"float", CLR_EDGES_FLOAT, CLR_TRAVERSAL_BBOX},
                           {"spans", CLR_EDGES_FIXED, CLR_TRAVERSAL_SPANS},
                           {"spans-float", CLR_EDGES_FIXED, CLR_TRAVERSAL_SPANS_FLOAT}};

FrameSettings methodSettings(const Args& a, const Method& m)
{
  FrameSettings s;
  s.width = a.width;
  s.height = a.height;
  s.edgeMode = m.edges;
  s.traversal = m.traversal;
  return s;
}

// The --csv file with its header line, or a closed stream without --csv.
std::ofstream openCsv(const Args& a, const char* header)
{
  std::ofstream csv;
  if (a.csv.empty()) return csv;
  csv.open(a.csv);
  if (!csv) throw Error(a.csv + ": cannot write");
  csv << header;
  return csv;
}

// One result row to stdout, flushed (a long run shows its progress), and to the CSV.
void emitRow(const char* line, std::ofstream& csv)
{
  std::fputs(line, stdout);
  std::fflush(stdout);
  if (csv) csv << line;
}

int coords(const Args& a)
{
  ClContext cl("");
  const double angle = 35.0;
  const double guard = stab::guardBandReach(a.width, a.height, a.bands, angle);
  std::vector<double> reaches;
  // Step 1: reaches from the smallest that covers the viewport (the band
  // lines must pass it) up by sqrt(2), the guard-band limit itself, then
  // beyond it (clipped).
  const double rad = angle * M_PI / 180.0;
  const double cover = 0.5 * (a.width * std::fabs(std::cos(rad)) + a.height * std::fabs(std::sin(rad))) + 4.0;
  for (double r = 64.0; r < guard; r *= std::sqrt(2.0))
    if (r >= cover) reaches.push_back(std::round(r));
  reaches.push_back(guard);
  for (double r = 131072.0; r <= 16777216.0; r *= 2.0) reaches.push_back(r);
  if (!a.reach.empty()) reaches = {a.reach == "guard" ? guard : double(parseUnsigned("--reach", a.reach, 1, 1u << 30))};
  std::ofstream csv = openCsv(a, "reach,magnitude,clipped,method,holes,doubles,cracked,pixels\n");
  // Step 2: per reach and method, cracks summed over the seeds.
  for (double reach : reaches)
    for (const Method& m : kMethods) {
      const FrameSettings s = methodSettings(a, m);
      stab::Cracks sum;
      double magnitude = 0.0;
      for (uint32_t seed = 1; seed <= a.seeds; ++seed) {
        const stab::Scene scene = stab::bandMesh(a.width, a.height, reach, a.bands, angle, seed);
        magnitude = std::max(magnitude, scene.magnitude);
        const stab::Cracks c = stab::countCracks(stab::coverageCounts(cl, scene, s));
        sum.holes += c.holes;
        sum.doubles += c.doubles;
      }
      char line[256];
      std::snprintf(line, sizeof line, "%.0f,%.1f,%d,%s,%zu,%zu,%zu,%llu\n", reach, magnitude, reach > guard ? 1 : 0,
                    m.name, sum.holes, sum.doubles, sum.total(),
                    (unsigned long long)(uint64_t(a.width) * a.height * a.seeds));
      emitRow(line, csv);
    }
  return 0;
}

// A strip mesh covering the viewport: `rows` level lines from below to
// above it (every other one on a sample row), `columns` vertices on each at
// jittered x (on the 1/256 grid) from `reach` px left of the viewport's
// centre to as far right, and between two lines a zig-zag of
// triangles with a level edge on one line: flat-bottom or flat-top. With
// lift > 0 each line's vertices move up and down by lift/256 px in turn, so
// the triangles are no longer flat: one half after the split is at most
// 2·lift/256 px tall. Classes: strip parity × triangle index mod 4.
stab::Scene stripMesh(uint32_t width, uint32_t height, double reach, uint32_t rows, uint32_t columns, int lift,
                      uint32_t seed)
{
  std::mt19937 rng(seed);
  const double left = std::min(-2.0, 0.5 * width - reach), spacing = (width - 2.0 * left) / columns;
  std::uniform_real_distribution<double> jitter(-spacing / 4, spacing / 4);
  stab::Scene s;
  std::vector<std::vector<uint32_t>> line(rows + 1);
  for (uint32_t j = 0; j <= rows; ++j) {
    double y = -2.0 + (height + 4.0) * j / rows;
    y = j % 2 ? std::floor(y) + 0.5 : std::round(y * 256.0) / 256.0;
    for (uint32_t i = 0; i <= columns; ++i) {
      const double x = left + spacing * i + (i == 0 || i == columns ? 0.0 : jitter(rng));
      const double dy = (i % 2 ? lift : -lift) / 256.0;
      line[j].push_back(uint32_t(s.positions.size() / 3));
      stab::addScreenVertex(s, std::round(x * 256.0) / 256.0, y + dy, width, height);
    }
  }
  auto xOf = [&](uint32_t v) { return s.positions[3 * v]; };
  for (uint32_t j = 0; j < rows; ++j) {
    const std::vector<uint32_t>&bottom = line[j], &top = line[j + 1];
    size_t b = 0, t = 0, n = 0;
    while (b + 1 < bottom.size() || t + 1 < top.size()) {
      const bool alongBottom = t + 1 >= top.size() || (b + 1 < bottom.size() && xOf(bottom[b + 1]) < xOf(top[t + 1]));
      if (alongBottom) {
        s.indices.insert(s.indices.end(), {bottom[b], bottom[b + 1], top[t]});
        ++b;
      } else {
        s.indices.insert(s.indices.end(), {bottom[b], top[t + 1], top[t]});
        ++t;
      }
      s.cls.push_back(uint8_t((j % 2) * 4 + n++ % 4));
    }
  }
  s.numClasses = 8;
  return s;
}

int walk(const Args& a)
{
  ClContext cl("");
  std::ofstream csv = openCsv(a, "case,param,reach,aspect,method,holes,doubles,cracked,pixels\n");
  struct Case {
    std::string name;
    double param, reach;
  };
  std::vector<Case> cases;
  for (double bands : {8, 32, 128, 512, 2048}) cases.push_back({"slivers", bands, 4096});
  for (double reach : {256, 2048, 16384}) cases.push_back({"flat", 0, reach});
  for (double reach : {256, 2048, 16384})
    for (double lift : {1, 4, 16}) cases.push_back({"split", lift, reach});
  const double angle = 35.0;
  for (const Case& c : cases)
    for (const Method& m : kMethods) {
      stab::Cracks sum;
      double aspect = 0.0;
      for (uint32_t seed = 1; seed <= a.seeds; ++seed) {
        stab::Scene scene;
        if (c.name == "slivers") {
          scene = stab::bandMesh(a.width, a.height, c.reach, uint32_t(c.param), angle, seed);
          const double rad = angle * M_PI / 180.0;  // the band spacing of stability_scenes.cpp's layout
          const double halfV = 0.5 * a.width * std::fabs(std::sin(rad)) + 0.5 * a.height * std::fabs(std::cos(rad));
          aspect = 2.0 * c.reach / (2.0 * (halfV + 2.0) / c.param);
        } else {
          scene = stripMesh(a.width, a.height, c.reach, 48, 40, int(c.param), seed);
          aspect = (a.width + 2.0 * c.reach) / 40.0 / ((a.height + 4.0) / 48.0);
        }
        const stab::Cracks k = stab::countCracks(stab::coverageCounts(cl, scene, methodSettings(a, m)));
        sum.holes += k.holes;
        sum.doubles += k.doubles;
      }
      char line[256];
      std::snprintf(line, sizeof line, "%s,%g,%g,%.0f,%s,%zu,%zu,%zu,%llu\n", c.name.c_str(), c.param, c.reach, aspect,
                    m.name, sum.holes, sum.doubles, sum.total(),
                    (unsigned long long)(uint64_t(a.width) * a.height * a.seeds));
      emitRow(line, csv);
    }
  return 0;
}

double msSince(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

int load(const Args& a)
{
  ClContext cl("");
  const uint32_t W = a.width, H = a.height;
  auto ndc = [&](double sx, double sy) { return glm::vec2(float(2.0 * sx / W - 1.0), float(2.0 * sy / H - 1.0)); };
  // Step 1: N triangles inside tile (1, 1), at depths that fall with the index.
  for (int scene = 0; scene < 2; ++scene) {
    Mesh m;
    const uint64_t n = scene == 0 ? a.tris : a.fullscreen;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> in(16.5, 31.5);
    m.positions.reserve(9 * n);
    for (uint64_t t = 0; t < n; ++t) {
      const float z = float(1.0 - 2.0 * double(t + 1) / double(n + 2));
      for (int v = 0; v < 3; ++v) {
        glm::vec2 p;
        if (scene == 0)
          p = ndc(in(rng), in(rng));
        else
          p = v == 0 ? glm::vec2(-1.0f, -1.0f) : v == 1 ? glm::vec2(3.0f, -1.0f) : glm::vec2(-1.0f, 3.0f);
        m.positions.insert(m.positions.end(), {p.x, p.y, z});
        m.indices.push_back(uint32_t(3 * t + v));
      }
    }
    m.normals.assign(m.positions.size(), 0.0f);
    // Step 2: a warm-up frame, then a timed one.
    Pipeline pipeline(cl);
    pipeline.uploadScene(m);
    FrameSettings s;
    s.width = W;
    s.height = H;
    s.shadeMode = CLR_SHADE_ID;
    std::vector<uint32_t> rgba;
    pipeline.render(s, rgba);
    const auto start = std::chrono::steady_clock::now();
    const FrameStats stats = pipeline.render(s, rgba);
    const double ms = msSince(start);
    const uint64_t tiles =
        uint64_t((W + CLR_TILE_SIZE - 1) / CLR_TILE_SIZE) * ((H + CLR_TILE_SIZE - 1) / CLR_TILE_SIZE);
    const uint64_t expected = scene == 0 ? stats.setupTriangles : n * tiles;
    // Step 3: the visible triangles against the scalar oracle (one tile) or
    // the last, nearest triangle everywhere (full screen).
    const std::vector<VisSample> vis = pipeline.readVis(0);
    const std::vector<clr::SetupRecord> setup = pipeline.readSetup();
    std::vector<uint32_t> want;
    if (scene == 0)
      want = ref::rasterize(m.positions, m.indices, glm::mat4(1.0f), {W, H, false}).triId;
    else
      want.assign(vis.size(), uint32_t(n - 1));
    uint64_t differing = 0;
    for (size_t p = 0; p < vis.size(); ++p)
      differing += (vis[p].setupIndex == CLR_NONE ? ref::kNone : setup[vis[p].setupIndex].triId) != want[p];
    std::printf(
        "{\"scene\":\"%s\",\"width\":%u,\"height\":%u,\"triangles\":%llu,\"setup_triangles\":%llu,"
        "\"bin_entries\":%llu,\"expected_bin_entries\":%llu,\"pixels_differing\":%llu,\"device_bytes\":%zu,"
        "\"frame_ms\":%.1f}\n",
        scene == 0 ? "one_tile" : "fullscreen", W, H, (unsigned long long)n, (unsigned long long)stats.setupTriangles,
        (unsigned long long)stats.binEntries, (unsigned long long)expected, (unsigned long long)differing,
        pipeline.deviceBytes(), ms);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  return runProgram("clraster_stability", [&] {
    const Args a = parse(argc, argv);
    return a.mode == "coords" ? coords(a) : a.mode == "walk" ? walk(a) : load(a);
  });
}
