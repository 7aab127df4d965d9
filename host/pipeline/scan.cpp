// scan.cpp — host side of kernels/scan.cl: an exclusive in-place prefix sum
// over n counts (data has n + 1 slots; data[n] receives the total), also of
// the non-zero counts into another buffer in the same launches
// (scanWithNonZero), or of the setup counts listing each record's input
// triangle (scanListingBegin, then scanListingFinish once the total is
// known, with partial sums of its own so that other scans may run between
// the two): the bytes, or in the CPU shape the clusters' sums, so that a
// cluster the count pass skipped costs one value. The 64-bit total is read
// back, so callers size buffers exactly and detect totals that do not fit
// in 32 bits; or it is copied among the frame's counters, so that several
// scans and setup's counters come back with one read (each read of its own
// leaves the device idle).
#include "pipeline/pipeline.h"

namespace clr {

ScanChunks scanChunks(uint32_t n)
{
  const uint32_t size =
      std::max<uint32_t>(CLR_SCAN_MIN_CHUNK, uint32_t((uint64_t(n) + CLR_SCAN_MAX_CHUNKS - 1) / CLR_SCAN_MAX_CHUNKS));
  return {size, std::max<uint32_t>(1, (n + size - 1) / size)};
}

cl::NDRange scanChunkItems(int lanes, uint32_t chunks)
{
  return cl::NDRange(size_t(chunks) * CLR_SCAN_GROUP(lanes));
}

void Pipeline::scanSums(const ScanJob& job, uint32_t n, DeviceBuffer<cl_ulong>& partials, const char* stage)
{
  // One kernel object per phase, each with its own arguments.
  const ScanChunks c = scanChunks(n);
  partials.reserve((job.alsoNonZero ? 2 : 1) * (uint64_t(c.count) + 1));
  const cl::NDRange group(CLR_SCAN_GROUP(cl_.lanes));
  setKernelArgs(scanReduceKernel_, scanArgs(job, n, partials, CLR_SCAN_REDUCE));
  launch(scanReduceKernel_, scanChunkItems(cl_.lanes, c.count), group, stage);
  setKernelArgs(scanPartialsKernel_, scanArgs(job, n, partials, CLR_SCAN_PARTIALS));
  launch(scanPartialsKernel_, group, group, stage);
}

void Pipeline::scanApply(const ScanJob& job, uint32_t n, const DeviceBuffer<cl_ulong>& partials, const char* stage)
{
  setKernelArgs(scanApplyKernel_, scanArgs(job, n, partials, CLR_SCAN_APPLY));
  launch(scanApplyKernel_, scanChunkItems(cl_.lanes, scanChunks(n).count), cl::NDRange(CLR_SCAN_GROUP(cl_.lanes)),
         stage);
}

ScanChunksArgs Pipeline::scanArgs(const ScanJob& job, uint32_t n, const DeviceBuffer<cl_ulong>& partials,
                                  uint32_t phase) const
{
  const ScanChunks c = scanChunks(n);
  ScanChunksArgs args;
  args.src = job.src, args.dst = job.dst, args.n = n, args.chunk = c.size, args.numChunks = c.count;
  args.partials = partials.get(), args.second = job.second, args.byteCounts = job.bytes;
  args.counters = counters_.get(), args.totalAt = job.totalAt, args.nonZeroTotalAt = job.nonZeroTotalAt;
  args.phase = phase, args.alsoNonZero = job.alsoNonZero, args.listSources = job.listing, args.listEnd = job.listEnd;
  return args;
}

uint64_t Pipeline::scan(DeviceBuffer<uint32_t>& data, uint32_t n, const char* stage, uint32_t totalAt)
{
  // (second and bytes are not read: data will do.)
  const ScanJob job{data.get(), data.get(), data.get(), data.get(), 0u, 0u, totalAt, CLR_SCAN_NO_TOTAL};
  scanSums(job, n, scanPartials_, stage);
  scanApply(job, n, scanPartials_, stage);
  // The 64-bit total: among the counters (with totalAt), or read now.
  return totalAt != CLR_SCAN_NO_TOTAL ? 0 : scanPartials_.download(1, scanChunks(n).count)[0];
}

void Pipeline::scanWithNonZero(DeviceBuffer<uint32_t>& data, DeviceBuffer<uint32_t>& nonZero, uint32_t n,
                               const char* stage, uint32_t totalAt, uint32_t nonZeroTotalAt)
{
  nonZero.reserve(uint64_t(n) + 1, true);
  const ScanJob job{data.get(), data.get(), nonZero.get(), data.get(), 1u, 0u, totalAt, nonZeroTotalAt};
  scanSums(job, n, scanPartials_, stage);
  scanApply(job, n, scanPartials_, stage);
}

void Pipeline::scanListingBegin(const char* stage)
{
  // (dst is not written: any buffer of the frame will do.)
  const ScanJob job = listingJob();
  scanSums(job, listingItems(), listingPartials_, stage);
}

void Pipeline::scanListingFinish(uint64_t total, const char* stage)
{
  if (total == 0) return;                                          // no record to list (nothing in view)
  setupSource_.reserve(total + scanChunks(listingItems()).count);  // + a spare entry per chunk (scan.cl)
  ScanJob job = listingJob();
  job.totalAt = CLR_SCAN_NO_TOTAL;  // (Begin copied it)
  scanApply(job, listingItems(), listingPartials_, stage);
}

Pipeline::ScanJob Pipeline::listingJob() const
{
  // The values scanned: the clusters' sums, or the bytes themselves (the listing reads the bytes either way).
  const bool clusters = listsClusters();
  const cl::Buffer& values = clusters ? clusterCount_.get() : triCount_.get();
  return {values,
          values,
          setupSource_.get(),
          triCount_.get(),
          0u,
          clusters ? CLR_SCAN_LIST_CLUSTERS : CLR_SCAN_LIST_BYTES,
          CLR_COUNTER_SETUP_TOTAL,
          CLR_SCAN_NO_TOTAL,
          clusters ? params_.numTris : 0u};
}

}  // namespace clr
