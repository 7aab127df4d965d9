# zfight.gnuplot — the z-fighting chart of bench/zfight.sh: per plane
# separation ε (relative to the distance), the fraction of wrongly ordered
# pixels against the far/near ratio, one line per depth format.
#
#   gnuplot -e "dir='DIR'" bench/zfight.gnuplot
#
# Reads DIR/zfight_summary.csv (clraster_zfight's columns: 1 format,
# 2 eps_rel, 3 far_near, 6 wrong_fraction). Writes DIR/zfight.png.
set datafile separator ","
set terminal pngcairo size 1500,900 font "DejaVu Sans,10"
set output dir."/zfight.png"
set multiplot layout 2, 3 title "Z-fighting: wrongly ordered pixels of two planes ε·d apart (both draw orders, 4 distances) vs far/near" font ",13"
set logscale x
set format x "10^{%L}"
set xrange [5:2e6]
set yrange [-0.02:0.6]
set grid xtics ytics lc rgb "#dddddd"
set xlabel "far / near"
set ylabel "wrong pixel fraction"
set key top left
epsilons = "0.01 0.001 0.0001 1e-05 1e-06 1e-07"
do for [i=1:words(epsilons)] {
  e = word(epsilons, i)
  set title "ε = ".e." · distance"
  plot dir."/zfight_summary.csv" using (strcol(1) eq "float32" && strcol(2) eq e ? $3 : NaN):6 skip 1 \
         with linespoints lw 2 pt 7 ps 1.2 lc rgb "#1f77b4" title "float32", \
       dir."/zfight_summary.csv" using (strcol(1) eq "unorm24" && strcol(2) eq e ? $3 : NaN):6 skip 1 \
         with linespoints lw 2 dt 2 pt 6 ps 1.8 lc rgb "#ff7f0e" title "unorm24", \
       dir."/zfight_summary.csv" using (strcol(1) eq "reversed" && strcol(2) eq e ? $3 : NaN):6 skip 1 \
         with linespoints lw 2 pt 5 ps 1.0 lc rgb "#2ca02c" title "reversed"
}
unset multiplot
