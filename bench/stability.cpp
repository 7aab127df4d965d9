// stability.cpp — clraster_stability: where the methods fail.
//
//   clraster_stability coords [--size WxH] [--bands N] [--seeds N] [--reach PX|guard] [--csv FILE]
//   clraster_stability load [--tris N] [--fullscreen N] [--size WxH]
//
// coords renders a band mesh (tests/stability_scenes.h: a shared-edge mesh whose vertices lie `reach` pixels from the
// viewport's centre) at growing reach with fixed-point and float edge functions, counts cracked pixels (holes and
// double hits, from the kernels' own coverage) and writes one CSV row per magnitude and method. Reaches past the guard
// band (fixed.h) are clipped to it. --reach renders one reach only ("guard": the largest inside the guard band), for
// one-off checks of large viewports. load renders N small triangles inside one tile and M triangles that each cover the
// whole viewport, and prints one JSON line per scene with the frame time, the bin entries against the expected count,
// the pixels that differ from the oracle (one tile) or from the nearest triangle (full screen) and the device memory.
// Times are wall-clock on whatever else the machine runs; the counts are exact.
#include "cli.h"
#include "device.h"
#include "pipeline.h"
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
  if (a.mode != "coords" && a.mode != "load") throw Error("unknown mode '" + a.mode + "' (coords, load)");
  return a;
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
  std::ofstream csv;
  if (!a.csv.empty()) {
    csv.open(a.csv);
    if (!csv) throw Error(a.csv + ": cannot write");
    csv << "reach,magnitude,clipped,method,holes,doubles,cracked,pixels\n";
  }
  // Step 2: per reach and method, cracks summed over the seeds.
  for (double reach : reaches)
    for (uint32_t edges : {CLR_EDGES_FIXED, CLR_EDGES_FLOAT}) {
      FrameSettings s;
      s.width = a.width;
      s.height = a.height;
      s.edgeMode = edges;
      stab::Cracks sum;
      double magnitude = 0.0;
      for (uint32_t seed = 1; seed <= a.seeds; ++seed) {
        const stab::Scene scene = stab::bandMesh(a.width, a.height, reach, a.bands, angle, seed);
        magnitude = std::max(magnitude, scene.magnitude);
        const stab::Cracks c = stab::countCracks(stab::coverageCounts(cl, scene, s));
        sum.holes += c.holes;
        sum.doubles += c.doubles;
      }
      const char* method = edges == CLR_EDGES_FIXED ? "fixed" : "float";
      char line[256];
      std::snprintf(line, sizeof line, "%.0f,%.1f,%d,%s,%zu,%zu,%zu,%llu\n", reach, magnitude, reach > guard ? 1 : 0,
                    method, sum.holes, sum.doubles, sum.total(),
                    (unsigned long long)(uint64_t(a.width) * a.height * a.seeds));
      std::fputs(line, stdout);
      std::fflush(stdout);
      if (csv) csv << line;
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
    return a.mode == "coords" ? coords(a) : load(a);
  });
}
