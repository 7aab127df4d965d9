// model_io.h — the files assimp opens while importing a model, under the
// file rule (file_rule.h). The model itself is served from memory, the
// one read of it that the checks saw (or its text with positions rewritten,
// exact_positions.h); every file it names (an OBJ's material library, a glTF
// buffer) is read whole under the model-folder rule too (asset_root.h). A
// file the rules refuse is not opened; the refusal is kept, so that the
// import's error or warning can say why.
#pragma once

#include "io/asset_root.h"

#include <assimp/DefaultIOSystem.h>

#include <cstdint>
#include <list>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>

namespace clr {

class RuleIOSystem : public Assimp::DefaultIOSystem {
 public:
  // `modelPath` as handed to assimp; `assets` as AssetRoot takes it.
  RuleIOSystem(const std::string& modelPath, const std::string& assets);
  bool Exists(const char* file) const override;
  Assimp::IOStream* Open(const char* file, const char* mode) override;

  // Serves `bytes` whenever `path`, the model, is opened (both must outlive
  // the import); other files are read as references of that model.
  void serve(const std::string& path, const std::string* bytes);
  // Counts the materials of every file the model names (an OBJ's libraries) against kMaxMaterials.
  void countMaterialLibraries() { countMaterials_ = true; }
  // The import budget's error (import_budget.h), "" while within it: the
  // files named exceed kReferencedBytes together, or their materials the limit.
  const std::string& overBudget() const { return overBudget_; }
  // "PATH: problem" for each file the rule refused, in order.
  const std::vector<std::string>& refusals() const { return refusals_; }

 private:
  bool isModel(const char* file) const { return modelPath_ == file; }
  std::string reference(const std::string& file) const;
  void refuseReference(const std::string& file, const std::string& why);
  std::string modelPath_, modelFolder_;
  AssetRoot root_;
  bool lastOpenFailed_ = false;
  bool countMaterials_ = false;
  uint64_t referencedBytes_ = 0, materials_ = 0;
  std::string overBudget_;
  std::list<std::string> kept_;  // libraries read whole, served from memory
  std::set<std::string> refusedReferences_;
  std::string servedPath_;
  const std::string* served_ = nullptr;
  void refuse(const struct stat& st, const std::string& why) const;
  mutable std::vector<std::string> refusals_;
  mutable std::set<std::pair<uint64_t, uint64_t>> refused_;  // (device, inode) of each refused file
};

}  // namespace clr
