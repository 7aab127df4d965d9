// bench_suite.cpp — clraster_bench: one benchmark case, clraster against Mesa llvmpipe, both shading lambert per
// pixel (the same image), and llvmpipe again with its fixed-function lighting per vertex.
//
//   clraster_bench [SCENE] [--sphere TRIANGLES] [--grid N] [--shuffle SEED] [--no-layout] [--no-speculation]
//                  [--micro-max N]
//                  [--view far|fill|near] [--size WxH] [--warmup K] [--frames N] [--rounds R] [--device SEL]
//                  [--no-ids] [--name NAME] [--csv FILE] [--images PREFIX]
//                  [--peak-lane-gops X] [--peak-copy-gbs Y] [--max-shade-mad M]
//   clraster_bench [the case's arguments] --serve [--shade MODE]
//
// The case: SCENE (a file assimp reads; the built-in scene when absent) or --sphere T (procedural.h), optionally
// --grid N copies, seen from --view far|fill|near; file materials are set aside so both light the built-in grey.
// Each renderer draws N timed frames to a host-readable RGBA8 image, in R rounds taking turns (K warm-up frames
// each); unless --no-ids one triangle-ID frame of each is compared as clraster_vs_llvmpipe does. Prints one JSON
// line; --csv appends a row (columns: columns() below); --images writes both lambert images. --serve: turns driven
// by bench/ab.sh (serveTurns). Every failure is one line on stderr and exit status 1.
// --shuffle SEED puts the triangles in a random order (layout.h: a file in no spatial order, the same camera);
// --no-layout keeps the file's order on the device (Pipeline::setLayout(false)), for bench/ab.sh turns;
// --no-speculation makes every frame wait for its counts mid-frame (Pipeline::setSpeculation(false)), likewise;
// --micro-max N sets the micro path's limit (FrameSettings::microMax, 0 off; bench/micro.sh), failing where the
// device or frame cannot take that path.
#include "llvmpipe_render.h"
#include "procedural.h"

#include "render/camera.h"
#include "render/flags.h"
#include "pipeline/cl.h"
#include "pipeline/device.h"
#include "render/frame_request.h"
#include "io/image_io.h"
#include "pipeline/layout.h"
#include "pipeline/pipeline.h"
#include "io/scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

using namespace clr;
using namespace clr::bench;

namespace {

struct Args {
  std::string scenePath;  // empty: the built-in scene (or --sphere)
  uint64_t sphereTriangles = 0;
  uint32_t gridSide = 0;
  std::optional<uint32_t> shuffleSeed;  // --shuffle
  bool layout = true;                   // --no-layout clears it
  bool speculation = true;              // --no-speculation clears it
  int32_t microMax = -1;                // --micro-max; -1 the device's default
  std::string view = "far";
  uint32_t width = 1920, height = 1080;
  uint32_t warmup = 2, frames = 5, rounds = 4;
  std::string device;
  bool ids = true;
  std::string name;
  std::string csvPath;
  std::string imagePrefix;
  std::optional<double> peakLaneGops, peakCopyGbs;
  std::optional<double> maxShadeMad;       // fail when the per-pixel images differ more (a CTest check)
  bool serve = false;                      // turns driven on stdin (header comment)
  uint32_t shadeMode = CLR_SHADE_LAMBERT;  // --shade, only with --serve
};

double parsePositive(const std::string& flag, const std::string& text)
{
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !(v > 0.0) || !std::isfinite(v))
    throw Error(flag + ": '" + text + "' must be a positive number");
  return v;
}

