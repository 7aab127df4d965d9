// image_io.h — PNG output that never leaves a half-written file: the image
// is encoded in memory, written to a temporary file beside the target,
// flushed, and renamed over it. Failure is a clr::Error naming the path.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace clr {

// rgba: width·height pixels, RGBA8 with R in the low byte, top row first.
// Written as 8-bit RGB.
void writePng(const std::string& path, uint32_t width, uint32_t height, const uint32_t* rgba);
inline void writePng(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint32_t>& rgba)
{
  writePng(path, width, height, rgba.data());
}

// The PNG's bytes (as writePng writes them).
std::vector<unsigned char> encodePng(const std::string& path, uint32_t width, uint32_t height, const uint32_t* rgba);

// Writes bytes to a temporary file beside path, flushes it and renames it
// over path (the pattern every output file follows). The file gets `mode`
// less the process's umask, as open(2) would give a new file; while it is a
// temporary file, SIGINT, SIGTERM and SIGHUP remove it (base/temp_files.h).
void writeFileAtomic(const std::string& path, std::vector<unsigned char> bytes, unsigned mode = 0666);

// One render's outputs together: every file is written and flushed to its
// temporary file first, then all are renamed into place, so a failure
// while writing leaves none of them.
struct OutputFile {
  std::string path;
  std::vector<unsigned char> bytes;
};
void writeFilesAtomic(const std::vector<OutputFile>& files, unsigned mode = 0666);

// Throws unless path is not a directory (checkTarget) and a file can be
// created in its directory (checked before rendering so a bad -o fails
// fast).
void checkTarget(const std::string& path);
void checkWritable(const std::string& path);

}  // namespace clr
