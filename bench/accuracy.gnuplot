# accuracy.gnuplot — the speed–accuracy chart of bench/accuracy.sh: per
# scene, every method's frame time against its error, the Pareto front
# joined by a line.
#
#   gnuplot -e "dir='DIR'; scenes='coverage default Wuson checker'" bench/accuracy.gnuplot
#
# Reads DIR/accuracy.csv and DIR/accuracy_pareto.csv (clraster_accuracy's
# columns: 1 scene, 2 method, 4 frame_ms, 8 rmse). Writes DIR/accuracy.png.
set datafile separator ","
set terminal pngcairo size 1400,1000 font "DejaVu Sans,10"
set output dir."/accuracy.png"
n = words(scenes)
set multiplot layout 2, (n + 1) / 2 title "Speed against accuracy: frame time (median, ms) vs RMSE against ground truth; line = Pareto front" font ",13"
set logscale xy
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set xlabel "frame time (ms)"
set key off
do for [i=1:n] {
  s = word(scenes, i)
  set title s." (".(s eq "coverage" ? "coverage RMSE vs exact area" : "image RMSE vs 64x64-sample reference").")" noenhanced
  set ylabel (s eq "coverage" ? "coverage RMSE" : "image RMSE")
  plot dir."/accuracy_pareto.csv" using (strcol(1) eq s ? $4 : NaN):8 skip 1 with lines lw 2 lc rgb "#2ca02c", \
       dir."/accuracy.csv" using (strcol(1) eq s ? $4 : NaN):8 skip 1 with points pt 7 ps 1.2 lc rgb "#1f77b4", \
       dir."/accuracy.csv" using (strcol(1) eq s ? $4 : NaN):8:2 skip 1 with labels offset 0.8, 0.6 left font ",8" noenhanced
}
unset multiplot
