#!/usr/bin/env bash
# charts.sh — the two log-log charts of a suite's results.csv: frame time
# against triangle count (sphere series and Wuson grid) and against pixel
# count (real meshes, far view), clraster and llvmpipe side by side. run.sh
# calls it; on its own it draws the charts of results written on a machine
# without gnuplot (run.sh with BENCH_CHARTS=0).
#
#   bash bench/charts.sh RESULTS.csv DIR
#
# Writes DIR/scaling_triangles.png and DIR/scaling_pixels.png; the charts'
# titles name clraster's device (the CSV's device column). Exits non-zero
# with a message when the CSV cannot be read or gnuplot fails.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
csv="$1"
dir="$2"
[[ -r "$csv" ]] || { echo "bench/charts.sh: cannot read '$csv'" >&2; exit 1; }
mkdir -p "$dir"
data=$(mktemp -d)
trap 'rm -rf "$data"' EXIT
columns='NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next } '

# Step 1: the series, as bench/plots.gnuplot reads them.
series() {  # PATTERN: triangles, pixels, clraster ms, llvmpipe ms of the matching cases
  awk -F, -v pattern="$1" "$columns"'$c["name"] ~ pattern { print $c["triangles"], $c["pixels"], $c["clr_ms"], $c["llvm_ms"] }' "$csv"
}
series '^sphere-far$' >"$data/sphere_far.dat"
series '^sphere-near$' >"$data/sphere_near.dat"
series '^grid16-far$' >"$data/grid_far.dat"
series '^grid16-near$' >"$data/grid_near.dat"
# One block per mesh (two blank lines apart), its name on the block's first line.
awk -F, "$columns"'$c["name"] ~ /^mesh-/ {
    name = substr($c["name"], 6)
    if (!(name in seen)) { seen[name] = ++n; order[n] = name }
    rows[name] = rows[name] $c["pixels"] " " $c["clr_ms"] " " $c["llvm_ms"] "\n"
  }
  END { for (i = 1; i <= n; ++i) printf "%s%s\n%s", (i > 1 ? "\n\n" : ""), order[i], rows[order[i]] }' "$csv" >"$data/meshes.dat"
mesh_count=$(awk -F, "$columns"'$c["name"] ~ /^mesh-/ && !($c["name"] in seen) { seen[$c["name"]]; ++n } END { print n + 0 }' "$csv")
device=$(awk -F, "$columns"'NR == 2 { print $c["device"] }' "$csv" | tr -d "'\"")

# Step 2: draw.
gnuplot -e "dir='$data'; meshes=$mesh_count; device='$device'" bench/plots.gnuplot ||
  { echo "bench/charts.sh: gnuplot failed" >&2; exit 1; }
cp "$data/scaling_triangles.png" "$data/scaling_pixels.png" "$dir/"
