// setup.cpp — host side of kernels/setup.cl (and clip.cl): count the screen
// triangles each input triangle yields, scan the counts into offsets, size
// the setup and ClipBary buffers from the totals, then emit.
#include "pipeline.h"

namespace clr {

void Pipeline::setup()
{
  const uint32_t numTris = params_.numTris;
  // Step 1: count.
  cl::Event countEvent;
  setupCountKernel_.setArg(0, paramsBuf_.get());
  setupCountKernel_.setArg(1, clipPos_.get());
  setupCountKernel_.setArg(2, indices_.get());
  setupCountKernel_.setArg(3, triCount_.get());
  setupCountKernel_.setArg(4, counters_.get());
  cl_.queue.enqueueNDRangeKernel(setupCountKernel_, cl::NullRange, linear(numTris), cl::NDRange(64), nullptr,
                                 &countEvent);
  record("setup_count", countEvent);

  // Step 2: offsets, and the exact sizes of this frame's outputs.
  const uint64_t total = scan(triCount_, numTris, "setup_scan");
  if (total > UINT32_MAX) throw Error("more than 2^32 screen triangles after clipping");
  numSetup_ = uint32_t(total);
  numClipSlots_ = counters_.download(1, CLR_COUNTER_CLIP_SLOTS)[0];
  setup_.reserve(numSetup_);
  clipBary_.reserve(numClipSlots_);

  // Step 3: emit.
  cl::Event emitEvent;
  setupEmitKernel_.setArg(0, paramsBuf_.get());
  setupEmitKernel_.setArg(1, clipPos_.get());
  setupEmitKernel_.setArg(2, indices_.get());
  setupEmitKernel_.setArg(3, triCount_.get());
  setupEmitKernel_.setArg(4, setup_.get());
  setupEmitKernel_.setArg(5, clipBary_.get());
  setupEmitKernel_.setArg(6, counters_.get());
  cl_.queue.enqueueNDRangeKernel(setupEmitKernel_, cl::NullRange, linear(numTris), cl::NDRange(64), nullptr,
                                 &emitEvent);
  record("setup_emit", emitEvent);
}

}  // namespace clr
