// file_rule.h — the one rule for every file clraster reads: a model, a file
// a model names (an OBJ's material library, a glTF buffer, a texture), a
// views file.
//
// The path must name a regular file (symbolic links are followed), no larger
// than its kind's limit, and it is checked before anything could block: a
// stat() first, then an open() with O_NONBLOCK (opening a FIFO that a race put
// in its place returns at once) and an fstat() of what was opened, which must
// be the regular file stat() saw. Reads take at most the size fstat() gave,
// so no read is unbounded, whatever the file turns into meanwhile. Every
// failure is a clr::Error "PATH: problem" on one line, the path quoted by
// userText(). docs/limits.md, "Hostile files", lists the limits.
#pragma once

#include "base/error.h"

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace clr {

struct InputKind {
  const char* what;   // "model", "texture", ... for messages
  uint64_t maxBytes;  // the size limit
};

inline constexpr InputKind kModelInput{"model file", uint64_t(1) << 30};                  // and the files it names
inline constexpr InputKind kTextureInput{"texture file", uint64_t(256) << 20};            // an image, compressed
inline constexpr InputKind kViewsInput{"views file", uint64_t(16) << 20};                 // JSON, ~100 bytes a view
inline constexpr InputKind kProgramCacheInput{"kernel cache file", uint64_t(256) << 20};  // program_cache.h

// A file over its kind's size limit (the one failure that names a limit).
struct InputOverLimit : Error {
  using Error::Error;
};

// An open input file; closes it when destroyed.
class InputFile {
 public:
  // Opens `path` under the rule; an empty file is an error too.
  InputFile(const std::string& path, const InputKind& kind);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  uint64_t size() const { return size_; }
  int descriptor() const { return fd_; }
  // Hands the descriptor over (to a FILE*, say); the caller closes it.
  int release();
  // Reads at most `limit` bytes from the start (all of them by default).
  std::string read(size_t limit = SIZE_MAX) const;

 private:
  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

// The whole file, or its first `limit` bytes, under the rule.
std::string readInputFile(const std::string& path, const InputKind& kind, size_t limit = SIZE_MAX);

// Called with the path, device and inode of every file the rule opens; for
// tests that count opens or change a file between opens. Empty: none.
using OpenObserver = std::function<void(const std::string& path, uint64_t device, uint64_t inode)>;
void setOpenObserver(OpenObserver observer);

}  // namespace clr
