#!/usr/bin/env bash
# plot_curves.sh — runs the pose, cube and earth examples at 64x64 and plots their
# loss curves (gnuplot-nox) into docs/nvdiffrast_pose.png and
# docs/nvdiffrast_cube.png and docs/nvdiffrast_earth.png, as docs/nvdiffrast.md shows them.
#   bash examples/plot_curves.sh BUILD_DIR
set -euo pipefail
build="$(cd "${1:?usage: plot_curves.sh BUILD_DIR}" && pwd)"
here="$(cd "$(dirname "$0")" && pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cd "$here"
PYTHONPATH="$build/python" /usr/bin/python3 pose.py --iterations 300 --curve "$tmp/pose.tsv"
PYTHONPATH="$build/python" /usr/bin/python3 cube.py --iterations 500 --curve "$tmp/cube.tsv"
PYTHONPATH="$build/python" /usr/bin/python3 earth.py --iterations 400 --curve "$tmp/earth.tsv"
gnuplot <<GP
set terminal pngcairo size 720,400
set logscale y
set xlabel "iteration"
set ylabel "image MSE"
set y2label "degrees to the target"
set y2tics
set key top right
set output "$here/../docs/nvdiffrast_pose.png"
set title "pose: a rotation 25 degrees away (64x64, clraster.torch on PoCL)"
plot "$tmp/pose.tsv" using 1:(\$2 > 0 ? \$2 : 1e-12) with lines title "loss", \
     "$tmp/pose.tsv" using 1:3 axes x1y2 with lines title "angle (degrees, right axis)"
set output "$here/../docs/nvdiffrast_cube.png"
set title "cube: corners and colours from random views (64x64)"
set y2label "mean error"
set logscale y2
plot "$tmp/cube.tsv" using 1:2 with lines title "loss", \
     "$tmp/cube.tsv" using 1:3 axes x1y2 with lines title "corner error (right axis)", \
     "$tmp/cube.tsv" using 1:4 axes x1y2 with lines title "colour error (right axis)"
set output "$here/../docs/nvdiffrast_earth.png"
set title "earth: a mip-mapped texture from random views (64x64)"
plot "$tmp/earth.tsv" using 1:(\$2 > 0 ? \$2 : 1e-12) with lines title "loss", \
     "$tmp/earth.tsv" using 1:3 axes x1y2 with lines title "mean texel error (right axis)"
GP
