// accuracy.cpp — clraster_accuracy: every method on the same scenes, its frame time against its error from ground
// truth, for the speed–accuracy chart (bench/accuracy.sh draws it; docs/accuracy.md explains it).
//
//   clraster_accuracy [MESH...] [--size WxH] [--warmup K] [--frames N]
//                     [--ref-samples S] [--crop C] [--device SEL]
//                     [--csv FILE] [--pareto FILE] [--markdown FILE]
//
// Scenes: "coverage" (disjoint random triangles on the 1/256 grid, white,
// against the exact area of tests/exact_coverage.h), "default" (the built-in
// scene, lambert), one per MESH (lambert), and "checker" (a checkerboard
// plane at a grazing angle). Methods: every --aa mode, float edges, affine
// interpolation, and the traversals (hierarchical, exact spans, each alone
// and with msaa4, and the float edge walk of span tables). For
// each scene and method: K warm-up and N timed frames of Pipeline::render at
// the full size (median, min, max ms), then the error:
//   coverage scene  the covered fraction of each pixel's samples (from the
//                   visibility planes) against the exact area: RMSE over all
//                   pixels, max, and RMSE over edge pixels (0 < area < 1),
//                   the constants of host/render/quality.cpp
//   other scenes    the RGBA8 image against the S×S-sample reference
//                   (tests/supersample_reference.h, same shading in double)
//                   on a C×C crop at the image centre: RMSE of all channels
//                   in [0, 1], max, PSNR; with the --aa auto model's
//                   prediction beside it (lambert scenes)
//   checker scene   also (u, v) from --shade uv and eye depth from --shade
//                   depth (aa none) against the analytic values at each
//                   pixel centre: RMSE and max
// Writes the CSV (one row per scene and method), the Pareto front per scene
// (methods no other method beats in both time and error), and a Markdown
// table. Every failure is one line on stderr and exit status 1.
#include "pipeline/aa.h"
#include "render/camera.h"
#include "pipeline/cl.h"
#include "render/flags.h"
#include "pipeline/device.h"
#include "pipeline/pipeline.h"
#include "render/quality.h"
#include "io/scene.h"

#include "exact_coverage.h"
#include "supersample_reference.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
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
  std::vector<std::string> meshes;
  uint32_t width = 1280, height = 720;
  uint32_t warmup = 2, frames = 7;
  uint32_t refSamples = 64, crop = 160;
  std::string device;
  std::string csvPath = "accuracy.csv", paretoPath = "accuracy_pareto.csv", markdownPath = "accuracy.md";
};

struct Method {
  std::string name;
  std::string aa;
  uint32_t edges = CLR_EDGES_FIXED, interp = CLR_INTERP_PERSPECTIVE, traversal = CLR_TRAVERSAL_BBOX;
};

std::vector<Method> methods()
{
  std::vector<Method> list;
  for (const AaMode& m : aaModes()) list.push_back({m.name, m.name});
  list.push_back({"float-edges", "none", CLR_EDGES_FLOAT});
  list.push_back({"affine", "none", CLR_EDGES_FIXED, CLR_INTERP_AFFINE});
  list.push_back({"hierarchical", "none", CLR_EDGES_FIXED, CLR_INTERP_PERSPECTIVE, CLR_TRAVERSAL_HIERARCHICAL});
  list.push_back({"hierarchical-msaa4", "msaa4", CLR_EDGES_FIXED, CLR_INTERP_PERSPECTIVE, CLR_TRAVERSAL_HIERARCHICAL});
  list.push_back({"spans", "none", CLR_EDGES_FIXED, CLR_INTERP_PERSPECTIVE, CLR_TRAVERSAL_SPANS});
  list.push_back({"spans-msaa4", "msaa4", CLR_EDGES_FIXED, CLR_INTERP_PERSPECTIVE, CLR_TRAVERSAL_SPANS});
  list.push_back({"spans-float", "none", CLR_EDGES_FIXED, CLR_INTERP_PERSPECTIVE, CLR_TRAVERSAL_SPANS_FLOAT});
  return list;
}