Args parseArgs(const std::vector<std::string>& args)
{
  Args r;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--size") {
      parseSize(a, flagValue(args, i), r.width, r.height);
    } else if (a == "--sphere") {
      r.sphereTriangles = parseUnsigned(a, flagValue(args, i), 12, 400000000);
    } else if (a == "--grid") {
      r.gridSide = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 1000));
    } else if (a == "--shuffle") {
      r.shuffleSeed = uint32_t(parseUnsigned(a, flagValue(args, i), 0, UINT32_MAX));
    } else if (a == "--no-layout") {
      r.layout = false;
    } else if (a == "--no-speculation") {
      r.speculation = false;
    } else if (a == "--micro-max") {
      r.microMax = int32_t(parseUnsigned(a, flagValue(args, i), 0, CLR_TILE_SIZE * CLR_TILE_SIZE));
    } else if (a == "--view") {
      r.view = flagValue(args, i);
      if (r.view != "far" && r.view != "fill" && r.view != "near" && r.view != "away")
        throw Error("--view: '" + r.view + "' is not far, fill, near or away");
    } else if (a == "--warmup") {
      r.warmup = uint32_t(parseUnsigned(a, flagValue(args, i), 0, 100000));
    } else if (a == "--frames") {
      r.frames = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 100000));
    } else if (a == "--rounds") {
      r.rounds = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 100000));
    } else if (a == "--device") {
      r.device = flagValue(args, i);
    } else if (a == "--no-ids") {
      r.ids = false;
    } else if (a == "--name") {
      r.name = flagValue(args, i);
    } else if (a == "--csv") {
      r.csvPath = flagValue(args, i);
    } else if (a == "--images") {
      r.imagePrefix = flagValue(args, i);
    } else if (a == "--peak-lane-gops") {
      r.peakLaneGops = parsePositive(a, flagValue(args, i));
    } else if (a == "--peak-copy-gbs") {
      r.peakCopyGbs = parsePositive(a, flagValue(args, i));
    } else if (a == "--max-shade-mad") {
      r.maxShadeMad = parsePositive(a, flagValue(args, i));
    } else if (a == "--serve") {
      r.serve = true;
    } else if (a == "--shade") {
      r.shadeMode = parseShadeMode(a, flagValue(args, i));
    } else {
      takeScenePath(a, r.scenePath);
    }
  }
  if (r.sphereTriangles && !r.scenePath.empty()) throw Error("--sphere and a SCENE exclude each other");
  // --serve times clraster alone and writes only its turns' lines.
  if (r.serve && (!r.csvPath.empty() || !r.imagePrefix.empty() || r.maxShadeMad))
    throw Error("--serve writes only its turns' lines: --csv, --images and --max-shade-mad do not apply");
  if (!r.serve && r.shadeMode != CLR_SHADE_LAMBERT)
    throw Error("--shade applies only with --serve: the comparison with llvmpipe shades lambert");
  return r;
}

// Text safe inside a JSON string and a CSV field: no quotes, backslashes,
// commas or control characters.
std::string plainText(const std::string& s)
{
  std::string out;
  for (char c : s)
    if (c != '"' && c != '\\' && c != ',' && static_cast<unsigned char>(c) >= 0x20) out += c;
  return out;
}

// The Mesa release that GL_VERSION names ("4.5 (Compatibility Profile) Mesa
// 22.3.6" gives "22.3.6"), empty when it names none. The library loaded is
// the one measured, which the system's package list need not describe (the
// GPU machine runs a copied libOSMesa).
std::string mesaRelease(const std::string& glVersion)
{
  const size_t at = glVersion.find("Mesa ");
  if (at == std::string::npos) return "";
  const std::string rest = glVersion.substr(at + 5);
  return plainText(rest.substr(0, rest.find(' ')));
}

