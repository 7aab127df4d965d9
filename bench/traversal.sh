#!/usr/bin/env bash
# traversal.sh — where each traversal method wins: kernel times of bbox,
# hierarchical, exact spans and the float edge walk against triangle size,
# from sub-pixel to full screen (bench/traversal.cpp), at 1920x1080.
#
#   bash bench/traversal.sh [--out DIR | --update-docs]
#
# Writes into build/bench, or DIR, or docs/bench with --update-docs
# (bench/common.sh), replacing earlier results:
#   traversal.csv  one row per size and method (medians)
#   traversal.md   the table
# Environment: REPS (default 7) alternated rounds.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source bench/common.sh
bench_args bench/traversal.sh "$@"
((${#bench_rest[@]} == 0)) || { echo "bench/traversal.sh: unexpected argument '${bench_rest[0]}'" >&2; exit 2; }
[[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target clraster_traversal
export POCL_CACHE_DIR="$PWD/build/pocl-cache"
out=$bench_out
mkdir -p "$out"
./build/clraster_traversal --reps "${REPS:-7}" --csv "$out/traversal.csv" --markdown "$out/traversal.md"
echo "traversal.sh: wrote $out/traversal.{csv,md}"