// One scene: geometry, camera, shading, and what its error is measured against.
struct Scene {
  std::string name;
  Mesh mesh;
  glm::mat4 mvp{1.0f};
  glm::vec3 lightDir{0, 0, 1};
  float zNear = 0.1f, zFar = 100.0f;
  uint32_t shadeMode = CLR_SHADE_LAMBERT;
  bool exactCoverage = false;  // the coverage scene
  bool analyticUv = false;     // the checker plane
};

struct Row {
  std::string scene, method, metric;
  uint32_t samples = 1;
  double frameMs = 0, frameMsMin = 0, frameMsMax = 0;
  double rmse = 0, maxError = 0, psnr = 0, edgeRmse = -1, predictedRmse = -1, uvRmse = -1, uvMax = -1;
  double depthRmse = -1, depthMax = -1;
  uint64_t binEntries = 0, setupTriangles = 0;
  double bytesPerPixel = 0;
  bool pareto = false;
};

// Step helpers -------------------------------------------------------------

Scene coverageScene(uint32_t width, uint32_t height)
{
  // Disjoint triangles: one per 20-pixel cell, inset by a pixel, with
  // vertices on the 1/256-pixel grid so that snapping moves nothing.
  Scene s;
  s.name = "coverage";
  s.exactCoverage = true;
  s.shadeMode = CLR_SHADE_DEPTH;
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> inCell(256, 19 * 256);
  const float hw = 0.5f * float(width), hh = 0.5f * float(height);
  for (uint32_t cy = 0; cy + 20 <= height; cy += 20)
    for (uint32_t cx = 0; cx + 20 <= width; cx += 20)
      for (int v = 0; v < 3; ++v) {
        const float x = float(cx) + float(inCell(rng)) / 256.0f, y = float(cy) + float(inCell(rng)) / 256.0f;
        s.mesh.positions.insert(s.mesh.positions.end(), {(x - hw) / hw, (y - hh) / hh, 0.0f});
        s.mesh.indices.push_back(uint32_t(s.mesh.indices.size()));
      }
  computeSmoothNormals(s.mesh);
  return s;
}

Scene meshScene(const std::string& name, Mesh mesh, uint32_t width, uint32_t height)
{
  Scene s;
  s.name = name;
  s.mesh = std::move(mesh);
  const Camera camera = frameCamera(CameraArgs{}, meshBounds(s.mesh));
  s.mvp = camera.viewProjection(width, height);
  s.lightDir = camera.lightDirection();
  s.zNear = camera.zNear;
  s.zFar = camera.zFar;
  return s;
}

// The grazing checker plane: y = 0, x in [−6, 6], z in [−1, −60].
glm::dvec2 checkerUv(glm::dvec3 p)
{
  return {(p.x + 6) / 12 * 4, (-p.z - 1) / 59 * 16};
}

Scene checkerScene(uint32_t width, uint32_t height)
{
  Scene s;
  s.name = "checker";
  s.shadeMode = CLR_SHADE_CHECKER;
  s.analyticUv = true;
  s.zNear = 0.5f;
  s.zFar = 100.0f;
  s.mvp = glm::perspective(glm::radians(60.0f), float(width) / float(height), s.zNear, s.zFar) *
          glm::lookAt(glm::vec3(0, 1, 0), glm::vec3(0, 0.75f, -1), glm::vec3(0, 1, 0));
  const glm::dvec3 corners[4] = {{-6, 0, -1}, {6, 0, -1}, {6, 0, -60}, {-6, 0, -60}};
  for (const glm::dvec3& c : corners) {
    s.mesh.positions.insert(s.mesh.positions.end(), {float(c.x), float(c.y), float(c.z)});
    s.mesh.normals.insert(s.mesh.normals.end(), {0, 1, 0});
    const glm::dvec2 uv = checkerUv(c);
    s.mesh.uvs.insert(s.mesh.uvs.end(), {float(uv.x), float(uv.y)});
  }
  s.mesh.indices = {0, 1, 2, 0, 2, 3};
  return s;
}

