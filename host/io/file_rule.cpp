// file_rule.cpp — the file-reading rule (see file_rule.h).
#include "io/file_rule.h"

#include "base/error.h"

#include <cerrno>
#include <algorithm>
#include <cstring>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace clr {

namespace {

OpenObserver& openObserver()
{
  static OpenObserver observer;
  return observer;
}

[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw Error(userText(path) + ": " + problem);
}

std::string describe(mode_t mode)
{
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO or pipe";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

void checkRegular(const std::string& path, const struct stat& st, const InputKind& kind)
{
  if (!S_ISREG(st.st_mode)) fail(path, "not a regular file (" + describe(st.st_mode) + ")");
  if (st.st_size <= 0) fail(path, "file is empty");
  if (uint64_t(st.st_size) > kind.maxBytes)
    throw InputOverLimit(userText(path) + ": " + kind.what + " of " + std::to_string(st.st_size) +
                         " bytes exceeds the limit of " + std::to_string(kind.maxBytes) + " bytes");
}

}  // namespace

InputFile::InputFile(const std::string& path, const InputKind& kind) : path_(path)
{
  // Step 1: what the path names, before opening it.
  struct stat before;
  if (stat(path.c_str(), &before) != 0)
    fail(path, std::string("cannot open ") + kind.what + " (" + std::strerror(errno) + ")");
  checkRegular(path, before, kind);
  // Step 2: open without blocking, and check what was opened.
  fd_ = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd_ < 0) fail(path, std::string("cannot open ") + kind.what + " (" + std::strerror(errno) + ")");
  struct stat opened;
  if (fstat(fd_, &opened) != 0) {
    const int err = errno;
    close(fd_);
    fail(path, std::string("cannot open (") + std::strerror(err) + ")");
  }
  if (opened.st_dev != before.st_dev || opened.st_ino != before.st_ino) {
    close(fd_);
    fail(path, "file changed while it was opened");
  }
  try {
    checkRegular(path, opened, kind);
  } catch (...) {
    close(fd_);
    throw;
  }
  size_ = uint64_t(opened.st_size);
  if (openObserver()) openObserver()(path, uint64_t(opened.st_dev), uint64_t(opened.st_ino));
}

InputFile::~InputFile()
{
  if (fd_ >= 0) close(fd_);
}

int InputFile::release()
{
  const int fd = fd_;
  fd_ = -1;
  return fd;
}

std::string InputFile::read(size_t limit) const
{
  const size_t want = size_t(std::min<uint64_t>(size_, limit));
  std::string bytes(want, '\0');
  size_t done = 0;
  while (done < want) {
    const ssize_t n = pread(fd_, &bytes[done], want - done, off_t(done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path_, std::string("cannot read (") + std::strerror(errno) + ")");
    if (n == 0) fail(path_, "file shrank while it was read");
    done += size_t(n);
  }
  return bytes;
}

std::string readInputFile(const std::string& path, const InputKind& kind, size_t limit)
{
  return InputFile(path, kind).read(limit);
}

void setOpenObserver(OpenObserver observer)
{
  openObserver() = std::move(observer);
}

}  // namespace clr
