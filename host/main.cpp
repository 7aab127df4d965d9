// main.cpp — the clraster command line: `render` and `devices`.
//
// Every failure, from a bad flag to a device that cannot hold the frame,
// ends as one line on stderr and exit status 1; no output file is left
// half-written (image_io.h).
#include "cli.h"
#include "device.h"
#include "image_io.h"
#include "pipeline.h"
#include "quality.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>

using namespace clr;

namespace {

int listDevicesCommand()
{
  const std::vector<DeviceInfo> devices = listDevices();
  if (devices.empty()) throw Error("no OpenCL platform or device found");
  for (const DeviceInfo& d : devices)
    std::printf("%zu: [%s] %s (platform: %s)\n", d.index, d.type.c_str(), d.name.c_str(), d.platformName.c_str());
  return 0;
}

void printStats(const RenderArgs& args, const ClContext& cl, const Pipeline& pipeline, const FrameSettings& settings,
                const std::string& autoJson, double firstFrameMs, const std::vector<double>& frameMs,
                const std::vector<FrameStats>& frames)
{
  std::printf(
      "{\"device\":\"%s\",\"width\":%u,\"height\":%u,\"frames\":%zu,\"frame_ms\":%.3f,"
      "\"frame_ms_min\":%.3f,\"frame_ms_max\":%.3f,\"first_frame_ms\":%.3f,\"stage_ms\":{",
      jsonEscape(cl.info.name).c_str(), args.width, args.height, frameMs.size(), median(frameMs),
      *std::min_element(frameMs.begin(), frameMs.end()), *std::max_element(frameMs.begin(), frameMs.end()),
      firstFrameMs);
  bool first = true;
  for (const auto& [stage, ms] : frames.front().stageMs) {
    std::vector<double> perFrame;
    for (const FrameStats& f : frames) perFrame.push_back(f.stageMs.at(stage));
    std::printf("%s\"%s\":%.3f", first ? "" : ",", stage.c_str(), median(perFrame));
    first = false;
  }
  const FrameStats& s = frames.back();
  std::printf(
      "},\"triangles_in\":%llu,\"triangles_clipped\":%llu,\"triangles_culled\":%llu,"
      "\"setup_triangles\":%llu,\"bin_entries\":%llu,\"device_bytes\":%zu,"
      "\"aa\":\"%s\",\"samples\":%u,\"bytes_per_pixel\":%.1f,\"edges\":\"%s\",\"interp\":\"%s\","
      "\"traversal\":\"%s\"%s%s}\n",
      (unsigned long long)s.trianglesIn, (unsigned long long)s.trianglesClipped, (unsigned long long)s.trianglesCulled,
      (unsigned long long)s.setupTriangles, (unsigned long long)s.binEntries, pipeline.deviceBytes(),
      aaModeName(settings.samples, settings.shadeEverySample).c_str(), settings.samples, pipeline.bytesPerPixel(),
      settings.edgeMode == CLR_EDGES_FLOAT ? "float" : "fixed",
      settings.interpMode == CLR_INTERP_AFFINE ? "affine" : "perspective",
      settings.traversal == CLR_TRAVERSAL_HIERARCHICAL ? "hierarchical" : "bbox",
      autoJson.empty() ? "" : ",\"auto\":", autoJson.c_str());
}

int renderCommand(const std::vector<std::string>& argList)
{
  // Step 1: arguments, output path, scene and camera, before any device work.
  const RenderArgs args = parseRenderArgs(argList);
  checkWritable(args.outPath);
  const Mesh mesh = args.scenePath.empty() ? defaultScene() : loadScene(args.scenePath);
  const Camera camera = frameCamera(args.camera, meshBounds(mesh));
  if (args.shadeMode == CLR_SHADE_ID && mesh.numTris() >= (1u << 24) - 1)
    std::fprintf(stderr, "clraster: warning: %zu triangles; --shade id encodes only 24 bits, ids wrap\n",
                 mesh.numTris());

  // Step 2: device, program, scene upload (not part of the frame time).
  ClContext cl(args.device);
  Pipeline pipeline(cl);
  pipeline.uploadScene(mesh);
  FrameSettings settings = camera.frameSettings(args.width, args.height, args.shadeMode, args.cullBack);
  applyMethods(args, settings);
  // --aa auto / --quality auto: a probe frame picks the methods (quality.h).
  std::string autoJson;
  if (args.aa == "auto" || args.qualityAuto)
    autoJson = chooseAutomatically(pipeline, settings, args.aa == "auto" || args.aa.empty(), args.qualityAuto).json();

  // Step 3: frames, timed from parameter upload to the image in host memory.
  // With --stats, one untimed frame first: PoCL finishes compiling each
  // kernel for its work-group size at its first launch, which is program
  // build, not frame time (reported as first_frame_ms).
  std::vector<uint32_t> image;
  std::vector<double> frameMs;
  std::vector<FrameStats> frames;
  double firstFrameMs = -1.0;
  if (args.stats) {
    const auto start = std::chrono::steady_clock::now();
    pipeline.render(settings, image);
    firstFrameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  for (uint32_t f = 0; f < args.frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    frames.push_back(pipeline.render(settings, image));
    frameMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }

  // Step 4: output.
  writePng(args.outPath, args.width, args.height, image);
  if (args.stats) printStats(args, cl, pipeline, settings, autoJson, firstFrameMs, frameMs, frames);
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  return runProgram("clraster", [&] {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      std::fputs(usageText(), args.empty() ? stderr : stdout);
      return args.empty() ? 1 : 0;
    }
    if (args[0] == "devices") return listDevicesCommand();
    if (args[0] == "render") return renderCommand({args.begin() + 1, args.end()});
    throw Error("unknown command '" + args[0] + "' (render, devices)");
  });
}
