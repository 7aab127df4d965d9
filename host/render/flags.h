// flags.h — command-line parsing for `clraster`. Every malformed or unknown
// argument is a clr::Error with a one-line message naming it.
#pragma once

#include "render/camera.h"
#include "render/depth.h"
#include "kernels/shared.h"
#include "render/views.h"

#include <functional>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace clr {

struct RenderArgs {
  std::string scenePath;  // empty: the built-in default scene
  std::string assets;     // --assets DIR|any: where the files the scene names may lie (asset_root.h)
  std::string outPath;
  uint32_t width = 1280, height = 720;
  CameraArgs camera;
  uint32_t shadeMode = 0;  // CLR_SHADE_*
  bool cullBack = false;
  std::string device;
  uint32_t frames = 1;
  bool framesGiven = false, shardGiven = false;  // --frames, --shard on the command line
  bool stats = false;
  // Methods (see README, "Methods"): --aa, --edges, --interp, --traversal.
  std::string aa;  // an aa.h mode name, "auto", or empty (none; --quality auto chooses)
  uint32_t edgeMode = CLR_EDGES_FIXED;
  uint32_t interpMode = CLR_INTERP_PERSPECTIVE;
  uint32_t traversal = CLR_TRAVERSAL_BBOX;
  bool qualityAuto = false;                      // --quality auto
  uint32_t depthMode = CLR_DEPTH_FLOAT32;        // --depth (CLR_DEPTH_*)
  bool depthAuto = false;                        // --depth auto (depth.h)
  bool depthGiven = false;                       // --depth on the command line
  uint32_t visibility = CLR_VISIBILITY_ZBUFFER;  // --visibility
  std::string viewsPath;                         // --views: outPath is then a pattern (views.h)
  Shard shard;                                   // --shard K/N, with --views only
  uint32_t texFilter = CLR_FILTER_TRILINEAR;     // --filter
  bool pointLightOn = false;                     // --light-point x,y,z[,r]
  glm::vec3 pointLight{0.0f};
  std::optional<float> pointLightRange;  // r; default: the scene's bounding radius
  // Lines (README, "Wireframe and lines"): --wireframe [only], --line, --line-width.
  uint32_t wireframe = CLR_WIREFRAME_OFF;
  uint32_t lineMethod = CLR_LINE_AA;
  float lineWidth = 1.0f;
  uint32_t pointSize = 1;  // --point-size: a file's points as squares of this many pixels a side
  std::string aovPath;     // --aov PATH.exr: the visibility-buffer outputs (aov.h)
};

// args: everything after "render". With outputsRequired false (the
// library's RenderOptions) -o and --aov may both be absent.
RenderArgs parseRenderArgs(const std::vector<std::string>& args, bool outputsRequired = true);
// The same flags one by one, not yet checked against each other.
RenderArgs parseRenderFlags(const std::vector<std::string>& args);
// The outputs a render must name: -o with --views, else -o or --aov.
void requireOutputs(const RenderArgs& args);

const char* usageText();

// The --traversal name of a CLR_TRAVERSAL_* value (for --stats).
const char* traversalName(uint32_t traversal);

// Whether a command's arguments ask for its usage (--help or -h anywhere).
bool wantsHelp(const std::vector<std::string>& args);

// A clr::Error naming `flag` unless `path` is a file name ending in
// `extension` (".png", ".exr"; any case): -o and --aov name their format.
void checkExtension(const std::string& flag, const std::string& path, const std::string& extension);

// The value after flag args[i], moving i onto it; a clr::Error naming the
// flag when it is the last argument. Every parse loop of the project uses it.
const std::string& flagValue(const std::vector<std::string>& args, size_t& i);

// An argument that no flag of the parse loop claimed: an unknown option is
// an error, otherwise it is the command's one SCENE.
void takeScenePath(const std::string& arg, std::string& scenePath);

// Shared flag parsers (the bench tools use them too); each throws a
// clr::Error naming the flag and the bad text.
uint64_t parseUnsigned(const std::string& flag, const std::string& text, uint64_t lo, uint64_t hi);
float parseFloat(const std::string& flag, const std::string& text);  // decimal, finite
void parseSize(const std::string& flag, const std::string& text, uint32_t& width, uint32_t& height);
uint32_t parseShadeMode(const std::string& flag, const std::string& text);  // a --shade name: its CLR_SHADE_*

// The --shade names, indexed by CLR_SHADE_* (kernels/shared.h): the one list
// that parsing, the usage text and the tests' mode lists read.
inline constexpr const char* kShadeModeNames[] = {"lambert", "normal", "depth",   "id",    "uv",     "checker",
                                                  "color",   "flat",   "gouraud", "phong", "texture"};
static_assert(std::size(kShadeModeNames) == CLR_NUM_SHADE_MODES, "one --shade name per CLR_SHADE_* mode");

// Helpers every command-line program of the project shares.
double median(std::vector<double> values);     // of a non-empty list
std::string jsonEscape(const std::string& s);  // for a JSON string literal

// The one-line message of the std::exception being handled (call it only
// inside a catch block): a clr::Error's text, "OpenCL call NAME failed:
// CL_ERROR (code)", "out of host memory", or another exception's what().
// runProgram and the library's guarded() (api_impl.h) both report through it.
std::string failureMessage();

// Runs a program's body and turns every failure (clr::Error, an OpenCL
// error, exhausted memory) into one line "PROGRAM: message" on stderr and
// exit status 1.
int runProgram(const char* program, const std::function<int()>& body);

}  // namespace clr
