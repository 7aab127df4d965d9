/* lanes.h — the kernels' lane types: how many items one work-item handles. OpenCL only (after shared.h).
 *
 * -D CLR_LANES per device: 1 on a GPU (scalar types, one pixel or triangle per work-item); 16 on a CPU (explicit
 * vectors, AVX-512 under PoCL, which vectorises across work-items only the simplest kernels). Comparisons yield
 * masks (1 or −1 for true), combined with & | CLR_NOT and consumed by select(), correct in both widths. For
 * Oclgrind, which gets both wrong for vectors: negate masks with CLR_NOT, never '!', and give min/max/clamp vector
 * arguments, never a scalar.
 */

/* Logical not of a mask, in either width. */
#define CLR_NOT(mask) ((mask) == 0)
#ifndef CLR_LANES
#define CLR_LANES 1
#endif

#if CLR_LANES == 1
typedef long longL;
typedef ushort ushortL;
typedef uchar ucharL;
typedef int intL;
typedef uint uintL;
typedef float floatL;
#define CLR_LANE_INDEX 0
#define CLR_ANY(mask) ((mask) != 0)
#define convert_longL convert_long
#define convert_intL convert_int
#define convert_uintL convert_uint
#define convert_ushortL convert_ushort
#define convert_ucharL convert_uchar
#define convert_floatL convert_float
#define convert_intL_rte convert_int_rte
#define convert_uintL_sat_rte convert_uint_sat_rte
#define as_uintL as_uint
#define as_intL as_int
#define as_floatL as_float
#define CLR_STORE_LANES(value, array) ((array)[0] = (value))
#define CLR_LOAD_LANES(array) ((array)[0])
CLR_INLINE uint clr_and_lanes(uint v)
{
  return v;
}
CLR_INLINE float clr_max_lanes(float v)
{
  return v;
}
#elif CLR_LANES == 16
typedef long16 longL;
typedef ushort16 ushortL;
typedef uchar16 ucharL;
typedef int16 intL;
typedef uint16 uintL;
typedef float16 floatL;
#define CLR_LANE_INDEX ((int16)(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15))
/* True when any lane of a mask is set: an OR tree over halves (PoCL's any() branches per lane). */
CLR_INLINE bool clr_any16(int16 mask)
{
  const int8 a = mask.lo | mask.hi;
  const int4 b = a.lo | a.hi;
  const int2 c = b.lo | b.hi;
  return (c.x | c.y) != 0;
}
#define CLR_ANY(mask) clr_any16(as_int16(mask))
/* The bits set in every lane, and the largest lane (max()'s NaN rule): trees over halves, as clr_any16. */
CLR_INLINE uint clr_and_lanes(uint16 v)
{
  const uint8 a = v.lo & v.hi;
  const uint4 b = a.lo & a.hi;
  const uint2 c = b.lo & b.hi;
  return c.x & c.y;
}
/* The smallest and the largest lane, and a mask's lanes as bits: trees over halves, as clr_any16. */
CLR_INLINE int clr_min_lanes_int(int16 v)
{
  const int8 a = min(v.lo, v.hi);
  const int4 b = min(a.lo, a.hi);
  const int2 c = min(b.lo, b.hi);
  return min(c.x, c.y);
}
CLR_INLINE int clr_max_lanes_int(int16 v)
{
  const int8 a = max(v.lo, v.hi);
  const int4 b = max(a.lo, a.hi);
  const int2 c = max(b.lo, b.hi);
  return max(c.x, c.y);
}
CLR_INLINE uint clr_lane_mask(int16 mask)
{
  const int16 bits = mask & (int16)(1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 4096, 8192, 16384, 32768);
  const int8 a = bits.lo | bits.hi;
  const int4 b = a.lo | a.hi;
  const int2 c = b.lo | b.hi;
  return (uint)(c.x | c.y);
}
CLR_INLINE float clr_max_lanes(float16 v)
{
  const float8 a = max(v.lo, v.hi);
  const float4 b = max(a.lo, a.hi);
  const float2 c = max(b.lo, b.hi);
  return max(c.x, c.y);
}
#define convert_longL convert_long16
#define convert_intL convert_int16
#define convert_uintL convert_uint16
#define convert_ushortL convert_ushort16
#define convert_ucharL convert_uchar16
#define convert_floatL convert_float16
#define convert_intL_rte convert_int16_rte
#define convert_uintL_sat_rte convert_uint16_sat_rte
#define as_uintL as_uint16
#define as_intL as_int16
#define as_floatL as_float16
#define CLR_STORE_LANES(value, array) vstore16((value), 0, (array))
#define CLR_LOAD_LANES(array) vload16(0, (array))
#else
#error "CLR_LANES must be 1 or 16"
#endif

/* Round to nearest even, exactly as rint() and _rte conversions: adding 2^23 with x's sign leaves no fraction bits
 * when |x| < 2^23; larger floats are integers. Three vector instructions where PoCL emulates rint() with a dozen
 * (a zero's sign may differ, which integer conversions ignore). */
CLR_INLINE floatL clr_rint(floatL x)
{
  const floatL big = 8388608.0f;  // 2^23
  const floatL magic = select(big, -big, x < 0.0f);
  return select((x + magic) - magic, x, fabs(x) >= big);
}

/* Each lane's exact doubled signed area (64 bits, fixed.h) and 1 / that: clr_inv_area2's operations, same floats. */
CLR_INLINE longL clr_area2L(intL x0, intL y0, intL x1, intL y1, intL x2, intL y2)
{
  return convert_longL(x1 - x0) * convert_longL(y2 - y0) - convert_longL(x2 - x0) * convert_longL(y1 - y0);
}
CLR_INLINE floatL clr_inv_area2L(intL x0, intL y0, intL x1, intL y1, intL x2, intL y2)
{
  return 1.0f / convert_floatL(clr_area2L(x0, y0, x1, y1, x2, y2));
}

/* A row of CLR_LANES values stored non-temporally on clang/x86 with 16 lanes (PoCL CPU), a plain store elsewhere:
 * the image is written once and read by the host, and a plain store first reads each line. The pointer must be
 * 64-byte aligned. Ordering: PoCL signals a kernel's end with LOCK-prefixed instructions, which drain the
 * write-combining buffers (Intel SDM vol. 3, 11.3.1), so no sfence is needed. */
#if CLR_LANES == 16 && defined(__clang__) && defined(__SSE2__)
#define CLR_STREAMS 1
#define CLR_STREAM_STORE(value, pointer) __builtin_nontemporal_store((value), (pointer))
#else
#define CLR_STREAMS 0
#define CLR_STREAM_STORE(value, pointer) (*(pointer) = (value))
#endif
