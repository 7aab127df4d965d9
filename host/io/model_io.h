// model_io.h — the files assimp opens while importing a model, under the
// file rule (file_rule.h). The model itself is served from memory, the
// one read of it that the checks saw (or its text with positions rewritten,
// exact_positions.h); every file it names (an OBJ's material library, a glTF
// buffer) is read whole through readModelReference. A file the rule refuses
// is not opened; the refusal is kept, so that the import's error or warning
// can say why.
#pragma once

#include <assimp/DefaultIOSystem.h>

#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>

namespace clr {

class RuleIOSystem : public Assimp::DefaultIOSystem {
 public:
  bool Exists(const char* file) const override;
  Assimp::IOStream* Open(const char* file, const char* mode) override;

  // Serves `bytes` whenever `path`, the model, is opened (both must outlive
  // the import); other files are read as references of that model.
  void serve(const std::string& path, const std::string* bytes);
  // "PATH: problem" for each file the rule refused, in order.
  const std::vector<std::string>& refusals() const { return refusals_; }

 private:
  std::string servedPath_;
  const std::string* served_ = nullptr;
  void refuse(const struct stat& st, const std::string& why) const;
  mutable std::vector<std::string> refusals_;
  mutable std::set<std::pair<uint64_t, uint64_t>> refused_;  // (device, inode) of each refused file
};

}  // namespace clr
