// main.cpp — the clraster command line: `render` (one camera, or a views
// file of many, views.h) and `devices`; and `__compile-ahead`, the helper
// process a render starts to compile kernels beside it (compile_ahead.h),
// which is not for users.
//
// Every failure, from a bad flag to a device that cannot hold the frame,
// ends as one line on stderr and exit status 1; no output file is left
// half-written (image_io.h).
#include "aov.h"
#include "cli.h"
#include "device.h"
#include "frame_writer.h"
#include "image_io.h"
#include "pipeline.h"
#include "quality.h"
#include "views.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <iostream>
#include <memory>
#include <optional>
#include <set>

using namespace clr;

namespace {

// Ends a successful render once its outputs are written, flushed and renamed
// into place, without tearing down the device context and scene. On a cold
// start PoCL would free the LLVM modules it compiled the kernels with: about
// 95 ms from the PNG's rename to the process's exit on the development
// machine (strace; now 1 ms), of a 1.5-1.7 s `clraster render`. Nothing in
// that teardown is needed: PoCL's kernel cache files are complete by each
// kernel's first launch. (The tests keep their context to the end likewise:
// tests/sanitize.sh.) Standard output carries --stats, so a failed flush is
// still a failure.
[[noreturn]] void exitAfterOutput()
{
  if (std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::fprintf(stderr, "clraster: cannot write standard output\n");
    std::_Exit(1);
  }
  std::fflush(stderr);
  std::_Exit(0);
}

int listDevicesCommand()
{
  const std::vector<DeviceInfo> devices = listDevices();
  if (devices.empty()) throw Error("no OpenCL platform or device found");
  for (const DeviceInfo& d : devices)
    std::printf("%zu: [%s] %s (platform: %s)\n", d.index, d.type.c_str(), d.name.c_str(), d.platformName.c_str());
  return 0;
}

void printStats(const RenderArgs& args, const ClContext& cl, const Pipeline& pipeline, const FrameSettings& settings,
                const DepthChoice& depth, const std::string& autoJson, double firstFrameMs,
                const std::vector<double>& frameMs, const std::vector<FrameStats>& frames)
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
  std::vector<double> idleMs;
  for (const FrameStats& f : frames) idleMs.push_back(f.deviceIdleMs);
  const FrameStats& s = frames.back();
  std::printf(
      "},\"device_idle_ms\":%.3f,\"triangles_in\":%llu,\"triangles_clipped\":%llu,\"triangles_culled\":%llu,"
      "\"setup_triangles\":%llu,\"bin_entries\":%llu,\"device_bytes\":%zu,\"prepare_ms\":%.3f,"
      "\"aa\":\"%s\",\"samples\":%u,\"bytes_per_pixel\":%.1f,\"edges\":\"%s\",\"interp\":\"%s\","
      "\"traversal\":\"%s\",\"depth\":\"%s\",\"depth_reason\":\"%s\",\"visibility\":\"%s\"%s%s}\n",
      median(idleMs), (unsigned long long)s.trianglesIn, (unsigned long long)s.trianglesClipped,
      (unsigned long long)s.trianglesCulled, (unsigned long long)s.setupTriangles, (unsigned long long)s.binEntries,
      pipeline.deviceBytes(), pipeline.prepareMs(), aaModeName(settings.samples, settings.shadeEverySample).c_str(),
      settings.samples, pipeline.bytesPerPixel(), settings.edgeMode == CLR_EDGES_FLOAT ? "float" : "fixed",
      settings.interpMode == CLR_INTERP_AFFINE ? "affine" : "perspective",
      settings.traversal == CLR_TRAVERSAL_HIERARCHICAL ? "hierarchical" : "bbox", depthModeName(depth.mode),
      jsonEscape(depth.reason).c_str(), settings.visibility == CLR_VISIBILITY_PAINTER ? "painter" : "zbuffer",
      autoJson.empty() ? "" : ",\"auto\":", autoJson.c_str());
}

double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// A loaded scene's warnings, on stderr.
void warnAbout(const RenderArgs& args, const Mesh& mesh)
{
  for (const std::string& w : mesh.warnings) std::fprintf(stderr, "clraster: warning: %s\n", w.c_str());
  if (args.shadeMode == CLR_SHADE_ID && mesh.numTris() >= (1u << 24) - 1)
    std::fprintf(stderr, "clraster: warning: %zu triangles; --shade id encodes only 24 bits, ids wrap\n",
                 mesh.numTris());
}

