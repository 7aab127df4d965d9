// zfight.cpp — clraster_zfight: z-fighting per depth format, the table behind `--depth auto` (host/render/depth.h) and
// docs/limits.md.
//
//   clraster_zfight [--size N] [--device SEL] [--csv FILE] [--summary FILE]
//
// Scene: two parallel planes covering the N×N view (eye at the origin looking down −z, fov 60°), turned 10° about
// y so depth varies; the farther centred at eye distance d, the nearer ε·d closer. Swept: far/near R = 10^1 … 10^6
// in half decades (near 1), d = R^0.25, R^0.5, R^0.75, far/1.25; ε = 10^-2 … 10^-7; both draw orders; each depth
// format (float32, unorm24, reversed). A pixel is wrong when it shows the farther plane or nothing; ties go to the
// earlier triangle, so both orders count. Writes a CSV row per case (--csv), the wrong fraction per format, ratio
// and ε (--summary, for bench/zfight.sh's chart), and prints per ε the largest clean ratio of each format.
// Deterministic: nothing is timed.
#include "render/camera.h"
#include "pipeline/cl.h"
#include "render/flags.h"
#include "render/depth.h"
#include "pipeline/device.h"
#include "pipeline/pipeline.h"
#include "io/scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

using namespace clr;

namespace {

struct Args {
  uint32_t size = 128;
  std::string device, csv = "zfight.csv", summary = "zfight_summary.csv";
};

Args parseArgs(const std::vector<std::string>& args)
{
  Args a;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--size")
      a.size = uint32_t(parseUnsigned("--size", flagValue(args, i), 16, 2048));
    else if (args[i] == "--device")
      a.device = flagValue(args, i);
    else if (args[i] == "--csv")
      a.csv = flagValue(args, i);
    else if (args[i] == "--summary")
      a.summary = flagValue(args, i);
    else
      throw Error("unknown argument '" + args[i] + "'");
  }
  return a;
}

// A square plane of two triangles centred at `centre`, spanned by u and v.
void addPlane(Mesh& m, glm::dvec3 centre, glm::dvec3 u, glm::dvec3 v, double half)
{
  const uint32_t base = uint32_t(m.numVerts());
  for (int k = 0; k < 4; ++k) {
    const glm::dvec3 p = centre + u * (k & 1 ? half : -half) + v * (k & 2 ? half : -half);
    m.positions.insert(m.positions.end(), {float(p.x), float(p.y), float(p.z)});
  }
  m.indices.insert(m.indices.end(), {base, base + 1, base + 3, base, base + 3, base + 2});
}

struct Case {
  uint32_t depthMode;
  double ratio, t, distance, eps;
  bool nearerFirst;
  uint64_t wrong = 0, pixels = 0;
};

}  // namespace

int main(int argc, char** argv)
{
  return runProgram("clraster_zfight", [&] {
    const Args args = parseArgs({argv + 1, argv + argc});
    ClContext cl(args.device);
    Pipeline pipeline(cl);
    const double tilt = glm::radians(10.0);
    const glm::dvec3 u(std::cos(tilt), 0, std::sin(tilt)), v(0, 1, 0), normal(-std::sin(tilt), 0, std::cos(tilt));
    std::vector<double> ratios;  // 10^1, 10^1.5, ..., 10^6
    for (int k = 2; k <= 12; ++k) ratios.push_back(std::pow(10.0, k / 2.0));
    const double ts[] = {0.25, 0.5, 0.75, -1};  // −1: d = far / 1.25
    const double epsilons[] = {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7};
    const uint32_t modes[] = {CLR_DEPTH_FLOAT32, CLR_DEPTH_UNORM24, CLR_DEPTH_REVERSED};
    std::vector<Case> cases;
    // Step 1: every case, one frame each.
    for (double ratio : ratios)
      for (double t : ts)
        for (double eps : epsilons)
          for (int nearerFirst = 0; nearerFirst < 2; ++nearerFirst) {
            const double d = t < 0 ? ratio / 1.25 : std::pow(ratio, t);
            Mesh mesh;
            const glm::dvec3 far(0, 0, -d), near = far + normal * (eps * d);
            addPlane(mesh, nearerFirst ? near : far, u, v, 1.5 * d);
            addPlane(mesh, nearerFirst ? far : near, u, v, 1.5 * d);
            computeSmoothNormals(mesh);
            pipeline.uploadScene(mesh);
            for (uint32_t mode : modes) {
              FrameSettings s;
              s.width = s.height = args.size;
              s.shadeMode = CLR_SHADE_ID;
              s.depthMode = mode;
              s.zNear = 1.0f;
              s.zFar = float(ratio);
              s.mvp = mode == CLR_DEPTH_REVERSED ? reversedPerspective(glm::radians(60.0f), 1.0f, 1.0f, float(ratio))
                                                 : glm::perspective(glm::radians(60.0f), 1.0f, 1.0f, float(ratio));
              std::vector<uint32_t> rgba;
              pipeline.render(s, rgba);
              const std::vector<VisSample> vis = pipeline.readVis();
              const std::vector<clr::SetupRecord> setup = pipeline.readSetup();
              Case c{mode, ratio, t, d, eps, nearerFirst == 1};
              const uint32_t nearerFirstTri = nearerFirst ? 0 : 2;
              for (const VisSample& sample : vis) {
                const bool nearer =
                    sample.setupIndex != CLR_NONE && setup.at(sample.setupIndex).triId / 2 == nearerFirstTri / 2;
                c.wrong += !nearer;
                ++c.pixels;
              }
              cases.push_back(c);
            }
          }
    // Step 2: the per-case CSV.
    std::ofstream csv(args.csv);
    csv << "format,far_near,distance_t,distance,eps_rel,order,wrong,pixels,wrong_fraction\n";
    for (const Case& c : cases) {
      char line[256];
      std::snprintf(line, sizeof line, "%s,%g,%g,%.6g,%g,%s,%llu,%llu,%.6f\n", depthModeName(c.depthMode), c.ratio,
                    c.t < 0 ? 1.0 : c.t, c.distance, c.eps, c.nearerFirst ? "nearer_first" : "farther_first",
                    (unsigned long long)c.wrong, (unsigned long long)c.pixels, double(c.wrong) / double(c.pixels));
      csv << line;
    }
    if (!csv) throw Error(args.csv + ": cannot write");
    // Step 3: the summary per format, ratio and ε, and the boundaries.
    std::map<std::tuple<uint32_t, double, double>, std::pair<uint64_t, uint64_t>> sums;
    for (const Case& c : cases) {
      auto& s = sums[{c.depthMode, c.eps, c.ratio}];
      s.first += c.wrong;
      s.second += c.pixels;
    }
    std::ofstream summary(args.summary);
    summary << "format,eps_rel,far_near,wrong,pixels,wrong_fraction\n";
    for (const auto& [key, s] : sums) {
      char line[200];
      std::snprintf(line, sizeof line, "%s,%g,%g,%llu,%llu,%.6f\n", depthModeName(std::get<0>(key)), std::get<1>(key),
                    std::get<2>(key), (unsigned long long)s.first, (unsigned long long)s.second,
                    double(s.first) / double(s.second));
      summary << line;
    }
    if (!summary) throw Error(args.summary + ": cannot write");
    for (double eps : epsilons)
      for (uint32_t mode : modes) {
        double largest = 0;
        for (double ratio : ratios) {
          if (sums[{mode, eps, ratio}].first != 0) break;
          largest = ratio;
        }
        std::printf("eps %-6g %-9s no wrong pixel up to far/near %g\n", eps, depthModeName(mode), largest);
      }
    return 0;
  });
}
