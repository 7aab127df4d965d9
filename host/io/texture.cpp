// texture.cpp — image decoding and mip chains for base-colour textures
// (texture.h). The sampling itself is kernels/texture.h.
#include "io/texture.h"

#include "base/error.h"
#include "io/file_rule.h"

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"  // inside stb_image, a known false positive of GCC 12
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

#include <algorithm>

namespace clr {

uint64_t mipChainBytes(uint32_t width, uint32_t height)
{
  uint64_t texels = 0;
  for (uint32_t w = width, h = height, l = 0;; ++l) {
    texels += uint64_t(w) * h;
    if ((w == 1 && h == 1) || l + 1 == CLR_MAX_MIP_LEVELS) break;
    w = std::max(1u, w / 2);
    h = std::max(1u, h / 2);
  }
  return 4 * texels;
}

void TextureBudget::claim(const std::string& name, uint32_t width, uint32_t height)
{
  const uint64_t bytes = mipChainBytes(width, height);
  auto mib = [](uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20); };
  if (bytes > left_)
    throw TextureOverBudget(userText(name, 160) + ": " + std::to_string(width) + "x" + std::to_string(height) +
                            " needs " + mib(bytes) + " MiB with its mip levels, over the scene's texture budget (" +
                            mib(left_) + " of " + mib(total_) + " MiB left)");
  left_ -= bytes;
}

namespace {

// stb's reason for the last failed decode, which may be empty.
std::string decodeFailure()
{
  const char* reason = stbi_failure_reason();
  return std::string("cannot decode image (") + (reason && *reason ? reason : "corrupt or unsupported data") + ")";
}

}  // namespace

Texture decodeTexture(const std::string& name, const unsigned char* data, size_t size, TextureBudget& budget)
{
  // Step 1: the header alone: size and budget before any pixel is decoded.
  if (size == 0 || size > size_t(INT32_MAX)) throw Error(userText(name) + ": empty or oversized image");
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(data, int(size), &w, &h, &channels)) throw Error(userText(name) + ": " + decodeFailure());
  if (w < 1 || h < 1 || w > CLR_MAX_VIEWPORT || h > CLR_MAX_VIEWPORT)
    throw Error(userText(name) + ": image size " + std::to_string(w) + "x" + std::to_string(h) + " outside 1..16384");
  budget.claim(name, uint32_t(w), uint32_t(h));
  // Step 2: decode to RGBA8.
  int dw = 0, dh = 0;
  unsigned char* pixels = stbi_load_from_memory(data, int(size), &dw, &dh, &channels, 4);
  if (!pixels) throw Error(userText(name) + ": " + decodeFailure());
  if (dw != w || dh != h) {
    stbi_image_free(pixels);
    throw Error(userText(name) + ": image decodes to another size than its header states");
  }
  // Step 3: pack, bottom row first.
  Texture t;
  t.name = name;
  t.width = uint32_t(w);
  t.height = uint32_t(h);
  t.rgba.resize(size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = pixels + 4 * (size_t(h - 1 - y) * w + x);
      t.rgba[size_t(y) * w + x] = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
    }
  stbi_image_free(pixels);
  return t;
}

std::vector<uint32_t> downsample(const std::vector<uint32_t>& rgba, uint32_t width, uint32_t height)
{
  const uint32_t w = std::max(1u, width / 2), h = std::max(1u, height / 2);
  std::vector<uint32_t> out(size_t(w) * h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      // The 2×2 block; an odd last row or column is used twice.
      const uint32_t x0 = std::min(2 * x, width - 1), x1 = std::min(2 * x + 1, width - 1);
      const uint32_t y0 = std::min(2 * y, height - 1), y1 = std::min(2 * y + 1, height - 1);
      const uint32_t q[4] = {rgba[size_t(y0) * width + x0], rgba[size_t(y0) * width + x1],
                             rgba[size_t(y1) * width + x0], rgba[size_t(y1) * width + x1]};
      uint32_t texel = 0;
      for (int c = 0; c < 4; ++c) {
        uint32_t sum = 2;  // round half up
        for (uint32_t v : q) sum += (v >> (8 * c)) & 0xFFu;
        texel |= (sum / 4) << (8 * c);
      }
      out[size_t(y) * w + x] = texel;
    }
  return out;
}

TexturePack packTextures(const std::vector<Texture>& textures)
{
  TexturePack pack;
  for (const Texture& t : textures) {
    TextureDesc d{};
    d.width = t.width;
    d.height = t.height;
    d.wrapS = t.wrapS;
    d.wrapT = t.wrapT;
    std::vector<uint32_t> level = t.rgba;
    uint32_t w = t.width, h = t.height;
    for (uint32_t l = 0;; ++l) {
      if (pack.texels.size() + level.size() > UINT32_MAX)
        throw Error(userText(t.name) + ": textures exceed 2^32 texels");
      d.levelOffset[l] = uint32_t(pack.texels.size());
      pack.texels.insert(pack.texels.end(), level.begin(), level.end());
      d.levels = l + 1;
      if ((w == 1 && h == 1) || l + 1 == CLR_MAX_MIP_LEVELS) break;
      level = downsample(level, w, h);
      w = std::max(1u, w / 2);
      h = std::max(1u, h / 2);
    }
    pack.descs.push_back(d);
  }
  return pack;
}

}  // namespace clr