FrameSettings settingsFor(const Scene& scene, const Method& method, const Args& args)
{
  FrameSettings f;
  f.width = args.width;
  f.height = args.height;
  f.mvp = scene.mvp;
  f.lightDir = scene.lightDir;
  f.zNear = scene.zNear;
  f.zFar = scene.zFar;
  f.shadeMode = scene.shadeMode;
  const AaMode& aa = findAaMode(method.aa);
  f.samples = aa.samples;
  f.shadeEverySample = aa.shadeEverySample;
  f.edgeMode = method.edges;
  f.interpMode = method.interp;
  f.traversal = method.traversal;
  return f;
}

glm::dvec3 unpack(uint32_t c)
{
  return glm::dvec3(c & 0xFF, (c >> 8) & 0xFF, (c >> 16) & 0xFF) / 255.0;
}

// The crop window [x0, x0 + size) × [y0, y0 + size) at the image centre.
struct Crop {
  uint32_t x0, y0, size;
};

// The reference image of a lambert or checker scene on the crop, shaded
// exactly as resolve.cl shades (in double).
oracle::SupersampleResult referenceImage(const Scene& scene, const FrameSettings& f, const Crop& crop,
                                         uint32_t samplesPerAxis)
{
  // Step 1: screen-space vertices of every triangle (all in front of the eye).
  const Mesh& m = scene.mesh;
  std::vector<oracle::ScreenVertex> verts;
  std::vector<uint32_t> source;  // input triangle of each reference triangle
  const glm::dmat4 mvp(f.mvp);
  for (size_t t = 0; t < m.numTris(); ++t) {
    oracle::ScreenVertex v[3];
    bool front = true;
    for (int i = 0; i < 3; ++i) {
      const uint32_t k = m.indices[3 * t + i];
      const glm::dvec4 c = mvp * glm::dvec4(m.positions[3 * k], m.positions[3 * k + 1], m.positions[3 * k + 2], 1);
      front = front && c.w > 1e-9 && c.z >= -c.w;
      v[i].invW = 1.0 / c.w;
      v[i].xy = glm::dvec2((c.x * v[i].invW * 0.5 + 0.5) * f.width - crop.x0,
                           (c.y * v[i].invW * 0.5 + 0.5) * f.height - crop.y0);
      v[i].z = c.z * v[i].invW * 0.5 + 0.5;
    }
    if (!front) continue;
    verts.insert(verts.end(), v, v + 3);
    source.push_back(uint32_t(t));
  }
  // Step 2: the shading of resolve.cl.
  const glm::dvec3 light = glm::normalize(glm::dvec3(f.lightDir));
  oracle::SupersampleOptions o;
  o.width = o.height = crop.size;
  o.samplesPerAxis = samplesPerAxis;
  o.threads = 0;
  o.background = scene.shadeMode == CLR_SHADE_LAMBERT ? glm::dvec3(0x1A, 0x1F, 0x26) / 255.0 : glm::dvec3(0);
  auto shade = [&](uint32_t tri, glm::dvec3 lambda) {
    const uint32_t t = source[tri];
    const uint32_t* idx = &m.indices[3 * t];
    if (scene.shadeMode == CLR_SHADE_CHECKER) {
      glm::dvec2 uv(0.0);
      for (int i = 0; i < 3; ++i) uv += lambda[i] * glm::dvec2(m.uvs[2 * idx[i]], m.uvs[2 * idx[i] + 1]);
      const bool odd = (int(std::floor(uv.x * 8)) + int(std::floor(uv.y * 8))) & 1;
      return glm::dvec3(odd ? 0.25 : 0.9);
    }
    glm::dvec3 n(0.0);
    for (int i = 0; i < 3; ++i)
      n += lambda[i] * glm::dvec3(m.normals[3 * idx[i]], m.normals[3 * idx[i] + 1], m.normals[3 * idx[i] + 2]);
    const glm::dvec2 a = verts[3 * tri].xy, b = verts[3 * tri + 1].xy, c = verts[3 * tri + 2].xy;
    const bool back = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y) < 0;
    const double len = glm::length(n);
    n = len > 0 ? n / len * (back ? -1.0 : 1.0) : glm::dvec3(0, 0, back ? -1 : 1);
    const double light01 = 0.12 + 0.88 * std::max(glm::dot(n, light), 0.0);
    return glm::clamp(glm::dvec3(0.80, 0.78, 0.74) * light01, 0.0, 1.0);
  };
  return oracle::supersampleRender(verts, shade, o);
}

