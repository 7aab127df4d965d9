// aov.h — the visibility-buffer outputs as a float32 OpenEXR file.
//
// Pipeline::aov() (aov.cpp, kernels/aov.cl) computes CLR_AOV_CHANNELS planes
// on the device; writeAovExr() writes them as one float32 channel each,
// ZIP-compressed (lossless), top row first as EXR expects, through a
// temporary file renamed into place (image_io.h). Channel names and their
// conventions are listed in aovChannelNames() and the README.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace clr {

// The EXR channel name of each CLR_AOV_* plane, in plane order.
const std::vector<std::string>& aovChannelNames();

// planes: CLR_AOV_CHANNELS planes of width·height floats, bottom row first
// (Pipeline::readAov()). Throws clr::Error naming the path on failure.
std::vector<unsigned char> encodeAovExr(const std::string& path, uint32_t width, uint32_t height,
                                        const std::vector<float>& planes);
void writeAovExr(const std::string& path, uint32_t width, uint32_t height, const std::vector<float>& planes);

}  // namespace clr
