# stability_coords.gnuplot — the stability chart of bench/stability.sh:
# cracked pixels (holes + double hits) of shared-edge meshes per coverage
# method, against the largest vertex coordinate (left) and against the
# slivers' aspect ratio (right).
#
#   gnuplot -e "dir='DIR'" bench/stability_coords.gnuplot
#
# Reads DIR/stability_coords.csv (clraster_stability coords: 1 reach,
# 2 magnitude, 3 clipped, 4 method, 5 holes, 6 doubles, 7 cracked,
# 8 pixels) and DIR/stability_walk.csv (clraster_stability walk: 1 case,
# 2 param, 3 reach, 4 aspect, 5 method, 6 holes, 7 doubles, 8 cracked,
# 9 pixels). Zero counts are drawn at 0.5 so they show on the log axis.
set datafile separator ","
set terminal pngcairo size 1500,600 font "DejaVu Sans,10"
set output dir."/stability_coords.png"
set multiplot layout 1,2 title "Cracks in shared-edge meshes (512x512, 3 seeds; 786,432 pixels)"
set logscale xy
set ylabel "cracked pixels (holes + double hits)"
set yrange [0.3:*]
set ytics add ("0" 0.5)
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key top left
z(v) = v > 0 ? v : 0.5
is(col, name) = strcol(col) eq name
set title "band mesh (64 bands) against coordinate magnitude"
set xlabel "largest vertex coordinate |x_s|, |y_s| before clipping (pixels)"
set arrow 1 from 65536, graph 0 to 65536, graph 1 nohead dt 2 lc rgb "#888888"
set label 1 "guard band 2^{16}: clipped beyond" at 65536, graph 0.95 offset 0.5, 0 font ",9"
f = dir."/stability_coords.csv"
plot f using (is(4, "fixed") ? $2 : NaN):(z($7)) skip 1 with points pt 7 ps 1.4 lc rgb "#2ca02c" title "fixed-point edges, exact spans", \
     f using (is(4, "float") ? $2 : NaN):(z($7)) skip 1 with linespoints pt 5 ps 1.1 lc rgb "#d62728" title "float edges", \
     f using (is(4, "spans-float") ? $2 : NaN):(z($7)) skip 1 with linespoints pt 9 ps 1.2 lc rgb "#1f77b4" title "float edge walk (spans-float)", \
     f using (is(4, "spans-float") ? $2 : NaN):(z($6)) skip 1 with points pt 8 lc rgb "#17becf" title "float edge walk: double hits", \
     f using (is(4, "spans") ? $2 : NaN):(z($7)) skip 1 with points pt 6 ps 1.8 lc rgb "#000000" title "exact spans"
unset arrow 1
unset label 1
set title "slivers: band meshes reaching 4096 px, 8 to 2048 bands"
set xlabel "band aspect ratio (length / width)"
w = dir."/stability_walk.csv"
plot w using (is(1, "slivers") && is(5, "fixed") ? $4 : NaN):(z($8)) skip 1 with points pt 7 ps 1.4 lc rgb "#2ca02c" title "fixed-point edges", \
     w using (is(1, "slivers") && is(5, "float") ? $4 : NaN):(z($8)) skip 1 with linespoints pt 5 lc rgb "#d62728" title "float edges", \
     w using (is(1, "slivers") && is(5, "spans-float") ? $4 : NaN):(z($8)) skip 1 with linespoints pt 9 lc rgb "#1f77b4" title "float edge walk (spans-float)", \
     w using (is(1, "slivers") && is(5, "spans") ? $4 : NaN):(z($8)) skip 1 with points pt 6 ps 1.8 lc rgb "#000000" title "exact spans"
unset multiplot
