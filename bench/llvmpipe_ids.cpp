// llvmpipe_ids.cpp — clraster_vs_llvmpipe: the same triangles, camera and
// viewport rendered as triangle-ID images by Mesa llvmpipe (OSMesa, legacy
// GL, depth LESS, flat colour = triangle index + 1) and by clraster
// (CLR_SHADE_ID), compared pixel by pixel.
//
//   clraster_vs_llvmpipe [SCENE] [--size WxH] [--device SEL] [--diff OUT.png]
//                        [--max-diff-fraction F] [--frames N]
//
// Ids are triangle index + 1 (0: background) in the low 24 bits, as in
// CLR_SHADE_ID. Prints one JSON line on stdout. A differing pixel is "near
// an edge" unless its 3x3 neighbourhood holds a single id in both images;
// differing pixels that are not near an edge are real disagreements (or
// exact depth ties of coplanar overlapping triangles), not vertex rounding.
// With --max-diff-fraction F the exit status is 1 when the differing
// fraction exceeds F or any differing pixel is not near an edge. Every
// failure is one line on stderr and exit status 1.
#include "camera.h"
#include "cl.h"
#include "device.h"
#include "image_io.h"
#include "pipeline.h"
#include "scene.h"

#include <GL/osmesa.h>
#include <GL/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

using namespace clr;

namespace {

constexpr uint32_t kIdMask = 0xFFFFFFu;  // ID images: low 24 bits = triangle + 1

struct Args {
  std::string scenePath;  // empty: the built-in default scene
  uint32_t width = 1280, height = 720;
  std::string device;
  std::string diffPath;
  std::optional<double> maxDiffFraction;
  uint32_t frames = 1;
};

uint32_t parseUint(const std::string& flag, const std::string& text, uint32_t lo, uint32_t hi)
{
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || text[0] == '-' || text[0] == '+' || *end != '\0' || v < lo || v > hi)
    throw Error(flag + ": '" + text + "' must be an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
  return uint32_t(v);
}

Args parseArgs(const std::vector<std::string>& args)
{
  Args r;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw Error(a + ": missing value");
      return args[++i];
    };
    if (a == "--size") {
      const std::string& s = value();
      const size_t x = s.find('x');
      if (x == std::string::npos) throw Error("--size: '" + s + "' is not WxH");
      r.width = parseUint(a, s.substr(0, x), 1, CLR_MAX_VIEWPORT);
      r.height = parseUint(a, s.substr(x + 1), 1, CLR_MAX_VIEWPORT);
    } else if (a == "--device") {
      r.device = value();
    } else if (a == "--diff") {
      r.diffPath = value();
    } else if (a == "--frames") {
      r.frames = parseUint(a, value(), 1, 100000);
    } else if (a == "--max-diff-fraction") {
      const std::string& s = value();
      char* end = nullptr;
      const double f = std::strtod(s.c_str(), &end);
      if (s.empty() || *end != '\0' || !(f >= 0.0 && f <= 1.0))
        throw Error("--max-diff-fraction: '" + s + "' must be a number in [0, 1]");
      r.maxDiffFraction = f;
    } else if (!a.empty() && a[0] == '-') {
      throw Error("unknown option '" + a + "'");
    } else if (r.scenePath.empty()) {
      r.scenePath = a;
    } else {
      throw Error("unexpected argument '" + a + "' (only one SCENE)");
    }
  }
  return r;
}

double median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::string jsonEscape(const std::string& s)
{
  std::string out;
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out;
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

// llvmpipe's ID image through OSMesa, flipped to top row first.
std::vector<uint32_t> renderLlvmpipe(const Args& args, const Mesh& mesh, const glm::mat4& mvp,
                                     std::vector<double>& frameMs)
{
  // Step 1: an RGBA8 context with a 24-bit depth buffer drawing into memory.
  const uint32_t w = args.width, h = args.height;
  OSMesaContext context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!context) throw Error("OSMesaCreateContextExt failed");
  std::vector<uint32_t> buffer(size_t(w) * h, 0);
  if (!OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, GLsizei(w), GLsizei(h))) {
    OSMesaDestroyContext(context);
    throw Error("OSMesaMakeCurrent failed for " + std::to_string(w) + "x" + std::to_string(h));
  }

  // Step 2: fixed-function state: the mvp as projection, no lighting,
  // blending, dithering, culling or multisampling; depth LESS against 1.
  glViewport(0, 0, GLsizei(w), GLsizei(h));
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixf(glm::value_ptr(mvp));
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_LIGHTING);
  glDisable(GL_DITHER);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_MULTISAMPLE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glClearDepth(1.0);
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glShadeModel(GL_FLAT);

  // Step 3: un-shared vertices in index order, each triangle's three
  // carrying its id (index + 1) as R (low byte), G, B (high byte).
  const size_t numTris = mesh.numTris();
  std::vector<float> positions(numTris * 9);
  std::vector<uint8_t> colours(numTris * 12);
  for (size_t t = 0; t < numTris; ++t) {
    const uint32_t id = uint32_t(t + 1) & kIdMask;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.indices[3 * t + k];
      std::copy_n(&mesh.positions[3 * size_t(v)], 3, &positions[9 * t + 3 * k]);
      uint8_t* c = &colours[12 * t + 4 * k];
      c[0] = uint8_t(id), c[1] = uint8_t(id >> 8), c[2] = uint8_t(id >> 16), c[3] = 255;
    }
  }
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, positions.data());
  glColorPointer(4, GL_UNSIGNED_BYTE, 0, colours.data());

  // Step 4: frames, timed from the clear to glFinish.
  for (uint32_t f = 0; f < args.frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(numTris * 3));
    glFinish();
    frameMs.push_back(msSince(start));
  }
  const GLenum glError = glGetError();
  OSMesaDestroyContext(context);
  if (glError != GL_NO_ERROR) throw Error("GL error " + std::to_string(glError) + " while drawing");

  // Step 5: OSMesa's rows are bottom first (OSMESA_Y_UP); flip them.
  std::vector<uint32_t> image(buffer.size());
  for (uint32_t y = 0; y < h; ++y)
    std::transform(&buffer[size_t(h - 1 - y) * w], &buffer[size_t(h - y) * w], &image[size_t(y) * w],
                   [](uint32_t p) { return p & kIdMask; });
  return image;
}

