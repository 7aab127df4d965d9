# plots.gnuplot — the two charts of bench/run.sh, log-log, both renderers.
#
#   gnuplot -e "dir='DIR'; meshes=N; device='NAME'" bench/plots.gnuplot
#
# Reads from DIR, as run.sh writes them (space-separated):
#   sphere_far.dat, sphere_near.dat, grid_far.dat, grid_near.dat
#               triangles pixels clraster_ms llvmpipe_ms
#   meshes.dat  N blocks, two blank lines apart, each a mesh name line then
#               pixels clraster_ms llvmpipe_ms rows
# Writes DIR/scaling_triangles.png and DIR/scaling_pixels.png; NAME is
# clraster's OpenCL device, named in the titles.
set terminal pngcairo size 1100,720 font "DejaVu Sans,11"
set logscale xy
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key top left box opaque
set ylabel "frame time (ms, median)"
set format x "10^{%L}"
set autoscale xfix
set offsets graph 0.04, graph 0.04, 0, 0

clr = "#1f77b4"
llvm = "#d62728"

set output dir."/scaling_triangles.png"
set title "Frame time vs triangle count, 1920x1080, lambert (displaced sphere; 16x16 Wuson grid)\nclraster on ".device noenhanced
set xlabel "triangles"
plot dir."/sphere_far.dat" using 1:3 with linespoints lw 2 pt 7 lc rgb clr title "clraster, far (small triangles)", \
     dir."/sphere_far.dat" using 1:4 with linespoints lw 2 pt 7 lc rgb llvm title "llvmpipe, far", \
     dir."/sphere_near.dat" using 1:3 with linespoints lw 2 dt 2 pt 5 lc rgb clr title "clraster, near (large triangles)", \
     dir."/sphere_near.dat" using 1:4 with linespoints lw 2 dt 2 pt 5 lc rgb llvm title "llvmpipe, near", \
     dir."/grid_far.dat" using 1:3 with points pt 9 ps 2 lc rgb clr title "clraster, Wuson grid, far", \
     dir."/grid_far.dat" using 1:4 with points pt 9 ps 2 lc rgb llvm title "llvmpipe, Wuson grid, far", \
     dir."/grid_near.dat" using 1:3 with points pt 8 ps 2 lw 2 lc rgb clr title "clraster, Wuson grid, near", \
     dir."/grid_near.dat" using 1:4 with points pt 8 ps 2 lw 2 lc rgb llvm title "llvmpipe, Wuson grid, near"

set output dir."/scaling_pixels.png"
set title "Frame time vs pixel count (1280x720, 1920x1080, 3840x2160), lambert, far view\nclraster on ".device noenhanced
set xlabel "pixels"
set xtics ("1280x720\n0.92 Mpx" 921600, "1920x1080\n2.07 Mpx" 2073600, "3840x2160\n8.29 Mpx" 8294400)
plot for [i=0:meshes-1] dir."/meshes.dat" index i using 1:2 with linespoints lw 2 pt 7 lc i+1 \
       title columnheader(1)." (clraster)" noenhanced, \
     for [i=0:meshes-1] dir."/meshes.dat" index i using 1:3 with linespoints lw 2 dt 2 pt 5 lc i+1 \
       title columnheader(1)." (llvmpipe)" noenhanced
