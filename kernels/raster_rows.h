/* raster_rows.h — the row loop of raster's CPU shape, included twice by raster.cl, each time specialised by the
 * macros it defines first (and this file undefines):
 *   CLR_ROWS_NAME           the function's name (raster_rows_fixed, raster_rows_fixed32)
 *   CLR_ROWS_EDGE_L, _EDGE  the edge functions' lane and scalar types (longL, long; or uintL, uint: modulo 2^32)
 *   CLR_ROWS_SIGNED_L(v)    an edge value read as signed lanes, CLR_ROWS_SIGNED_EDGE its scalar type
 *   CLR_ROWS_EDGE_FUNCTION  edge_function or edge_function32
 *   CLR_ROWS_TO_INT_L(m)    a comparison mask as intL
 *   CLR_ROWS_SKIP_EMPTY     whether an empty row skips the depth test
 * Rows rowBegin .. rowEnd of one tile column, the first at sample y firstSy: the edge functions are evaluated once
 * and stepped by their exact row increment (bx − ax)·ONE. raster_rows_fixed runs in 64-bit lanes,
 * raster_rows_fixed32 in 32-bit lanes (stepped modulo 2^32, read as ints) for a triangle within CLR_EDGE32_SPAN or
 * rows that raster_segment_rows admits; the barycentrics convert the same integers. Coverage by traversal: the edge
 * test (or every sample with acceptAll), the exact span, or the float walk from the tile's first row,
 * firstSy − rowBegin·ONE. Skipping empty rows pays where they come in long runs (large triangles) and not where they
 * are few (bench/ab.sh), so only the 64-bit loop does.
 */
CLR_HOT void CLR_ROWS_NAME(CLR_RECORD_SPACE const TriSetup* t, uint s, intL sx, int firstSy, int rowBegin, int rowEnd,
                           RowBest* best, const DepthRule* rule, uint rank, const bool acceptAll, const uint traversal)
{
  CLR_ROWS_EDGE_L e0 = CLR_ROWS_EDGE_FUNCTION(t->x[1], t->y[1], t->x[2], t->y[2], sx, firstSy);
  CLR_ROWS_EDGE_L e1 = CLR_ROWS_EDGE_FUNCTION(t->x[2], t->y[2], t->x[0], t->y[0], sx, firstSy);
  CLR_ROWS_EDGE_L e2 = CLR_ROWS_EDGE_FUNCTION(t->x[0], t->y[0], t->x[1], t->y[1], sx, firstSy);
  const CLR_ROWS_EDGE step0 = (CLR_ROWS_EDGE)(t->x[2] - t->x[1]) * CLR_FIXED_ONE;
  const CLR_ROWS_EDGE step1 = (CLR_ROWS_EDGE)(t->x[0] - t->x[2]) * CLR_FIXED_ONE;
  const CLR_ROWS_EDGE step2 = (CLR_ROWS_EDGE)(t->x[1] - t->x[0]) * CLR_FIXED_ONE;
  const CLR_ROWS_SIGNED_EDGE low0 = -(CLR_ROWS_SIGNED_EDGE)edge_bias(t->x[1], t->y[1], t->x[2], t->y[2]);
  const CLR_ROWS_SIGNED_EDGE low1 = -(CLR_ROWS_SIGNED_EDGE)edge_bias(t->x[2], t->y[2], t->x[0], t->y[0]);
  const CLR_ROWS_SIGNED_EDGE low2 = -(CLR_ROWS_SIGNED_EDGE)edge_bias(t->x[0], t->y[0], t->x[1], t->y[1]);
  const float invArea2 = CLR_RECORD_INV_AREA2(*t);
  const int firstSx = CLR_LANE0(sx);
  Spans sp;
  Walk w;
  if (traversal == CLR_TRAVERSAL_SPANS) sp = spans_begin(t, firstSx, firstSy, true);
  if (traversal == CLR_TRAVERSAL_SPANS_FLOAT) {
    w = walk_begin(t, (float)(firstSy - rowBegin * CLR_FIXED_ONE) * (1.0f / CLR_FIXED_ONE));
    for (int row = 0; row < rowBegin; ++row) w.x += w.step;
  }
  for (int row = rowBegin; row <= rowEnd; ++row) {
    intL inside = (intL)(-1);
    bool any = true;
    if (traversal == CLR_TRAVERSAL_SPANS) {
      const int2 span = spans_row(&sp);
      inside = (CLR_LANE_INDEX >= (intL)span.x) & (CLR_LANE_INDEX <= (intL)span.y);
      any = span.x <= span.y;
      spans_step(&sp);
    } else if (traversal == CLR_TRAVERSAL_SPANS_FLOAT) {
      inside = walk_inside(&w, sx, firstSy + (row - rowBegin) * CLR_FIXED_ONE);
      any = CLR_ANY(inside);
      w.x += w.step;
    } else if (!acceptAll) {
      inside = CLR_ROWS_TO_INT_L((CLR_ROWS_SIGNED_L(e0) > low0) & (CLR_ROWS_SIGNED_L(e1) > low1) &
                                 (CLR_ROWS_SIGNED_L(e2) > low2));
      any = !CLR_ROWS_SKIP_EMPTY || CLR_ANY(inside);
    }
    if (any)
      raster_depth_test(t, s, inside, convert_floatL(CLR_ROWS_SIGNED_L(e1)) * invArea2,
                        convert_floatL(CLR_ROWS_SIGNED_L(e2)) * invArea2, &best[row], rule, rank);
    e0 += step0;
    e1 += step1;
    e2 += step2;
  }
}

#undef CLR_ROWS_NAME
#undef CLR_ROWS_EDGE_L
#undef CLR_ROWS_EDGE
#undef CLR_ROWS_SIGNED_L
#undef CLR_ROWS_SIGNED_EDGE
#undef CLR_ROWS_EDGE_FUNCTION
#undef CLR_ROWS_TO_INT_L
#undef CLR_ROWS_SKIP_EMPTY
