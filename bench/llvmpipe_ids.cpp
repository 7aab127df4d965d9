// llvmpipe_ids.cpp — clraster_vs_llvmpipe: the same triangles, camera and viewport rendered as triangle-ID images by
// Mesa llvmpipe (OSMesa, legacy GL, depth LESS, flat colour = triangle index + 1) and by clraster (CLR_SHADE_ID),
// compared pixel by pixel.
//
//   clraster_vs_llvmpipe [SCENE] [--size WxH] [--device SEL] [--diff OUT.png]
//                        [--max-diff-fraction F] [--frames N]
//
// Ids are triangle index + 1 (0: background) in the low 24 bits, as in CLR_SHADE_ID. Prints one JSON line on stdout. A
// differing pixel is "near an edge" unless its 3x3 neighbourhood holds a single id in both images; differing pixels
// that are not near an edge are real disagreements (or exact depth ties of coplanar overlapping triangles), not vertex
// rounding. With --max-diff-fraction F the exit status is 1 when the differing fraction exceeds F or any differing
// pixel is not near an edge. Every failure is one line on stderr and exit status 1.
#include "render/camera.h"
#include "render/flags.h"
#include "pipeline/cl.h"
#include "pipeline/device.h"
#include "io/image_io.h"
#include "llvmpipe_render.h"
#include "pipeline/pipeline.h"
#include "io/scene.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

using namespace clr;
using clr::bench::compareIds;
using clr::bench::fixHeapTrimThreshold;
using clr::bench::IdComparison;
using clr::bench::kIdMask;
using clr::bench::LlvmpipeFrames;
using clr::bench::renderLlvmpipeIds;

namespace {

struct Args {
  std::string scenePath;  // empty: the built-in default scene
  uint32_t width = 1280, height = 720;
  std::string device;
  std::string diffPath;
  std::optional<double> maxDiffFraction;
  uint32_t frames = 1;
};

Args parseArgs(const std::vector<std::string>& args)
{
  Args r;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--size") {
      parseSize(a, flagValue(args, i), r.width, r.height);
    } else if (a == "--device") {
      r.device = flagValue(args, i);
    } else if (a == "--diff") {
      r.diffPath = flagValue(args, i);
    } else if (a == "--frames") {
      r.frames = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 100000));
    } else if (a == "--max-diff-fraction") {
      const std::string& s = flagValue(args, i);
      char* end = nullptr;
      const double f = std::strtod(s.c_str(), &end);
      if (s.empty() || *end != '\0' || !(f >= 0.0 && f <= 1.0))
        throw Error("--max-diff-fraction: '" + s + "' must be a number in [0, 1]");
      r.maxDiffFraction = f;
    } else {
      takeScenePath(a, r.scenePath);
    }
  }
  return r;
}

double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// clraster's ID image, top row first; frame times in frameMs.
std::vector<uint32_t> renderClraster(const Args& args, const Mesh& mesh, const glm::mat4& mvp,
                                     std::vector<double>& frameMs)
{
  ClContext cl(args.device);
  Pipeline pipeline(cl);
  pipeline.uploadScene(mesh);
  FrameSettings settings;
  settings.width = args.width;
  settings.height = args.height;
  settings.shadeMode = CLR_SHADE_ID;
  settings.mvp = mvp;
  std::vector<uint32_t> image;
  for (uint32_t f = 0; f < args.frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    pipeline.render(settings, image);
    frameMs.push_back(msSince(start));
  }
  for (uint32_t& p : image) p &= kIdMask;
  return image;
}

int run(const Args& args)
{
  // Step 1: llvmpipe's timing mode (llvmpipe_render.h); scene, camera and the
  // output path, before any rendering.
  fixHeapTrimThreshold();
  if (!args.diffPath.empty()) checkWritable(args.diffPath);
  const Mesh mesh = args.scenePath.empty() ? defaultScene() : loadScene(args.scenePath);
  if (mesh.numTris() >= kIdMask)
    std::fprintf(stderr, "clraster_vs_llvmpipe: warning: %zu triangles; ids encode only 24 bits and wrap\n",
                 mesh.numTris());
  const Camera camera = frameCamera(CameraArgs{}, meshBounds(mesh));
  const glm::mat4 mvp = camera.viewProjection(args.width, args.height);

  // Step 2: both renderers, same triangles, camera and viewport.
  std::vector<double> clrasterMs, llvmpipeMs;
  const std::vector<uint32_t> ours = renderClraster(args, mesh, mvp, clrasterMs);
  const LlvmpipeFrames llvmpipe = renderLlvmpipeIds(mesh, args.width, args.height, mvp, args.frames);
  const std::vector<uint32_t>& theirs = llvmpipe.image;
  llvmpipeMs = llvmpipe.frameMs;

  // Step 3: pixel-by-pixel comparison and the report.
  const IdComparison c = compareIds(ours, theirs, args.width, args.height);
  if (!args.diffPath.empty()) writePng(args.diffPath, args.width, args.height, c.diffImage);
  const char* threads = std::getenv("LP_NUM_THREADS");
  std::printf(
      "{\"scene\":\"%s\",\"width\":%u,\"height\":%u,\"triangles\":%zu,"
      "\"covered_pixels_clraster\":%llu,\"covered_pixels_llvmpipe\":%llu,"
      "\"differing_pixels\":%llu,\"differing_fraction\":%.8f,\"differing_not_near_edge\":%llu,"
      "\"clraster_ms\":%.3f,\"llvmpipe_ms\":%.3f,\"llvmpipe_threads\":\"%s\"}\n",
      args.scenePath.empty() ? "default" : jsonEscape(args.scenePath).c_str(), args.width, args.height, mesh.numTris(),
      (unsigned long long)c.coveredOurs, (unsigned long long)c.coveredTheirs, (unsigned long long)c.differing,
      c.differingFraction(), (unsigned long long)c.differingNotNearEdge, median(clrasterMs), median(llvmpipeMs),
      threads ? jsonEscape(threads).c_str() : "default");
  std::fflush(stdout);

  // Step 4: the optional bound, every failed condition on one stderr line.
  if (!args.maxDiffFraction) return 0;
  std::string reasons;
  if (c.differingFraction() > *args.maxDiffFraction) {
    char text[96];
    std::snprintf(text, sizeof text, "differing fraction %.8f exceeds %.8f", c.differingFraction(),
                  *args.maxDiffFraction);
    reasons = text;
  }
  if (c.differingNotNearEdge > 0)
    reasons += std::string(reasons.empty() ? "" : "; ") + std::to_string(c.differingNotNearEdge) +
               " differing pixels are not near an edge, first at " + c.firstNotNearEdge;
  if (reasons.empty()) return 0;
  std::fprintf(stderr, "clraster_vs_llvmpipe: %s\n", reasons.c_str());
  return 1;
}

}  // namespace

int main(int argc, char** argv)
{
  return runProgram("clraster_vs_llvmpipe",
                    [&] { return run(parseArgs(std::vector<std::string>(argv + 1, argv + argc))); });
}
