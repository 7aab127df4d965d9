// views.cpp — the views file, shards and output names (see views.h). JSON is
// parsed with nlohmann::json; every error is one line naming the file, the
// view and the key.
#include "render/views.h"

#include "base/error.h"
#include "render/flags.h"
#include "io/file_rule.h"

#include "kernels/shared.h"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <climits>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <set>
#include <sstream>

namespace clr {

namespace {

using Json = nlohmann::json;

// A JSON number as a finite float; `what` names the key in errors.
float finiteFloat(const Json& value, const std::string& what)
{
  if (!value.is_number()) throw Error(what + " must be a number");
  const double v = value.get<double>();
  if (!std::isfinite(v) || std::fabs(v) > 3.0e38) throw Error(what + " must be a finite number");
  return float(v);
}

glm::vec3 vec3Field(const Json& value, const std::string& what)
{
  if (!value.is_array() || value.size() != 3) throw Error(what + " must be an array of 3 numbers");
  glm::vec3 v;
  for (int k = 0; k < 3; ++k) v[k] = finiteFloat(value[k], what + "[" + std::to_string(k) + "]");
  return v;
}

uint32_t sizeSide(const Json& value, const std::string& what)
{
  if (!value.is_number_integer() || value.get<int64_t>() < 1 || value.get<int64_t>() > CLR_MAX_VIEWPORT)
    throw Error(what + " must be an integer in 1.." + std::to_string(CLR_MAX_VIEWPORT));
  return uint32_t(value.get<int64_t>());
}

// One element of "views", merged over the defaults.
ViewSpec parseView(const Json& view, ViewSpec spec)
{
  if (!view.is_object()) throw Error("must be an object {\"eye\": [x, y, z], ...}");
  for (const auto& [key, value] : view.items()) {
    const std::string what = "\"" + userText(key, 60) + "\"";
    if (key == "eye") {
      spec.camera.eye = vec3Field(value, what);
    } else if (key == "target") {
      spec.camera.target = vec3Field(value, what);
    } else if (key == "up") {
      spec.camera.up = vec3Field(value, what);
    } else if (key == "fov") {
      spec.camera.fovDegrees = finiteFloat(value, what);
      if (!(spec.camera.fovDegrees > 0.0f && spec.camera.fovDegrees < 180.0f))
        throw Error(what + " must lie in (0, 180) degrees");
    } else if (key == "near") {
      spec.camera.zNear = finiteFloat(value, what);
      if (!(*spec.camera.zNear > 0.0f)) throw Error(what + " must be > 0");
    } else if (key == "far") {
      spec.camera.zFar = finiteFloat(value, what);
      if (!(*spec.camera.zFar > 0.0f)) throw Error(what + " must be > 0");
    } else if (key == "size") {
      if (!value.is_array() || value.size() != 2) throw Error(what + " must be [W, H]");
      spec.width = sizeSide(value[0], what + "[0]");
      spec.height = sizeSide(value[1], what + "[1]");
    } else {
      throw Error("unknown key " + what + " (eye, target, up, fov, near, far, size)");
    }
  }
  if (spec.camera.zNear && spec.camera.zFar && !(*spec.camera.zFar > *spec.camera.zNear))
    throw Error("\"far\" must be greater than \"near\"");
  return spec;
}

// The widest a width or a precision of the output pattern may be: a name
// then has at most 9 digits more than the index itself needs.
constexpr unsigned kMaxPatternWidth = 9;

// Length of the conversion starting at pattern[i] == '%' when it is an
// integer one (%[-+ 0]*[0-9]*(.[0-9]*)?[diu]), else 0. A width or precision
// above kMaxPatternWidth is an error of its own.
size_t integerConversion(const std::string& pattern, size_t i)
{
  size_t j = i + 1;
  auto number = [&](const char* what) {
    const size_t start = j;
    while (j < pattern.size() && pattern[j] >= '0' && pattern[j] <= '9') ++j;
    const std::string digits = pattern.substr(start, std::min<size_t>(j - start, 3));
    if (j - start > 2 || (!digits.empty() && unsigned(std::stoul(digits)) > kMaxPatternWidth))
      throw Error("-o: '" + userText(pattern, 120) + "' has a " + what + " over " + std::to_string(kMaxPatternWidth));
  };
  while (j < pattern.size() && std::strchr("-+ 0", pattern[j]) && pattern[j] != '\0') ++j;
  number("width");
  if (j < pattern.size() && pattern[j] == '.') {
    ++j;
    number("precision");
  }
  if (j < pattern.size() && (pattern[j] == 'd' || pattern[j] == 'i' || pattern[j] == 'u')) return j + 1 - i;
  return 0;
}

// Calls fn(view) for each view; an error names the file and the view.
template <class Fn>
void forEachView(const std::string& path, const std::vector<ViewSpec>& views, Fn fn)
{
  for (size_t i = 0; i < views.size(); ++i) {
    try {
      fn(views[i]);
    } catch (const Error& e) {
      throw Error(userText(path) + ": view " + std::to_string(i) + ": " + e.what());
    }
  }
}

// nlohmann's DOM parser, plus what the views file needs while parsing: a
// key repeated in one object is an error, and the values of the top-level
// array are counted against kMaxViews. (nlohmann's callback parser scans the
// parent array at every object's end: quadratic in the number of views.)
class ViewsSax : public nlohmann::detail::json_sax_dom_parser<Json> {
 public:
  using Base = nlohmann::detail::json_sax_dom_parser<Json>;
  ViewsSax(Json& root, const std::string& path) : Base(root), path_(path) {}

