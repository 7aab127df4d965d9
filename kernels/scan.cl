/* scan.cl — exclusive prefix sum of a uint array, in place.
 *
 * Used twice a frame: over per-triangle setup counts and over per-tile bin
 * counts. data has n + 1 elements; on return data[i] is the sum of the
 * first i counts and data[n] the total. Sums are accumulated in 64 bits and
 * the 64-bit total is left in partials[numChunks], so the host can detect a
 * total that does not fit in 32 bits and fail loudly instead of wrapping.
 * Three kernels: scan_reduce (a sum per chunk), scan_partials (one
 * work-group scans the chunk sums), scan_apply (each chunk is rescanned).
 */

__kernel void scan_reduce(__global const uint* data, uint n, uint chunk, uint numChunks,
                          __global ulong* partials)  // numChunks + 1
{
  const uint g = get_global_id(0);
  if (g >= numChunks) return;
  const uint begin = g * chunk;
  const uint end = min(begin + chunk, n);
  ulong sum = 0;
  for (uint i = begin; i < end; ++i) sum += data[i];
  partials[g] = sum;
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

__kernel void scan_apply(__global uint* data, uint n, uint chunk, uint numChunks, __global const ulong* partials)
{
  const uint g = get_global_id(0);
  if (g >= numChunks) return;
  const uint begin = g * chunk;
  const uint end = min(begin + chunk, n);
  ulong running = partials[g];
  for (uint i = begin; i < end; ++i) {
    const uint v = data[i];
    data[i] = (uint)running;
    running += v;
  }
  if (g == numChunks - 1) data[n] = (uint)partials[numChunks];
}
