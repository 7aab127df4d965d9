/* scan.cl — exclusive prefix sum of a uint array.
 *
 * Used over per-triangle setup counts, per-tile bin counts and (counting
 * the non-zero tile counts) the visibility buffer's tile slots. src and
 * dst have n + 1 elements and may be the same buffer; on return dst[i] is
 * the sum of the first i values and dst[n] the total, where a value is
 * src[i], or 1 for a non-zero src[i] when countNonZero. Sums are
 * accumulated in 64 bits and the 64-bit total is left in
 * partials[numChunks], so the host can detect a total that does not fit in
 * 32 bits and fail loudly instead of wrapping. Two kernels: scan_chunks,
 * launched twice (CLR_SCAN_REDUCE: a sum per chunk; then CLR_SCAN_APPLY:
 * each chunk rescanned from its offset), and between them scan_partials
 * (one work-group scans the chunk sums). One kernel for both chunk passes
 * means one compile at a cold start.
 */

__kernel void scan_chunks(__global const uint* src, __global uint* dst, uint n, uint chunk, uint numChunks,
                          __global ulong* partials,  // numChunks + 1
                          uint phase, uint countNonZero)
{
  const uint g = get_global_id(0);
  if (g >= numChunks) return;
  const uint begin = g * chunk;
  const uint end = min(begin + chunk, n);
  if (phase == CLR_SCAN_REDUCE) {
    ulong sum = 0;
    for (uint i = begin; i < end; ++i) sum += countNonZero ? (src[i] != 0) : src[i];
    partials[g] = sum;
    return;
  }
  ulong running = partials[g];
  for (uint i = begin; i < end; ++i) {
    const uint v = countNonZero ? (src[i] != 0) : src[i];
    dst[i] = (uint)running;
    running += v;
  }
  if (g == numChunks - 1) dst[n] = (uint)partials[numChunks];
}
#define CLR_SCAN_GROUP 64

__kernel __attribute__((reqd_work_group_size(CLR_SCAN_GROUP, 1, 1))) void scan_partials(__global ulong* partials,
                                                                                        uint numChunks)
{
  __local ulong groupSums[CLR_SCAN_GROUP];
  const uint lid = get_local_id(0);
  const uint per = (numChunks + CLR_SCAN_GROUP - 1) / CLR_SCAN_GROUP;
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
    for (uint i = 0; i < CLR_SCAN_GROUP; ++i) {
      const ulong v = groupSums[i];
      groupSums[i] = running;
      running += v;
    }
    partials[numChunks] = running;
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
