// texture.h — base-colour textures on the host: decoding, mip chains and the
// one packed upload the resolve kernel samples (kernels/texture.h).
//
// Images are decoded with stb_image (Debian's libstb-dev) to RGBA8 and
// flipped so that row 0 is the bottom (v = 0, assimp's convention). Texel
// values are used as they are stored (no sRGB conversion anywhere in the
// pipeline). packTextures() builds every texture's mip chain with a 2×2 box
// filter (odd sides repeat their last row or column) down to 1×1 and puts
// all levels of all textures into one texel array with one TextureDesc each
// (shared.h). A file that cannot be opened or decoded is a clr::Error
// naming the file; the textures of a scene share one memory budget.
#pragma once

#include "kernels/shared.h"
#include "base/error.h"

#include <cstdint>
#include <string>
#include <vector>

namespace clr {

struct Texture {
  std::string name;  // file path or "model.glb: embedded texture *N", for messages
  uint32_t width = 0, height = 0;
  uint32_t wrapS = CLR_WRAP_REPEAT, wrapT = CLR_WRAP_REPEAT;
  std::vector<uint32_t> rgba;  // width·height, R in the low byte, bottom row first
};

// The host memory all textures of one scene may take, their mip chains
// counted (4 bytes a texel): a texture that would take the total past it is
// not decoded (docs/limits.md, "Hostile files").
inline constexpr uint64_t kTextureBudgetBytes = uint64_t(512) << 20;

// Bytes of a w×h texture's mip chain down to 1×1, as packTextures lays it out.
uint64_t mipChainBytes(uint32_t width, uint32_t height);

// What the textures of a scene have taken of the budget so far.
class TextureBudget {
 public:
  explicit TextureBudget(uint64_t bytes = kTextureBudgetBytes) : left_(bytes), total_(bytes) {}
  // Takes a w×h texture's chain, or throws TextureOverBudget naming it.
  void claim(const std::string& name, uint32_t width, uint32_t height);

 private:
  uint64_t left_, total_;
};

// A texture the budget cannot hold: the scene renders without it.
struct TextureOverBudget : Error {
  using Error::Error;
};

// Decodes an image held in memory (PNG, JPEG, BMP, TGA, ... as stb_image
// reads them; a model's texture files are read under the model-folder rule,
// asset_root.h); `name` is what errors call it. Its size and channels come
// from the header first (stbi_info): a size outside 1..16384 is an error, one
// the budget cannot hold a TextureOverBudget, both before any pixel is decoded.
Texture decodeTexture(const std::string& name, const unsigned char* data, size_t size, TextureBudget& budget);

struct TexturePack {
  std::vector<TextureDesc> descs;
  std::vector<uint32_t> texels;  // every level of every texture
};
TexturePack packTextures(const std::vector<Texture>& textures);

// Mip level `level` of a texture from the level above (exposed for tests).
std::vector<uint32_t> downsample(const std::vector<uint32_t>& rgba, uint32_t width, uint32_t height);

}  // namespace clr
