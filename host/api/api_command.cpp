// api_command.cpp — the command line's commands as public calls
// (clraster.hpp, "The command line"): usage, help detection, `info`, and
// `render` for one view or a views file, with its --stats line. The CLI
// (host/cli/main.cpp) is a thin client of these; they share every step with the
// scene-level calls (frame_request.h, quality.h, views.h).
//
// renderCommand checks arguments and output paths before any device work,
// loads a file (quick checks first, then the import and the scene's layout
// on a second thread while the device's program builds; an import error is
// reported in preference to a device error), renders, and writes every output through
// a temporary file renamed into place, so a failure leaves none half-written.
#include "pipeline/aov.h"
#include "pipeline/layout.h"
#include "api/api_impl.h"
#include "render/camera.h"
#include "render/frame_request.h"
#include "render/frame_writer.h"
#include "io/image_io.h"
#include "render/info.h"
#include "pipeline/program_cache.h"
#include "render/quality.h"
#include "render/views.h"
#include "pipeline/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <future>
#include <optional>
#include <set>
#include <utility>

namespace clraster {

using namespace clr;

namespace {

double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// printf into a std::string.
template <typename... Args>
std::string format(const char* fmt, Args... args)
{
  const int n = std::snprintf(nullptr, 0, fmt, args...);
  std::string out(size_t(n) + 1, '\0');
  std::snprintf(out.data(), out.size(), fmt, args...);
  out.pop_back();
  return out;
}

// Where a run's time went before and after its frames (--stats).
struct RunTimes {
  double readMs = 0.0, parseMs = 0.0, buildMs = 0.0, encodeMs = 0.0;
  double layoutMs = 0.0;  // the scene's layout, on the import's thread: part of prepare_ms
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
};

std::string statsLine(const RenderArgs& args, const ClContext& cl, const Pipeline& pipeline, const RunTimes& times,
                      const FrameSettings& settings, const DepthChoice& depth, const std::string& autoJson,
                      double firstFrameMs, const std::vector<double>& frameMs,
                      const std::vector<clr::FrameStats>& frames)
{
  std::string out = format(
      "{\"device\":\"%s\",\"width\":%u,\"height\":%u,\"frames\":%zu,\"frame_ms\":%.3f,"
      "\"frame_ms_min\":%.3f,\"frame_ms_max\":%.3f,\"first_frame_ms\":%.3f,\"stage_ms\":{",
      jsonEscape(cl.info.name).c_str(), args.width, args.height, frameMs.size(), median(frameMs),
      *std::min_element(frameMs.begin(), frameMs.end()), *std::max_element(frameMs.begin(), frameMs.end()),
      firstFrameMs);
  bool first = true;
  for (const auto& [stage, ms] : frames.front().stageMs) {
    std::vector<double> perFrame;
    for (const clr::FrameStats& f : frames) perFrame.push_back(f.stageMs.at(stage));
    out += format("%s\"%s\":%.3f", first ? "" : ",", stage.c_str(), median(perFrame));
    first = false;
  }
  std::vector<double> idleMs;
  for (const clr::FrameStats& f : frames) idleMs.push_back(f.deviceIdleMs);
  const clr::FrameStats& s = frames.back();
  out += format(
      "},\"device_idle_ms\":%.3f,\"triangles_in\":%llu,\"triangles_clipped\":%llu,\"triangles_culled\":%llu,"
      "\"setup_triangles\":%llu,\"bin_entries\":%llu,\"micro_max\":%u,\"device_bytes\":%zu,\"prepare_ms\":%.3f,"
      "\"aa\":\"%s\",\"samples\":%u,\"bytes_per_pixel\":%.1f,\"edges\":\"%s\",\"interp\":\"%s\","
      "\"traversal\":\"%s\",\"depth\":\"%s\",\"depth_reason\":\"%s\",\"visibility\":\"%s\",\"read_ms\":%.3f,"
      "\"parse_ms\":%.3f,\"build_ms\":%.3f,\"encode_ms\":%.3f,\"total_ms\":%.3f%s%s}\n",
      median(idleMs), (unsigned long long)s.trianglesIn, (unsigned long long)s.trianglesClipped,
      (unsigned long long)s.trianglesCulled, (unsigned long long)s.setupTriangles, (unsigned long long)s.binEntries,
      s.microMax, pipeline.deviceBytes(), times.layoutMs + pipeline.prepareMs(),
      aaModeName(settings.samples, settings.shadeEverySample).c_str(), settings.samples, pipeline.bytesPerPixel(),
      settings.edgeMode == CLR_EDGES_FLOAT ? "float" : "fixed",
      settings.interpMode == CLR_INTERP_AFFINE ? "affine" : "perspective", traversalName(settings.traversal),
      depthModeName(depth.mode), jsonEscape(depth.reason).c_str(),
      settings.visibility == CLR_VISIBILITY_PAINTER ? "painter" : "zbuffer", times.readMs, times.parseMs, times.buildMs,
      times.encodeMs, msSince(times.start), autoJson.empty() ? "" : ",\"auto\":", autoJson.c_str());
  return out;
}

// A command's warnings on stderr, through one bounded sink (base/warnings.h):
// each new line as it comes, and at the end (finish) the lines whose kind
// repeated since, with their counts, and the count of those past the bound.
class StderrWarnings {
 public:
  void add(const std::string& kind, const std::string& line)
  {
    if (!sink_.add(kind, line)) return;
    printed_.push_back(line);
    std::fprintf(stderr, "clraster: warning: %s\n", line.c_str());
  }
  void finish()
  {
    const std::vector<std::string>& lines = sink_.lines();
    for (size_t k = 0; k < lines.size(); ++k)
      if (k >= printed_.size() || lines[k] != printed_[k])
        std::fprintf(stderr, "clraster: warning: %s\n", lines[k].c_str());
  }

