// api_bench.cpp — clraster_api_bench: the library's rasterize against the
// CLI's frame of the same view (`clraster render --shade id`), both up to
// an output the host can read.
//
//   clraster_api_bench [--sphere TRIANGLES] [--size WxH] [--view far|fill|near]
//                      [--frames N] [--rounds R] [--device SEL]
//
// The scene is procedural.h's displaced sphere (1M triangles by default) at
// 1024x1024, "fill" view. Its clip positions are computed on the host in
// transform.cl's order, so rasterize sees the very floats the CLI's setup
// computes, and the ids of both must agree (checked, not timed). Timed in R
// rounds (4 unless --rounds) that take turns, N frames in all per method
// (medians reported), each after one warm-up frame per round:
//   cli_ms        Pipeline::render of the --shade id frame into an
//                 ImageView, as `clraster render --stats` times frame_ms;
//   rasterize_ms  rasterize's work without the upload: the stages it runs
//                 (setup, bin, raster, rast_outputs) on its clip-input
//                 context, and the read of rast (16 B per pixel) into host
//                 memory, as clraster::rasterizeInto does after uploading;
//   api_ms        clraster::rasterizeInto itself (index checks and upload
//                 included), for reference.
// Prints one JSON line with ratio = rasterize_ms / cli_ms and the median
// device time of each stage of both (OpenCL profiling).
#include "render/flags.h"
#include "render/frame_request.h"
#include "procedural.h"
#include "pipeline/pipeline.h"

#include <clraster/clraster.hpp>

#include <chrono>
#include <cstdio>
#include <functional>
#include <map>

using namespace clr;

namespace {

double msSince(std::chrono::steady_clock::time_point t)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

// transform.cl's CLR_TRANSFORM_ROW, in the same order (built without FMA contraction).
std::vector<float> clipPositions(const Mesh& mesh, const glm::mat4& m)
{
  std::vector<float> clip(4 * mesh.numVerts());
  for (size_t v = 0; v < mesh.numVerts(); ++v) {
    const float* p = &mesh.positions[3 * v];
    for (int row = 0; row < 4; ++row)
      clip[4 * v + row] = m[0][row] * p[0] + m[1][row] * p[1] + m[2][row] * p[2] + m[3][row];
  }
  return clip;
}

}  // namespace

