#!/usr/bin/env bash
# traversal.sh — where each traversal method wins: kernel times of bbox,
# hierarchical, exact spans and the float edge walk against triangle size,
# from sub-pixel to full screen (bench/traversal.cpp), at 1920x1080.
#
#   bash bench/traversal.sh
#
# Writes, replacing earlier results:
#   docs/bench/traversal.csv  one row per size and method (medians)
#   docs/bench/traversal.md   the table
# Environment: REPS (default 7) alternated rounds. Took about 3 minutes on
# the 2-core development machine.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
[[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target clraster_traversal
export POCL_CACHE_DIR="$PWD/build/pocl-cache"
out=docs/bench
mkdir -p "$out"
./build/clraster_traversal --reps "${REPS:-7}" --csv "$out/traversal.csv" --markdown "$out/traversal.md"
echo "traversal.sh: wrote $out/traversal.{csv,md}"