 private:
  Warnings sink_;
  std::vector<std::string> printed_;
};

// A loaded scene's warnings (already bounded: each of its lines is a kind).
void warnAbout(const RenderArgs& args, const Mesh& mesh, StderrWarnings& warnings)
{
  for (const std::string& w : mesh.warnings.lines()) warnings.add(w, w);
  if (args.shadeMode == CLR_SHADE_ID && mesh.numTris() >= (1u << 24) - 1)
    warnings.add("ids", std::to_string(mesh.numTris()) + " triangles; --shade id encodes only 24 bits, ids wrap");
}

// A loaded scene, laid out (layout.h) for its upload.
struct LoadedScene {
  SceneLayout layout;
  Bounds bounds;  // of the file's vertices
};

// The scene, laid out, and the device context with its frame program, at
// once (see the file's contract); the context goes to `context`.
LoadedScene loadSceneDuringBuild(const RenderArgs& args, std::unique_ptr<Context>& context, StderrWarnings& warnings,
                                 RunTimes* times = nullptr)
{
  RunTimes ignored;
  if (!times) times = &ignored;
  // The file's import, then its bounds and layout; the mesh moves into the layout.
  auto prepare = [times](Mesh mesh) {
    LoadedScene scene;
    scene.bounds = meshBounds(mesh);
    const auto start = std::chrono::steady_clock::now();
    scene.layout = layOutScene(std::move(mesh));
    times->layoutMs = msSince(start);
    return scene;
  };
  LoadedScene scene;
  std::future<LoadedScene> importing;  // a file's import and layout, when valid()
  double importMs = 0.0;               // written by the import's thread, read after get()
  if (args.scenePath.empty()) {
    const auto start = std::chrono::steady_clock::now();
    Mesh mesh = defaultScene();
    times->parseMs = msSince(start);
    scene = prepare(std::move(mesh));
  } else {
    ModelFile file = checkSceneFile(args.scenePath);
    times->readMs = file.readMs;
    times->parseMs = file.checkMs;
    importing = std::async(std::launch::async, [file = std::move(file), &args, &importMs, prepare]() mutable {
      const auto start = std::chrono::steady_clock::now();
      Mesh imported = importScene(std::move(file), args.assets);
      importMs = msSince(start);
      return prepare(std::move(imported));
    });
  }
  try {
    const auto start = std::chrono::steady_clock::now();
    context = std::make_unique<Context>(args.device);
    context->impl().frameContext();
    times->buildMs = msSince(start);
  } catch (...) {
    if (importing.valid()) importing.get();  // the scene's error first (this waits for the import either way)
    throw;
  }
  if (importing.valid()) {
    scene = importing.get();
    times->parseMs += importMs;
  }
  warnAbout(args, scene.layout.mesh, warnings);
  return scene;
}

// `render --views`: one scene upload, then the shard's views in order, each
// image handed to the writer thread while the next one renders.
std::string renderViews(const RenderArgs& args, std::unique_ptr<Context>& context)
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
    if (folders.insert(folder).second)
      checkWritable(name);  // (checkTarget too)
    else
      checkTarget(name);
  }
  StderrWarnings warnings;
  // The host memory of the largest frame: the writer's capacity + 1 images
  // waiting (4 bytes a pixel) and the one it encodes (image_io.h).
  uint64_t largest = 0;
  for (size_t v : selected) largest = std::max<uint64_t>(largest, uint64_t(views[v].width) * views[v].height);
  checkHostMemory("--views " + userText(args.viewsPath) + ": frames in flight", largest * (3 * 4 + 15));
  RunTimes times;
  LoadedScene scene = loadSceneDuringBuild(args, context, warnings, &times);
  ClContext& cl = context->impl().frameContext();
  const Bounds bounds = scene.bounds;
  const std::vector<Camera> cameras = frameViews(args.viewsPath, views, bounds);

