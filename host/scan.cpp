// scan.cpp — host side of kernels/scan.cl: an exclusive in-place prefix sum
// over n counts (data has n + 1 slots; data[n] receives the total), or of
// the non-zero counts into another buffer (scanNonZero), or of the setup
// counts' bytes listing each record's input triangle (scanListingSources). The
// 64-bit total is read back, so callers size buffers exactly and detect
// totals that do not fit in 32 bits; or the read is enqueued, so that
// several scans share one synchronisation.
#include "pipeline.h"

namespace clr {

uint64_t Pipeline::scan(DeviceBuffer<uint32_t>& data, uint32_t n, const char* stage, cl_ulong* total)
{
  return scanInto(data.get(), data.get(), false, n, stage, total);
}

uint64_t Pipeline::scanNonZero(const DeviceBuffer<uint32_t>& counts, DeviceBuffer<uint32_t>& out, uint32_t n,
                               const char* stage, cl_ulong* total)
{
  out.reserve(uint64_t(n) + 1, true);
  return scanInto(counts.get(), out.get(), true, n, stage, total);
}

uint64_t Pipeline::scanListingSources(const DeviceBuffer<uint8_t>& counts, uint32_t n, DeviceBuffer<uint32_t>& sources,
                                      const char* stage)
{
  // (src and dst are not read: any buffer of the frame will do.)
  return scanInto(counts.get(), counts.get(), false, n, stage, nullptr, &counts.get(), &sources);
}

uint64_t Pipeline::scanInto(const cl::Buffer& src, const cl::Buffer& dst, bool countNonZero, uint32_t n,
                            const char* stage, cl_ulong* total, const cl::Buffer* byteCounts,
                            DeviceBuffer<uint32_t>* sources)
{
  // Step 1: at most 4096 chunks of at least 64 counts each.
  const uint32_t chunk = std::max<uint32_t>(64, (n + 4095) / 4096);
  const uint32_t numChunks = std::max<uint32_t>(1, (n + chunk - 1) / chunk);
  scanPartials_.reserve(numChunks + 1);

  // Step 2: chunk sums and their scan (one kernel object per phase, each
  // with its own arguments).
  cl::Event reduceEvent, partialsEvent, applyEvent;
  const uint32_t nonZero = countNonZero ? 1u : 0u, listing = sources ? 1u : 0u;
  const cl::Buffer& bytes = byteCounts ? *byteCounts : src;  // unused without sources
  setArgs(scanReduceKernel_, src, dst, n, chunk, numChunks, scanPartials_.get(), dst, bytes, CLR_SCAN_REDUCE, nonZero,
          listing);
  const cl::NDRange group(CLR_SCAN_GROUP(cl_.lanes));
  cl_.queue.enqueueNDRangeKernel(scanReduceKernel_, cl::NullRange, linear(numChunks), group, nullptr, &reduceEvent);
  setArgs(scanPartialsKernel_, src, dst, n, chunk, numChunks, scanPartials_.get(), dst, bytes, CLR_SCAN_PARTIALS,
          nonZero, listing);
  cl_.queue.enqueueNDRangeKernel(scanPartialsKernel_, cl::NullRange, group, group, nullptr, &partialsEvent);
  record(stage, reduceEvent);
  record(stage, partialsEvent);

  // Step 3: listing sources needs the total first, to size their buffer
  // (a total over 32 bits is returned unscanned: the caller fails on it).
  uint64_t sum = 0;
  if (sources) {
    sum = scanPartials_.download(1, numChunks)[0];
    if (sum > UINT32_MAX) return sum;
    sources->reserve(sum + numChunks);  // + a spare entry per chunk (scan.cl)
  }

  // Step 4: the rescan of every chunk.
  setArgs(scanApplyKernel_, src, dst, n, chunk, numChunks, scanPartials_.get(), sources ? sources->get() : dst, bytes,
          CLR_SCAN_APPLY, nonZero, listing);
  cl_.queue.enqueueNDRangeKernel(scanApplyKernel_, cl::NullRange, linear(numChunks), group, nullptr, &applyEvent);
  record(stage, applyEvent);

  // Step 5: the 64-bit total: read now, or (with `total`) enqueued to land
  // in *total, valid once the queue has finished.
  if (sources) return sum;
  if (total) {
    cl_.queue.enqueueReadBuffer(scanPartials_.get(), CL_FALSE, numChunks * sizeof(cl_ulong), sizeof(cl_ulong), total);
    return 0;
  }
  return scanPartials_.download(1, numChunks)[0];
}

}  // namespace clr
