/* vis.h — reading and writing the visibility buffer (shared.h, visIndex): its 16-, 24- or 32-bit index entries
 * (raster writes them; resolve, lines, aov and rast_outputs read them), and the screen barycentrics resolve
 * recomputes where a frame kept no barycentric planes, with raster's integers (vis_barycentrics).
 */
#ifndef CLR_VIS_H
#define CLR_VIS_H

/* The visibility buffer's index entries (shared.h, visIndex): 16 or 24 bits
 * (all ones for none, 24 as a low half and a high byte in planes of their
 * own) or 32, by FrameParams.visIndexBits; i counts entries.
 * vis_load_index_lanes returns the lanes as a vector too: use that, not a
 * reload of `lanes`, which would wait for the split store. */
CLR_INLINE uint vis_index_at(__constant FrameParams* params, __global const uint* visIndex, uint i)
{
  const uint bits = params->visIndexBits;
  if (bits == 16) {
    const uint v = ((__global const ushort*)visIndex)[i];
    return v == 0xFFFFu ? CLR_NONE : v;
  }
  if (bits == 32) return visIndex[i];
  const uint v =
      ((__global const ushort*)visIndex)[i] | (uint)((__global const uchar*)visIndex)[2 * params->visEntries + i] << 16;
  return v == 0xFFFFFFu ? CLR_NONE : v;
}
CLR_INLINE uintL vis_load_index_lanes(__constant FrameParams* params, __global const uint* visIndex, uint i, uint count,
                                      uint* lanes)
{
  if (count < CLR_LANES) {
    for (uint lane = 0; lane < CLR_LANES; ++lane)
      lanes[lane] = lane < count ? vis_index_at(params, visIndex, i + lane) : CLR_NONE;
    return CLR_LOAD_LANES(lanes);  // the viewport's edge
  }
  const uint bits = params->visIndexBits;
  uintL v;
  if (bits == 16) {
    const uintL wide = convert_uintL(CLR_LOAD_LANES((__global const ushort*)visIndex + i));
    v = select(wide, (uintL)CLR_NONE, wide == 0xFFFFu);
  } else if (bits == 32) {
    v = CLR_LOAD_LANES(visIndex + i);
  } else {
    const uintL wide = convert_uintL(CLR_LOAD_LANES((__global const ushort*)visIndex + i)) |
                       convert_uintL(CLR_LOAD_LANES((__global const uchar*)visIndex + 2 * params->visEntries + i))
                           << 16;
    v = select(wide, (uintL)CLR_NONE, wide == 0xFFFFFFu);
  }
  CLR_STORE_LANES(v, lanes);
  return v;
}
CLR_INLINE void vis_store_index_lanes(__constant FrameParams* params, uintL index, __global uint* visIndex, uint i)
{
  const uint bits = params->visIndexBits;
  if (bits == 32) {
    CLR_STORE_LANES(index, visIndex + i);
    return;
  }
  // The low halves, then for 24 bits the high bytes (conversions keep the low bits: CLR_NONE gives all ones).
#if CLR_LANES == 16
  // One aligned vector store each (i is a multiple of 16: vis_address; so is
  // 2·visEntries); vstore16 of ushorts compiles to 16 scalar stores on PoCL.
  *(__global ushort16*)((__global ushort*)visIndex + i) = convert_ushort16(index);
  if (bits == 24)
    *(__global uchar16*)((__global uchar*)visIndex + 2 * params->visEntries + i) = convert_uchar16(index >> 16);
#else
  CLR_STORE_LANES(convert_ushortL(index), (__global ushort*)visIndex + i);
  if (bits == 24) CLR_STORE_LANES(convert_ucharL(index >> 16), (__global uchar*)visIndex + 2 * params->visEntries + i);
#endif
}

/* The edge function with a and b per lane: edge_function's integers. */
CLR_INLINE longL edge_function_lanes(intL ax, intL ay, intL bx, intL by, intL px, int py)
{
  return convert_longL(bx - ax) * convert_longL(py - ay) - convert_longL(by - ay) * convert_longL(px - ax);
}

/* The screen barycentrics b1, b2 that raster kept with fixed edges, for
 * resolve when the frame has no barycentric planes: the same integers E1,
 * E2, so bit-identical floats. In 32 bits when every covered lane's scale
 * is at least 2^-30: a covered sample's E lies in [0, 2·area], and
 * scale = RN(1 / RN(2·area)) >= 2^-30 bounds 2·area below 2^30 + 64 < 2^31,
 * so the low 32 bits read as an int are E. Lanes outside `covered` give
 * values the caller discards. */
CLR_INLINE void vis_barycentrics(intL x0, intL y0, intL x1, intL y1, intL x2, intL y2, floatL scale, intL covered,
                                 intL sx, int sy, floatL* b1, floatL* b2)
{
  const float minScale = 1.0f / 1073741824.0f;  // 2^-30
  if (!CLR_ANY(covered & (scale < minScale))) {
    const uintL py = (uintL)(uint)sy, px = as_uintL(sx);
    const uintL ax0 = as_uintL(x0), ax1 = as_uintL(x1), ax2 = as_uintL(x2);
    const uintL ay0 = as_uintL(y0), ay1 = as_uintL(y1), ay2 = as_uintL(y2);
    *b1 = convert_floatL(as_intL((ax0 - ax2) * (py - ay2) - (ay0 - ay2) * (px - ax2))) * scale;
    *b2 = convert_floatL(as_intL((ax1 - ax0) * (py - ay0) - (ay1 - ay0) * (px - ax0))) * scale;
    return;
  }
  *b1 = convert_floatL(edge_function_lanes(x2, y2, x0, y0, sx, sy)) * scale;
  *b2 = convert_floatL(edge_function_lanes(x0, y0, x1, y1, sx, sy)) * scale;
}

#endif /* CLR_VIS_H */
