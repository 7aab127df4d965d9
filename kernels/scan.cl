/* scan.cl — exclusive prefix sum of a uint array (setup counts per triangle, bin counts per tile).
 *
 * src and dst have n + 1 elements (may alias): dst[i] = sum of the first i values, dst[n] the total. alsoNonZero
 * also scans the non-zero count into `second` (the tile slots), its chunk sums after the values' in `partials`.
 * Sums are 64-bit; totals land in partials[numChunks] and, unless CLR_SCAN_NO_TOTAL, counters[totalAt..+1] (low,
 * high), so the host fails loudly on a total over 32 bits and reads all totals at once. One kernel, scan_chunks,
 * runs three phases (CLR_SCAN_REDUCE, _PARTIALS, _APPLY): one compile. With listSources the apply phase over the
 * byte counts (0, 1 or CLR_MAX_SUBTRIS) lists each setup record's input triangle (setupSource) instead of offsets;
 * CLR_SCAN_LIST_CLUSTERS scans the clusters' totals instead, and reads the bytes of non-empty clusters only.
 */
#if !CLR_EXTRAS /* the frame program (CLR_EXTRAS, shared.h) */

/* The total's copy among the frame's counters (two uints, low word first). */
CLR_INLINE void scan_store_total(__global uint* counters, uint totalAt, ulong total)
{
  if (totalAt == CLR_SCAN_NO_TOTAL) return;
  counters[totalAt] = (uint)total;
  counters[totalAt + 1] = (uint)(total >> 32);
}

/* Whether a frame sized from the last one's totals (counters[CLR_COUNTER_SPECULATIVE], Pipeline::beginFrame) fits
 * what the host gave it: nothing clipped (setup_clip did not run), and the setup records (the listing's total, copied
 * before the tile scan), bin entries and tile slots within the capacities among the counters. */
CLR_INLINE bool scan_frame_fits(__global const uint* counters, ulong bins, ulong slots)
{
  const ulong records = counters[CLR_COUNTER_SETUP_TOTAL] | (ulong)counters[CLR_COUNTER_SETUP_TOTAL + 1] << 32;
  return counters[CLR_COUNTER_CLIPPED_TRIS] == 0 && records <= counters[CLR_COUNTER_CAP_RECORDS] &&
         bins <= counters[CLR_COUNTER_CAP_BINS] && slots <= counters[CLR_COUNTER_CAP_SLOTS];
}

/* CLR_SCAN_PARTIALS: exclusive scan of partials[0 .. numChunks), total into partials[numChunks]. GPU: one
 * work-group with barriers. CPU: one work-item scans the <= CLR_SCAN_MAX_CHUNKS sums, no barrier (barriers slow PoCL's
 * compile). */
