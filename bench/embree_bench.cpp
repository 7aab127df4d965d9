// embree_bench.cpp — clraster_embree: visibility alone (a triangle-ID frame, `--shade id`) against Embree's primary
// rays, the renderer a user who wants ID and depth buffers on a CPU would otherwise pick.
//
//   clraster_embree [SCENE] [--sphere TRIANGLES] [--grid N] [--shuffle SEED] [--view far|fill|near]
//                   [--size WxH] [--warmup K] [--frames N] [--rounds R] [--device SEL] [--name NAME] [--csv FILE]
//                   [--max-differing FRACTION]
//
// The case is bench_suite.cpp's (procedural.h: the scene, its grid and view; layout.h: the shuffle). clraster draws
// ID frames through the Pipeline into a mapped image. Embree (Debian libembree-dev, 3.x) builds its BVH once, timed
// apart, then casts one ray per pixel centre in 16-ray packets (4x4 pixels), rows of packets split over as many
// threads as clraster's device has compute units. Each ray runs from the pixel centre's point on the near plane to
// its point on the far plane (both unprojected through the same view-projection matrix), so it sees what the depth
// test keeps. The two take turns in R rounds; each round has K untimed frames. Prints one JSON line; --csv appends a
// row. Agreement: the pixels where the two ID images differ, over the pixels either covers (the ray's float
// unprojection and the rasterizer's 1/256-pixel snapping disagree only on edges); --max-differing fails the run
// (exit 1) above that fraction, a check that both sides see the same scene through the same camera.
#include "procedural.h"

#include "pipeline/device.h"
#include "pipeline/layout.h"
#include "pipeline/pipeline.h"
#include "render/flags.h"
#include "render/frame_request.h"

#include <embree3/rtcore.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>
#include <vector>

using namespace clr;
using namespace clr::bench;

namespace {

struct Args {
  std::string scenePath;
  uint64_t sphereTriangles = 0;
  uint32_t gridSide = 0;
  std::optional<uint32_t> shuffleSeed;
  std::string view = "far";
  uint32_t width = 1920, height = 1080;
  uint32_t warmup = 2, frames = 10, rounds = 2;
  std::string device, name, csvPath;
  double maxDiffering = 1.0;
};

Args parseArgs(const std::vector<std::string>& args)
{
  Args r;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--size")
      parseSize(a, flagValue(args, i), r.width, r.height);
    else if (a == "--sphere")
      r.sphereTriangles = parseUnsigned(a, flagValue(args, i), 12, 400000000);
    else if (a == "--grid")
      r.gridSide = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 1000));
    else if (a == "--shuffle")
      r.shuffleSeed = uint32_t(parseUnsigned(a, flagValue(args, i), 0, UINT32_MAX));
    else if (a == "--view")
      r.view = flagValue(args, i);
    else if (a == "--warmup")
      r.warmup = uint32_t(parseUnsigned(a, flagValue(args, i), 0, 1000));
    else if (a == "--frames")
      r.frames = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 100000));
    else if (a == "--rounds")
      r.rounds = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 1000));
    else if (a == "--device")
      r.device = flagValue(args, i);
    else if (a == "--name")
      r.name = flagValue(args, i);
    else if (a == "--max-differing") {
      const std::string& v = flagValue(args, i);
      char* end = nullptr;
      r.maxDiffering = std::strtod(v.c_str(), &end);
      if (v.empty() || *end || !(r.maxDiffering >= 0 && r.maxDiffering <= 1))
        throw Error("--max-differing: '" + userText(v) + "' is not a fraction in [0, 1]");
    } else if (a == "--csv")
      r.csvPath = flagValue(args, i);
    else
      takeScenePath(a, r.scenePath);
  }
  if (r.sphereTriangles && !r.scenePath.empty()) throw Error("--sphere and a SCENE exclude each other");
  return r;
}

