// flags.cpp — strict parsing of the render command's flags (see flags.h).
#include "render/flags.h"

#include "pipeline/aa.h"

#include "pipeline/cl.h"

#include "kernels/shared.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cmath>
#include <cstdlib>

namespace clr {

namespace {
const char* const kTraversalNames[] = {"bbox", "hierarchical", "spans", "spans-float"};  // by CLR_TRAVERSAL_*
}  // namespace

const char* traversalName(uint32_t traversal)
{
  return traversal < 4 ? kTraversalNames[traversal] : "unknown";
}

namespace {
// "lambert|normal|...": the --shade choices in CLR_SHADE_* order.
std::string shadeModeChoices()
{
  std::string choices;
  for (const char* name : kShadeModeNames) choices += std::string(choices.empty() ? "" : "|") + name;
  return choices;
}
}  // namespace

const char* usageText()
{
  static const std::string text =
      std::string(
          "usage:\n"
          "  clraster render [SCENE] [-o OUT.png] [--aov OUT.exr] [--size WxH] [--eye x,y,z]\n"
          "                  [--target x,y,z] [--up x,y,z] [--fov DEG] [--near N] [--far F]\n"
          "                  [--shade ") +
      shadeModeChoices() +
      "]\n"
      "                  [--filter nearest|bilinear|trilinear] [--light-point x,y,z[,r]]\n"
      "                  [--cull none|back]\n"
      "                  [--aa none|msaa2|msaa4|msaa8|msaa16|ssaa4|ssaa16|auto]\n"
      "                  [--edges fixed|float] [--interp perspective|affine]\n"
      "                  [--traversal bbox|hierarchical|spans|spans-float] [--quality auto]\n"
      "                  [--depth float32|unorm24|reversed|auto] [--visibility zbuffer|painter]\n"
      "                  [--wireframe [only]] [--line aa|bresenham] [--line-width PX]\n"
      "                  [--point-size PX] [--device SEL] [--frames N] [--stats]\n"
      "                  [--assets DIR|any]\n"
      "  clraster render [SCENE] --views VIEWS.json -o OUT_%04d.png [--shard K/N]\n"
      "                  [--size WxH] [camera flags as defaults] [--shade ...] [--cull ...]\n"
      "                  [--device SEL] [--stats]\n"
      "  clraster info MESH [--fov DEG] [--json] [--assets DIR|any]\n"
      "  clraster devices\n"
      "  clraster cache [--device SEL]\n"
      "  clraster help | COMMAND --help\n"
      "SCENE is any mesh assimp reads (OBJ, PLY, OFF, STL, glTF/GLB); without it the\n"
      "built-in scene is rendered. A render writes -o (a .png), --aov (a .exr), or both.\n"
      "Files a model names (textures, material libraries, buffers) are read only\n"
      "inside its folder; --assets DIR adds a folder, --assets any lifts the rule.\n"
      "`info` prints a mesh's counts, bounds, materials and the default camera's flags.\n"
      "`cache` compiles the kernels for a device and stores them (CLRASTER_CACHE_DIR,\n"
      "else ~/.cache/clraster), so later starts skip the compiler front end.\n"
      "SEL is a device index or a name substring.\n"
      "VIEWS.json is {\"views\": [{\"eye\": [x,y,z], \"target\": [x,y,z], \"up\": [x,y,z],\n"
      "\"fov\": DEG, \"near\": N, \"far\": F, \"size\": [W,H]}, ...]}, every key optional; the\n"
      "output pattern's one integer conversion is the view's index in the list, and\n"
      "--shard K/N renders the views K, K+N, K+2N, ...\n";
  return text.c_str();
}

bool wantsHelp(const std::vector<std::string>& args)
{
  return std::any_of(args.begin(), args.end(), [](const std::string& a) { return a == "--help" || a == "-h"; });
}

void checkExtension(const std::string& flag, const std::string& path, const std::string& extension)
{
  std::string tail = path.size() >= extension.size() ? path.substr(path.size() - extension.size()) : "";
  std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (tail != extension || path.size() == extension.size() || path.back() == '/')
    throw Error(flag + ": '" + userText(path) + "' must be a file name ending in " + extension);
}

float parseFloat(const std::string& flag, const std::string& text)
{
  // Decimal only: strtof also takes leading spaces and hexadecimal ("0x2Dp0").
  errno = 0;
  char* end = nullptr;
  const float v = std::strtof(text.c_str(), &end);
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])) ||
      text.find_first_of("xX") != std::string::npos || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw Error(flag + ": '" + userText(text) + "' is not a finite number");
  return v;
}