// Frame times of one method: K warm-up frames, then the median of N.
void timeFrames(Pipeline& pipeline, const FrameSettings& f, const Args& args, Row& row, std::vector<uint32_t>& rgba)
{
  std::vector<double> ms;
  FrameStats stats;
  for (uint32_t i = 0; i < args.warmup + args.frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    stats = pipeline.render(f, rgba);
    const double t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (i >= args.warmup) ms.push_back(t);
  }
  row.frameMs = median(ms);
  row.frameMsMin = *std::min_element(ms.begin(), ms.end());
  row.frameMsMax = *std::max_element(ms.begin(), ms.end());
  row.binEntries = stats.binEntries;
  row.setupTriangles = stats.setupTriangles;
  row.bytesPerPixel = pipeline.bytesPerPixel();
}

void coverageError(const Pipeline& pipeline, const FrameSettings& f, const std::vector<double>& exact, Row& row)
{
  // Step 1: the covered fraction of each pixel's samples.
  std::vector<double> covered(exact.size(), 0.0);
  for (uint32_t k = 0; k < f.samples; ++k) {
    const std::vector<VisSample> vis = pipeline.readVis(k);
    for (size_t p = 0; p < vis.size(); ++p) covered[p] += vis[p].setupIndex != CLR_NONE ? 1.0 / f.samples : 0.0;
  }
  // Step 2: RMSE, max, and RMSE over the edge pixels.
  double sum = 0, edgeSum = 0;
  size_t edges = 0;
  for (size_t p = 0; p < exact.size(); ++p) {
    const double e = covered[p] - exact[p];
    sum += e * e;
    row.maxError = std::max(row.maxError, std::abs(e));
    if (exact[p] > 1e-12 && exact[p] < 1 - 1e-12) {
      edgeSum += e * e;
      ++edges;
    }
  }
  row.metric = "coverage";
  row.rmse = std::sqrt(sum / double(exact.size()));
  row.edgeRmse = edges ? std::sqrt(edgeSum / double(edges)) : 0.0;
  row.psnr = row.rmse > 0 ? -20 * std::log10(row.rmse) : 999;
}

void imageError(const std::vector<uint32_t>& rgba, const FrameSettings& f, const Crop& crop,
                const oracle::SupersampleResult& ref, Row& row)
{
  double sum = 0;
  for (uint32_t y = 0; y < crop.size; ++y)
    for (uint32_t x = 0; x < crop.size; ++x) {
      const uint32_t sy = crop.y0 + y, sx = crop.x0 + x;
      const glm::dvec3 got = unpack(rgba[size_t(f.height - 1 - sy) * f.width + sx]);
      const glm::dvec3 e = got - ref.color[size_t(y) * crop.size + x];
      sum += glm::dot(e, e);
      row.maxError = std::max({row.maxError, std::abs(e.x), std::abs(e.y), std::abs(e.z)});
    }
  row.metric = "image";
  row.rmse = std::sqrt(sum / (3.0 * crop.size * crop.size));
  row.psnr = row.rmse > 0 ? -20 * std::log10(row.rmse) : 999;
}