// True when the 3x3 neighbourhood of (x, y), clipped to the image, holds one id.
bool uniformNeighbourhood(const std::vector<uint32_t>& image, uint32_t w, uint32_t h, uint32_t x, uint32_t y)
{
  const uint32_t id = image[size_t(y) * w + x];
  for (uint32_t ny = y ? y - 1 : 0; ny <= std::min(y + 1, h - 1); ++ny)
    for (uint32_t nx = x ? x - 1 : 0; nx <= std::min(x + 1, w - 1); ++nx)
      if (image[size_t(ny) * w + nx] != id) return false;
  return true;
}

struct Comparison {
  uint64_t coveredClraster = 0, coveredLlvmpipe = 0, coveredUnion = 0;
  uint64_t differing = 0, differingNotNearEdge = 0;
  std::string firstNotNearEdge;     // "(x, y): clraster id A, llvmpipe id B", top row 0
  std::vector<uint32_t> diffImage;  // RGBA8: black equal, red differing
  double differingFraction() const { return double(differing) / double(std::max<uint64_t>(1, coveredUnion)); }
};

Comparison compare(const std::vector<uint32_t>& ours, const std::vector<uint32_t>& theirs, uint32_t w, uint32_t h)
{
  Comparison c;
  c.diffImage.assign(ours.size(), 0xFF000000u);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      c.coveredClraster += ours[i] != 0;
      c.coveredLlvmpipe += theirs[i] != 0;
      c.coveredUnion += ours[i] != 0 || theirs[i] != 0;
      if (ours[i] == theirs[i]) continue;
      ++c.differing;
      c.diffImage[i] = 0xFF0000FFu;
      if (uniformNeighbourhood(ours, w, h, x, y) && uniformNeighbourhood(theirs, w, h, x, y) &&
          c.differingNotNearEdge++ == 0)
        c.firstNotNearEdge = "(" + std::to_string(x) + ", " + std::to_string(y) + "): clraster id " +
                             std::to_string(ours[i]) + ", llvmpipe id " + std::to_string(theirs[i]);
    }
  return c;
}

int run(const Args& args)
{
  // Step 1: scene, camera and the output path, before any rendering.
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
  const std::vector<uint32_t> theirs = renderLlvmpipe(args, mesh, mvp, llvmpipeMs);

  // Step 3: pixel-by-pixel comparison and the report.
  const Comparison c = compare(ours, theirs, args.width, args.height);
  if (!args.diffPath.empty()) writePng(args.diffPath, args.width, args.height, c.diffImage);
  const char* threads = std::getenv("LP_NUM_THREADS");
  std::printf(
      "{\"scene\":\"%s\",\"width\":%u,\"height\":%u,\"triangles\":%zu,"
      "\"covered_pixels_clraster\":%llu,\"covered_pixels_llvmpipe\":%llu,"
      "\"differing_pixels\":%llu,\"differing_fraction\":%.8f,\"differing_not_near_edge\":%llu,"
      "\"clraster_ms\":%.3f,\"llvmpipe_ms\":%.3f,\"llvmpipe_threads\":\"%s\"}\n",
      args.scenePath.empty() ? "default" : jsonEscape(args.scenePath).c_str(), args.width, args.height, mesh.numTris(),
      (unsigned long long)c.coveredClraster, (unsigned long long)c.coveredLlvmpipe, (unsigned long long)c.differing,
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
  try {
    return run(parseArgs(std::vector<std::string>(argv + 1, argv + argc)));
  } catch (const Error& e) {
    std::fprintf(stderr, "clraster_vs_llvmpipe: %s\n", e.what());
  } catch (const cl::Error& e) {
    std::fprintf(stderr, "clraster_vs_llvmpipe: OpenCL call %s failed: %s (%d)\n", e.what(), clErrorName(e.err()),
                 e.err());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "clraster_vs_llvmpipe: out of host memory\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "clraster_vs_llvmpipe: %s\n", e.what());
  }
  return 1;
}
