// bin.cpp — host side of kernels/bin.cl. setup() has counted every
// triangle's tiles; this scans the counts into per-tile offsets, gives each
// non-empty tile its block of the visibility buffer, sizes binEntries from
// the exact total (one synchronisation reads both totals, setup's own when
// it enqueued the scans before it: setup.cpp), then emits the
// unclipped triangles with setup_emit, which fills their bins as it writes
// their records, and fills the clipped triangles' bins.
#include "pipeline/pipeline.h"

namespace clr {

void Pipeline::bin()
{
  // Step 1: a slot of the visibility buffer for each tile with triangles,
  // the tile offsets, and both totals in one read (setup() may have done
  // this before its own wait).
  if (!binScanned_) {
    enqueueBinScans();
    takeBinTotals(readCounters());
  }
  // (A speculative frame's: the capacities, scan.cl checking its totals.)
  numBinEntries_ = speculate_ ? specCaps_[2] : binTotal_;
  numVisSlots_ = speculate_ ? specCaps_[3] : uint32_t(slotTotal_);
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

  // Step 3: the clipped triangles' bins.
  if (numClipped_ == 0) return;
  cl::Event fillEvent;
  setArgs(binFillClippedKernel_, paramsBuf_.get(), setup_.get(), clipBary_.get(), setupSource_.get(), clipList_.get(),
          numClipped_, tileCount_.get(), tileCursor_.get(), binEntries_.get());
  cl_.queue.enqueueNDRangeKernel(binFillClippedKernel_, cl::NullRange, linear(uint64_t(numClipped_) * CLR_MAX_SUBTRIS),
                                 cl::NDRange(64), nullptr, &fillEvent);
  record("bin_fill", fillEvent);
}

void Pipeline::enqueueBinScans()
{
  scanWithNonZero(tileCount_, tileSlot_, numTiles_, "bin_scan", CLR_COUNTER_BIN_TOTAL, CLR_COUNTER_SLOT_TOTAL);
}

}  // namespace clr