int main(int argc, char** argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  return runProgram("clraster_api_bench", [&] {
    // Step 1: arguments, scene, view.
    uint64_t triangles = 1000000, frames = 20, rounds = 4;
    uint32_t width = 1024, height = 1024;
    std::string view = "fill", device;
    for (size_t i = 0; i < args.size(); ++i) {
      const std::string& a = args[i];
      if (a == "--sphere")
        triangles = parseUnsigned(a, flagValue(args, i), 12, 100000000);
      else if (a == "--size")
        parseSize(a, flagValue(args, i), width, height);
      else if (a == "--view")
        view = flagValue(args, i);
      else if (a == "--frames")
        frames = parseUnsigned(a, flagValue(args, i), 1, 10000);
      else if (a == "--rounds")
        rounds = parseUnsigned(a, flagValue(args, i), 1, 100);
      else if (a == "--device")
        device = flagValue(args, i);
      else
        throw Error("unknown argument '" + a + "'");
    }
    rounds = std::min(rounds, frames);
    const bench::BenchScene scene = bench::displacedSphere(triangles);
    const Camera camera = bench::benchCamera(scene, view, width, height);
    RenderArgs idArgs;  // `clraster render --shade id` with the bench's camera
    idArgs.shadeMode = CLR_SHADE_ID;
    const FrameSettings cliSettings = makeFrameSettings(idArgs, camera, width, height, meshBounds(scene.mesh));
    const std::vector<float> clip = clipPositions(scene.mesh, cliSettings.mvp);
    const std::vector<int32_t> tri(scene.mesh.indices.begin(), scene.mesh.indices.end());
    const size_t nv = scene.mesh.numVerts(), nt = scene.mesh.numTris(), pixels = size_t(width) * height;

    // Step 2: the CLI's pipeline, rasterize's (as api.cpp sets it up) and the API's context.
    ClContext cliContext(device);
    Pipeline cli(cliContext);
    cli.uploadScene(scene.mesh);
    ClContext clipContext(device, 0, true);
    Pipeline raster(clipContext);
    raster.uploadClipScene(clip.data(), nv, scene.mesh.indices.data(), nt);
    FrameSettings rasterSettings;
    rasterSettings.width = width;
    rasterSettings.height = height;
    rasterSettings.shadeMode = CLR_SHADE_ID;
    rasterSettings.keepVisAttributes = true;
    clraster::Context api(device);
    std::vector<float> rast(4 * pixels), apiRast(4 * pixels);
    ImageView image;
    std::map<std::string, std::vector<double>> cliStages, rasterStages;  // per stage, the timed frames'
    bool timing = false;
    auto keep = [&](const FrameStats& stats, std::map<std::string, std::vector<double>>& stages) {
      for (const auto& [stage, ms] : stats.stageMs)
        if (timing) stages[stage].push_back(ms);
    };
    auto cliFrame = [&] { keep(cli.render(cliSettings, image), cliStages); };
    auto rasterFrame = [&] {
      raster.beginFrame(rasterSettings);
      raster.setup();
      raster.setupEmit();
      raster.raster();
      raster.rastOutputs(false, false);
      raster.readRastOutputs(rast.data(), nullptr, nullptr);
      keep(raster.finishFrame(), rasterStages);
    };
    auto apiFrame = [&] {
      clraster::rasterizeInto(api, clip.data(), nv, tri.data(), nt, width, height, apiRast.data(), nullptr);
    };

    // Step 3: the rounds, taking turns; one untimed frame each first.
    std::vector<double> cliMs, rasterMs, apiMs;
    const std::vector<std::pair<std::function<void()>, std::vector<double>*>> turns = {{cliFrame, &cliMs},
                                                                                       {rasterFrame, &rasterMs}};
    for (uint64_t r = 0; r < rounds; ++r) {
      const uint64_t n = frames / rounds + (r < frames % rounds ? 1 : 0);
      for (auto& [frame, ms] : turns) {
        timing = false;
        frame();
        timing = true;
        for (uint64_t f = 0; f < n; ++f) {
          const auto start = std::chrono::steady_clock::now();
          frame();
          ms->push_back(msSince(start));
        }
      }
      apiFrame();
      for (uint64_t f = 0; f < n; ++f) {
        const auto start = std::chrono::steady_clock::now();
        apiFrame();
        apiMs.push_back(msSince(start));
      }
    }

    // Step 4: the ids agree (the 24 bits the id image holds), then the line.
    uint64_t covered = 0;
    for (uint32_t y = 0; y < height; ++y)
      for (uint32_t x = 0; x < width; ++x) {
        const uint32_t cliId = image.pixels[size_t(height - 1 - y) * width + x] & 0xFFFFFFu;
        const uint32_t id = clraster::decodeTriangleId(rast[4 * (size_t(y) * width + x) + 3]);
        const uint32_t apiId = clraster::decodeTriangleId(apiRast[4 * (size_t(y) * width + x) + 3]);
        if ((id & 0xFFFFFFu) != cliId || apiId != id)
          throw Error("ids differ at pixel (" + std::to_string(x) + ", " + std::to_string(y) + ")");
        covered += id != 0;
      }
    auto stages = [](const std::map<std::string, std::vector<double>>& m) {
      std::string out;
      for (const auto& [stage, ms] : m)
        out += (out.empty() ? "\"" : ",\"") + stage + "\":" + std::to_string(median(ms));
      return "{" + out + "}";
    };
    std::printf(
        "{\"device\":\"%s\",\"triangles\":%zu,\"width\":%u,\"height\":%u,\"view\":\"%s\",\"covered\":%llu,"
        "\"frames\":%llu,\"cli_ms\":%.3f,\"rasterize_ms\":%.3f,\"api_ms\":%.3f,\"ratio\":%.3f,\"cli_stage_ms\":%s,"
        "\"rasterize_stage_ms\":%s}\n",
        jsonEscape(cliContext.info.name).c_str(), nt, width, height, view.c_str(), (unsigned long long)covered,
        (unsigned long long)frames, median(cliMs), median(rasterMs), median(apiMs), median(rasterMs) / median(cliMs),
        stages(cliStages).c_str(), stages(rasterStages).c_str());
    return 0;
  });
}
