#!/usr/bin/env bash
# accuracy.sh — the speed–accuracy chart, on a Debian 12 machine with the
# packages of scripts/bootstrap.sh (gnuplot-nox among them).
#
#   bash bench/accuracy.sh [--out DIR | --update-docs] [MESH ...]
#
# Builds clraster_accuracy in build/ and runs it on the coverage scene, the
# built-in scene, Wuson.off (assimp-testmodels) or the MESH files given, and
# the grazing checker plane, every method at 1280x720 (see
# bench/accuracy.cpp), then draws the chart. Writes into build/bench, or DIR,
# or docs/bench with --update-docs (bench/common.sh), replacing earlier results:
#   accuracy.csv         one row per scene and method
#   accuracy_pareto.csv  the Pareto front of each scene
#   accuracy.md          the table
#   accuracy.png         the chart
# Environment: FRAMES (default 15) timed frames after WARMUP (default 3),
# REF_SAMPLES (default 64, per axis) for the reference. Took about 20 s on
# the 2-core development machine.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source bench/common.sh
bench_args bench/accuracy.sh "$@"
need_gnuplot bench/accuracy.sh
[[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target clraster_accuracy
export POCL_CACHE_DIR="$PWD/build/pocl-cache"
meshes=(${bench_rest[@]+"${bench_rest[@]}"})
((${#meshes[@]})) || meshes=(/usr/share/assimp/models/OFF/Wuson.off)
out=$bench_out
mkdir -p "$out"
./build/clraster_accuracy "${meshes[@]}" --frames "${FRAMES:-15}" --warmup "${WARMUP:-3}" \
  --ref-samples "${REF_SAMPLES:-64}" --csv "$out/accuracy.csv" --pareto "$out/accuracy_pareto.csv" \
  --markdown "$out/accuracy.md"
scenes=$(tail -n +2 "$out/accuracy.csv" | cut -d, -f1 | uniq | tr '\n' ' ')
gnuplot -e "dir='$out'; scenes='${scenes% }'" bench/accuracy.gnuplot
echo "accuracy.sh: wrote $out/accuracy.{csv,md,png}"