  bool null() { return value() && Base::null(); }
  bool boolean(bool v) { return value() && Base::boolean(v); }
  bool number_integer(number_integer_t v) { return value() && Base::number_integer(v); }
  bool number_unsigned(number_unsigned_t v) { return value() && Base::number_unsigned(v); }
  bool number_float(number_float_t v, const string_t& s) { return value() && Base::number_float(v, s); }
  bool string(string_t& v) { return value() && Base::string(v); }
  bool binary(binary_t& v) { return value() && Base::binary(v); }
  bool start_object(size_t n)
  {
    value();
    open_.push_back({true, {}});
    return Base::start_object(n);
  }
  bool end_object()
  {
    open_.pop_back();
    return Base::end_object();
  }
  bool start_array(size_t n)
  {
    value();
    open_.push_back({false, {}});
    return Base::start_array(n);
  }
  bool end_array()
  {
    open_.pop_back();
    return Base::end_array();
  }
  bool key(string_t& k)
  {
    if (!open_.back().keys.insert(k).second)
      throw Error(userText(path_) + ": duplicate key \"" + userText(k, 60) + "\"");
    return Base::key(k);
  }

 private:
  struct Open {
    bool object;
    std::set<std::string> keys;
  };
  // A value begins: one more view when it is an element of the array under the top-level object.
  bool value()
  {
    if (open_.size() == 2 && open_[0].object && !open_[1].object && ++views_ > kMaxViews)
      throw Error(userText(path_) + ": more than " + std::to_string(kMaxViews) + " views (the limit of a views file)");
    return true;
  }
  const std::string& path_;
  std::vector<Open> open_;
  size_t views_ = 0;
};

}  // namespace

std::vector<ViewSpec> parseViews(const std::string& path, const std::string& text, const CameraArgs& defaults,
                                 uint32_t width, uint32_t height)
{
  // Step 1: the JSON itself (nlohmann's message names line and column), in
  // one linear pass; a key repeated in one object is an error, not "the last
  // one wins"; more than kMaxViews views are refused.
  Json doc;
  ViewsSax sax(doc, path);
  try {
    Json::sax_parse(text, &sax);
  } catch (const Json::exception& e) {
    std::string message = e.what();
    if (message.rfind("[json.exception.", 0) == 0 && message.find("] ") != std::string::npos)
      message = message.substr(message.find("] ") + 2);
    throw Error(userText(path) + ": " + userText(message, 80));
  }

  // Step 2: the top level, {"views": [...]}.
  if (!doc.is_object()) throw Error(userText(path) + ": must be a JSON object {\"views\": [...]}");
  for (const auto& item : doc.items())
    if (item.key() != "views")
      throw Error(userText(path) + ": unknown key \"" + userText(item.key(), 60) + "\" (only \"views\")");
  if (!doc.contains("views")) throw Error(userText(path) + ": missing \"views\"");
  const Json& list = doc["views"];
  if (!list.is_array()) throw Error(userText(path) + ": \"views\" must be an array");
  if (list.empty()) throw Error(userText(path) + ": \"views\" is empty");
  if (list.size() > size_t(INT_MAX)) throw Error(userText(path) + ": too many views");

  // Step 3: each view, merged over the command line's values.
  ViewSpec base;
  base.camera = defaults;
  base.width = width;
  base.height = height;
  std::vector<ViewSpec> views;
  views.reserve(list.size());
  for (size_t i = 0; i < list.size(); ++i) {
    try {
      views.push_back(parseView(list[i], base));
    } catch (const Error& e) {
      throw Error(userText(path) + ": view " + std::to_string(i) + ": " + e.what());
    }
  }
  return views;
}

std::vector<ViewSpec> loadViews(const std::string& path, const CameraArgs& defaults, uint32_t width, uint32_t height)
{
  return parseViews(path, readInputFile(path, kViewsInput), defaults, width, height);
}

void checkViewCameras(const std::string& path, const std::vector<ViewSpec>& views)
{
  forEachView(path, views, [](const ViewSpec& view) { checkCameraArgs(view.camera, ""); });
}

std::vector<Camera> frameViews(const std::string& path, const std::vector<ViewSpec>& views, const Bounds& bounds)
{
  std::vector<Camera> cameras;
  cameras.reserve(views.size());
  forEachView(path, views, [&](const ViewSpec& view) { cameras.push_back(frameCamera(view.camera, bounds, "")); });
  return cameras;
}

Shard parseShard(const std::string& text)
{
  const size_t slash = text.find('/');
  if (slash == std::string::npos) throw Error("--shard: '" + userText(text) + "' is not K/N");
  Shard s;
  s.index = uint32_t(parseUnsigned("--shard K", text.substr(0, slash), 0, UINT32_MAX));
  s.count = uint32_t(parseUnsigned("--shard N", text.substr(slash + 1), 1, UINT32_MAX));
  if (s.index >= s.count)
    throw Error("--shard: K must be less than N in K/N (K counts from 0), got '" + userText(text) + "'");
  return s;
}

std::vector<size_t> shardViews(size_t numViews, const Shard& shard)
{
  std::vector<size_t> indices;
  for (size_t i = shard.index; i < numViews; i += shard.count) indices.push_back(i);
  return indices;
}

void checkOutputPattern(const std::string& pattern)
{
  // Step 1: the conversions, before anything is formatted.
  if (pattern.size() >= PATH_MAX)
    throw Error("-o: '" + userText(pattern, 120) + "' is longer than a path may be (" + std::to_string(PATH_MAX - 1) +
                " bytes)");
  if (pattern.find('\0') != std::string::npos) throw Error("-o: the pattern holds a NUL byte");
  size_t conversions = 0;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') continue;
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      ++i;
      continue;
    }
    const size_t length = integerConversion(pattern, i);
    if (length == 0) throw Error("-o: '" + userText(pattern, 120) + "' has a conversion other than %d, %i or %u");
    ++conversions;
    i += length - 1;
  }
  if (conversions != 1)
    throw Error("-o: with --views, '" + userText(pattern, 120) +
                "' needs exactly one integer conversion for the view index (e.g. out_%04d.png)");
  // Step 2: the longest name it can give (the index up to INT_MAX) must fit
  // the file system: each path component NAME_MAX bytes, the whole PATH_MAX.
  const std::string longest = outputName(pattern, size_t(INT_MAX));
  size_t start = 0;
  while (start <= longest.size()) {
    const size_t slash = std::min(longest.find('/', start), longest.size());
    if (slash - start > NAME_MAX)
      throw Error("-o: '" + userText(pattern, 120) + "' gives a file or folder name over " + std::to_string(NAME_MAX) +
                  " bytes");
    start = slash + 1;
  }
}

std::string outputName(const std::string& pattern, size_t index)
{
  // A checked pattern formats to less than PATH_MAX + 2·kMaxPatternWidth
  // bytes; the buffer is bounded whatever the pattern.
  char name[PATH_MAX + 32];
  if (pattern.size() >= PATH_MAX) throw Error("-o: '" + userText(pattern, 120) + "' is too long");
  const int n = std::snprintf(name, sizeof name, pattern.c_str(), int(std::min<size_t>(index, INT_MAX)));
  if (n < 0 || size_t(n) >= sizeof name) throw Error("-o: cannot format '" + userText(pattern, 120) + "'");
  if (size_t(n) >= PATH_MAX)
    throw Error("-o: '" + userText(pattern, 120) + "' gives a name over " + std::to_string(PATH_MAX - 1) + " bytes");
  return std::string(name, size_t(n));
}

}  // namespace clr
