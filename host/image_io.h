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

// Writes bytes to a temporary file beside path, flushes it and renames it
// over path (the pattern every output file follows).
void writeFileAtomic(const std::string& path, const std::vector<unsigned char>& bytes);

// Throws unless a file can be created in path's directory (checked before
// rendering so a bad -o fails fast).
void checkWritable(const std::string& path);

}  // namespace clr