// The analytic point of the checker plane (y = 0) seen through the centre
// of pixel (x, y).
glm::dvec3 planePoint(const glm::dmat4& inverseMvp, const FrameSettings& f, uint32_t x, uint32_t y)
{
  const glm::dvec2 ndc((x + 0.5) / f.width * 2 - 1, (y + 0.5) / f.height * 2 - 1);
  const glm::dvec4 a = inverseMvp * glm::dvec4(ndc, -1, 1), b = inverseMvp * glm::dvec4(ndc, 1, 1);
  const glm::dvec3 p0 = glm::dvec3(a) / a.w, p1 = glm::dvec3(b) / b.w;
  return p0 + (p1 - p0) * (p0.y / (p0.y - p1.y));
}

// Attributes of the checker plane against their analytic values at each
// pixel centre: (u, v) from --shade uv, and eye depth from --shade depth
// (grey = 1 − (depth − near) / (far − near), so its error is in units of the
// near–far range). Both 8-bit, so half a step (0.002) is the floor.
void attributeError(Pipeline& pipeline, FrameSettings f, const glm::vec3& eye, Row& row)
{
  f.samples = 1;
  f.shadeEverySample = false;
  const glm::dmat4 inv = glm::inverse(glm::dmat4(f.mvp));
  for (uint32_t mode : {CLR_SHADE_UV, CLR_SHADE_DEPTH}) {
    f.shadeMode = mode;
    std::vector<uint32_t> rgba;
    pipeline.render(f, rgba);
    const std::vector<VisSample> vis = pipeline.readVis();
    double sum = 0, worst = 0;
    size_t n = 0;
    for (uint32_t y = 0; y < f.height; ++y)
      for (uint32_t x = 0; x < f.width; ++x) {
        if (vis[size_t(y) * f.width + x].setupIndex == CLR_NONE) continue;
        const glm::dvec3 p = planePoint(inv, f, x, y);
        const glm::dvec3 c = unpack(rgba[size_t(f.height - 1 - y) * f.width + x]);
        if (mode == CLR_SHADE_UV) {
          // --shade uv shows the fractional parts; compare on the circle of [0, 1).
          const glm::dvec2 uv = checkerUv(p);
          for (int k = 0; k < 2; ++k) {
            double d = std::abs(c[k] - (uv[k] - std::floor(uv[k])));
            d = std::min(d, 1.0 - d);
            sum += d * d;
            worst = std::max(worst, d);
            ++n;
          }
        } else {
          // Eye depth is the distance along the view direction.
          const glm::dvec3 forward = glm::normalize(glm::dvec3(0, 0.75, -1) - glm::dvec3(eye));
          const double depth = glm::dot(p - glm::dvec3(eye), forward);
          const double grey = 1.0 - (depth - f.zNear) / (f.zFar - f.zNear);
          const double d = std::abs(c.x - std::clamp(grey, 0.0, 1.0));
          sum += d * d;
          worst = std::max(worst, d);
          ++n;
        }
      }
    const double rmse = n ? std::sqrt(sum / double(n)) : 0.0;
    (mode == CLR_SHADE_UV ? row.uvRmse : row.depthRmse) = rmse;
    (mode == CLR_SHADE_UV ? row.uvMax : row.depthMax) = worst;
  }
}

void markPareto(std::vector<Row>& rows)
{
  for (Row& a : rows) {
    a.pareto = true;
    for (const Row& b : rows)
      if (&a != &b && b.scene == a.scene && b.frameMs <= a.frameMs && b.rmse <= a.rmse &&
          (b.frameMs < a.frameMs || b.rmse < a.rmse))
        a.pareto = false;
  }
}

