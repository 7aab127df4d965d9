/* fixed.h — fixed-point limits keeping the integer edge functions exact (host, kernels, oracle; change with bound).
 * After clipping |x_s|, |y_s| <= 2^16 px: |X| <= 2^24 units (+ float rounding; int32, 2^7 slack), edge deltas <= 2^25,
 * terms <= 2^50, E and 2·area <= 2^51: int64 exact, 2^12 slack. Setup and binning use 64 bits; raster 32-bit lanes
 * only where E fits an int (CLR_EDGE32_SPAN, raster_segment_rows); resolve's 32-bit path needs 2·area < 2^31. */
#ifndef CLR_FIXED_H
#define CLR_FIXED_H

#define CLR_SUBPIXEL_BITS 8 /* snap (round half even) to 1/256 px, as llvmpipe's FIXED_ORDER */
#define CLR_FIXED_ONE (1 << CLR_SUBPIXEL_BITS)
#define CLR_FIXED_HALF (CLR_FIXED_ONE / 2) /* offset of a pixel centre */

#define CLR_MAX_VIEWPORT 16384 /* 2^14 px a side: sample positions i·256 + 128 stay below 2^22 */

#define CLR_GUARD_BAND_PIXELS 65536 /* clip planes x = ±g·w, g = 2·this / size − 1: x_s in [size − 2^16, 2^16] */

#ifndef CLR_TILE_SIZE
#define CLR_TILE_SIZE 16 /* binning tile and raster work-group side; the kernels get it as -D CLR_TILE_SIZE */
#endif

#define CLR_MAX_CLIP_VERTS 8 /* near + four guard planes add <= 1 vertex each: 3 + 5, fanned into 6 triangles */
#define CLR_MAX_SUBTRIS (CLR_MAX_CLIP_VERTS - 2)

/* Fill rule (GL as llvmpipe, y up): a sample on CCW edge a→b is inside on a left edge (by < ay) or a horizontal
 * bottom edge (bx > ax). A mask, 1 (scalar) or −1 (vector); raster, binning and setup all use it. */
#define CLR_EDGE_HOLDS_SAMPLES(ax, ay, bx, by) (((by) < (ay)) | (((by) == (ay)) & ((bx) > (ax))))

#endif /* CLR_FIXED_H */
