// model_io.cpp — assimp's file access under the file rule (see model_io.h).
#include "io/model_io.h"

#include "base/error.h"
#include "io/file_rule.h"

#include <assimp/MemoryIOWrapper.h>

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

bool RuleIOSystem::Exists(const char* file) const
{
  if (!file) return false;
  if (served_ && servedPath_ == file) return true;
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

Assimp::IOStream* RuleIOSystem::Open(const char* file, const char* mode)
{
  if (!file || !mode || std::strchr(mode, 'w') || std::strchr(mode, 'a') || std::strchr(mode, '+')) return nullptr;
  if (served_ && servedPath_ == file)
    return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(served_->data()), served_->size());
  struct stat st;
  if (stat(file, &st) != 0) return nullptr;  // missing: the importer reports or skips it
  try {
    return new OwnedStream(readModelReference(servedPath_, file, kModelInput));
  } catch (const Error& e) {
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
