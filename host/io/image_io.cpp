// image_io.cpp — atomic PNG writing through stb_image_write (image_io.h),
// with zlib's deflate in place of stb's own and one fixed row filter.
#include "io/image_io.h"

#include "base/error.h"
#include "base/memory.h"
#include "base/temp_files.h"

#include <cstdlib>
#include <zlib.h>

namespace {

// stb_image_write's deflate hook: zlib at its default level, which encodes renders faster and smaller than stb's
// own deflate (level 1 is faster still but its files much larger). Returns a malloc'ed buffer, as stb frees it.
unsigned char* zlibCompress(unsigned char* data, int length, int* outLength, int /*stbQuality*/)
{
  uLongf size = compressBound(uLong(length));
  auto* out = static_cast<unsigned char*>(std::malloc(size));
  if (!out) return nullptr;
  if (compress2(out, &size, data, uLong(length), Z_DEFAULT_COMPRESSION) != Z_OK) {
    std::free(out);
    return nullptr;
  }
  *outLength = int(size);
  return out;
}

}  // namespace

#define STBIW_ZLIB_COMPRESS zlibCompress
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

namespace {

// The Sub filter for every row, where stb tries all five per row: with zlib it gives the smallest files of the
// fixed filters on renders, and the search costs more than the deflate. Set at static initialisation, before any
// writer thread runs.
const bool kPngFilterChosen = (stbi_write_force_png_filter = 1, true);

}  // namespace

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace clr {

namespace {

std::string failure(const std::string& path, int err)
{
  return userText(path) + ": cannot write (" + std::strerror(err) + ")";
}

// The process's umask, read once before any thread starts (umask(2) both
// reads and sets it).
const mode_t kUmask = [] {
  const mode_t m = umask(0);
  umask(m);
  return m;
}();

}  // namespace

void checkTarget(const std::string& path)
{
  if (path.empty()) throw Error("output path is empty");
  struct stat st;
  if (stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) throw Error(failure(path, EISDIR));
}

void checkWritable(const std::string& path)
{
  checkTarget(path);
  const LiveTemp temp(path);
  close(temp.fd());
  unlink(temp.name().c_str());
}

namespace {

// bytes in a new temporary file beside path, flushed, with mode less the
// umask; returns it.
LiveTemp stageFile(const std::string& path, const std::vector<unsigned char>& bytes, mode_t mode)
{
  LiveTemp temp(path);
  const int fd = temp.fd();
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = errno;
      close(fd);
      unlink(temp.name().c_str());
      throw Error(failure(path, err));
    }
    done += size_t(n);
  }
  if (fchmod(fd, mode & ~kUmask) != 0 || fsync(fd) != 0 || close(fd) != 0) {
    const int err = errno;
    unlink(temp.name().c_str());
    throw Error(failure(path, err));
  }
  return temp;
}

}  // namespace

void writeFilesAtomic(const std::vector<OutputFile>& files, unsigned mode)
{
  // Step 1: every file staged; a failure removes those staged before it.
  std::vector<LiveTemp> temps;
  try {
    for (const OutputFile& f : files) {
      checkTarget(f.path);
      temps.push_back(stageFile(f.path, f.bytes, mode_t(mode)));
    }
  } catch (...) {
    for (const LiveTemp& t : temps) unlink(t.name().c_str());
    throw;
  }
  // Step 2: the renames, each within its target's folder; each temporary
  // file stays listed until it is renamed or removed.
  for (size_t k = 0; k < files.size(); ++k)
    if (rename(temps[k].name().c_str(), files[k].path.c_str()) != 0) {
      const int err = errno;
      for (size_t j = k; j < temps.size(); ++j) unlink(temps[j].name().c_str());
      throw Error(failure(files[k].path, err));
    }
}

void writeFileAtomic(const std::string& path, std::vector<unsigned char> bytes, unsigned mode)
{
  std::vector<OutputFile> files(1);
  files[0] = {path, std::move(bytes)};
  writeFilesAtomic(files, mode);
}

std::vector<unsigned char> encodePng(const std::string& path, uint32_t width, uint32_t height, const uint32_t* rgba)
{
  // At most 15 bytes a pixel: the RGB copy, stb's filtered rows, zlib's bound, stb's output and the copy here.
  checkHostMemory(userText(path) + ": a PNG of " + std::to_string(width) + "x" + std::to_string(height),
                  uint64_t(15) * width * height);
  std::vector<unsigned char> rgb(size_t(width) * height * 3);
  for (size_t i = 0; i < size_t(width) * height; ++i)
    for (int c = 0; c < 3; ++c) rgb[3 * i + c] = (rgba[i] >> (8 * c)) & 0xFF;
  std::vector<unsigned char> png;
  auto append = [](void* ctx, void* data, int size) {
    auto* out = static_cast<std::vector<unsigned char>*>(ctx);
    out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &png, int(width), int(height), 3, rgb.data(), int(width) * 3))
    throw Error(userText(path) + ": PNG encoding failed");
  return png;
}

void writePng(const std::string& path, uint32_t width, uint32_t height, const uint32_t* rgba)
{
  writeFileAtomic(path, encodePng(path, width, height, rgba));
}

}  // namespace clr