BenchScene buildScene(const Args& args)
{
  BenchScene scene;
  if (args.sphereTriangles) {
    scene = displacedSphere(args.sphereTriangles);
    if (args.gridSide) scene = instancedGrid(scene.mesh, args.gridSide);
  } else {
    Mesh mesh = args.scenePath.empty() ? defaultScene() : loadScene(args.scenePath);
    mesh.triMaterial.clear();
    mesh.materials.clear();
    mesh.textures.clear();
    mesh.colors.clear();
    scene = args.gridSide ? instancedGrid(mesh, args.gridSide) : BenchScene{mesh, meshBounds(mesh)};
  }
  if (args.shuffleSeed) scene.mesh = shuffledTriangles(scene.mesh, *args.shuffleSeed);
  return scene;
}

double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Embree's side: a device, the scene's BVH and the packet tracer.
class EmbreeIds {
 public:
  EmbreeIds(const Mesh& mesh, unsigned threads) : threads_(threads)
  {
    device_ = rtcNewDevice(("threads=" + std::to_string(threads)).c_str());
    if (!device_) throw Error("Embree: rtcNewDevice failed");
    const auto start = std::chrono::steady_clock::now();
    scene_ = rtcNewScene(device_);
    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), mesh.numVerts()));
    auto* t = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(uint32_t), mesh.numTris()));
    if (!v || !t) throw Error("Embree: cannot allocate the geometry buffers");
    std::copy(mesh.positions.begin(), mesh.positions.end(), v);
    std::copy(mesh.indices.begin(), mesh.indices.end(), t);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene_);
    buildMs = msSince(start);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw Error("Embree: building the BVH failed");
  }
  ~EmbreeIds()
  {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  EmbreeIds(const EmbreeIds&) = delete;
  EmbreeIds& operator=(const EmbreeIds&) = delete;

  // One ID frame, top row first as clraster's image: primitive + 1 per pixel, 0 where no ray hits.
  void trace(const glm::mat4& viewProjection, uint32_t width, uint32_t height, std::vector<uint32_t>& ids) const
  {
    ids.assign(size_t(width) * height, 0);
    const glm::mat4 inv = glm::inverse(viewProjection);
    const uint32_t packetRows = (height + 3) / 4;
    auto rows = [&](uint32_t first) {
      RTCIntersectContext context;
      for (uint32_t pr = first; pr < packetRows; pr += threads_) {
        for (uint32_t px = 0; px < width; px += 4) {
          alignas(64) RTCRayHit16 rh;
          alignas(64) int valid[16];
          for (int k = 0; k < 16; ++k) {
            const uint32_t x = px + k % 4, y = pr * 4 + k / 4;  // y: row from the bottom
            valid[k] = x < width && y < height ? -1 : 0;
            const float nx = (float(x) + 0.5f) / float(width) * 2 - 1, ny = (float(y) + 0.5f) / float(height) * 2 - 1;
            const glm::vec4 n = inv * glm::vec4(nx, ny, -1, 1), f = inv * glm::vec4(nx, ny, 1, 1);
            const glm::vec3 o = glm::vec3(n) / n.w, d = glm::vec3(f) / f.w - o;
            rh.ray.org_x[k] = o.x, rh.ray.org_y[k] = o.y, rh.ray.org_z[k] = o.z;
            rh.ray.dir_x[k] = d.x, rh.ray.dir_y[k] = d.y, rh.ray.dir_z[k] = d.z;
            rh.ray.tnear[k] = 0, rh.ray.tfar[k] = 1, rh.ray.time[k] = 0;
            rh.ray.mask[k] = ~0u, rh.ray.id[k] = 0, rh.ray.flags[k] = 0;
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
          }
          rtcInitIntersectContext(&context);
          rtcIntersect16(valid, scene_, &context, &rh);
          for (int k = 0; k < 16; ++k) {
            const uint32_t x = px + k % 4, y = pr * 4 + k / 4;
            if (!valid[k] || rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) continue;
            ids[size_t(height - 1 - y) * width + x] = rh.hit.primID[k] + 1;
          }
        }
      }
    };
    std::vector<std::thread> pool;
    for (unsigned i = 1; i < threads_; ++i) pool.emplace_back(rows, i);
    rows(0);
    for (std::thread& th : pool) th.join();
  }

  double buildMs = 0;

 private:
  unsigned threads_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

int run(const Args& args)
{
  if (!args.csvPath.empty()) {
    FILE* csv = std::fopen(args.csvPath.c_str(), "a");
    if (!csv) throw Error("--csv: cannot open '" + userText(args.csvPath) + "' for appending");
    std::fclose(csv);
  }
  const BenchScene scene = buildScene(args);
  const Mesh& mesh = scene.mesh;
  if (mesh.numTris() == 0) throw Error("the scene has no triangles");
  const Camera camera = benchCamera(scene, args.view, args.width, args.height);

  ClContext cl(args.device);
  Pipeline pipeline(cl);
  pipeline.uploadScene(mesh);
  FrameSettings settings = makeFrameSettings(RenderArgs{}, camera, args.width, args.height, meshBounds(mesh));
  settings.shadeMode = CLR_SHADE_ID;
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  EmbreeIds embree(mesh, threads);
  const glm::mat4 mvp = camera.viewProjection(args.width, args.height);

  std::vector<double> clrMs, embreeMs;
  ImageView view;
  std::vector<uint32_t> rays;
  const uint32_t rounds = std::min(args.rounds, args.frames);
  for (uint32_t round = 0; round < rounds; ++round) {
    const uint32_t frames = args.frames / rounds + (round < args.frames % rounds ? 1 : 0);
    for (uint32_t f = 0; f < args.warmup + frames; ++f) {
      const auto start = std::chrono::steady_clock::now();
      pipeline.render(settings, view);
      if (f >= args.warmup) clrMs.push_back(msSince(start));
    }
    for (uint32_t f = 0; f < args.warmup + frames; ++f) {
      const auto start = std::chrono::steady_clock::now();
      embree.trace(mvp, args.width, args.height, rays);
      if (f >= args.warmup) embreeMs.push_back(msSince(start));
    }
  }
  uint64_t covered = 0, differing = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const uint32_t ours = view.pixels[i] & 0xFFFFFFu, theirs = rays[i];
    covered += ours || theirs;
    differing += ours != theirs;
  }
  const double clrMedian = median(clrMs), embreeMedian = median(embreeMs);
  std::string name = args.name;
  if (name.empty()) {
    name = args.sphereTriangles     ? "sphere" + std::to_string(args.sphereTriangles)
           : args.scenePath.empty() ? "default"
                                    : args.scenePath.substr(args.scenePath.find_last_of('/') + 1);
    if (args.gridSide) name = "grid" + std::to_string(args.gridSide) + "-" + name;
    if (args.shuffleSeed) name = "shuffled-" + name;
    name += "-" + args.view;
  }
  std::printf(
      "{\"name\":\"%s\",\"triangles\":%zu,\"width\":%u,\"height\":%u,\"threads\":%u,"
      "\"clraster_id_ms\":%.4f,\"embree_ms\":%.4f,\"ratio\":%.4f,\"embree_build_ms\":%.2f,"
      "\"covered\":%llu,\"differing\":%llu}\n",
      jsonEscape(name).c_str(), mesh.numTris(), args.width, args.height, threads, clrMedian, embreeMedian,
      clrMedian / embreeMedian, embree.buildMs, (unsigned long long)covered, (unsigned long long)differing);
  if (!args.csvPath.empty()) {
    FILE* csv = std::fopen(args.csvPath.c_str(), "a");
    if (!csv) throw Error("--csv: cannot open '" + userText(args.csvPath) + "' for appending");
    std::fprintf(csv, "%s,%zu,%u,%u,%u,%.4f,%.4f,%.4f,%.2f,%llu,%llu\n", name.c_str(), mesh.numTris(), args.width,
                 args.height, threads, clrMedian, embreeMedian, clrMedian / embreeMedian, embree.buildMs,
                 (unsigned long long)covered, (unsigned long long)differing);
    if (std::fclose(csv) != 0) throw Error("--csv: cannot write '" + userText(args.csvPath) + "'");
  }
  const double fraction = covered ? double(differing) / double(covered) : 0.0;
  if (fraction > args.maxDiffering)
    throw Error("the ID images of clraster and Embree differ on " + std::to_string(differing) + " of " +
                std::to_string(covered) + " covered pixels, above --max-differing");
  return 0;
}

}  // namespace

int main(int argc, char** argv)
{
  return runProgram("clraster_embree", [&] { return run(parseArgs(std::vector<std::string>(argv + 1, argv + argc))); });
}