#if CLR_LANES == 1
CLR_INLINE void scan_partials(__global ulong* partials, uint numChunks, __local ulong* groupSums,
                              __global uint* counters, uint totalAt)
{
  const uint lid = get_local_id(0);
  const uint per = (numChunks + CLR_SCAN_GROUP(1) - 1) / CLR_SCAN_GROUP(1);
  const uint begin = min(lid * per, numChunks);
  const uint end = min(begin + per, numChunks);
  // Step 1: each work-item sums its run of chunk sums.
  ulong sum = 0;
  for (uint i = begin; i < end; ++i) sum += partials[i];
  groupSums[lid] = sum;
  barrier(CLK_LOCAL_MEM_FENCE);
  // Step 2: one work-item scans the 64 run sums.
  if (lid == 0) {
    ulong running = 0;
    for (uint i = 0; i < CLR_SCAN_GROUP(1); ++i) {
      const ulong v = groupSums[i];
      groupSums[i] = running;
      running += v;
    }
    partials[numChunks] = running;
    scan_store_total(counters, totalAt, running);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  // Step 3: each work-item rescans its run, exclusive.
  ulong running = groupSums[lid];
  for (uint i = begin; i < end; ++i) {
    const ulong v = partials[i];
    partials[i] = running;
    running += v;
  }
}
#else
CLR_INLINE void scan_partials(__global ulong* partials, uint numChunks, __global uint* counters, uint totalAt)
{
  if (get_global_id(0) != 0) return;
  ulong running = 0;
  for (uint i = 0; i < numChunks; ++i) {
    const ulong v = partials[i];
    partials[i] = running;
    running += v;
  }
  partials[numChunks] = running;
  scan_store_total(counters, totalAt, running);
}
#endif

#if CLR_LANES == 1
/* GPU shape of reduce and apply: one work-group per chunk, its work-items reading consecutive values (coalesced),
 * each step scanned in local memory (Hillis–Steele); a chunk per work-item leaves too few loads to hide latency.
 * Values enter as (v << 8) | (v != 0): one scan gives the sum (64 uints < 2^38) and the non-zero count (<= 64).
 * Both phases walk the chunk with the same loop and barriers: PoCL mis-compiles barriers under a branch. */
CLR_INLINE ulong scan_group_inclusive(ulong packed, __local ulong* steps)
{
  const uint lid = get_local_id(0);
  barrier(CLK_LOCAL_MEM_FENCE);  // the previous step's readers are done
  steps[lid] = packed;
  for (uint offset = 1; offset < CLR_SCAN_GROUP(1); offset <<= 1) {
    barrier(CLK_LOCAL_MEM_FENCE);
    const ulong before = lid >= offset ? steps[lid - offset] : 0;
    barrier(CLK_LOCAL_MEM_FENCE);
    steps[lid] += before;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  return steps[lid];
}

CLR_INLINE uint scan_value(__global const uint* src, __global const uchar* byteCounts, uint listSources, uint i,
                           uint end)
{
  if (i >= end) return 0;
  return listSources ? byteCounts[i] : src[i];
}

CLR_INLINE void scan_chunk_group(__global const uint* src, __global uint* dst, uint n, uint chunk, uint numChunks,
                                 __global ulong* partials, __global ulong* nonZeroPartials, __global uint* second,
                                 __global const uchar* byteCounts, uint phase, uint alsoNonZero, uint listSources,
                                 uint keep, bool write, __local ulong* steps)
{
  const uint g = get_group_id(0), lid = get_local_id(0);
  const uint begin = g * chunk, end = min(begin + chunk, n);
  const bool apply = phase == CLR_SCAN_APPLY;
  // A step of CLR_SCAN_GROUP(1) values at a time: reduce sums the steps, apply also writes each offset.
  ulong running = apply ? partials[g] : 0, runningNonZero = apply && alsoNonZero ? nonZeroPartials[g] : 0;
  for (uint first = begin; first < end; first += CLR_SCAN_GROUP(1)) {
    const uint i = first + lid, v = scan_value(src, byteCounts, listSources, i, end);
    const ulong packed = ((ulong)v << 8) | (ulong)(v != 0);
    const ulong inclusive = scan_group_inclusive(packed, steps), exclusive = inclusive - packed;
    const ulong stepTotal = steps[CLR_SCAN_GROUP(1) - 1];
    if (apply && i < end && write) {
      if (listSources) {
        // A culled triangle stores nothing: a shared spare entry would take many work-items' stores at once.
        const ulong record = running + (exclusive >> 8);
        if (v == 1) second[record] = i;
        for (uint k = 0; v == CLR_MAX_SUBTRIS && k < CLR_MAX_SUBTRIS; ++k) second[record + k] = CLR_SOURCE_CLIPPED | i;
      } else {
        dst[i] = (uint)(running + (exclusive >> 8)) & keep;
        if (alsoNonZero) second[i] = (uint)(runningNonZero + (exclusive & 0xFF)) & keep;
      }
    }
    running += stepTotal >> 8;
    runningNonZero += stepTotal & 0xFF;
  }
  if (lid != 0) return;
  if (!apply) {
    partials[g] = running;
    if (alsoNonZero) nonZeroPartials[g] = runningNonZero;
  } else if (g == numChunks - 1 && !listSources) {
    dst[n] = (uint)partials[numChunks] & keep;
    if (alsoNonZero) second[n] = (uint)nonZeroPartials[numChunks] & keep;
  }
}
#else
/* CLR_SCAN_APPLY listing input triangles [begin, end) from record `running`: a survivor (1) owns its record; a
 * clipped one's CLR_MAX_SUBTRIS records get CLR_SOURCE_CLIPPED | its index (sorted, for clip_first_record's binary
 * search); a culled one (0) stores to the chunk's spare entry instead of branching (culls are unpredictable). */
CLR_INLINE void scan_list_sources(__global const uchar* counts, uint begin, uint end, ulong running, ulong spare,
                                  __global uint* sources)
{
  for (uint i = begin; i < end; ++i) {
    const uint v = counts[i];
    sources[v == 1 ? running : spare] = i;
    for (uint k = 0; v == CLR_MAX_SUBTRIS && k < CLR_MAX_SUBTRIS; ++k) sources[running + k] = CLR_SOURCE_CLIPPED | i;
    running += v;
  }
}

/* CPU shape of reduce and apply: work-item g walks chunk g alone. With CLR_SCAN_LIST_CLUSTERS the values are the
 * clusters' totals and apply lists the bytes of triangles [c · CLR_CLUSTER_TRIS, listEnd) of non-empty clusters c. */
CLR_INLINE void scan_chunk_item(__global const uint* src, __global uint* dst, uint n, uint chunk, uint numChunks,
                                __global ulong* partials, __global ulong* nonZeroPartials, __global uint* second,
                                __global const uchar* byteCounts, uint phase, uint alsoNonZero, uint listSources,
                                uint listEnd, uint keep, bool write)
{
  const uint g = get_global_id(0);
  if (g >= numChunks) return;
  const uint begin = g * chunk;
  const uint end = min(begin + chunk, n);
  if (phase == CLR_SCAN_REDUCE) {
    ulong sum = 0, nonZero = 0;
    if (listSources == CLR_SCAN_LIST_BYTES) {
      for (uint i = begin; i < end; ++i) sum += byteCounts[i];
    } else {
      for (uint i = begin; i < end; ++i) {
        const uint v = src[i];
        sum += v;
        nonZero += v != 0;
      }
    }
    partials[g] = sum;
    if (alsoNonZero) nonZeroPartials[g] = nonZero;
    return;
  }
  ulong running = partials[g];
  if (listSources == CLR_SCAN_LIST_CLUSTERS) {
    for (uint c = begin; write && c < end; ++c) {
      const uint v = src[c];
      if (v == 0) continue;  // a cluster beside the view: its bytes were not written (setup.cl)
      const uint first = c * CLR_CLUSTER_TRIS;
      scan_list_sources(byteCounts, first, min(first + CLR_CLUSTER_TRIS, listEnd), running, partials[numChunks] + g,
                        second);
      running += v;
    }
    return;
  }
  if (listSources) {
    if (write) scan_list_sources(byteCounts, begin, end, running, partials[numChunks] + g, second);
    return;
  }
  if (!alsoNonZero) {
    for (uint i = begin; i < end; ++i) {
      const uint v = src[i];
      dst[i] = (uint)running;
      running += v;
    }
  } else {
    ulong runningNonZero = nonZeroPartials[g];
    for (uint i = begin; i < end; ++i) {
      const uint v = src[i];
      dst[i] = (uint)running & keep;
      second[i] = (uint)runningNonZero & keep;
      running += v;
      runningNonZero += v != 0;
    }
  }
  if (g == numChunks - 1) {
    dst[n] = (uint)partials[numChunks] & keep;
    if (alsoNonZero) second[n] = (uint)nonZeroPartials[numChunks] & keep;
  }
}
#endif

__kernel __attribute__((reqd_work_group_size(CLR_SCAN_GROUP(CLR_LANES), 1, 1))) void scan_chunks(
    __global const uint* src, __global uint* dst, uint n, uint chunk, uint numChunks,
    __global ulong* partials,          // numChunks + 1, twice with alsoNonZero (the values', then the non-zero counts')
    __global uint* second,             // listSources: the sources (setup records); alsoNonZero: n + 1; else unused
    __global const uchar* byteCounts,  // listSources: n, read instead of src; else unused
    __global uint* counters,           // CLR_NUM_COUNTERS: the partials phase copies the totals there
    uint totalAt, uint nonZeroTotalAt, uint phase, uint alsoNonZero,
    uint listSources,  // CLR_SCAN_LIST_*; CLR_SCAN_LIST_CLUSTERS in the CPU shape only
    uint listEnd)      // CLR_SCAN_LIST_CLUSTERS: the input triangles (the last cluster's end)
{
#if CLR_LANES == 1
  __local ulong groupSums[CLR_SCAN_GROUP(1)];
#endif
  __global ulong* nonZeroPartials = partials + numChunks + 1;
  // A speculative frame that does not fit (scan_frame_fits): the tile scan writes every offset and slot as 0, so
  // that raster and resolve see empty tiles, and the listing writes nothing; the host redoes the frame.
  uint keep = ~0u;
  bool write = true;
  if (phase == CLR_SCAN_APPLY && counters[CLR_COUNTER_SPECULATIVE]) {
    if (listSources) {
      write = !counters[CLR_COUNTER_OVERFLOW];
    } else if (alsoNonZero && !scan_frame_fits(counters, partials[numChunks], nonZeroPartials[numChunks])) {
      keep = 0u;
      if (get_global_id(0) == 0) counters[CLR_COUNTER_OVERFLOW] = 1u;
    }
  }
  if (phase == CLR_SCAN_PARTIALS) {  // the same phase for the whole group, so its barriers are safe
#if CLR_LANES == 1
    scan_partials(partials, numChunks, groupSums, counters, totalAt);
    barrier(CLK_LOCAL_MEM_FENCE);  // groupSums is reused
    if (alsoNonZero) scan_partials(nonZeroPartials, numChunks, groupSums, counters, nonZeroTotalAt);
#else
    scan_partials(partials, numChunks, counters, totalAt);
    if (alsoNonZero) scan_partials(nonZeroPartials, numChunks, counters, nonZeroTotalAt);
#endif
  } else {
#if CLR_LANES == 1
    scan_chunk_group(src, dst, n, chunk, numChunks, partials, nonZeroPartials, second, byteCounts, phase, alsoNonZero,
                     listSources, keep, write, groupSums);
#else
    scan_chunk_item(src, dst, n, chunk, numChunks, partials, nonZeroPartials, second, byteCounts, phase, alsoNonZero,
                    listSources, listEnd, keep, write);
#endif
  }
}
#endif
