// scan.cpp — host side of kernels/scan.cl: an exclusive in-place prefix sum
// over n counts (data has n + 1 slots; data[n] receives the total), or of
// the non-zero counts into another buffer (scanNonZero), or of the setup
// counts' bytes listing each record's input triangle (scanListingBegin, then
// scanListingFinish once the total is known, with partial sums of its own so
// that other scans may run between the two). The 64-bit total is read back,
// so callers size buffers exactly and detect totals that do not fit in 32
// bits; or it is copied among the frame's counters, so that several scans
// and setup's counters come back with one read (a read of its own cost the
// device 30-50 us of idle time each on an NVIDIA H100).
#include "pipeline.h"

namespace clr {

uint64_t Pipeline::scan(DeviceBuffer<uint32_t>& data, uint32_t n, const char* stage, uint32_t totalAt)
{
  return scanInto(data.get(), data.get(), false, n, stage, totalAt);
}

uint64_t Pipeline::scanNonZero(const DeviceBuffer<uint32_t>& counts, DeviceBuffer<uint32_t>& out, uint32_t n,
                               const char* stage, uint32_t totalAt)
{
  out.reserve(uint64_t(n) + 1, true);
  return scanInto(counts.get(), out.get(), true, n, stage, totalAt);
}

namespace {

// At most 4096 chunks of at least 64 counts each.
struct ScanChunks {
  uint32_t size, count;
};

ScanChunks scanChunks(uint32_t n)
{
  const uint32_t size = std::max<uint32_t>(64, (n + 4095) / 4096);
  return {size, std::max<uint32_t>(1, (n + size - 1) / size)};
}

}  // namespace

void Pipeline::scanSums(const ScanJob& job, uint32_t n, DeviceBuffer<cl_ulong>& partials, const char* stage,
                        uint32_t totalAt)
{
  // One kernel object per phase, each with its own arguments.
  const ScanChunks c = scanChunks(n);
  partials.reserve(c.count + 1);
  const cl::NDRange group(CLR_SCAN_GROUP(cl_.lanes));
  cl::Event reduceEvent, partialsEvent;
  setArgs(scanReduceKernel_, job.src, job.dst, n, c.size, c.count, partials.get(), job.dst, job.bytes, counters_.get(),
          totalAt, CLR_SCAN_REDUCE, job.nonZero, job.listing);
  cl_.queue.enqueueNDRangeKernel(scanReduceKernel_, cl::NullRange, linear(c.count), group, nullptr, &reduceEvent);
  setArgs(scanPartialsKernel_, job.src, job.dst, n, c.size, c.count, partials.get(), job.dst, job.bytes,
          counters_.get(), totalAt, CLR_SCAN_PARTIALS, job.nonZero, job.listing);
  cl_.queue.enqueueNDRangeKernel(scanPartialsKernel_, cl::NullRange, group, group, nullptr, &partialsEvent);
  record(stage, reduceEvent);
  record(stage, partialsEvent);
}

void Pipeline::scanApply(const ScanJob& job, uint32_t n, const DeviceBuffer<cl_ulong>& partials, const cl::Buffer& out,
                         const char* stage)
{
  const ScanChunks c = scanChunks(n);
  cl::Event applyEvent;
  setArgs(scanApplyKernel_, job.src, job.dst, n, c.size, c.count, partials.get(), out, job.bytes, counters_.get(),
          CLR_SCAN_NO_TOTAL, CLR_SCAN_APPLY, job.nonZero, job.listing);
  cl_.queue.enqueueNDRangeKernel(scanApplyKernel_, cl::NullRange, linear(c.count),
                                 cl::NDRange(CLR_SCAN_GROUP(cl_.lanes)), nullptr, &applyEvent);
  record(stage, applyEvent);
}

void Pipeline::scanListingBegin(const DeviceBuffer<uint8_t>& counts, uint32_t n, const char* stage, uint32_t totalAt)
{
  // (src and dst are not read: any buffer of the frame will do.)
  const ScanJob job{counts.get(), counts.get(), counts.get(), 0u, 1u};
  scanSums(job, n, listingPartials_, stage, totalAt);
}

void Pipeline::scanListingFinish(const DeviceBuffer<uint8_t>& counts, uint32_t n, uint64_t total,
                                 DeviceBuffer<uint32_t>& sources, const char* stage)
{
  sources.reserve(total + scanChunks(n).count);  // + a spare entry per chunk (scan.cl)
  const ScanJob job{counts.get(), counts.get(), counts.get(), 0u, 1u};
  scanApply(job, n, listingPartials_, sources.get(), stage);
}

uint64_t Pipeline::scanInto(const cl::Buffer& src, const cl::Buffer& dst, bool countNonZero, uint32_t n,
                            const char* stage, uint32_t totalAt)
{
  // (bytes is read only by a listing: src will do.)
  const ScanJob job{src, dst, src, countNonZero ? 1u : 0u, 0u};
  scanSums(job, n, scanPartials_, stage, totalAt);
  scanApply(job, n, scanPartials_, dst, stage);
  // The 64-bit total: among the counters (with totalAt), or read now.
  return totalAt != CLR_SCAN_NO_TOTAL ? 0 : scanPartials_.download(1, scanChunks(n).count)[0];
}

}  // namespace clr
