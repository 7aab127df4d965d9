// bin.cpp — host side of kernels/bin.cl. setup() has counted every
// triangle's tiles; enqueueBinScans scans the counts into per-tile offsets
// and gives each non-empty tile its block of the visibility buffer (one
// read takes both totals: setupEmit, setup.cpp); binClipped fills the
// clipped triangles' bins once setupEmit has filled the unclipped ones'.
#include "pipeline/pipeline.h"

namespace clr {

void Pipeline::binClipped()
{
  if (numClipped_ == 0) return;
  setArgs(binFillClippedKernel_, paramsBuf_.get(), setup_.get(), clipBary_.get(), setupSource_.get(), clipList_.get(),
          numClipped_, tileCount_.get(), tileCursor_.get(), binEntries_.get());
  launchLinear(binFillClippedKernel_, uint64_t(numClipped_) * CLR_MAX_SUBTRIS, "bin_fill");
}

void Pipeline::enqueueBinScans()
{
  scanWithNonZero(tileCount_, tileSlot_, numTiles_, "bin_scan", CLR_COUNTER_BIN_TOTAL, CLR_COUNTER_SLOT_TOTAL);
}

}  // namespace clr