namespace {

glm::vec3 parseVec3(const std::string& flag, const std::string& text)
{
  glm::vec3 v;
  size_t start = 0;
  for (int k = 0; k < 3; ++k) {
    const size_t comma = text.find(',', start);
    if ((k < 2) != (comma != std::string::npos)) throw Error(flag + ": '" + userText(text) + "' is not x,y,z");
    v[k] = parseFloat(flag, text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    start = comma + 1;
  }
  return v;
}

// The index of `text` in `choices`, or an error listing them.
uint32_t parseChoice(const std::string& flag, const std::string& text, const std::vector<const char*>& choices)
{
  std::string names;
  uint32_t index = 0;
  for (const char* c : choices) {
    if (text == c) return index;
    names += std::string(index++ ? ", " : "") + c;
  }
  throw Error(flag + ": unknown value '" + userText(text, 120) + "' (" + names + ")");
}

}  // namespace

const std::string& flagValue(const std::vector<std::string>& args, size_t& i)
{
  if (i + 1 >= args.size()) throw Error(userText(args[i]) + ": missing value");
  return args[++i];
}

void takeScenePath(const std::string& arg, std::string& scenePath)
{
  if (!arg.empty() && arg[0] == '-') throw Error("unknown option '" + userText(arg) + "'");
  if (!scenePath.empty()) throw Error("unexpected argument '" + userText(arg) + "' (only one SCENE)");
  scenePath = arg;
}

uint64_t parseUnsigned(const std::string& flag, const std::string& text, uint64_t lo, uint64_t hi)
{
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || !std::isdigit(static_cast<unsigned char>(text[0])) || *end != '\0' || errno == ERANGE || v < lo ||
      v > hi)
    throw Error(flag + ": '" + userText(text) + "' must be an integer in " + std::to_string(lo) + ".." +
                std::to_string(hi));
  return v;
}

uint32_t parseShadeMode(const std::string& flag, const std::string& text)
{
  return parseChoice(flag, text, {std::begin(kShadeModeNames), std::end(kShadeModeNames)});
}

void parseSize(const std::string& flag, const std::string& text, uint32_t& width, uint32_t& height)
{
  const size_t x = text.find('x');
  if (x == std::string::npos) throw Error(flag + ": '" + userText(text) + "' is not WxH");
  width = uint32_t(parseUnsigned(flag, text.substr(0, x), 1, CLR_MAX_VIEWPORT));
  height = uint32_t(parseUnsigned(flag, text.substr(x + 1), 1, CLR_MAX_VIEWPORT));
}

void requireOutputs(const RenderArgs& r)
{
  if (!r.viewsPath.empty() && r.outPath.empty()) throw Error("missing -o OUT_%04d.png");
  if (r.outPath.empty() && r.aovPath.empty()) throw Error("missing -o OUT.png (or --aov OUT.exr)");
}