  // Step 2: scene upload, once.
  Pipeline pipeline(cl);
  pipeline.uploadScene(std::move(scene.layout));

  // Step 3: frames, rendered here and written by the writer thread. frame_ms
  // is camera set-up to the image copied into host memory (the writer keeps it),
  // where a single view's ends at the image mapped where the device left it.
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
      DepthChoice depth;
      FrameSettings settings = makeFrameSettings(args, cameras[v], frame.width, frame.height, bounds, &depth);
      if (!depth.warning.empty()) warnings.add("depth", "view " + std::to_string(v) + ": " + depth.warning);
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
  warnings.finish();
  const double totalMs = msSince(start);

  // Step 4: one JSON line for the run.
  if (!args.stats) return "";
  auto stat = [](const std::vector<double>& ms, double (*pick)(std::vector<double>)) {
    return ms.empty() ? 0.0 : pick(ms);
  };
  auto lo = [](std::vector<double> ms) { return *std::min_element(ms.begin(), ms.end()); };
  auto hi = [](std::vector<double> ms) { return *std::max_element(ms.begin(), ms.end()); };
  double encodeMs = 0.0;  // all of the writer thread's encodes and writes, overlapping the frames
  for (double ms : writeMs) encodeMs += ms;
  return format(
      "{\"device\":\"%s\",\"views\":%zu,\"shard\":\"%u/%u\",\"frames\":%zu,\"startup_ms\":%.3f,"
      "\"prepare_ms\":%.3f,\"total_ms\":%.3f,\"frames_per_s\":%.3f,"
      "\"frame_ms\":%.3f,\"frame_ms_min\":%.3f,\"frame_ms_max\":%.3f,\"write_ms\":%.3f,"
      "\"read_ms\":%.3f,\"parse_ms\":%.3f,\"build_ms\":%.3f,\"encode_ms\":%.3f,\"command_ms\":%.3f}\n",
      jsonEscape(cl.info.name).c_str(), views.size(), args.shard.index, args.shard.count, selected.size(), startupMs,
      times.layoutMs + pipeline.prepareMs(), totalMs, totalMs > 0.0 ? selected.size() * 1000.0 / totalMs : 0.0,
      stat(frameMs, median), stat(frameMs, lo), stat(frameMs, hi), stat(writeMs, median), times.readMs, times.parseMs,
      times.buildMs, encodeMs, msSince(commandStart));
}

