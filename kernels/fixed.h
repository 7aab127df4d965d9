/* fixed.h — the fixed-point contract of clraster, in one place.
 *
 * Every limit that keeps the integer edge functions exact is defined and
 * derived here; host code, kernels and the test oracle all read these values
 * (the kernels receive this file first in their program sources). Change a
 * constant only together with its derivation.
 */
#ifndef CLR_FIXED_H
#define CLR_FIXED_H

/* Subpixel precision: vertices snap to a grid of 1/2^8 pixel, as in Mesa
 * llvmpipe (FIXED_ORDER = 8). Snapping is round-to-nearest-even of
 * screen_coordinate * CLR_FIXED_ONE. */
#define CLR_SUBPIXEL_BITS 8
#define CLR_FIXED_ONE (1 << CLR_SUBPIXEL_BITS)
#define CLR_FIXED_HALF (CLR_FIXED_ONE / 2) /* offset of a pixel centre */

/* Largest viewport side, in pixels (2^14). */
#define CLR_MAX_VIEWPORT 16384

/* Guard band: after clipping, every vertex satisfies |x_s|, |y_s| <= 2^16
 * pixels in screen space. The clip kernel enforces it with the planes
 * x = ±g_x·w, y = ±g_y·w, where g = 2·CLR_GUARD_BAND_PIXELS / size − 1, so
 * that x_s ∈ [size − 2^16, 2^16]. Triangles inside the band are never
 * clipped in x/y; those crossing it are clipped in homogeneous space.
 *
 * Overflow derivation (why these numbers are safe):
 *   |X| <= 2^16 · 2^8 = 2^24 fixed units (+ a few units of float rounding at
 *       the band edge)                               -> fits int32 with 2^7 slack
 *   edge deltas |X_j − X_i| <= 2^25                  -> fits int32
 *   an edge term (X_j − X_i)·(Y − Y_i) <= 2^25·2^25 = 2^50
 *   E = difference of two terms, |E| <= 2^51         -> int64 exact, 2^12 slack
 *   2·area = E evaluated at a vertex, same bound     -> int64 exact
 * Pixel-centre sample positions (i·256 + 128 for i < 2^14) stay below 2^22.
 * A 32-bit edge evaluation (modulo 2^32, read as an int) is exact only
 * where E fits an int: raster uses 32-bit lanes when a triangle's bounds
 * span at most 2^14 units (64 pixels) each way, with the derivation beside
 * CLR_EDGE32_SPAN in raster.cl, and for a larger triangle's tile rows over
 * which raster_segment_rows bounds all three edge functions within an int;
 * 64-bit lanes otherwise. Resolve recomputes barycentrics in 32 bits when
 * 2·area < 2^31 (vis_barycentrics). Setup and binning always use 64 bits. */
#define CLR_GUARD_BAND_PIXELS 65536

/* Screen tiles used by binning and by the per-pixel kernel's work-groups.
 * The kernels receive it as -D CLR_TILE_SIZE; this is the default. */
#ifndef CLR_TILE_SIZE
#define CLR_TILE_SIZE 16
#endif

/* Clipping against near + four guard planes adds at most one vertex per
 * plane to a convex polygon: 3 + 5 = 8 vertices, fanned into 6 triangles. */
#define CLR_MAX_CLIP_VERTS 8
#define CLR_MAX_SUBTRIS (CLR_MAX_CLIP_VERTS - 2)

/* The fill rule (GL as in llvmpipe, y up): a sample exactly on the directed
 * edge a→b of a counter-clockwise triangle is inside when the edge is a left
 * edge (going down, by < ay) or a horizontal bottom edge (bx > ax). In
 * scalar or lane types alike: a mask, 1 (scalar) or −1 (vector) when true.
 * Raster, binning's tile test and setup's coverage test all take it from
 * here. */
#define CLR_EDGE_HOLDS_SAMPLES(ax, ay, bx, by) (((by) < (ay)) | (((by) == (ay)) & ((bx) > (ax))))

#endif /* CLR_FIXED_H */
