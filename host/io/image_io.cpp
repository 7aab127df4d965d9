// image_io.cpp — atomic PNG writing through stb_image_write (image_io.h),
// with zlib's deflate in place of stb's own (a large image's on two
// threads) and one fixed row filter.
#include "io/image_io.h"

#include "base/error.h"
#include "base/memory.h"
#include "base/temp_files.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <zlib.h>

namespace {

// Filtered image data from this size up is deflated on two threads (deflateHalves).
constexpr size_t kParallelDeflateBytes = size_t(1) << 20;

// One zlib stream of `data` in two halves, deflated at once: the first
// with the zlib header, ending on a sync flush (whole bytes, no final
// block); the second raw, primed with the first's last 32 KiB as its
// dictionary, ending the stream; then the Adler-32 of the whole (the
// halves' combined). Any inflater reads it as one stream (pigz does the
// same). Both halves deflate into one malloc'ed buffer, as large as
// compress2's; null on failure.
unsigned char* deflateHalves(const unsigned char* data, size_t length, int* outLength)
{
  const size_t half = length / 2, window = std::min<size_t>(half, 32768);
  z_stream first{}, second{};
  const bool started = deflateInit2(&first, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15, 8, Z_DEFAULT_STRATEGY) == Z_OK;
  const bool secondStarted =
      deflateInit2(&second, Z_DEFAULT_COMPRESSION, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) == Z_OK;
  const size_t firstBound = started ? deflateBound(&first, uLong(half)) + 16 : 0;
  const size_t secondBound = secondStarted ? deflateBound(&second, uLong(length - half)) + 16 : 0;
  auto* out =
      started && secondStarted ? static_cast<unsigned char*>(std::malloc(firstBound + secondBound + 4)) : nullptr;
  bool ok = out && deflateSetDictionary(&second, data + half - window, uInt(window)) == Z_OK;
  if (ok) {
    first.next_in = const_cast<unsigned char*>(data);
    first.avail_in = uInt(half);
    first.next_out = out;
    first.avail_out = uInt(firstBound);
    second.next_in = const_cast<unsigned char*>(data + half);
    second.avail_in = uInt(length - half);
    second.next_out = out + firstBound;
    second.avail_out = uInt(secondBound);
    int secondStatus = Z_STREAM_ERROR;
    std::thread other([&] { secondStatus = deflate(&second, Z_FINISH); });
    const int firstStatus = deflate(&first, Z_SYNC_FLUSH);
    other.join();
    ok = firstStatus == Z_OK && first.avail_in == 0 && first.avail_out > 0 && secondStatus == Z_STREAM_END;
  }
  if (ok) {
    const size_t firstUsed = firstBound - first.avail_out, secondUsed = secondBound - second.avail_out;
    std::memmove(out + firstUsed, out + firstBound, secondUsed);
    const uLong check =
        adler32_combine(adler32(adler32(0, nullptr, 0), data, uInt(half)),
                        adler32(adler32(0, nullptr, 0), data + half, uInt(length - half)), z_off_t(length - half));
    unsigned char* end = out + firstUsed + secondUsed;
    for (int shift = 24; shift >= 0; shift -= 8) *end++ = static_cast<unsigned char>(check >> shift);
    *outLength = int(end - out);
  }
  if (started) deflateEnd(&first);
  if (secondStarted) deflateEnd(&second);
  if (!ok) std::free(out);
  return ok ? out : nullptr;
}

// stb_image_write's deflate hook: zlib at its default level, which encodes renders faster and smaller than stb's
// own deflate (level 1 is faster still but its files much larger); large images on two threads
// (deflateHalves). Returns a malloc'ed buffer, as stb frees it.
unsigned char* zlibCompress(unsigned char* data, int length, int* outLength, int /*stbQuality*/)
{
  if (size_t(length) >= kParallelDeflateBytes) return deflateHalves(data, size_t(length), outLength);
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
