// test_scan.cpp — the scan kernels (scan.cl): exclusive sums, non-zero
// counts and the list of setup sources, phase by phase, against host sums.
#include "test_support.h"

#include <catch2/catch.hpp>

#include <random>
#include <vector>

TEST_CASE("scan_chunks gives exclusive sums and non-zero counts and lists setup sources", "[scan]")
{
  // scan.cl's three phases launched as the pipeline launches them (scan.cpp),
  // in the device's work shape, against sums computed here: plain scans of
  // uint counts (with values near 2^26, so sums pass 2^32 and the 64-bit
  // total and the uint entries' wrap are checked), the same with the
  // non-zero counts, the setup counts' listing (bytes 0, 1 or
  // CLR_MAX_SUBTRIS), and in the CPU shape the listing over clusters' sums,
  // where a third of the clusters are skipped (sum 0) and their bytes are
  // garbage it must not read. Sizes around a step (64 values) and a chunk,
  // and one past 4096 chunks of 64, where scanChunks makes a chunk span
  // several steps. The last case reaches the same paths with chunks set
  // here: 199 full chunks of 130 values (two steps and part of a third) and
  // a partial one, more chunks than the partials phase's group, so its
  // work-items scan runs of several sums, some none; under Oclgrind it
  // stands in for the large one.
  const clr::ClContext& ctx = test::context();
  std::mt19937 rng(23);
  struct Case {
    uint32_t n, chunk;  // chunk 0: scanChunks's
  };
  for (const Case& cs : {Case{1, 0}, Case{63, 0}, Case{64, 0}, Case{65, 0}, Case{1000, 0}, Case{4096 * 64 + 4321, 0},
                         Case{130 * 199 + 57, 130}}) {
    const uint32_t n = cs.n;
    if (n > 4096u * 64u && test::underOclgrind()) continue;
    INFO("n = " << n << ", chunk " << cs.chunk);
    const uint32_t clusters = (n + CLR_CLUSTER_TRIS - 1) / CLR_CLUSTER_TRIS;
    for (int mode = 0; mode < 4; ++mode) {  // plain, with non-zero counts, listing bytes, listing clusters
      INFO("mode " << mode);
      const bool alsoNonZero = mode == 1, listing = mode >= 2, byCluster = mode == 3;
      if (byCluster && ctx.lanes == 1) continue;  // (the GPU shape counts no clusters: Pipeline::listsClusters)
      const uint32_t items = byCluster ? clusters : n;
      const clr::ScanChunks c = cs.chunk && !byCluster ? clr::ScanChunks{cs.chunk, (items + cs.chunk - 1) / cs.chunk}
                                                       : clr::scanChunks(items);
      // Step 1: counts, mostly zero or small, some large.
      std::vector<uint32_t> values(size_t(n) + 1, 0u);
      std::vector<uint8_t> bytes(n);
      std::uniform_int_distribution<int> kind(0, 9);
      for (uint32_t i = 0; i < n; ++i) {
        const int k = kind(rng);
        values[i] = k < 4 ? 0u : k < 8 ? uint32_t(k) : (1u << 26) + uint32_t(k);
        bytes[i] = uint8_t(k < 3 ? 0 : k < 8 ? 1 : CLR_MAX_SUBTRIS);
      }
      if (byCluster) {  // every third cluster skipped: sum 0, garbage bytes
        values.assign(size_t(clusters) + 1, 0u);
        for (uint32_t i = 0; i < n; ++i) {
          const uint32_t cluster = i / CLR_CLUSTER_TRIS;
          if (cluster % 3 == 1)
            bytes[i] = 0xAB;
          else
            values[cluster] += bytes[i];
        }
      }
      const auto skipped = [&](uint32_t i) { return byCluster && (i / CLR_CLUSTER_TRIS) % 3 == 1; };
      // Step 2: the three phases.
      uint64_t listed = 0;
      for (uint32_t i = 0; i < n; ++i) listed += skipped(i) ? 0 : bytes[i];
      const size_t secondSize = listing ? size_t(listed) + c.count : size_t(n) + 1;
      cl::Buffer data(ctx.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, values.size() * 4, values.data());
      cl::Buffer counts(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes.size(), bytes.data());
      cl::Buffer partials(ctx.context, CL_MEM_READ_WRITE, 2 * (size_t(c.count) + 1) * 8);
      cl::Buffer second(ctx.context, CL_MEM_READ_WRITE, secondSize * 4);
      const std::vector<uint32_t> zeros(CLR_NUM_COUNTERS, 0u);
      cl::Buffer counters(ctx.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, zeros.size() * 4,
                          const_cast<uint32_t*>(zeros.data()));
      const cl::NDRange group(CLR_SCAN_GROUP(ctx.lanes));
      for (uint32_t phase : {CLR_SCAN_REDUCE, CLR_SCAN_PARTIALS, CLR_SCAN_APPLY}) {
        cl::Kernel kernel(ctx.program, "scan_chunks");
        clr::ScanChunksArgs args;
        args.src = data, args.dst = data, args.n = items, args.chunk = c.size, args.numChunks = c.count;
        args.partials = partials, args.second = second, args.byteCounts = counts, args.counters = counters;
        args.totalAt = CLR_COUNTER_SETUP_TOTAL, args.nonZeroTotalAt = CLR_COUNTER_SLOT_TOTAL, args.phase = phase;
        args.alsoNonZero = alsoNonZero, args.listEnd = n;
        args.listSources = byCluster ? CLR_SCAN_LIST_CLUSTERS : listing ? CLR_SCAN_LIST_BYTES : CLR_SCAN_LIST_NONE;
        clr::setKernelArgs(kernel, args);
        const cl::NDRange items = phase == CLR_SCAN_PARTIALS ? group : clr::scanChunkItems(ctx.lanes, c.count);
        ctx.queue.enqueueNDRangeKernel(kernel, cl::NullRange, items, group);
      }
      std::vector<uint32_t> scanned(values.size()), seconds(secondSize), totals(CLR_NUM_COUNTERS);
      ctx.queue.enqueueReadBuffer(data, CL_TRUE, 0, scanned.size() * 4, scanned.data());
      ctx.queue.enqueueReadBuffer(second, CL_TRUE, 0, seconds.size() * 4, seconds.data());
      ctx.queue.enqueueReadBuffer(counters, CL_TRUE, 0, totals.size() * 4, totals.data());
      // Step 3: the sums here, compared.
      const auto total64 = [&](int at) { return uint64_t(totals[at]) | uint64_t(totals[at + 1]) << 32; };
      uint64_t sum = 0, nonZero = 0;
      size_t wrongSums = 0, wrongNonZero = 0, wrongSources = 0;
      for (uint32_t i = 0; i < n; ++i) {
        if (listing) {
          if (skipped(i)) continue;
          for (uint32_t k = 0; k < bytes[i]; ++k)
            wrongSources += seconds[sum + k] != (bytes[i] == 1 ? i : CLR_SOURCE_CLIPPED | i);
          sum += bytes[i];
          continue;
        }
        wrongSums += scanned[i] != uint32_t(sum);
        wrongNonZero += alsoNonZero && seconds[i] != uint32_t(nonZero);
        sum += values[i];
        nonZero += values[i] != 0;
      }
      CHECK(wrongSums == 0);
      CHECK(wrongNonZero == 0);
      CHECK(wrongSources == 0);
      CHECK(total64(CLR_COUNTER_SETUP_TOTAL) == sum);
      if (!listing) CHECK(scanned[n] == uint32_t(sum));
      if (alsoNonZero) CHECK(seconds[n] == uint32_t(nonZero));
      if (alsoNonZero) CHECK(total64(CLR_COUNTER_SLOT_TOTAL) == nonZero);
      if (n > 20000 && !listing) CHECK(sum > (uint64_t(1) << 32));  // the totals need 64 bits
    }
  }
}