void writeOutputs(std::vector<Row> rows, const Args& args, const std::string& deviceName)
{
  // Scenes in their order, each by frame time.
  std::vector<std::string> order;
  for (const Row& r : rows)
    if (std::find(order.begin(), order.end(), r.scene) == order.end()) order.push_back(r.scene);
  auto rank = [&](const Row& r) { return std::find(order.begin(), order.end(), r.scene) - order.begin(); };
  std::stable_sort(rows.begin(), rows.end(), [&](const Row& a, const Row& b) {
    return rank(a) != rank(b) ? rank(a) < rank(b) : a.frameMs < b.frameMs;
  });
  std::ofstream csv(args.csvPath), pareto(args.paretoPath), md(args.markdownPath);
  if (!csv || !pareto || !md)
    throw Error("cannot write " + args.csvPath + ", " + args.paretoPath + " or " + args.markdownPath);
  const char* header =
      "scene,method,samples,frame_ms,frame_ms_min,frame_ms_max,metric,rmse,max_error,psnr_db,edge_rmse,"
      "predicted_rmse,uv_rmse,uv_max,depth_rmse,depth_max,bin_entries,setup_triangles,bytes_per_pixel,pareto\n";
  csv << header;
  pareto << header;
  md << "Device: " << deviceName << ", " << args.width << "x" << args.height << ", median of " << args.frames
     << " frames after " << args.warmup << " warm-up; reference " << args.refSamples << "x" << args.refSamples
     << " samples per pixel on a " << args.crop << "x" << args.crop << " centre crop.\n\n"
     << "| scene | method | frame ms | error (RMSE) | max | PSNR dB | edge RMSE | predicted | uv RMSE | depth RMSE | "
        "Pareto |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "%s,%s,%u,%.3f,%.3f,%.3f,%s,%.6f,%.6f,%.2f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%llu,%llu,%.1f,%d\n",
                  r.scene.c_str(), r.method.c_str(), r.samples, r.frameMs, r.frameMsMin, r.frameMsMax, r.metric.c_str(),
                  r.rmse, r.maxError, r.psnr, r.edgeRmse, r.predictedRmse, r.uvRmse, r.uvMax, r.depthRmse, r.depthMax,
                  (unsigned long long)r.binEntries, (unsigned long long)r.setupTriangles, r.bytesPerPixel,
                  r.pareto ? 1 : 0);
    csv << line;
    if (r.pareto) pareto << line;
    auto opt = [](double v, const char* fmt) {
      char b[32];
      if (v < 0) return std::string("–");
      std::snprintf(b, sizeof b, fmt, v);
      return std::string(b);
    };
    md << "| " << r.scene << " | " << r.method << " | " << opt(r.frameMs, "%.2f") << " | " << opt(r.rmse, "%.4f")
       << " | " << opt(r.maxError, "%.3f") << " | " << opt(r.psnr, "%.1f") << " | " << opt(r.edgeRmse, "%.4f") << " | "
       << opt(r.predictedRmse, "%.4f") << " | " << opt(r.uvRmse, "%.4f") << " | " << opt(r.depthRmse, "%.4f") << " | "
       << (r.pareto ? "yes" : "") << " |\n";
  }
}

Args parseArgs(const std::vector<std::string>& argv)
{
  Args a;
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& f = argv[i];
    if (f == "--size")
      parseSize(f, flagValue(argv, i), a.width, a.height);
    else if (f == "--warmup")
      a.warmup = uint32_t(parseUnsigned(f, flagValue(argv, i), 0, 100));
    else if (f == "--frames")
      a.frames = uint32_t(parseUnsigned(f, flagValue(argv, i), 1, 1000));
    else if (f == "--ref-samples")
      a.refSamples = uint32_t(parseUnsigned(f, flagValue(argv, i), 1, 256));
    else if (f == "--crop")
      a.crop = uint32_t(parseUnsigned(f, flagValue(argv, i), 8, 4096));
    else if (f == "--device")
      a.device = flagValue(argv, i);
    else if (f == "--csv")
      a.csvPath = flagValue(argv, i);
    else if (f == "--pareto")
      a.paretoPath = flagValue(argv, i);
    else if (f == "--markdown")
      a.markdownPath = flagValue(argv, i);
    else if (!f.empty() && f[0] == '-')
      throw Error("unknown option '" + f + "'");
    else
      a.meshes.push_back(f);
  }
  if (a.crop > a.width || a.crop > a.height) throw Error("--crop larger than the image");
  return a;
}

}  // namespace

