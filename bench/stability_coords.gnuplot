# stability_coords.gnuplot — the coordinate-magnitude chart of
# bench/stability.sh: cracked pixels (holes + double hits) of a shared-edge
# mesh against the largest vertex coordinate, per edge method.
#
#   gnuplot -e "dir='DIR'" bench/stability_coords.gnuplot
#
# Reads DIR/stability_coords.csv (clraster_stability coords: 1 reach,
# 2 magnitude, 3 clipped, 4 method, 5 holes, 6 doubles, 7 cracked,
# 8 pixels). Zero counts are drawn at 0.5 so they show on the log axis.
set datafile separator ","
set terminal pngcairo size 1000,600 font "DejaVu Sans,10"
set output dir."/stability_coords.png"
set title "Cracks in a shared-edge mesh against coordinate magnitude (512x512, 64 bands, 3 seeds; 786,432 pixels)"
set logscale xy
set xlabel "largest vertex coordinate |x_s|, |y_s| before clipping (pixels)"
set ylabel "cracked pixels (holes + double hits)"
set yrange [0.3:*]
set ytics add ("0" 0.5)
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key top left
set arrow from 65536, graph 0 to 65536, graph 1 nohead dt 2 lc rgb "#888888"
set label "guard band 2^{16}: clipped beyond" at 65536, graph 0.95 offset 0.5, 0 font ",9"
z(v) = v > 0 ? v : 0.5
plot dir."/stability_coords.csv" using (strcol(4) eq "fixed" ? $2 : NaN):(z($7)) skip 1 with points pt 7 ps 1.2 lc rgb "#2ca02c" title "fixed-point edges (64-bit)", \
     dir."/stability_coords.csv" using (strcol(4) eq "float" ? $2 : NaN):(z($7)) skip 1 with points pt 5 ps 1.2 lc rgb "#d62728" title "float edges: holes + doubles", \
     dir."/stability_coords.csv" using (strcol(4) eq "float" ? $2 : NaN):(z($5)) skip 1 with points pt 6 lc rgb "#ff7f0e" title "float edges: holes", \
     dir."/stability_coords.csv" using (strcol(4) eq "float" ? $2 : NaN):(z($6)) skip 1 with points pt 4 lc rgb "#9467bd" title "float edges: double hits"