// The frame-program kernels a helper compiles ahead (compile_ahead.h) for
// these arguments' frames: the scan, and the resolve kernel the frame will
// likely take (Pipeline::resolve decides, by resolveIsLean and the scene's
// attributes, unknown here; a wrong guess costs only the head start). The
// render compiles setup and raster itself meanwhile.
CompileAheadRequest compileAheadFor(const RenderArgs& args)
{
  const uint32_t samples = args.aa.empty() || args.aa == "none" ? 1 : 0;  // 0: several, or --aa auto's choice
  const bool lean = resolveIsLean(args.shadeMode, samples, args.interpMode, args.pointLightOn, 0);
  return {"/proc/self/exe", {"scan_chunks", lean ? "resolve_lambert" : "resolve"}};
}

// The scene and the device context (ClContext: the compile-ahead helper's
// start, the device's choice, the program's build) at once. A file gets its
// quick checks first (checkSceneFile: most bad files fail there, before any
// device work), then imports on a second thread while this one builds the
// program, so the import (0.2-0.4 s for assimp's larger test models) no
// longer waits for the build, nor the build for it. An import that fails is
// reported rather than a device error, as when the scene loaded first; the
// context is then dropped (its helper stopped) as the error unwinds. The
// built-in scene is generated first: it takes milliseconds.
Mesh loadSceneDuringBuild(const RenderArgs& args, std::unique_ptr<ClContext>& cl)
{
  Mesh mesh;
  std::future<Mesh> importing;  // a file's import, when valid()
  if (args.scenePath.empty()) {
    mesh = defaultScene();
  } else {
    checkSceneFile(args.scenePath);
    importing = std::async(std::launch::async, [&args] { return importScene(args.scenePath); });
  }
  try {
    cl = std::make_unique<ClContext>(args.device, 0, compileAheadFor(args));
  } catch (...) {
    if (importing.valid()) importing.get();  // the scene's error first (this waits for the import either way)
    throw;
  }
  if (importing.valid()) mesh = importing.get();
  warnAbout(args, mesh);
  return mesh;
}

// Half the bounding box diagonal: the point light's default range.
float sceneRadius(const Mesh& mesh)
{
  const Bounds b = meshBounds(mesh);
  return b.empty ? 1.0f : 0.5f * glm::length(b.max - b.min);
}

// `render --views`: one scene upload, then the shard's views in order, each
// image handed to the writer thread while the next one renders.
int renderViewsCommand(const RenderArgs& args)
{
  // Step 1: views file and output folders, before any device work; then the
  // scene, loaded while the program builds, and the cameras; all before any
  // output: a bad view writes nothing.
  const auto commandStart = std::chrono::steady_clock::now();
  const std::vector<ViewSpec> views = loadViews(args.viewsPath, args.camera, args.width, args.height);
  checkViewCameras(args.viewsPath, views);
  const std::vector<size_t> selected = shardViews(views.size(), args.shard);
  std::set<std::string> folders;
  for (size_t v : selected) {
    const std::string name = outputName(args.outPath, v);
    const std::string folder = name.find('/') == std::string::npos ? "." : name.substr(0, name.rfind('/') + 1);
    if (folders.insert(folder).second) checkWritable(name);
  }
  std::unique_ptr<ClContext> context;
  const Mesh mesh = loadSceneDuringBuild(args, context);
  ClContext& cl = *context;
  const std::vector<Camera> cameras = frameViews(args.viewsPath, views, meshBounds(mesh));

  // Step 2: scene upload, once.
  Pipeline pipeline(cl);
  pipeline.uploadScene(mesh);

  // Step 3: frames, rendered here and written by the writer thread. frame_ms
  // is camera upload to image in host memory, as for a single view.
  const double startupMs = msSince(commandStart);
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> frameMs, writeMs;
  {
    ProgressBar progress(selected.size(), ProgressBar::stderrIsTerminal());
    FrameWriter writer(2, [&](size_t written) { progress.update(written); });
    progress.update(0);
    // --aa auto / --quality auto choose once, on the first view of the shard.
    std::optional<FrameSettings> chosen;
    for (size_t v : selected) {
      const auto frameStart = std::chrono::steady_clock::now();
      Frame frame{outputName(args.outPath, v), views[v].width, views[v].height, {}};
      FrameSettings settings = cameras[v].frameSettings(frame.width, frame.height, args.shadeMode, args.cullBack,
                                                        chooseDepth(args, cameras[v]).mode);
      applyMethods(args, settings, sceneRadius(mesh));
      if ((args.aa == "auto" || args.qualityAuto) && !chosen) {
        chooseAutomatically(pipeline, settings, args.aa == "auto" || args.aa.empty(), args.qualityAuto);
        chosen = settings;
      }
      if (chosen) {
        settings.samples = chosen->samples;
        settings.shadeEverySample = chosen->shadeEverySample;
        settings.traversal = chosen->traversal;
      }
      pipeline.render(settings, frame.rgba);
      frameMs.push_back(msSince(frameStart));
      writer.push(std::move(frame));
    }
    writer.finish();
    writeMs = writer.writeMs();
  }
  const double totalMs = msSince(start);

  // Step 4: one JSON line for the run.
  if (args.stats) {
    auto stat = [](const std::vector<double>& ms, double (*pick)(std::vector<double>)) {
      return ms.empty() ? 0.0 : pick(ms);
    };
    auto lo = [](std::vector<double> ms) { return *std::min_element(ms.begin(), ms.end()); };
    auto hi = [](std::vector<double> ms) { return *std::max_element(ms.begin(), ms.end()); };
    std::printf(
        "{\"device\":\"%s\",\"views\":%zu,\"shard\":\"%u/%u\",\"frames\":%zu,\"startup_ms\":%.3f,"
        "\"total_ms\":%.3f,\"frames_per_s\":%.3f,\"frame_ms\":%.3f,\"frame_ms_min\":%.3f,\"frame_ms_max\":%.3f,"
        "\"write_ms\":%.3f}\n",
        jsonEscape(cl.info.name).c_str(), views.size(), args.shard.index, args.shard.count, selected.size(), startupMs,
        totalMs, totalMs > 0.0 ? selected.size() * 1000.0 / totalMs : 0.0, stat(frameMs, median), stat(frameMs, lo),
        stat(frameMs, hi), stat(writeMs, median));
  }
  exitAfterOutput();
}

