// setup.cpp — host side of kernels/setup.cl (and clip.cl): count the screen
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
  for (;;) {
    std::vector<cl::Event> fills;
    tileCount_.zero(numTiles_ + 1, &fills);
    cl::Event countEvent;
    // (The emit pass's outputs are bound too; this pass does not touch them.)
    setup_.reserve(1);
    tileCursor_.reserve(1);
    binEntries_.reserve(1);
    setupSource_.reserve(1);
    setArgs(setupCountKernel_, paramsBuf_.get(), positions_.get(), indices_.get(), triCount_.get(), counters_.get(),
            clipList_.get(), uint32_t(clipList_.capacity()), tileCount_.get(), setup_.get(), tileCursor_.get(),
            binEntries_.get(), setupSource_.get(), 0u, uint32_t(CLR_SETUP_PASS_COUNT), clusterBounds_.get(),
            clusterCount_.get());
    cl_.queue.enqueueNDRangeKernel(setupCountKernel_, cl::NullRange, linear(countItems),
                                   cl::NDRange(CLR_SETUP_GROUP(cl_.lanes)), nullptr, &countEvent);
    record("setup_count", countEvent);
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
  setArgs(setupClipKernel_, paramsBuf_.get(), positions_.get(), indices_.get(), setupSource_.get(), numSetup_,
          clipList_.get(), setup_.get(), clipBary_.get(), counters_.get(), tileCount_.get());
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
  cl::Event emitEvent;
  setArgs(setupEmitKernel_, paramsBuf_.get(), positions_.get(), indices_.get(), triCount_.get(), counters_.get(),
          clipList_.get(), uint32_t(clipList_.capacity()), tileCount_.get(), setup_.get(), tileCursor_.get(),
          binEntries_.get(), setupSource_.get(), numSetup_, uint32_t(CLR_SETUP_PASS_EMIT), clusterBounds_.get(),
          clusterCount_.get());
  cl_.queue.enqueueNDRangeKernel(setupEmitKernel_, cl::NullRange, linear(batches),
                                 cl::NDRange(CLR_SETUP_GROUP(cl_.lanes)), nullptr, &emitEvent);
  record("setup_emit", emitEvent);
  binClipped();
}

}  // namespace clr
