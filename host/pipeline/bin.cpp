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
  BinFillClippedArgs args;
  args.params = paramsBuf_.get(), args.setup = setup_.get(), args.clipBary = clipBary_.get();
  args.source = setupSource_.get(), args.clipList = clipList_.get(), args.numClipped = numClipped_;
  args.tileOffset = tileCount_.get(), args.tileCursor = tileCursor_.get(), args.binEntries = binEntries_.get();
  setKernelArgs(binFillClippedKernel_, args);
  launchLinear(binFillClippedKernel_, uint64_t(numClipped_) * CLR_MAX_SUBTRIS, "bin_fill");
}

void Pipeline::enqueueBinScans()
{
  scanWithNonZero(tileCount_, tileSlot_, numTiles_, "bin_scan", CLR_COUNTER_BIN_TOTAL, CLR_COUNTER_SLOT_TOTAL);
}

}  // namespace clr
