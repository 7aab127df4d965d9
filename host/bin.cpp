// bin.cpp — host side of kernels/bin.cl: count tile overlaps, scan them into
// per-tile offsets, size binEntries from the exact total, give each
// non-empty tile its block of the visibility buffer, then fill.
#include "pipeline.h"

namespace clr {

void Pipeline::bin()
{
  // Step 1: count the triangles touching each tile.
  std::vector<cl::Event> fills;
  tileCount_.zero(numTiles_ + 1, &fills);
  cl::Event countEvent;
  setArgs(binCountKernel_, paramsBuf_.get(), setup_.get(), numSetup_, tileCount_.get());
  cl_.queue.enqueueNDRangeKernel(binCountKernel_, cl::NullRange, linear(numSetup_), cl::NDRange(64), nullptr,
                                 &countEvent);
  record("bin_count", countEvent);

  // Step 2: offsets; the bins take exactly the memory the counts ask for.
  numBinEntries_ = scan(tileCount_, numTiles_, "bin_scan");
  if (numBinEntries_ > UINT32_MAX)
    throw Error("the frame needs " + std::to_string(numBinEntries_) +
                " bin entries, more than the 2^32 a 32-bit offset can address");
  binEntries_.reserve(numBinEntries_);

  // Step 2b: a block of the visibility buffer for each tile with triangles.
  tileSlot_.reserve(numTiles_ + 1, true);
  cl::Event slotsEvent;
  setArgs(binSlotsKernel_, tileCount_.get(), numTiles_, tileSlot_.get());
  cl_.queue.enqueueNDRangeKernel(binSlotsKernel_, cl::NullRange, linear(numTiles_), cl::NDRange(64), nullptr,
                                 &slotsEvent);
  record("bin_slots", slotsEvent);
  numVisSlots_ = uint32_t(scan(tileSlot_, numTiles_, "bin_slots"));

  // Step 3: fill.
  tileCursor_.zero(numTiles_, &fills);
  cl::Event fillEvent;
  setArgs(binFillKernel_, paramsBuf_.get(), setup_.get(), numSetup_, tileCount_.get(), tileCursor_.get(),
          binEntries_.get());
  cl_.queue.enqueueNDRangeKernel(binFillKernel_, cl::NullRange, linear(numSetup_), cl::NDRange(64), nullptr,
                                 &fillEvent);
  record("bin_fill", fillEvent);
}

}  // namespace clr
