#!/usr/bin/env bash
# zfight.sh — the z-fighting measurement of the depth formats, on a Debian 12
# machine, as root (it installs gnuplot-nox when missing).
#
#   bash bench/zfight.sh
#
# Builds clraster_zfight in build/ and runs it (bench/zfight.cpp: two planes
# ε·d apart, far/near 10 … 10^6, 128x128, each depth format), then draws the
# chart. Writes, replacing earlier results:
#   docs/bench/zfight.csv          one row per case
#   docs/bench/zfight_summary.csv  wrong fraction per format, ε and far/near
#   docs/bench/zfight.png          the chart
# Deterministic (nothing is timed).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
if ! command -v gnuplot >/dev/null; then
  echo "bench/zfight.sh: installing gnuplot-nox"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends gnuplot-nox
fi
[[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target clraster_zfight
export POCL_CACHE_DIR="$PWD/build/pocl-cache"
out=docs/bench
mkdir -p "$out"
./build/clraster_zfight --csv "$out/zfight.csv" --summary "$out/zfight_summary.csv"
gnuplot -e "dir='$out'" bench/zfight.gnuplot
echo "zfight.sh: wrote $out/zfight.{csv,png} and $out/zfight_summary.csv"