std::string baseName(const std::string& path)
{
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The case's scene (built here, not timed) and its default name.
BenchScene buildSceneInOrder(const Args& args);
BenchScene buildScene(const Args& args)
{
  BenchScene scene = buildSceneInOrder(args);
  if (args.shuffleSeed) scene.mesh = shuffledTriangles(scene.mesh, *args.shuffleSeed);
  return scene;
}
BenchScene buildSceneInOrder(const Args& args)
{
  if (args.sphereTriangles) {
    BenchScene sphere = displacedSphere(args.sphereTriangles);
    return args.gridSide ? instancedGrid(sphere.mesh, args.gridSide) : sphere;
  }
  // Geometry only: llvmpipe lights the built-in albedo, so clraster does too.
  Mesh mesh = args.scenePath.empty() ? defaultScene() : loadScene(args.scenePath);
  mesh.triMaterial.clear();
  mesh.materials.clear();
  mesh.textures.clear();
  mesh.colors.clear();
  if (args.gridSide) return instancedGrid(mesh, args.gridSide);
  return BenchScene{mesh, meshBounds(mesh)};
}

std::string caseName(const Args& args)
{
  if (!args.name.empty()) return plainText(args.name);
  std::string scene = args.sphereTriangles     ? "sphere" + std::to_string(args.sphereTriangles)
                      : args.scenePath.empty() ? "default"
                                               : baseName(args.scenePath);
  if (args.gridSide) scene = "grid" + std::to_string(args.gridSide) + "x" + std::to_string(args.gridSide) + "-" + scene;
  if (args.shuffleSeed) scene += "-shuffled";
  return plainText(scene + "-" + args.view);
}

struct ClrasterRun {
  std::string device;
  std::vector<double> frameMs;
  std::map<std::string, double> stageMs;  // medians over the timed frames
  double deviceIdleMs = 0;                // median over the timed frames (FrameStats)
  FrameStats last;
  size_t deviceBytes = 0;
  double prepareMs = 0;  // Pipeline::prepareMs: the scene's layout and upload
  std::vector<uint32_t> image, ids;
};

// clraster's timed frames of one round (after `warmup` untimed ones),
// appended to run.frameMs and `timed`; run.image holds the last frame.
void timeClrasterRound(Pipeline& pipeline, const FrameSettings& settings, uint32_t warmup, uint32_t frames,
                       ClrasterRun& run, std::vector<FrameStats>& timed)
{
  ImageView view;
  for (uint32_t f = 0; f < warmup + frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    FrameStats stats = pipeline.render(settings, view);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (f < warmup) continue;
    run.frameMs.push_back(ms);
    timed.push_back(std::move(stats));
  }
  run.image.assign(view.pixels, view.pixels + size_t(view.width) * view.height);
}

// Each kernel stage's median over the timed frames (a stage the first frame
// ran and a later one did not counts 0 there).
std::map<std::string, double> stageMedians(const std::vector<FrameStats>& timed)
{
  std::map<std::string, double> medians;
  for (const auto& entry : timed.front().stageMs) {
    std::vector<double> perFrame;
    for (const FrameStats& s : timed) perFrame.push_back(s.stageMs.count(entry.first) ? s.stageMs.at(entry.first) : 0);
    medians[entry.first] = median(perFrame);
  }
  return medians;
}

// After the rounds: the stages' medians, the memory, and the ID frame for
// the coverage comparison.
void finishClraster(const Args& args, Pipeline& pipeline, FrameSettings settings, const std::vector<FrameStats>& timed,
                    ClrasterRun& run)
{
  run.stageMs = stageMedians(timed);
  std::vector<double> idle;
  for (const FrameStats& s : timed) idle.push_back(s.deviceIdleMs);
  run.deviceIdleMs = median(idle);
  run.last = timed.back();
  run.deviceBytes = pipeline.deviceBytes();
  run.prepareMs = pipeline.prepareMs();
  if (args.ids) {
    settings.shadeMode = CLR_SHADE_ID;
    pipeline.render(settings, run.ids);
    for (uint32_t& p : run.ids) p &= kIdMask;
  }
}

// A renderer's timed frames: median, fastest and slowest, ms.
struct FrameTimes {
  double median = 0, min = 0, max = 0;
};

FrameTimes frameTimes(const std::vector<double>& ms)
{
  return {median(ms), *std::min_element(ms.begin(), ms.end()), *std::max_element(ms.begin(), ms.end())};
}

// The numbers of one case, as printed.
struct Report {
  std::string name, scene, device, llvmpipeThreads, llvmpipeRenderer, mesaRelease;
  uint64_t pixels = 0, triangles = 0, vertices = 0;
  FrameTimes clr, llvm, llvmVertex;                 // llvmVertex: llvmpipe lit per vertex
  double roundRatioMin = NAN, roundRatioMax = NAN;  // the rounds' own ratios (header comment)
  double rasterMs = NAN, resolveMs = NAN, otherMs = 0;
  std::string stages;  // "name=ms;..." for the CSV
  uint64_t minBytes = 0;
  std::optional<IdComparison> ids;
  double shadeDifference = 0, shadeDifferenceVertex = 0;
  double edgeEvalsPerS = NAN, rasterResolveBytesPerS = NAN;
};

std::string number(double v, const char* format = "%.6g")
{
  if (!std::isfinite(v)) return "";
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

std::string fraction(double value, const std::optional<double>& peak)
{
  return peak ? number(value / *peak) : "";
}

// The columns, in order: header name and value (already formatted). Timing: clraster is Pipeline::render into an
// ImageView (parameter upload to the mapped image: no copy on a CPU device); llvmpipe is glClear + glDrawElements +
// glFinish into OSMesa's buffer with LP_NUM_THREADS threads (the core count when unset), first with a GLSL program of
// clraster's lambert (llvm_ms, ratio, shade_mad), then lit per vertex (llvm_vertex_ms, ratio_vertex,
// shade_mad_vertex; llvmpipe_render.h). Derived columns:
//   vertices      = the mesh's distinct vertices (weldVertices, layout.h: a file's vertices equal in every attribute
//                   count once).
//   min_bytes     = 24 B per vertex (position + normal) + 12 B per triangle + 4 B per pixel: what any renderer must
//                   hold on the device; mem_ratio = device_bytes / min_bytes.
//   edge_gevals_s = bin_entries x CLR_TILE_SIZE^2 x 3 / raster time, the nominal edge evaluations; raster steps each
//                   with one add per lane, so edge_frac_lane_ops = edge_gevals_s / the device's 32-bit lane ops per
//                   second (--peak-lane-gops: half clraster_peak's fp32 FLOP peak, one FMA per lane).
//   rr_gbs        = (12 B per pixel: setup index written and read, image written; plus a 36 B TriSetup per bin
//                   entry) / (raster + resolve time); rr_frac_copy = rr_gbs / the peak copy bandwidth.
//   mesa          = the Mesa release llvmpipe's GL_VERSION names (the library that ran).
//   ratio_round_min, ratio_round_max = the least and greatest rounds' own ratios (clraster's median over
//                   llvmpipe's in the same round): how far the host's spells move the ratio.
// --max-shade-mad M fails the run (after printing) when shade_mad exceeds M: CTest's check of the lambert images.
std::vector<std::pair<std::string, std::string>> columns(const Args& args, const Report& r, const ClrasterRun& clr)
{
  const FrameStats& s = clr.last;
  const double mem = double(clr.deviceBytes) / double(std::max<uint64_t>(1, r.minBytes));
  const auto perS = [](double count, double ms) { return count / (ms * 1e-3); };
  return {
      {"name", r.name},
      {"scene", r.scene},
      {"view", args.view},
      {"order", args.shuffleSeed ? "shuffled" : "file"},
      {"width", std::to_string(args.width)},
      {"height", std::to_string(args.height)},
      {"pixels", std::to_string(r.pixels)},
      {"triangles", std::to_string(r.triangles)},
      {"vertices", std::to_string(r.vertices)},
      {"setup_triangles", std::to_string(s.setupTriangles)},
      {"bin_entries", std::to_string(s.binEntries)},
      {"warmup", std::to_string(args.warmup)},
      {"frames", std::to_string(args.frames)},
      {"clr_ms", number(r.clr.median, "%.3f")},
      {"clr_ms_min", number(r.clr.min, "%.3f")},
      {"clr_ms_max", number(r.clr.max, "%.3f")},
      {"llvm_ms", number(r.llvm.median, "%.3f")},
      {"llvm_ms_min", number(r.llvm.min, "%.3f")},
      {"llvm_ms_max", number(r.llvm.max, "%.3f")},
      {"ratio", number(r.clr.median / r.llvm.median, "%.3f")},
      {"ratio_round_min", number(r.roundRatioMin, "%.3f")},
      {"ratio_round_max", number(r.roundRatioMax, "%.3f")},
      {"llvm_vertex_ms", number(r.llvmVertex.median, "%.3f")},
      {"llvm_vertex_ms_min", number(r.llvmVertex.min, "%.3f")},
      {"llvm_vertex_ms_max", number(r.llvmVertex.max, "%.3f")},
      {"ratio_vertex", number(r.clr.median / r.llvmVertex.median, "%.3f")},
      {"clr_mtris_s", number(perS(double(r.triangles), r.clr.median) * 1e-6)},
      {"llvm_mtris_s", number(perS(double(r.triangles), r.llvm.median) * 1e-6)},
      {"clr_mpix_s", number(perS(double(r.pixels), r.clr.median) * 1e-6)},
      {"llvm_mpix_s", number(perS(double(r.pixels), r.llvm.median) * 1e-6)},
      {"raster_ms", number(r.rasterMs, "%.3f")},
      {"resolve_ms", number(r.resolveMs, "%.3f")},
      {"other_stages_ms", number(r.otherMs, "%.3f")},
      {"stage_ms", r.stages},
      {"device_idle_ms", number(clr.deviceIdleMs, "%.3f")},
      {"device_bytes", std::to_string(clr.deviceBytes)},
      {"min_bytes", std::to_string(r.minBytes)},
      {"mem_ratio", number(mem, "%.3f")},
      {"prepare_ms", number(clr.prepareMs, "%.3f")},
      {"covered_pixels", r.ids ? std::to_string(r.ids->coveredUnion) : ""},
      {"differing_pixels", r.ids ? std::to_string(r.ids->differing) : ""},
      {"differing_fraction", r.ids ? number(r.ids->differingFraction(), "%.3e") : ""},
      {"differing_not_near_edge", r.ids ? std::to_string(r.ids->differingNotNearEdge) : ""},
      {"shade_mad", number(r.shadeDifference, "%.3f")},
      {"shade_mad_vertex", number(r.shadeDifferenceVertex, "%.3f")},
      {"edge_gevals_s", number(r.edgeEvalsPerS * 1e-9)},
      {"edge_frac_lane_ops", fraction(r.edgeEvalsPerS * 1e-9, args.peakLaneGops)},
      {"rr_gbs", number(r.rasterResolveBytesPerS * 1e-9)},
      {"rr_frac_copy", fraction(r.rasterResolveBytesPerS * 1e-9, args.peakCopyGbs)},
      {"lp_threads", r.llvmpipeThreads},
      {"device", r.device},
      {"llvmpipe", r.llvmpipeRenderer},
      {"mesa", r.mesaRelease},
  };
}

void printJson(const std::vector<std::pair<std::string, std::string>>& cols, const ClrasterRun& clr)
{
  // Numbers stay bare, empty values become null, text is quoted.
  std::string line = "{";
  for (const auto& [key, value] : cols) {
    if (key == "stage_ms") {
      line += "\"stage_ms\":{";
      bool first = true;
      for (const auto& [stage, ms] : clr.stageMs) {
        line += (first ? "\"" : ",\"") + stage + "\":" + number(ms, "%.3f");
        first = false;
      }
      line += "},";
      continue;
    }
    char* end = nullptr;
    std::strtod(value.c_str(), &end);
    const bool isNumber = !value.empty() && *end == '\0';
    line += "\"" + key + "\":" + (value.empty() ? "null" : isNumber ? value : "\"" + value + "\"") + ",";
  }
  line.back() = '}';
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

void appendCsv(const std::string& path, const std::vector<std::pair<std::string, std::string>>& cols)
{
  FILE* file = std::fopen(path.c_str(), "a");
  if (!file) throw Error("--csv: cannot open '" + path + "' for appending");
  std::string header, row;
  for (const auto& [key, value] : cols) {
    header += (header.empty() ? "" : ",") + key;
    row += (row.empty() ? "" : ",") + value;
  }
  std::fseek(file, 0, SEEK_END);
  if (std::ftell(file) == 0) std::fprintf(file, "%s\n", header.c_str());
  std::fprintf(file, "%s\n", row.c_str());
  if (std::fclose(file) != 0) throw Error("--csv: cannot write '" + path + "'");
}

// Fails when --micro-max asked for the micro path and the frame did not take it (a device without
// cl_khr_int64_extended_atomics, Pipeline::microMaxFor), so no run compares a path that never ran.
void checkMicro(const Args& args, const FrameStats& stats)
{
  if (args.microMax > 0 && stats.microMax == 0)
    throw Error("--micro-max " + std::to_string(args.microMax) +
                ": this device cannot take the micro path (it needs cl_khr_int64_extended_atomics)");
}

// --serve: clraster alone, in turns another process drives (bench/ab.sh): after loading it prints "ready", then per
// "turn" line on stdin renders K untimed and N timed frames and prints "frame=MS STAGE=MS ...", the turn's medians,
// until stdin ends. No ID frame; refuses --csv, --images and --max-shade-mad. --shade MODE (only here: no peer to
// match) shades another mode, so bench/ab.sh can compare the general resolve kernel.
int serveTurns(const Args& args, const Mesh& mesh, const Camera& camera)
{
  ClContext cl(args.device);
  Pipeline pipeline(cl);
  pipeline.setLayout(args.layout);
  pipeline.setSpeculation(args.speculation);
  pipeline.uploadScene(mesh);
  RenderArgs frameArgs;  // the CLI's defaults, but the shading
  frameArgs.shadeMode = args.shadeMode;
  FrameSettings settings = makeFrameSettings(frameArgs, camera, args.width, args.height, meshBounds(mesh));
  settings.microMax = args.microMax;
  ImageView view;
  checkMicro(args, pipeline.render(settings, view));  // the first frame: kernel code generation
  std::printf("ready\n");
  std::fflush(stdout);
  for (std::string line; std::getline(std::cin, line);) {
    if (line != "turn") throw Error("--serve: '" + line + "' on stdin is not 'turn'");
    ClrasterRun turn;
    std::vector<FrameStats> timed;
    timeClrasterRound(pipeline, settings, args.warmup, args.frames, turn, timed);
    std::printf("frame=%.4f", median(turn.frameMs));
    for (const auto& [name, ms] : stageMedians(timed)) std::printf(" %s=%.4f", name.c_str(), ms);
    std::printf("\n");
    std::fflush(stdout);
  }
  return 0;
}

int run(const Args& args)
{
  // Step 0: llvmpipe timed at its faster mode (llvmpipe_render.h).
  fixHeapTrimThreshold();

  // Step 1: llvmpipe's threads (the core count unless set), outputs, scene, camera.
  if (!std::getenv("LP_NUM_THREADS"))
    setenv("LP_NUM_THREADS", std::to_string(std::max(1u, std::thread::hardware_concurrency())).c_str(), 1);
  if (!args.csvPath.empty()) {
    FILE* csv = std::fopen(args.csvPath.c_str(), "a");  // fail before any rendering
    if (!csv) throw Error("--csv: cannot open '" + args.csvPath + "' for appending");
    std::fclose(csv);
  }
  if (!args.imagePrefix.empty())
    for (const char* suffix : {"-clraster.png", "-llvmpipe.png"}) checkWritable(args.imagePrefix + suffix);
  const BenchScene scene = buildScene(args);
  const Mesh& mesh = scene.mesh;
  if (mesh.numTris() == 0) throw Error("the scene has no triangles");
  const Camera camera = benchCamera(scene, args.view, args.width, args.height);
  if (args.serve) return serveTurns(args, mesh, camera);  // no ID frames: any triangle count
  if (args.ids && mesh.numTris() >= kIdMask) throw Error("ids encode only 24 bits: use --no-ids for this scene");

  // Step 2: the three renderers in turn (never concurrently), round after
  // round, each round with its own warm-up: a slower spell of the shared
  // host then falls on all three, not on whichever ran during it. clraster's
  // device, program and scene stay loaded across the rounds.
  ClContext cl(args.device);
  Pipeline pipeline(cl);
  pipeline.setLayout(args.layout);
  pipeline.setSpeculation(args.speculation);
  pipeline.uploadScene(mesh);
  FrameSettings settings = makeFrameSettings(RenderArgs{}, camera, args.width, args.height, meshBounds(mesh));
  settings.microMax = args.microMax;
  const glm::mat4 mvp = camera.viewProjection(args.width, args.height);
  ClrasterRun clr;
  clr.device = cl.info.name;
  std::vector<FrameStats> timed;
  LlvmpipeFrames llvm, llvmVertex;
  const uint32_t rounds = std::min(args.rounds, args.frames);
  std::vector<double> roundRatios;  // each round's clraster median over its llvmpipe (per pixel) median
  for (uint32_t round = 0; round < rounds; ++round) {
    const uint32_t frames = args.frames / rounds + (round < args.frames % rounds ? 1 : 0);
    const size_t clrFirst = clr.frameMs.size();
    timeClrasterRound(pipeline, settings, args.warmup, frames, clr, timed);
    checkMicro(args, timed.back());
    for (LambertShading shading : {LambertShading::perPixel, LambertShading::perVertex}) {
      LlvmpipeFrames part = renderLlvmpipeLambert(mesh, args.width, args.height, mvp, camera.lightDirection(), shading,
                                                  args.warmup, frames);
      if (shading == LambertShading::perPixel)
        roundRatios.push_back(median(std::vector<double>(clr.frameMs.begin() + clrFirst, clr.frameMs.end())) /
                              median(part.frameMs));
      LlvmpipeFrames& all = shading == LambertShading::perPixel ? llvm : llvmVertex;
      all.frameMs.insert(all.frameMs.end(), part.frameMs.begin(), part.frameMs.end());
      all.image = std::move(part.image);
      all.renderer = part.renderer;
      all.version = part.version;
    }
  }
  finishClraster(args, pipeline, settings, timed, clr);

  // Step 3: agreement: ID coverage and the lambert images.
  Report r;
  if (args.ids)
    r.ids = compareIds(clr.ids, renderLlvmpipeIds(mesh, args.width, args.height, mvp).image, args.width, args.height);
  r.shadeDifference = meanShadeDifference(clr.image, llvm.image, CLR_BACKGROUND_LIT);
  r.shadeDifferenceVertex = meanShadeDifference(clr.image, llvmVertex.image, CLR_BACKGROUND_LIT);

  // Step 4: derived numbers (definitions in the header comment).
  r.name = caseName(args);
  r.scene = args.sphereTriangles ? "procedural" : args.scenePath.empty() ? "default" : plainText(args.scenePath);
  r.device = plainText(clr.device);
  r.llvmpipeThreads = plainText(std::getenv("LP_NUM_THREADS"));
  r.llvmpipeRenderer = plainText(llvm.renderer);
  r.mesaRelease = mesaRelease(llvm.version);
  r.pixels = uint64_t(args.width) * args.height;
  r.triangles = mesh.numTris();
  std::vector<uint32_t> weld;
  r.vertices = weldVertices(mesh, weld);
  r.clr = frameTimes(clr.frameMs);
  r.llvm = frameTimes(llvm.frameMs);
  r.llvmVertex = frameTimes(llvmVertex.frameMs);
  r.roundRatioMin = *std::min_element(roundRatios.begin(), roundRatios.end());
  r.roundRatioMax = *std::max_element(roundRatios.begin(), roundRatios.end());
  for (const auto& [stage, ms] : clr.stageMs) {
    if (stage == "raster")
      r.rasterMs = ms;
    else if (stage == "resolve")
      r.resolveMs = ms;
    else
      r.otherMs += ms;
    r.stages += (r.stages.empty() ? "" : ";") + stage + "=" + number(ms, "%.3f");
  }
  r.minBytes = 24 * r.vertices + 12 * r.triangles + 4 * r.pixels;
  const double tilePixels = double(CLR_TILE_SIZE) * CLR_TILE_SIZE;
  r.edgeEvalsPerS = double(clr.last.binEntries) * tilePixels * 3.0 / (r.rasterMs * 1e-3);
  r.rasterResolveBytesPerS = (12.0 * double(r.pixels) + double(sizeof(TriSetup)) * double(clr.last.binEntries)) /
                             ((r.rasterMs + r.resolveMs) * 1e-3);

  // Step 5: output.
  if (!args.imagePrefix.empty()) {
    writePng(args.imagePrefix + "-clraster.png", args.width, args.height, clr.image);
    writePng(args.imagePrefix + "-llvmpipe.png", args.width, args.height, llvm.image);
  }
  const auto cols = columns(args, r, clr);
  printJson(cols, clr);
  if (!args.csvPath.empty()) appendCsv(args.csvPath, cols);
  if (args.maxShadeMad && !(r.shadeDifference <= *args.maxShadeMad))
    throw Error("the lambert images of clraster and llvmpipe (per pixel) differ by a mean of " +
                number(r.shadeDifference, "%.4f") + " of 255, more than --max-shade-mad " +
                number(*args.maxShadeMad, "%.4f"));
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  return runProgram("clraster_bench", [&] { return run(parseArgs(std::vector<std::string>(argv + 1, argv + argc))); });
}
