// model_io.cpp — assimp's file access under the file rule (see model_io.h).
#include "io/model_io.h"

#include "base/error.h"
#include "io/file_rule.h"
#include "io/import_budget.h"
#include "io/mtl.h"

#include <assimp/MemoryIOWrapper.h>

#include <algorithm>
#include <cstring>
#include <utility>

#include <sys/stat.h>

namespace clr {

namespace {

// A file the model names, read whole; the stream owns its bytes.
struct OwnedBytes {
  std::string bytes;
};
struct OwnedStream : private OwnedBytes, public Assimp::MemoryIOStream {
  explicit OwnedStream(std::string read)
      : OwnedBytes{std::move(read)},
        Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size())
  {
  }
};

}  // namespace

RuleIOSystem::RuleIOSystem(const std::string& modelPath, const std::string& assets)
    : modelPath_(modelPath), modelFolder_(modelPath.substr(0, modelPath.rfind('/') + 1)), root_(modelPath, assets)
{
}

bool RuleIOSystem::Exists(const char* file) const
{
  if (!file) return false;
  if (served_ && servedPath_ == file) return true;
  if (!isModel(file) && root_.confined()) {
    // Under the model-folder rule, only a file it would open exists.
    try {
      root_.open(file, file, kModelInput);
      return true;
    } catch (const Error&) {
      return false;
    }
  }
  struct stat st;
  if (stat(file, &st) != 0) return false;  // a missing file: the importer decides
  if (S_ISREG(st.st_mode)) return true;
  try {
    InputFile(file, kModelInput);  // refuses it by its type, before opening
  } catch (const Error& e) {
    refuse(st, e.what());
  }
  return false;
}

void RuleIOSystem::refuse(const struct stat& st, const std::string& why) const
{
  // Importers try one file under several names; each file is named once.
  if (refused_.insert({uint64_t(st.st_dev), uint64_t(st.st_ino)}).second) refusals_.push_back(why);
}

std::string RuleIOSystem::reference(const std::string& file) const
{
  // The reference as the model wrote it: the path without the folder the reader put before it.
  return file.compare(0, modelFolder_.size(), modelFolder_) == 0 ? file.substr(modelFolder_.size()) : file;
}

void RuleIOSystem::refuseReference(const std::string& file, const std::string& why)
{
  // The OBJ reader tries "MODEL.mtl" after a library it could not open: not a reference of the file's own.
  const std::string fallback = modelPath_.substr(0, modelPath_.size() - std::min<size_t>(3, modelPath_.size())) + "mtl";
  if (lastOpenFailed_ && file == fallback) return;
  lastOpenFailed_ = true;
  if (refusedReferences_.insert(reference(file)).second) refusals_.push_back(why);
}

Assimp::IOStream* RuleIOSystem::Open(const char* file, const char* mode)
{
  if (!file || !mode || std::strchr(mode, 'w') || std::strchr(mode, 'a') || std::strchr(mode, '+')) return nullptr;
  if (served_ && servedPath_ == file)
    return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(served_->data()), served_->size());
  const bool ruled = !isModel(file) && root_.confined();  // under the model-folder rule
  struct stat st;
  if (!ruled && stat(file, &st) != 0) return nullptr;  // missing: the importer reports or skips it
  try {
    std::unique_ptr<InputFile> input =
        ruled ? root_.open(file, reference(file), kModelInput) : std::make_unique<InputFile>(file, kModelInput);
    if (!isModel(file)) {
      // The import budget: every file named counts each time it is read.
      referencedBytes_ += input->size();
      if (referencedBytes_ > kReferencedBytes) {
        overBudget_ = userText(modelPath_, 120) + ": the files it names take more than " +
                      std::to_string(kReferencedBytes >> 20) +
                      " MiB together, the limit for one import (docs/limits.md)";
        return nullptr;
      }
      if (countMaterials_) {
        kept_.push_back(input->read());
        materials_ += countMaterials(kept_.back());
        if (materials_ > kMaxMaterials) {
          overBudget_ = userText(modelPath_, 120) + ": more than " + std::to_string(kMaxMaterials) +
                        " materials in its material libraries, the limit for one OBJ (docs/limits.md)";
          return nullptr;
        }
        // A statement assimp's MTL reader would apply to no material (a crash there): the library is refused.
        if (!mtlReadableByAssimp(kept_.back())) {
          kept_.pop_back();
          refuseReference(file, userText(reference(file), 120) +
                                    ": a map, bump, refl, norm, disp or anisotropy statement before any newmtl");
          return nullptr;
        }
        lastOpenFailed_ = false;
        return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(kept_.back().data()), kept_.back().size());
      }
    }
    lastOpenFailed_ = false;
    return new OwnedStream(input->read());
  } catch (const Error& e) {
    if (ruled)
      refuseReference(file, e.what());
    else
      refuse(st, e.what());
    return nullptr;
  }
}

void RuleIOSystem::serve(const std::string& path, const std::string* bytes)
{
  servedPath_ = path;
  served_ = bytes;
}

}  // namespace clr
