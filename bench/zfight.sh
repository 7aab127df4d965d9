#!/usr/bin/env bash
# zfight.sh — the z-fighting measurement of the depth formats, on a Debian 12
# machine with the packages of scripts/bootstrap.sh (gnuplot-nox among them).
#
#   bash bench/zfight.sh [--out DIR | --update-docs]
#
# Builds clraster_zfight in build/ and runs it (bench/zfight.cpp: two planes
# ε·d apart, far/near 10 … 10^6, 128x128, each depth format), then draws the
# chart. Writes into build/bench, or DIR, or docs/bench with --update-docs
# (bench/common.sh), replacing earlier results:
#   zfight.csv          one row per case
#   zfight_summary.csv  wrong fraction per format, ε and far/near
#   zfight.png          the chart
# Deterministic (nothing is timed); took about 10 s on the 2-core
# development machine.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source bench/common.sh
bench_args bench/zfight.sh "$@"
((${#bench_rest[@]} == 0)) || { echo "bench/zfight.sh: unexpected argument '${bench_rest[0]}'" >&2; exit 2; }
need_gnuplot bench/zfight.sh
[[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target clraster_zfight
export POCL_CACHE_DIR="$PWD/build/pocl-cache"
out=$bench_out
mkdir -p "$out"
./build/clraster_zfight --csv "$out/zfight.csv" --summary "$out/zfight_summary.csv"
gnuplot -e "dir='$out'" bench/zfight.gnuplot
echo "zfight.sh: wrote $out/zfight.{csv,png} and $out/zfight_summary.csv"
