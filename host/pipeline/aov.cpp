// aov.cpp — host side of kernels/aov.cl: one work-item per pixel turns
// sample 0 of the visibility buffer into float planes (triangle id,
// barycentrics, depths, normal), and the planes are written as a float32
// EXR with tinyexr (Debian's libtinyexr-dev).
#include "pipeline/aov.h"

#include "io/image_io.h"
#include "pipeline/pipeline.h"

#include <tinyexr.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <numeric>

namespace clr {

void Pipeline::aov()
{
  if (!params_.visAttributes)
    throw Error("aov: the frame has no depth and barycentric planes (set FrameSettings.keepVisAttributes)");
  // The normal planes read the vertex normals whatever the shading mode uploaded.
  if (!(resident_ & kResidentNormals)) {
    normals_.upload(scene_.normals);
    resident_ |= kResidentNormals;
  }
  aov_.reserve(uint64_t(CLR_AOV_CHANNELS) * params_.width * params_.height, true);
  cl::Kernel& kernel = extraKernel(aovKernel_, "aov");
  AovArgs args;
  args.params = paramsBuf_.get(), args.visIndex = visIndex_.get(), args.visAttr = visAttr_.get();
  args.tileOffset = tileCount_.get(), args.source = setupSource_.get(), args.clipBary = clipBary_.get();
  args.indices = indices_.get(), args.positions = positions_.get(), args.normals = normals_.get();
  args.out = aov_.get(), args.tileSlot = tileSlot_.get(), args.visPlane = visPlane(), args.fileTri = fileTri_.get();
  setKernelArgs(kernel, args);
  launchPixels(kernel, "aov");
}

std::vector<float> Pipeline::readAov() const
{
  return aov_.download(uint64_t(CLR_AOV_CHANNELS) * params_.width * params_.height);
}

const std::vector<std::string>& aovChannelNames()
{
  static const std::vector<std::string> names = {"triangle_id",   "bary.u",  "bary.v",    "bary_screen.u",
                                                 "bary_screen.v", "z_w",     "eye_depth", "normal.X",
                                                 "normal.Y",      "normal.Z"};
  return names;
}

std::vector<unsigned char> encodeAovExr(const std::string& path, uint32_t width, uint32_t height,
                                        const std::vector<float>& planes)
{
  // Step 1: rows top first; channels sorted by name, as EXR readers expect.
  const size_t n = size_t(width) * height;
  const std::vector<std::string>& names = aovChannelNames();
  static_assert(CLR_AOV_CHANNELS == 10, "aovChannelNames() lists every plane");
  if (planes.size() != names.size() * n) throw Error(userText(path) + ": AOV planes do not match the image size");
  std::vector<size_t> order(names.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return names[a] < names[b]; });
  std::vector<std::vector<float>> flipped(names.size(), std::vector<float>(n));
  std::vector<unsigned char*> images(names.size());
  std::vector<EXRChannelInfo> channels(names.size());
  std::vector<int> pixelTypes(names.size(), TINYEXR_PIXELTYPE_FLOAT);
  for (size_t k = 0; k < order.size(); ++k) {
    const size_t c = order[k];
    for (uint32_t y = 0; y < height; ++y)
      std::copy_n(&planes[c * n + size_t(y) * width], width, &flipped[k][size_t(height - 1 - y) * width]);
    images[k] = reinterpret_cast<unsigned char*>(flipped[k].data());
    std::memset(&channels[k], 0, sizeof channels[k]);
    std::strncpy(channels[k].name, names[c].c_str(), sizeof channels[k].name - 1);
  }
  // Step 2: encode in memory (float32, ZIP: lossless).
  EXRHeader header;
  InitEXRHeader(&header);
  EXRImage image;
  InitEXRImage(&image);
  image.num_channels = int(names.size());
  image.images = images.data();
  image.width = int(width);
  image.height = int(height);
  header.num_channels = int(names.size());
  header.channels = channels.data();
  header.pixel_types = pixelTypes.data();
  header.requested_pixel_types = pixelTypes.data();
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const size_t size = SaveEXRImageToMemory(&image, &header, &memory, &err);
  if (size == 0) {
    const std::string why = err ? err : "unknown error";
    if (err) FreeEXRErrorMessage(err);
    throw Error(userText(path) + ": EXR encoding failed (" + why + ")");
  }
  std::vector<unsigned char> bytes(memory, memory + size);
  std::free(memory);
  return bytes;
}

void writeAovExr(const std::string& path, uint32_t width, uint32_t height, const std::vector<float>& planes)
{
  writeFileAtomic(path, encodeAovExr(path, width, height, planes));
}

}  // namespace clr
