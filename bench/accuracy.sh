#!/usr/bin/env bash
# accuracy.sh — the speed–accuracy chart, on a Debian 12 machine, as root (it installs gnuplot-nox when
# missing).
#
#   bash bench/accuracy.sh [MESH ...]
#
# Builds clraster_accuracy in build/ and runs it on the coverage scene, the built-in scene, Wuson.off
# (assimp-testmodels) or the MESH files given, and the grazing checker plane, every method at 1280x720 (see
# bench/accuracy.cpp), then draws the chart. Writes, replacing earlier results:
#   docs/bench/accuracy.csv         one row per scene and method
#   docs/bench/accuracy_pareto.csv  the Pareto front of each scene
#   docs/bench/accuracy.md          the table
#   docs/bench/accuracy.png         the chart
# Environment: FRAMES (default 15) timed frames after WARMUP (default 3), REF_SAMPLES (default 64, per axis)
# for the reference.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
if ! command -v gnuplot >/dev/null; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends gnuplot-nox
fi
[[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target clraster_accuracy
export POCL_CACHE_DIR="$PWD/build/pocl-cache"
meshes=("$@")
((${#meshes[@]})) || meshes=(/usr/share/assimp/models/OFF/Wuson.off)
out=docs/bench
mkdir -p "$out"
./build/clraster_accuracy "${meshes[@]}" --frames "${FRAMES:-15}" --warmup "${WARMUP:-3}" \
  --ref-samples "${REF_SAMPLES:-64}" --csv "$out/accuracy.csv" --pareto "$out/accuracy_pareto.csv" \
  --markdown "$out/accuracy.md"
scenes=$(tail -n +2 "$out/accuracy.csv" | cut -d, -f1 | uniq | tr '\n' ' ')
gnuplot -e "dir='$out'; scenes='${scenes% }'" bench/accuracy.gnuplot
echo "accuracy.sh: wrote $out/accuracy.{csv,md,png}"