std::string renderOne(const RenderArgs& args, std::unique_ptr<Context>& context)
{
  // Step 1: output paths, before any device work; then the scene, loaded
  // while the program builds, and the camera.
  RunTimes times;
  checkCameraArgs(args.camera);
  if (!args.outPath.empty()) checkWritable(args.outPath);
  if (!args.aovPath.empty()) checkWritable(args.aovPath);
  StderrWarnings warnings;
  LoadedScene scene = loadSceneDuringBuild(args, context, warnings, &times);
  ClContext& cl = context->impl().frameContext();
  const Bounds bounds = scene.bounds;
  const Camera camera = frameCamera(args.camera, bounds);

  // Step 2: scene upload (not part of the frame time).
  Pipeline pipeline(cl);
  pipeline.uploadScene(std::move(scene.layout));
  DepthChoice depth;
  FrameSettings settings = makeFrameSettings(args, camera, args.width, args.height, bounds, &depth);
  if (!depth.warning.empty()) warnings.add("depth", depth.warning);
  // --aa auto / --quality auto: a probe frame picks the methods (quality.h).
  std::string autoJson;
  if (args.aa == "auto" || args.qualityAuto)
    autoJson = chooseAutomatically(pipeline, settings, args.aa == "auto" || args.aa.empty(), args.qualityAuto).json();

  // Step 3: frames, timed from parameter upload to the image the host can
  // read where the device left it (an ImageView, as the bench times: on a
  // CPU device no copy). With --stats and --frames, one untimed frame first:
  // PoCL finishes compiling each kernel for its work-group size at its first
  // launch, which is program build, not frame time (reported as
  // first_frame_ms). A single picture renders its one frame only, both the
  // first and the timed one, so that total_ms is the time to picture.
  ImageView image;
  std::vector<double> frameMs;
  std::vector<clr::FrameStats> frames;
  double firstFrameMs = -1.0;
  if (args.stats && args.framesGiven) {
    const auto start = std::chrono::steady_clock::now();
    pipeline.render(settings, image);
    firstFrameMs = msSince(start);
  }
  for (uint32_t f = 0; f < args.frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    frames.push_back(pipeline.render(settings, image));
    frameMs.push_back(msSince(start));
  }
  if (firstFrameMs < 0.0) firstFrameMs = frameMs.front();

  // Step 4: output, both files or neither.
  const auto encodeStart = std::chrono::steady_clock::now();
  std::vector<OutputFile> outputs;
  if (!args.outPath.empty())
    outputs.push_back({args.outPath, encodePng(args.outPath, image.width, image.height, image.pixels)});
  if (!args.aovPath.empty()) {
    checkAovMemory(args.aovPath, args.width, args.height, cl);
    try {
      pipeline.aov();
      outputs.push_back({args.aovPath, encodeAovExr(args.aovPath, args.width, args.height, pipeline.readAov())});
    } catch (const std::bad_alloc&) {
      throw Error("--aov " + userText(args.aovPath) + ": out of host memory for " + std::to_string(args.width) + "x" +
                  std::to_string(args.height) + " pixels of visibility outputs");
    }
  }
  writeFilesAtomic(outputs);
  warnings.finish();
  times.encodeMs = msSince(encodeStart);
  return args.stats ? statsLine(args, cl, pipeline, times, settings, depth, autoJson, firstFrameMs, frameMs, frames)
                    : "";
}

}  // namespace

const char* usageText()
{
  return clr::usageText();
}

std::string userText(const std::string& text)
{
  return clr::userText(text);
}

bool wantsHelp(const std::vector<std::string>& args)
{
  return clr::wantsHelp(args);
}

int infoCommand(const std::vector<std::string>& args)
{
  return guarded([&] { return clr::infoCommand(args); });
}

int cacheCommand(const std::vector<std::string>& args)
{
  return guarded([&] { return clr::cacheCommand(args); });
}

std::string renderCommand(const RenderOptions& options, std::unique_ptr<Context>& context)
{
  return guarded([&] {
    const RenderArgs& args = options.impl().args;
    clr::requireOutputs(args);
    return args.viewsPath.empty() ? renderOne(args, context) : renderViews(args, context);
  });
}

}  // namespace clraster