int renderCommand(const std::vector<std::string>& argList)
{
  // Step 1: arguments and output paths, before any device work; then the
  // scene, loaded while the program builds, and the camera.
  const RenderArgs args = parseRenderArgs(argList);
  if (!args.viewsPath.empty()) return renderViewsCommand(args);
  checkCameraArgs(args.camera);
  checkWritable(args.outPath);
  if (!args.aovPath.empty()) checkWritable(args.aovPath);
  std::unique_ptr<ClContext> context;
  const Mesh mesh = loadSceneDuringBuild(args, context);
  ClContext& cl = *context;
  const Camera camera = frameCamera(args.camera, meshBounds(mesh));

  // Step 2: scene upload (not part of the frame time).
  Pipeline pipeline(cl);
  pipeline.uploadScene(mesh);
  const DepthChoice depth = chooseDepth(args, camera);
  FrameSettings settings = camera.frameSettings(args.width, args.height, args.shadeMode, args.cullBack, depth.mode);
  applyMethods(args, settings, sceneRadius(mesh));
  settings.keepVisAttributes = !args.aovPath.empty();  // the AOVs read the depth and barycentric planes
  // --aa auto / --quality auto: a probe frame picks the methods (quality.h).
  std::string autoJson;
  if (args.aa == "auto" || args.qualityAuto)
    autoJson = chooseAutomatically(pipeline, settings, args.aa == "auto" || args.aa.empty(), args.qualityAuto).json();

  // Step 3: frames, timed from parameter upload to the image the host can
  // read where the device left it (an ImageView, as the bench times: on a
  // CPU device no copy). With --stats, one untimed frame first: PoCL
  // finishes compiling each kernel for its work-group size at its first
  // launch, which is program build, not frame time (reported as
  // first_frame_ms).
  ImageView image;
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
  std::vector<float> aov;  // --aov: the last frame's visibility buffer (aov.h)
  if (!args.aovPath.empty()) pipeline.aov(), aov = pipeline.readAov();
  writePng(args.outPath, image.width, image.height, image.pixels);
  if (!args.aovPath.empty()) writeAovExr(args.aovPath, args.width, args.height, aov);
  if (args.stats) printStats(args, cl, pipeline, settings, depth, autoJson, firstFrameMs, frameMs, frames);
  exitAfterOutput();
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
    if (args[0] == "__compile-ahead") compileAheadCommand({args.begin() + 1, args.end()});
    throw Error("unknown command '" + args[0] + "' (render, devices)");
  });
}
