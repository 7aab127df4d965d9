// views.h — many cameras in one run (`clraster render --views FILE`): the views file, the shard of it one process
// renders, and the output names.
//
// A views file is one JSON object with one key, "views", a non-empty array of objects; each object is one camera and
// may hold these keys, all of them optional, and no others:
//   "eye", "target", "up"  arrays of 3 numbers (world space)
//   "fov"                  vertical field of view in degrees, in (0, 180)
//   "near", "far"          clip planes, 0 < near < far
//   "size"                 [W, H], integers in 1..16384
// A key a view leaves out takes the command line's value (--eye, --size, ...) and, failing that, the framing default of
// camera.h. Every problem is a clr::Error "FILE: view I: problem" (or "FILE: problem" for the whole file), found before
// anything is rendered.
//
// A shard K/N is the views K, K + N, K + 2N, ... of the list; output names come from a printf pattern with one integer
// conversion, given the view's index in the whole list, so shards never collide.
#pragma once

#include "render/camera.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace clr {

// The most views one file may hold; more are refused while parsing, so that
// memory and time stay linear in what is rendered.
inline constexpr size_t kMaxViews = 1000000;

// One entry of a views file after merging with the command line's defaults.
struct ViewSpec {
  CameraArgs camera;
  uint32_t width = 0, height = 0;
};

// Reads and checks a views file; `defaults` and the size fill the keys a
// view leaves out.
std::vector<ViewSpec> loadViews(const std::string& path, const CameraArgs& defaults, uint32_t width, uint32_t height);

// Same, from the file's text; `path` only names the file in errors.
std::vector<ViewSpec> parseViews(const std::string& path, const std::string& text, const CameraArgs& defaults,
                                 uint32_t width, uint32_t height);

// The checks of every view's camera that need no scene (checkCameraArgs),
// before any device work; a clr::Error "PATH: view I: problem".
void checkViewCameras(const std::string& path, const std::vector<ViewSpec>& views);

// Frames every view on the scene's bounds (frameCamera); an impossible
// camera is a clr::Error "PATH: view I: problem".
std::vector<Camera> frameViews(const std::string& path, const std::vector<ViewSpec>& views, const Bounds& bounds);

struct Shard {
  uint32_t index = 0, count = 1;  // K and N of K/N, 0 <= K < N
};

// Parses "K/N"; errors name the --shard flag.
Shard parseShard(const std::string& text);

// The indices of the views that shard renders, ascending.
std::vector<size_t> shardViews(size_t numViews, const Shard& shard);

// Throws unless pattern holds exactly one integer conversion (%d, %i or %u,
// with optional flags, width and precision; %% is a literal percent sign).
void checkOutputPattern(const std::string& pattern);

// The pattern with the conversion replaced by index (pattern checked).
std::string outputName(const std::string& pattern, size_t index);

}  // namespace clr
