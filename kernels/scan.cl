/* scan.cl — exclusive prefix sum of a uint array.
 *
 * Used over per-triangle setup counts and per-tile bin counts. src and dst
 * have n + 1 elements and may be the same buffer; on return dst[i] is the
 * sum of the first i values and dst[n] the total. With alsoNonZero the same
 * pass also scans the count of non-zero values into `second` (n + 1
 * elements; over the tile counts, the visibility buffer's tile slots), with
 * its chunk sums after the values' in `partials`. Sums are accumulated in
 * 64 bits and a 64-bit total is left in partials[numChunks] (the non-zero
 * count's after it), and also in counters[totalAt], [totalAt + 1] (low and
 * high words; shared.h, CLR_COUNTER_*) unless totalAt is CLR_SCAN_NO_TOTAL
 * (likewise nonZeroTotalAt), so the host can detect a total that does not
 * fit in 32 bits and fail loudly instead of wrapping, and read the totals of
 * several scans and setup's counters with one read. One kernel, scan_chunks,
 * launched three times with its phase: CLR_SCAN_REDUCE (a sum per chunk),
 * CLR_SCAN_PARTIALS (one work-group scans the chunk sums) and
 * CLR_SCAN_APPLY (each chunk rescanned from its offset). One kernel means
 * one compile at a cold start (about 70 ms each for PoCL on the 2-core
 * development machine). Over the setup counts the apply phase also lists
 * the input triangle behind each setup record (listSources; shared.h,
 * setupSource), which saves the emit pass a kernel of its own. Those
 * counts are bytes (byteCounts: 0, 1 or CLR_MAX_SUBTRIS per input
 * triangle) and are not turned into offsets: the listing is the only
 * output, and setup_clip finds a clipped triangle's records in it.
 */
#if !CLR_EXTRAS /* the frame program (CLR_EXTRAS, shared.h) */

/* The total's copy among the frame's counters (two uints, low word first). */
CLR_INLINE void scan_store_total(__global uint* counters, uint totalAt, ulong total)
{
  if (totalAt == CLR_SCAN_NO_TOTAL) return;
  counters[totalAt] = (uint)total;
  counters[totalAt + 1] = (uint)(total >> 32);
}

