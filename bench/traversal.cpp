// traversal.cpp — clraster_traversal: the traversal methods against
// triangle size, from sub-pixel to full screen (bench/traversal.sh).
//
//   clraster_traversal [--size WxH] [--reps N] [--sizes S,S,...] [--device SEL] [--csv FILE]
//                      [--markdown FILE]
//
// For each triangle size s (pixels: the triangles are near-equilateral with
// circumradius s/2, random centres on the screen and random depths; as many
// as cover the screen about twice, from 8 up to 1,000,000), every method
// renders the scene (ID shading, one sample) once to warm up, then N times
// in turn, the methods alternated within each round so that the load of a
// shared machine falls on all alike. Per size and method: the median
// raster kernel time, the median of all kernels (binning differs between
// methods), and the bin entries. Times come from OpenCL profiling events.
#include "render/flags.h"
#include "pipeline/device.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace clr;

namespace {

struct Args {
  uint32_t width = 1920, height = 1080, reps = 7;
  std::string device, csv = "traversal.csv", markdown = "traversal.md";
  std::vector<double> sizes = {0.5, 1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2200};
};

Args parse(int argc, char** argv)
{
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) throw Error(flag + ": missing value");
    const std::string value = argv[++i];
    if (flag == "--size")
      parseSize(flag, value, a.width, a.height);
    else if (flag == "--reps")
      a.reps = uint32_t(parseUnsigned(flag, value, 1, 1000));
    else if (flag == "--sizes") {
      a.sizes.clear();
      size_t start = 0;
      while (start <= value.size()) {
        const size_t comma = std::min(value.find(',', start), value.size());
        a.sizes.push_back(double(parseUnsigned(flag, value.substr(start, comma - start), 1, 100000)));
        start = comma + 1;
      }
    } else if (flag == "--device")
      a.device = value;
    else if (flag == "--csv")
      a.csv = value;
    else if (flag == "--markdown")
      a.markdown = value;
    else
      throw Error("unknown flag " + flag);
  }
  return a;
}

Mesh sizedTriangles(uint32_t width, uint32_t height, double size, uint64_t count)
{
  std::mt19937 rng(uint32_t(size * 1000));
  std::uniform_real_distribution<double> x(0.0, width), y(0.0, height), angle(0.0, 2.0 * M_PI), depth(-0.9, 0.9);
  Mesh m;
  for (uint64_t t = 0; t < count; ++t) {
    const double cx = x(rng), cy = y(rng), a0 = angle(rng), z = depth(rng);
    for (int k = 0; k < 3; ++k) {
      const double a = a0 + k * 2.0 * M_PI / 3.0;
      const double sx = cx + 0.5 * size * std::cos(a), sy = cy + 0.5 * size * std::sin(a);
      m.positions.insert(m.positions.end(), {float(2.0 * sx / width - 1.0), float(2.0 * sy / height - 1.0), float(z)});
      m.indices.push_back(uint32_t(3 * t + k));
    }
  }
  m.normals.assign(m.positions.size(), 0.0f);
  return m;
}

struct Method {
  const char* name;
  uint32_t traversal;
};
const Method kMethods[] = {{"bbox", CLR_TRAVERSAL_BBOX},
                           {"hierarchical", CLR_TRAVERSAL_HIERARCHICAL},
                           {"spans", CLR_TRAVERSAL_SPANS},
                           {"spans-float", CLR_TRAVERSAL_SPANS_FLOAT}};
constexpr int kNumMethods = 4;

double kernelMs(const FrameStats& s)
{
  double sum = 0.0;
  for (const auto& [stage, ms] : s.stageMs) sum += ms;
  return sum;
}

int run(const Args& a)
{
  ClContext cl(a.device);
  std::ofstream csv(a.csv), md(a.markdown);
  if (!csv) throw Error(a.csv + ": cannot write");
  if (!md) throw Error(a.markdown + ": cannot write");
  csv << "size,triangles,method,raster_ms,kernels_ms,bin_entries\n";
  md << "Device: " << cl.info.name << ", " << a.width << "x" << a.height << ", ID shading, one sample; median of "
     << a.reps << " rounds with the methods alternated in each (a shared, loaded machine). Raster kernel ms "
     << "(all kernels ms in brackets: binning differs by method); in bold the exact method with the least "
     << "time over all kernels.\n\n"
     << "| triangle size (px) | triangles | bbox | hierarchical | spans | spans-float |\n|---|---|---|---|---|---|\n";
  const double screen = double(a.width) * a.height;
  for (double size : a.sizes) {
    const double area = 0.75 * std::sqrt(3.0) * 0.25 * size * size;  // equilateral, circumradius size/2
    const uint64_t count = uint64_t(std::clamp(std::round(2.0 * screen / area), 8.0, 1e6));
    Pipeline pipeline(cl);
    pipeline.uploadScene(sizedTriangles(a.width, a.height, size, count));
    FrameSettings s;
    s.width = a.width;
    s.height = a.height;
    s.shadeMode = CLR_SHADE_ID;
    std::vector<uint32_t> rgba;
    std::vector<double> raster[kNumMethods], kernels[kNumMethods];
    uint64_t entries[kNumMethods] = {};
    for (uint32_t round = 0; round <= a.reps; ++round)
      for (int m = 0; m < kNumMethods; ++m) {
        s.traversal = kMethods[m].traversal;
        const FrameStats stats = pipeline.render(s, rgba);
        if (round == 0) continue;  // warm-up
        raster[m].push_back(stats.stageMs.at("raster"));
        kernels[m].push_back(kernelMs(stats));
        entries[m] = stats.binEntries;
      }
    double med[kNumMethods], all[kNumMethods];
    int best = 0;
    for (int m = 0; m < kNumMethods; ++m) {
      med[m] = median(raster[m]);
      all[m] = median(kernels[m]);
      if (m < 3 && all[m] < all[best]) best = m;
      char line[200];
      std::snprintf(line, sizeof line, "%g,%llu,%s,%.3f,%.3f,%llu\n", size, (unsigned long long)count, kMethods[m].name,
                    med[m], all[m], (unsigned long long)entries[m]);
      csv << line;
      std::fputs(line, stdout);
      std::fflush(stdout);
    }
    md << "| " << size << " | " << count;
    for (int m = 0; m < kNumMethods; ++m) {
      char cell[80];
      std::snprintf(cell, sizeof cell, m == best ? " | **%.2f (%.2f)**" : " | %.2f (%.2f)", med[m], all[m]);
      md << cell;
    }
    md << " |\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  return runProgram("clraster_traversal", [&] { return run(parse(argc, argv)); });
}