int main(int argc, char** argv)
{
  return runProgram("clraster_accuracy", [&] {
    const Args args = parseArgs({argv + 1, argv + argc});
    // Step 1: scenes.
    std::vector<Scene> scenes;
    scenes.push_back(coverageScene(args.width, args.height));
    scenes.push_back(meshScene("default", defaultScene(), args.width, args.height));
    for (const std::string& path : args.meshes) {
      const size_t slash = path.find_last_of('/');
      std::string name = path.substr(slash == std::string::npos ? 0 : slash + 1);
      name = name.substr(0, name.find('.'));
      scenes.push_back(meshScene(name, loadScene(path), args.width, args.height));
    }
    scenes.push_back(checkerScene(args.width, args.height));
    ClContext cl(args.device);
    const Crop crop{(args.width - args.crop) / 2, (args.height - args.crop) / 2, args.crop};
    std::vector<Row> rows;
    for (const Scene& scene : scenes) {
      // Step 2: the ground truth of the scene.
      Pipeline pipeline(cl);
      pipeline.uploadScene(scene.mesh);
      std::vector<double> exact;
      oracle::SupersampleResult reference;
      const FrameSettings base = settingsFor(scene, methods().front(), args);
      if (scene.exactCoverage) {
        std::vector<glm::dvec2> verts;
        for (uint32_t k : scene.mesh.indices)
          verts.push_back({(scene.mesh.positions[3 * k] * 0.5 + 0.5) * args.width,
                           (scene.mesh.positions[3 * k + 1] * 0.5 + 0.5) * args.height});
        exact = oracle::exactCoverage(verts, args.width, args.height);
      } else {
        const auto start = std::chrono::steady_clock::now();
        reference = referenceImage(scene, base, crop, args.refSamples);
        std::fprintf(stderr, "clraster_accuracy: %s reference in %.1f s\n", scene.name.c_str(),
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      }
      // Step 3: every method, timed, then its error. The scene's first frames
      // grow its buffers; they are rendered untimed first so that no method
      // pays for them.
      {
        std::vector<uint32_t> rgba;
        for (int i = 0; i < 3; ++i) pipeline.render(base, rgba);
      }
      EdgeContrast contrast;
      for (const Method& method : methods()) {
        Row row;
        row.scene = scene.name;
        row.method = method.name;
        const FrameSettings f = settingsFor(scene, method, args);
        row.samples = f.samples;
        std::vector<uint32_t> rgba;
        timeFrames(pipeline, f, args, row, rgba);
        if (scene.exactCoverage) {
          coverageError(pipeline, f, exact, row);
        } else {
          imageError(rgba, f, crop, reference, row);
          if (method.name == "none")
            contrast = measureEdgeContrast(rgba, pipeline.readVis(), f.width, f.height,
                                           {crop.x0, crop.y0, crop.size, crop.size});
          if (scene.shadeMode == CLR_SHADE_LAMBERT && method.edges == CLR_EDGES_FIXED &&
              method.interp == CLR_INTERP_PERSPECTIVE)
            row.predictedRmse = predictRmse(findAaMode(method.aa), contrast);
        }
        if (scene.analyticUv && method.aa == "none") attributeError(pipeline, f, glm::vec3(0, 1, 0), row);
        std::fprintf(stderr, "clraster_accuracy: %-9s %-19s %8.2f ms  rmse %.5f\n", row.scene.c_str(),
                     row.method.c_str(), row.frameMs, row.rmse);
        rows.push_back(row);
      }
    }
    // Step 4: the Pareto front and the outputs.
    markPareto(rows);
    writeOutputs(rows, args, cl.info.name);
    return 0;
  });
}
