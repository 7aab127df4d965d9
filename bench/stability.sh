#!/usr/bin/env bash
# stability.sh — where the methods fail: the coordinate-magnitude chart and
# the load cases, on a Debian 12 machine with the packages of
# scripts/bootstrap.sh (gnuplot-nox among them).
#
#   bash bench/stability.sh [--out DIR | --update-docs] [coords] [load]   (both when none is named)
#
# Writes into build/bench, or DIR, or docs/bench with --update-docs
# (bench/common.sh).
#
# coords: clraster_stability coords renders a shared-edge band mesh
# (tests/stability_scenes.h) at 512x512 with 64 bands and 3 seeds, at reaches
# from the smallest that covers the viewport to the guard band and on to
# 2^24 px (clipped), with fixed-point and float edge functions, exact spans
# and the float edge walk, and counts cracked pixels (holes and double
# hits); then clraster_stability walk counts them on slivers (band meshes
# of 8 to 2048 bands reaching 4096 px), flat-top and flat-bottom triangles
# and triangles one of whose halves after the split is 1-16/256 px tall.
# About 60 s. Writes into build/bench, or DIR, or docs/bench with
# --update-docs (bench/common.sh), replacing earlier results:
#   stability_coords.csv  one row per reach and method
#   stability_walk.csv    one row per case and method
#   stability_coords.png  cracked pixels against magnitude and against
#                         sliver aspect
# load: 10 million triangles in one 16x16 tile and 4000 full-screen
# triangles at 1920x1080; one JSON line each (bin entries against the
# expected count, pixels differing from the oracle, device bytes, frame time)
# to stability_load.jsonl. About 45 s and 4 GB of memory.
# Environment: TRIS (default 10000000), FULLSCREEN (default 4000).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source bench/common.sh
bench_args bench/stability.sh "$@"
parts=(${bench_rest[@]+"${bench_rest[@]}"})
((${#parts[@]})) || parts=(coords load)
[[ " ${parts[*]} " != *" coords "* ]] || need_gnuplot bench/stability.sh
[[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" --target clraster_stability
export POCL_CACHE_DIR="$PWD/build/pocl-cache"
out=$bench_out
mkdir -p "$out"
for part in "${parts[@]}"; do
  case "$part" in
    coords)
      ./build/clraster_stability coords --size 512x512 --bands 64 --seeds 3 --csv "$out/stability_coords.csv"
      ./build/clraster_stability walk --size 512x512 --seeds 3 --csv "$out/stability_walk.csv"
      gnuplot -e "dir='$out'" bench/stability_coords.gnuplot
      echo "stability.sh: wrote $out/stability_coords.{csv,png} and $out/stability_walk.csv"
      ;;
    load)
      ./build/clraster_stability load --tris "${TRIS:-10000000}" --fullscreen "${FULLSCREEN:-4000}" \
        | tee "$out/stability_load.jsonl"
      echo "stability.sh: wrote $out/stability_load.jsonl"
      ;;
    *) echo "stability.sh: unknown part '$part' (coords, load)" >&2; exit 1 ;;
  esac
done