/* CLR_SCAN_PARTIALS: the exclusive scan of partials[0 .. numChunks), the
 * total into partials[numChunks]. On a GPU one work-group shares it out
 * (with barriers). On a CPU (CLR_LANES > 1) one work-item scans the at
 * most 4096 sums in a few microseconds, so the kernel has no barrier: with
 * one, PoCL took twice as long to compile it (measured: 182 against 81 ms
 * of code generation). */
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
/* GPU shape of the reduce and apply phases: one work-group per chunk, its
 * CLR_SCAN_GROUP(1) work-items reading consecutive values (one coalesced
 * load per step), a step's values scanned in local memory
 * (scan_group_inclusive, Hillis and Steele's scan). When each work-item
 * walked a chunk of its own, as in the CPU shape, the 4096 work-items'
 * loads lay far apart and were too few to hide their latency: the setup
 * counts' scans of 10M triangles took 0.64 ms on an H100. Each value
 * enters the scan as (v << 8) | (v != 0), so that one scan gives both the
 * sum (64 uints sum below 2^38) and the count of non-zero values (at most
 * 64). Both phases walk the chunk the same way, with the same barriers:
 * PoCL mishandled a version whose reduce phase had its own loop and
 * barriers under a branch (its totals came out as garbage). */
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
                                 __local ulong* steps)
{
  const uint g = get_group_id(0), lid = get_local_id(0);
  const uint begin = g * chunk, end = min(begin + chunk, n);
  const bool apply = phase == CLR_SCAN_APPLY;
  // The chunk a step of CLR_SCAN_GROUP(1) values at a time: the reduce
  // phase sums the steps, the apply phase also writes each value's offset.
  ulong running = apply ? partials[g] : 0, runningNonZero = apply && alsoNonZero ? nonZeroPartials[g] : 0;
  for (uint first = begin; first < end; first += CLR_SCAN_GROUP(1)) {
    const uint i = first + lid, v = scan_value(src, byteCounts, listSources, i, end);
    const ulong packed = ((ulong)v << 8) | (ulong)(v != 0);
    const ulong inclusive = scan_group_inclusive(packed, steps), exclusive = inclusive - packed;
    const ulong stepTotal = steps[CLR_SCAN_GROUP(1) - 1];
    if (apply && i < end) {
      if (listSources) {
        // (A culled triangle stores nothing: the CPU shape's spare entry
        // would be a store by many work-items at once here.)
        const ulong record = running + (exclusive >> 8);
        if (v == 1) second[record] = i;
        for (uint k = 0; v == CLR_MAX_SUBTRIS && k < CLR_MAX_SUBTRIS; ++k) second[record + k] = CLR_SOURCE_CLIPPED | i;
      } else {
        dst[i] = (uint)(running + (exclusive >> 8));
        if (alsoNonZero) second[i] = (uint)(runningNonZero + (exclusive & 0xFF));
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
    dst[n] = (uint)partials[numChunks];
    if (alsoNonZero) second[n] = (uint)nonZeroPartials[numChunks];
  }
}
#else
/* CLR_SCAN_APPLY over the setup counts of input triangles [begin, end),
 * whose first record is `running`: lists the input triangle behind each
 * record. An unclipped survivor (1) owns its record; a clipped triangle's
 * CLR_MAX_SUBTRIS reserved records get CLR_SOURCE_CLIPPED | its index, so
 * the listing stays sorted by input triangle and setup_clip finds them by
 * binary search (clip_first_record); a culled one (0) owns none, and its
 * store goes to the chunk's spare entry past the records instead of behind a
 * branch (survivors and culled triangles alternate unpredictably on a dense
 * mesh seen from afar). */
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

/* CPU shape of the reduce and apply phases: work-item g walks chunk g
 * alone (one work-item per chunk). */
CLR_INLINE void scan_chunk_item(__global const uint* src, __global uint* dst, uint n, uint chunk, uint numChunks,
                                __global ulong* partials, __global ulong* nonZeroPartials, __global uint* second,
                                __global const uchar* byteCounts, uint phase, uint alsoNonZero, uint listSources)
{
  const uint g = get_global_id(0);
  if (g >= numChunks) return;
  const uint begin = g * chunk;
  const uint end = min(begin + chunk, n);
  if (phase == CLR_SCAN_REDUCE) {
    ulong sum = 0, nonZero = 0;
    if (listSources) {
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
  if (listSources) {
    scan_list_sources(byteCounts, begin, end, running, partials[numChunks] + g, second);
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
      dst[i] = (uint)running;
      second[i] = (uint)runningNonZero;
      running += v;
      runningNonZero += v != 0;
    }
  }
  if (g == numChunks - 1) {
    dst[n] = (uint)partials[numChunks];
    if (alsoNonZero) second[n] = (uint)nonZeroPartials[numChunks];
  }
}
#endif

__kernel __attribute__((reqd_work_group_size(CLR_SCAN_GROUP(CLR_LANES), 1, 1))) void scan_chunks(
    __global const uint* src, __global uint* dst, uint n, uint chunk, uint numChunks,
    __global ulong* partials,          // numChunks + 1, twice with alsoNonZero (the values', then the non-zero counts')
    __global uint* second,             // listSources: the sources (setup records); alsoNonZero: n + 1; else unused
    __global const uchar* byteCounts,  // listSources: n, read instead of src; else unused
    __global uint* counters,           // CLR_NUM_COUNTERS: the partials phase copies the totals there
    uint totalAt, uint nonZeroTotalAt, uint phase, uint alsoNonZero, uint listSources)
{
#if CLR_LANES == 1
  __local ulong groupSums[CLR_SCAN_GROUP(1)];
#endif
  __global ulong* nonZeroPartials = partials + numChunks + 1;
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
                     listSources, groupSums);
#else
    scan_chunk_item(src, dst, n, chunk, numChunks, partials, nonZeroPartials, second, byteCounts, phase, alsoNonZero,
                    listSources);
#endif
  }
}
#endif