RenderArgs parseRenderFlags(const std::vector<std::string>& args)
{
  RenderArgs r;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    // Step 1: flags that take a value.
    if (a == "-o" || a == "--output") {
      r.outPath = flagValue(args, i);
    } else if (a == "--size") {
      parseSize(a, flagValue(args, i), r.width, r.height);
    } else if (a == "--eye") {
      r.camera.eye = parseVec3(a, flagValue(args, i));
    } else if (a == "--target") {
      r.camera.target = parseVec3(a, flagValue(args, i));
    } else if (a == "--up") {
      r.camera.up = parseVec3(a, flagValue(args, i));
    } else if (a == "--fov") {
      r.camera.fovDegrees = parseFloat(a, flagValue(args, i));
    } else if (a == "--near") {
      r.camera.zNear = parseFloat(a, flagValue(args, i));
    } else if (a == "--far") {
      r.camera.zFar = parseFloat(a, flagValue(args, i));
    } else if (a == "--shade") {
      r.shadeMode = parseShadeMode(a, flagValue(args, i));
    } else if (a == "--filter") {
      r.texFilter = parseChoice(a, flagValue(args, i), {"nearest", "bilinear", "trilinear"});
    } else if (a == "--light-point") {
      // x,y,z or x,y,z,r.
      const std::string& text = flagValue(args, i);
      const size_t commas = size_t(std::count(text.begin(), text.end(), ','));
      if (commas == 3) {
        const size_t last = text.rfind(',');
        r.pointLight = parseVec3(a, text.substr(0, last));
        const float range = parseFloat(a, text.substr(last + 1));
        if (!(range > 0.0f)) throw Error(a + ": range r must be > 0 in '" + userText(text) + "'");
        r.pointLightRange = range;
      } else {
        r.pointLight = parseVec3(a, text);
      }
      r.pointLightOn = true;
    } else if (a == "--aa") {
      r.aa = flagValue(args, i);
      if (r.aa != "auto") findAaMode(r.aa);  // throws for an unknown name
    } else if (a == "--edges") {
      r.edgeMode = parseChoice(a, flagValue(args, i), {"fixed", "float"});
    } else if (a == "--interp") {
      r.interpMode = parseChoice(a, flagValue(args, i), {"perspective", "affine"});
    } else if (a == "--traversal") {
      r.traversal = parseChoice(a, flagValue(args, i),
                                {kTraversalNames[0], kTraversalNames[1], kTraversalNames[2], kTraversalNames[3]});
    } else if (a == "--depth") {
      const uint32_t choice = parseChoice(a, flagValue(args, i), {"float32", "unorm24", "reversed", "auto"});
      r.depthAuto = choice == 3;
      r.depthMode = r.depthAuto ? CLR_DEPTH_FLOAT32 : choice;
      r.depthGiven = true;
    } else if (a == "--visibility") {
      r.visibility = parseChoice(a, flagValue(args, i), {"zbuffer", "painter"});
    } else if (a == "--quality") {
      parseChoice(a, flagValue(args, i), {"auto"});
      r.qualityAuto = true;
    } else if (a == "--wireframe") {
      // An optional value: "only" draws the edges alone, "overlay" (the
      // default) over the shaded image.
      r.wireframe = CLR_WIREFRAME_OVERLAY;
      if (i + 1 < args.size() && (args[i + 1] == "only" || args[i + 1] == "overlay"))
        r.wireframe = args[++i] == "only" ? CLR_WIREFRAME_ONLY : CLR_WIREFRAME_OVERLAY;
    } else if (a == "--line") {
      r.lineMethod = parseChoice(a, flagValue(args, i), {"aa", "bresenham"}) == 0 ? CLR_LINE_AA : CLR_LINE_BRESENHAM;
    } else if (a == "--line-width") {
      r.lineWidth = parseFloat(a, flagValue(args, i));
      if (!(r.lineWidth > 0.0f && r.lineWidth <= 16.0f)) throw Error("--line-width must lie in (0, 16] pixels");
    } else if (a == "--point-size") {
      r.pointSize = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 16));
    } else if (a == "--aov") {
      r.aovPath = flagValue(args, i);
      if (r.aovPath.empty()) throw Error("--aov: empty path");
    } else if (a == "--cull") {
      const std::string& s = flagValue(args, i);
      if (s != "none" && s != "back") throw Error("--cull: unknown mode '" + userText(s) + "' (none, back)");
      r.cullBack = s == "back";
    } else if (a == "--device") {
      r.device = flagValue(args, i);
    } else if (a == "--frames") {
      r.frames = uint32_t(parseUnsigned(a, flagValue(args, i), 1, 100000));
      r.framesGiven = true;
    } else if (a == "--assets") {
      r.assets = flagValue(args, i);
      if (r.assets.empty()) throw Error("--assets: empty path (a directory, or 'any')");
    } else if (a == "--views") {
      r.viewsPath = flagValue(args, i);
      if (r.viewsPath.empty()) throw Error("--views: empty path");
    } else if (a == "--shard") {
      r.shard = parseShard(flagValue(args, i));
      r.shardGiven = true;
      // Step 2: switches and the scene path.
    } else if (a == "--stats") {
      r.stats = true;
    } else {
      takeScenePath(a, r.scenePath);
    }
  }
  return r;
}

RenderArgs parseRenderArgs(const std::vector<std::string>& args, bool outputsRequired)
{
  const RenderArgs r = parseRenderFlags(args);
  if (outputsRequired) requireOutputs(r);
  if (!r.outPath.empty()) checkExtension("-o", r.outPath, ".png");
  if (!r.aovPath.empty()) checkExtension("--aov", r.aovPath, ".exr");
  if (r.shardGiven && r.viewsPath.empty()) throw Error("--shard needs --views");
  if (r.framesGiven && !r.viewsPath.empty()) throw Error("--frames cannot be combined with --views");
  if (!r.viewsPath.empty() && !r.outPath.empty()) checkOutputPattern(r.outPath);
  if (!r.aovPath.empty() && !r.viewsPath.empty()) throw Error("--aov cannot be combined with --views");
  if (r.wireframe != CLR_WIREFRAME_OFF && r.shadeMode == CLR_SHADE_ID)
    throw Error("--wireframe cannot be combined with --shade id (the id image stays exact)");
  // Check the camera now, before any file is read.
  if (!(r.camera.fovDegrees > 0.0f && r.camera.fovDegrees < 180.0f)) throw Error("--fov must lie in (0, 180) degrees");
  if (r.camera.zNear && !(*r.camera.zNear > 0.0f)) throw Error("--near must be > 0");
  if (r.camera.zFar && r.camera.zNear && !(*r.camera.zFar > *r.camera.zNear))
    throw Error("--far must be greater than --near");
  if (r.camera.zFar && !(*r.camera.zFar > 0.0f)) throw Error("--far must be > 0");
  return r;
}

double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
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

std::string failureMessage()
{
  try {
    throw;
  } catch (const Error& e) {
    return e.what();
  } catch (const cl::Error& e) {
    return std::string("OpenCL call ") + e.what() + " failed: " + clErrorName(e.err()) + " (" +
           std::to_string(e.err()) + ")";
  } catch (const std::bad_alloc&) {
    return "out of host memory";
  } catch (const std::exception& e) {
    return e.what();
  }
}

int runProgram(const char* program, const std::function<int()>& body)
{
  try {
    return body();
  } catch (const std::exception&) {
    std::fprintf(stderr, "%s: %s\n", program, failureMessage().c_str());
  }
  return 1;
}

}  // namespace clr
