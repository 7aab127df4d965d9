// asset_root.h — the one rule for the files a model names (material
// libraries, textures, glTF buffers): a model reaches only its own folder.
//
// A referenced file is opened only if its path, with every symbolic link
// and ".." resolved (realpath), lies inside the model's folder or below it,
// or inside the folder --assets DIR adds; --assets any lifts the rule for
// trusted files. The file is then opened under the file rule (file_rule.h),
// and what was opened is checked again (/proc/self/fd), so a link swapped in
// meanwhile cannot lead outside. Every refusal, and under the rule every
// failure to read the file (missing, unreadable, not a regular file, not
// decodable), has one wording that names the reference as the model wrote
// it and never tells whether a file exists. docs/limits.md, "Files a model
// may reach", states the rule.
#pragma once

#include "io/file_rule.h"

#include <memory>
#include <string>
#include <vector>

namespace clr {

// --assets any: every file the process can read.
inline constexpr const char* kAnyAssets = "any";

class AssetRoot {
 public:
  // The model's folder, widened by `assets`: "" none, kAnyAssets, or a
  // directory (an Error naming --assets unless it is one).
  AssetRoot(const std::string& modelPath, const std::string& assets);

  bool confined() const { return confined_; }
  // Opens `path`, the file `reference` names (both as the reader built and
  // the model wrote them), under this rule and the file rule; throws a
  // clr::Error: refusal(reference) when confined, the file rule's otherwise.
  std::unique_ptr<InputFile> open(const std::string& path, const std::string& reference, const InputKind& kind) const;
  // The one wording for a reference that cannot be used under the rule.
  static std::string refusal(const std::string& reference);

 private:
  bool confined_ = false;
  std::vector<std::string> roots_;  // canonical folders, each ending in '/' (none: the model's folder vanished)
  bool inside(const std::string& canonical) const;
};

}  // namespace clr
