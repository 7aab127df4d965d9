// clraster.hpp — the clraster library: an exact OpenCL triangle rasterizer
// for C++ programs (the Python module and the CLI are its clients).
//
// Two levels, one Context (a device, chosen by the CLI's --device rule):
//  - rasterize / interpolate: nvdiffrast's primitives on caller arrays.
//    Positions are clip space (x, y, z, w), OpenGL conventions (visible:
//    -w <= x, y <= w, -w <= z < w: GL's LESS test against the clear depth 1
//    draws nothing at z = w); triangles are int32 vertex triples; images are
//    row-major with row 0 at the bottom (y up), pixel centres at
//    x_ndc = (2i + 1) / W - 1. Coverage and triangle ids are those of the
//    `clraster render` pipeline: fixed-point, watertight, nearest z/w wins,
//    ties to the lower triangle index, no face culled, non-finite vertices
//    culled with their triangles.
//  - Scene / RenderOptions / Renderer: the `clraster render` command (a mesh
//    file, camera, shading, anti-aliasing, a PNG) as calls.
// Every failure is a clraster::Error with a one-line message (the CLI's).
// No OpenCL type appears here; the kernels are inside the library. A Context
// and what uses it belong to one thread at a time.
#pragma once

#include "error.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#define CLRASTER_VERSION_MAJOR 1
#define CLRASTER_VERSION_MINOR 0

namespace clraster {

// An OpenCL device as `clraster devices` lists it.
struct DeviceInfo {
  size_t index = 0;  // position in the platform-major list
  std::string name, platform;
  std::string type;  // "GPU", "CPU", "ACCELERATOR", "OTHER"
};
CLRASTER_API std::vector<DeviceInfo> listDevices();

// One device and the kernels built for it (on first use, from the source
// embedded in the library). device: "" picks the first GPU, else the first
// CPU; a decimal index; or a case-insensitive substring of the device or
// platform name (clraster::Error naming --device when none matches).
class CLRASTER_API Context {
 public:
  explicit Context(const std::string& device = "");
  ~Context();
  Context(Context&&) noexcept;
  Context& operator=(Context&&) noexcept;
  const DeviceInfo& device() const;
  // A limit on the memory one call may take (device buffers in all, and
  // the host arrays it allocates); 0 (the default): only the device's and
  // the host's own. Every call checks its needs against the device's
  // largest allocation and global memory, this limit and the host's free
  // memory (and RLIMIT_AS) before allocating: an Error naming the size.
  void setMemoryLimit(uint64_t bytes);
  uint64_t memoryLimit() const;
  // Frees the device buffers rasterize keeps between calls (the built
  // kernels stay); the next call allocates again.
  void release();
  struct Impl;
  Impl& impl() { return *Error::live(impl_.get(), "clraster::Context"); }

 private:
  std::unique_ptr<Impl> impl_;
};

// rasterize's result for one image of width × height pixels.
struct Raster {
  uint32_t width = 0, height = 0;
  size_t numTriangles = 0;  // of the rasterized mesh (interpolate checks against it)
  // 4 floats per pixel: (u, v, z/w, triangle id + 1), nvdiffrast's layout: u
  // and v are the perspective-correct weights of the triangle's vertices 0
  // and 1 (vertex 2 weighs 1 - u - v), z/w is clip z over clip w at the
  // pixel centre, and the id is a float in nvdiffrast's encoding (exact up to
  // 2^24, above that a biased bit pattern). All 0 where nothing covers.
  std::vector<float> rast;
  // Per pixel, the exact triangle index + 1 (0: background).
  std::vector<uint32_t> ids;
  // With derivatives: 4 floats per pixel (du/dX, du/dY, dv/dX, dv/dY) per
  // pixel step (X right, Y up), 0 where nothing covers; else empty.
  std::vector<float> db;
};

// pos: numVertices × 4 floats; tri: numTriangles × 3 vertex indices, each in
// [0, numVertices) (else an Error naming tri); width, height in 1..16384.
CLRASTER_API Raster rasterize(Context& ctx, const float* pos, size_t numVertices, const int32_t* tri,
                              size_t numTriangles, uint32_t width, uint32_t height, bool derivatives = false);
// The same into the caller's arrays (height·width·4 floats for rast and db,
// height·width for ids); any of them may be null to skip it.
// checkRasterizeMemory: an Error naming the size unless a rasterize of
// width × height, whose caller allocates outputBytes for its outputs,
// fits the device, the host and ctx's limit (rasterize checks its own; a
// caller allocating large outputs itself calls it first).
CLRASTER_API void checkRasterizeMemory(Context& ctx, uint32_t width, uint32_t height, uint64_t outputBytes);
CLRASTER_API void rasterizeInto(Context& ctx, const float* pos, size_t numVertices, const int32_t* tri,
                                size_t numTriangles, uint32_t width, uint32_t height, float* rast, uint32_t* ids,
                                float* db = nullptr);

// Per-pixel attributes, perspective-correct: out[p·numAttrs + c] =
// u·attr[i0][c] + v·attr[i1][c] + (1 - u - v)·attr[i2][c] for the triangle
// (i0, i1, i2) = tri[id - 1] that covers pixel p, 0 elsewhere. attr:
// numVertices × numAttrs floats; tri: the Raster's numTriangles triples.
CLRASTER_API std::vector<float> interpolate(Context& ctx, const float* attr, size_t numVertices, size_t numAttrs,
                                            const Raster& r, const int32_t* tri);
// The same on arrays: rast as in Raster (ids decoded from channel 3), for
// `pixels` pixels; a channel 3 that is neither 0 nor an id in 1..numTriangles
// is an Error naming rast; out: pixels × numAttrs. With db (Raster::db's layout) and
// diffAttrs (attribute indices), outDa gets pixels × 2·diffAttrs.size()
// floats, (dA/dX, dA/dY) per listed attribute.
CLRASTER_API void interpolateInto(const float* attr, size_t numVertices, size_t numAttrs, const float* rast,
                                  size_t pixels, const int32_t* tri, size_t numTriangles, float* out,
                                  const float* db = nullptr, const std::vector<int>& diffAttrs = {},
                                  float* outDa = nullptr);

// nvdiffrast's triangle-id encoding of rast channel 3, both ways.
CLRASTER_API float encodeTriangleId(uint32_t idPlusOne);
CLRASTER_API uint32_t decodeTriangleId(float channel3);

// ---- Scene level: the `clraster render` command as calls ----

// A triangle mesh: a file any format assimp reads (OBJ, PLY, OFF, STL,
// glTF/GLB; checked as the CLI checks it), or the built-in scene. The files
// a model names are read only inside its folder; `assets` is the CLI's
// --assets: a directory that widens that, or "any" for trusted files.
class CLRASTER_API Scene {
 public:
  static Scene load(const std::string& path, const std::string& assets = "");
  static Scene builtin();
  ~Scene();
  Scene(Scene&&) noexcept;
  Scene& operator=(Scene&&) noexcept;
  size_t numVertices() const;
  size_t numTriangles() const;
  const std::vector<std::string>& warnings() const;  // what loading left out, one line each
  struct Impl;
  const Impl& impl() const { return *Error::live(impl_.get(), "clraster::Scene"); }

