// setup.cpp — host side of kernels/setup.cl (and clip.h): count the screen
// triangles each input triangle yields (and, for binning, the tiles each
// unclipped one touches), scan the counts into the list of the input
// triangle behind each setup record, size the setup and ClipBary buffers
// from the totals, and clip the listed triangles into their reserved
// records, which they find in that list (counting their tiles too). The
// unclipped triangles are emitted by setupEmit() once the tile offsets are
// known (bin.cpp scans them), because setup_emit also fills their bins.
#include "pipeline/pipeline.h"

namespace clr {

void Pipeline::setup()
{
  const uint32_t numTris = params_.numTris;
  // The count pass's work-items: one per cluster where the listing scans clusters (setup_triangles), else
  // CLR_LANES triangles each.
  const uint32_t countItems = listsClusters() ? listingItems() : (numTris + cl_.lanes - 1) / cl_.lanes;
  // Step 1: count, and sum the counts, reading the clip-list length and the
  // total with one wait (one read of the counters, where the scans copy
  // their totals); if the clip list was too short, grow it and redo.
  // When the previous frame clipped nothing, setupEmit()'s tile scans go before the
  // wait too, so that a frame without clipping waits once; a frame that does clip counts
  // again without them, since setup_clip adds to the tile counts they scan.
  uint32_t clipped = 0;
  cl_ulong total = 0;
  bool scanTiles = speculate_ || !clippedLastFrame_;
  // The micro slots: a speculative frame's are the last frame's count (its
  // tiles past them bin their triangles, micro.h); a waiting frame's are
  // sized from its count, read below.
  if (speculate_)
    reserveMicroKeys(microTiles_);
  else
    microCap_ = microMax_ > 0 ? UINT32_MAX : 0;
  for (;;) {
    std::vector<cl::Event> fills;
    tileCount_.zero(numTiles_ + 1, &fills);
    tileMicro_.zero(numTiles_, &fills);  // the micro path's flags (micro.h)
    // (The emit pass's outputs are bound too; this pass does not touch them.)
    setup_.reserve(1);
    tileCursor_.reserve(1);
    binEntries_.reserve(1);
    setupSource_.reserve(1);
    setKernelArgs(setupCountKernel_, setupTrianglesArgs(0, CLR_SETUP_PASS_COUNT));
    launch(setupCountKernel_, linear(countItems), cl::NDRange(CLR_SETUP_GROUP(cl_.lanes)), "setup_count");
    scanListingBegin("setup_scan");
    if (scanTiles) enqueueBinScans();
    // A speculative frame (Pipeline::runFrame) does not wait: its sizes are
    // the capacities beginFrame chose, and scan.cl empties its tiles when the
    // totals exceed them.
    if (speculate_) {
      binScanned_ = true;
      numSetup_ = specCaps_.records;
      numClipped_ = 0;
      scanListingFinish(numSetup_, "setup_scan");
      return;
    }
    const std::vector<uint32_t> counters = readCounters();
    clipped = counters[CLR_COUNTER_CLIPPED_TRIS];
    microTiles_ = counters[CLR_COUNTER_MICRO_TILES];
    total = counterTotal(counters, CLR_COUNTER_SETUP_TOTAL);
    if (scanTiles) takeBinTotals(counters);
    const bool growList = clipped > clipList_.capacity(), recount = scanTiles && clipped > 0;
    if (!growList && !recount) break;
    if (growList) clipList_.reserve(clipped);
    scanTiles = false;
    counters_.zero(CLR_NUM_COUNTERS);
  }
  binScanned_ = scanTiles;
  clippedLastFrame_ = clipped > 0;

  // Step 2: the sizes of this frame's outputs, and the listing of the input
  // triangle behind each record, for the emit pass.
  if (total > UINT32_MAX) throw Error("more than 2^32 screen triangles after clipping");
  scanListingFinish(total, "setup_scan");
  numSetup_ = uint32_t(total);
  numClipped_ = clipped;
  if (uint64_t(clipped) * CLR_MAX_SUBTRIS > CLR_MAX_CLIP_SLOTS)
    throw Error("more than " + std::to_string(CLR_MAX_CLIP_SLOTS / CLR_MAX_SUBTRIS) +
                " clipped triangles in one frame (the source word's limit, shared.h)");
  // The count pass writes 1 for each unclipped survivor and CLR_MAX_SUBTRIS
  // for each clipped triangle, so the rest of the input was culled there
  // (setup_clip counts the clipped triangles that produce nothing).
  numCulledUnclipped_ = uint32_t(numTris - (total - uint64_t(clipped) * CLR_MAX_SUBTRIS) - clipped);
  setup_.reserve(numSetup_);
  clipBary_.reserve(uint64_t(clipped) * CLR_MAX_SUBTRIS);

  // Step 3: clip the listed triangles into their reserved slots.
  if (clipped == 0) return;
  SetupClipArgs args;
  args.params = paramsBuf_.get(), args.positions = positions_.get(), args.indices = indices_.get();
  args.source = setupSource_.get(), args.numSetup = numSetup_, args.clipList = clipList_.get();
  args.setup = setup_.get(), args.clipBary = clipBary_.get(), args.counters = counters_.get();
  args.tileCount = tileCount_.get();
  setKernelArgs(setupClipKernel_, args);
  launchLinear(setupClipKernel_, clipped, "setup_clip");
}

void Pipeline::setupEmit()
{
  // Step 1: a slot of the visibility buffer for each tile with triangles,
  // the tile offsets, and both totals in one read (setup() may have done
  // this before its own wait).
  if (!binScanned_) {
    enqueueBinScans();
    takeBinTotals(readCounters());
  }
  // (A speculative frame's: the capacities, scan.cl checking its totals.)
  numBinEntries_ = speculate_ ? specCaps_.bins : binTotal_;
  numVisSlots_ = speculate_ ? specCaps_.slots : uint32_t(slotTotal_);
  usedVisSlots_ = numVisSlots_;
  if (numBinEntries_ > UINT32_MAX)
    throw Error("the frame needs " + std::to_string(numBinEntries_) +
                " bin entries, more than the 2^32 a 32-bit offset can address");
  binEntries_.reserve(numBinEntries_);
  if (numSetup_ == 0) return;  // nothing in view: no record to emit, no bin to fill

  // Step 2: emit the unclipped triangles into the setup buffer and their bins.
  std::vector<cl::Event> fills;
  tileCursor_.zero(numTiles_, &fills);
  const uint32_t batches = (numSetup_ + cl_.lanes - 1) / cl_.lanes;  // over the records, not the input
  if (!speculate_) reserveMicroKeys(microTiles_);
  setKernelArgs(setupEmitKernel_, setupTrianglesArgs(numSetup_, CLR_SETUP_PASS_EMIT));
  launch(setupEmitKernel_, linear(batches), cl::NDRange(CLR_SETUP_GROUP(cl_.lanes)), "setup_emit");
  binClipped();
}

SetupTrianglesArgs Pipeline::setupTrianglesArgs(uint32_t numSetup, uint32_t pass) const
{
  SetupTrianglesArgs args;
  args.params = paramsBuf_.get(), args.positions = positions_.get(), args.indices = indices_.get();
  args.triCount = triCount_.get(), args.counters = counters_.get(), args.clipList = clipList_.get();
  args.clipListCapacity = uint32_t(clipList_.capacity()), args.tileCount = tileCount_.get();
  args.setup = setup_.get(), args.tileCursor = tileCursor_.get(), args.binEntries = binEntries_.get();
  args.source = setupSource_.get(), args.numSetup = numSetup, args.pass = pass;
  args.clusterBounds = clusterBounds_.get(), args.clusterCount = clusterCount_.get();
  args.microMax = microMax_, args.microCap = microCap_, args.tileMicro = tileMicro_.get();
  args.microKey = microKey_.get(), args.microRecord = microRecord_.get(), args.paintRank = fileTri_.get();
  return args;
}

}  // namespace clr
