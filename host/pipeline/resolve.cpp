// resolve.cpp — host side of kernels/resolve.cl and resolve_lambert.cl: perspective-correct
// attribute resolve and shading of the visibility buffer into RGBA8, with
// the lean resolve_lambert kernel for the common case and resolve for the rest.
#include "pipeline/pipeline.h"

#include <algorithm>

namespace clr {

bool resolveIsLean(uint32_t shadeMode, uint32_t samples, uint32_t interpMode, bool pointLightOn, uint32_t sceneFlags)
{
  return shadeMode == CLR_SHADE_LAMBERT && samples == 1 && interpMode == CLR_INTERP_PERSPECTIVE && !pointLightOn &&
         !(sceneFlags & (CLR_SCENE_TEXTURES | CLR_SCENE_COLORS));
}

bool resolveMayPrefetch(const FrameParams& params, uint32_t numSetup, uint64_t numBinEntries)
{
  // What resolve gathers per covered run of pixels: the setup record and its
  // source word, the input triangle's vertex indices and positions (for
  // 1/w) and, where the mode reads them, its vertex normals. Below 2 MB they
  // stay cached; a larger triangle (more tiles) repeats in the rows of its
  // tiles and stays cached too, where prefetching only costs (bench/ab.sh).
  const uint64_t normalBytes = CLR_NEEDS_NORMALS(params.shadeMode) ? 12 * uint64_t(params.numVerts) : 0;
  const uint64_t gathered = uint64_t(numSetup) * (sizeof(TriSetup) + 4) + 12 * uint64_t(params.numTris) +
                            12 * uint64_t(params.numVerts) + normalBytes;
  return gathered > (2u << 20) && numBinEntries <= 2 * uint64_t(numSetup);
}

bool PrefetchChooser::next(const Case& c)
{
  if (!started_ || !(c == case_)) *this = PrefetchChooser{};
  started_ = true;
  case_ = c;
  // The first frame on (untimed), then turns on, off, off, on; then the faster.
  const int turn = frames_ - 1;
  current_ = turn < 0 ? true : turn < kTrials ? (turn == 0 || turn == kTrials - 1) : onMs_ <= offMs_;
  return current_;
}

void PrefetchChooser::report(double resolveMs)
{
  if (!started_ || frames_ > kTrials) return;
  if (frames_++ == 0) return;  // the case's first frame also pays its buffers' first touch
  double& fastest = current_ ? onMs_ : offMs_;
  fastest = std::min(fastest, resolveMs);
}

void Pipeline::resolve()
{
  image_.reserve(uint64_t(params_.width) * params_.height, true);
  // Step 0: a frame with nothing binned paints only background; when the
  // image already is that background at this size (the last resolve painted
  // only it and nothing drew since), it stays. The buffer keeps its
  // contents: it is reallocated only to grow, which changes the size.
  const BlankImage blank{params_.width, params_.height, CLR_BACKGROUND(params_.shadeMode)};
  const bool nothing = numBinEntries_ == 0;
  resolveSkipped_ = nothing && blankImage_ == blank;
  blankImage_ = nothing ? blank : BlankImage{};
  if (resolveSkipped_) {
    leanResolve_ = timedPrefetch_ = resolvePrefetch_ = false;
    return;
  }
  // The tiles' background flags (resolve.cl) hold while the image keeps its size and background and nothing else
  // drew on it.
  if (!(tileBlankImage_ == blank)) tileBlank_.zero(numTiles_);
  tileBlankImage_ = blank;
  // Step 1: the lean lambert kernel when the frame is its case (resolve_lambert.cl).
  const bool lean = settings_.leanResolve && resolveIsLean(params_.shadeMode, params_.samples, params_.interpMode,
                                                           params_.pointLightOn, params_.sceneFlags);
  leanResolve_ = lean;
  // Step 2: whether it fetches rows ahead (CPU shape, PoCL), timed per case
  // (PrefetchChooser) because the gain depends on the mesh's order in memory:
  // a mesh stored row by row is already served by the caches.
  timedPrefetch_ = cl_.prefetch && cl_.lanes > 1 && resolveMayPrefetch(params_, numSetup_, numBinEntries_);
  const PrefetchChooser::Case frameCase{sceneUploads_,     params_.width,   params_.height,
                                        params_.shadeMode, params_.samples, lean};
  resolvePrefetch_ = timedPrefetch_ && prefetchChooser_.next(frameCase);
  cl::Kernel& kernel = lean ? resolveLambertKernel_ : resolveKernel_;
  ResolveArgs args;
  args.params = paramsBuf_.get(), args.visIndex = visIndex_.get(), args.visAttr = visAttr_.get();
  args.tileOffset = tileCount_.get(), args.setup = setup_.get(), args.source = setupSource_.get();
  args.clipBary = clipBary_.get(), args.indices = indices_.get(), args.positions = positions_.get();
  args.normals = normals_.get(), args.uvs = uvs_.get(), args.colours = colors_.get();
  args.triMaterial = triMaterial_.get(), args.materials = materials_.get(), args.texDescs = texDescs_.get();
  args.texels = texels_.get(), args.image = image_.get(), args.tileSlot = tileSlot_.get();
  args.visPlane = visPlane(), args.prefetchRows = cl_uint(resolvePrefetch_), args.fileTri = fileTri_.get();
  args.tileBlank = tileBlank_.get();
  setKernelArgs(kernel, args);
  const WorkShape shape = resolveShape(cl_.lanes, params_.tilesX, params_.tilesY);
  launch(kernel, shape.global, shape.local, "resolve");
}

WorkShape resolveShape(int lanes, uint32_t tilesX, uint32_t tilesY)
{
  // With rows of lanes as wide as a tile, one work-item per tile; else one
  // per row of lanes, a tile per work-group.
  const uint32_t row = uint32_t(lanes);
  if (row == CLR_TILE_SIZE) return {cl::NDRange(tilesX, tilesY), cl::NDRange(1, 1)};
  return {cl::NDRange(tilesX * CLR_TILE_SIZE / row, tilesY * CLR_TILE_SIZE),
          cl::NDRange(CLR_TILE_SIZE / row, CLR_TILE_SIZE)};
}

}  // namespace clr