 private:
  explicit Scene(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// What to render, in the render command's flags (`clraster render --help`):
// parse() takes them as the CLI does (same checks, same messages); set()
// adds one flag and its value (an Error names a flag that takes none, or a
// word that is no flag). The output path (-o) is optional here. For example
//   auto o = RenderOptions::parse({"--size", "640x480", "--shade", "normal"});
class CLRASTER_API RenderOptions {
 public:
  RenderOptions();  // the CLI's defaults
  static RenderOptions parse(const std::vector<std::string>& flags);
  // As `clraster render` takes its arguments: -o (or --aov) required.
  static RenderOptions parseCommandLine(const std::vector<std::string>& args);
  RenderOptions& set(const std::string& flag, const std::string& value = "");
  ~RenderOptions();
  RenderOptions(const RenderOptions&);
  RenderOptions& operator=(const RenderOptions&);
  uint32_t width() const;
  uint32_t height() const;
  const std::string& scenePath() const;   // the SCENE argument; empty: the built-in scene
  const std::string& outputPath() const;  // -o; empty when not given
  const std::string& aovPath() const;     // --aov
  const std::string& viewsPath() const;   // --views
  const std::string& device() const;      // --device
  uint32_t frames() const;                // --frames
  bool stats() const;                     // --stats
  bool idShading() const;                 // --shade id
  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// An RGBA8 image, R in the low byte, top row first (as written to PNG).
struct Image {
  uint32_t width = 0, height = 0;
  std::vector<uint32_t> rgba;
};

// One frame's device times (from OpenCL profiling) and counts.
struct FrameStats {
  std::map<std::string, double> stageMs;
  double deviceIdleMs = 0;
  uint64_t trianglesIn = 0, trianglesClipped = 0, trianglesCulled = 0, setupTriangles = 0, binEntries = 0;
};

// A scene uploaded to a context's device once, rendered under any options
// (its camera framed on the scene's bounds where the options leave it open).
// render() draws the Renderer's scene, not the options' SCENE, and writes no
// file (writePng, writeAov do); options with --views are an Error.
class CLRASTER_API Renderer {
 public:
  Renderer(Context& ctx, const Scene& scene);
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;
  Image render(const RenderOptions& options, FrameStats* stats = nullptr);
  // After render() with --aov: the visibility-buffer planes written as a
  // float32 EXR (the CLI's --aov file).
  void writeAov(const std::string& path);
  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Writes an image as an 8-bit RGB PNG via a temporary file renamed into
// place (never half-written); an Error names the path on failure, a path
// not ending in .png, or an empty image.
CLRASTER_API void writePng(const std::string& path, const Image& image);

// The whole command: load options.scenePath() (or the built-in scene),
// render once, write options.outputPath() (and --aov's file) when given.
// Options with --views are an Error (renderCommand draws a views file).
CLRASTER_API Image render(Context& ctx, const RenderOptions& options);

// ---- The command line: each `clraster` command as a call ----
// (the CLI, host/cli/main.cpp, is these calls and nothing else)

// The text of `clraster --help`.
CLRASTER_API const char* usageText();
// A user's string as every message quotes it: control characters as
// spaces, a long one shortened around " ... ".
CLRASTER_API std::string userText(const std::string& text);
// Whether a command's arguments ask for help (--help or -h).
CLRASTER_API bool wantsHelp(const std::vector<std::string>& args);
// `clraster info ARGS`: prints what it reports on stdout; the exit status.
CLRASTER_API int infoCommand(const std::vector<std::string>& args);
// `clraster cache [--device SEL]`: compiles the kernels for the device and
// stores their binaries, so later starts skip the compiler front end.
CLRASTER_API int cacheCommand(const std::vector<std::string>& args);
// `clraster render` with parsed options: one view (-o, --aov; an Error
// without either), or every view of a --views file; writes the outputs and returns the --stats JSON line
// ("" without --stats). Warnings go to stderr, --views' progress bar too
// when stderr is a terminal. `context` receives the device context the
// command built, so that a caller about to exit may skip its teardown.
CLRASTER_API std::string renderCommand(const RenderOptions& options, std::unique_ptr<Context>& context);

}  // namespace clraster
