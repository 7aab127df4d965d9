#!/usr/bin/env bash
# micro.sh — the micro-triangle path's size limit for one device, chosen by measurement.
#
#   bash bench/micro.sh [--out DIR | --update-docs] [-n PAIRS] [LIMIT ...]
#
# For each dense case (below) and each LIMIT (default 1 4 16 64), bench/ab.sh runs one clraster_bench build twice
# in alternated turns: the micro path off (--micro-max 0) against on (--micro-max LIMIT), PAIRS pairs (default 12).
# Cases, at 1920x1080: the 16x16 Wuson.off grid (955k triangles) far, in the file's order and shuffled, and its
# visibility alone (--shade id); the same grid near, both orders; the 5x5 grid filling the screen; a 1M-triangle
# sphere far away. Writes micro.csv and micro.md into build/bench, or DIR, or docs/bench with --update-docs
# (bench/common.sh): per case and limit both frame medians, on/off, the pairs in which the limit was faster, and the
# raster and setup_emit stages; then the verdict: the limit with the lowest geometric mean of on/off over the
# cases where that is below 1, else 0 (off). Set it with CLRASTER_MICRO_MAX or FrameSettings::microMax.
# DEVICE picks the device as --device does. On a device without cl_khr_int64_extended_atomics the path cannot
# run: clraster_bench refuses --micro-max and this script stops with that line, writing nothing.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
source bench/common.sh
bench_args bench/micro.sh "$@"
set -- ${bench_rest[@]+"${bench_rest[@]}"}

fail() { echo "bench/micro.sh: $*" >&2; exit 1; }
pairs=12
if [[ "${1:-}" == "-n" ]]; then
  [[ "${2:-}" =~ ^[1-9][0-9]*$ ]] || fail "-n needs a positive number of pairs"
  pairs=$2
  shift 2
fi
limits=("$@")
[[ ${#limits[@]} -gt 0 ]] || limits=(1 4 16 64)
for limit in "${limits[@]}"; do
  [[ "$limit" =~ ^[1-9][0-9]*$ && "$limit" -le 256 ]] || fail "limit '$limit' is not a pixel count in 1..256"
done
grid=/usr/share/assimp/models/OFF/Wuson.off
[[ -r "$grid" ]] || fail "cannot read $grid (assimp-testmodels)"
device_args=()
[[ -n "${DEVICE:-}" ]] && device_args=(--device "$DEVICE")

# Step 1: build.
[[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target clraster_bench >/dev/null || fail "build failed (cmake --build build)"

# Step 2: each case against each limit; ab.sh's lines become one CSV row.
cases=(
  "grid16-far|$grid --grid 16 --view far"
  "shuffled-grid16-far|$grid --grid 16 --view far --shuffle 1"
  "grid16-far-id|$grid --grid 16 --view far --shade id"
  "grid16-near|$grid --grid 16 --view near"
  "shuffled-grid16-near|$grid --grid 16 --view near --shuffle 1"
  "grid5-fill|$grid --grid 5 --view fill"
  "sphere1M-far|--sphere 1000000 --view far"
)
csv=$(mktemp)
trap 'rm -f "$csv"' EXIT
echo "case,limit,off_ms,on_ms,on_off,pairs_faster,pairs,off_raster_ms,on_raster_ms,off_emit_ms,on_emit_ms" >"$csv"
stage() {  # LINE NAME: the stage's median in one of ab.sh's "A frame ..." lines
  sed -n "s/.* $2 \([0-9.]*\).*/\1/p" <<<"$1"
}
for entry in "${cases[@]}"; do
  name=${entry%%|*}
  read -r -a args <<<"${entry#*|}"
  for limit in "${limits[@]}"; do
    echo "bench/micro.sh: $name, limit $limit"
    out=$(AB_ARGS_A="--micro-max 0" AB_ARGS_B="--micro-max $limit" \
      bash bench/ab.sh -n "$pairs" build build "${args[@]}" --size 1920x1080 ${device_args[@]+"${device_args[@]}"} 2>&1) ||
      fail "$name, limit $limit: $(tail -n 1 <<<"$out")"
    a=$(grep '^A frame' <<<"$out") b=$(grep '^B frame' <<<"$out")
    faster=$(sed -n 's/^B lower: frame \([0-9]*\).*/\1/p' <<<"$out")
    off=$(sed -n 's/^A frame \([0-9.]*\) ms.*/\1/p' <<<"$a") on=$(sed -n 's/^B frame \([0-9.]*\) ms.*/\1/p' <<<"$b")
    [[ -n "$off" && -n "$on" && -n "$faster" ]] || fail "$name, limit $limit: bench/ab.sh printed no medians"
    ratio=$(awk -v a="$off" -v b="$on" 'BEGIN { printf "%.3f", b / a }')
    echo "$name,$limit,$off,$on,$ratio,$faster,$pairs,$(stage "$a" raster),$(stage "$b" raster),$(stage "$a" setup_emit),$(stage "$b" setup_emit)" >>"$csv"
  done
done

# Step 3: the verdict and the table.
verdict=$(awk -F, 'NR > 1 { sum[$2] += log($5); n[$2]++ }
  END { best = 0; low = 0; for (l in sum) { g = sum[l] / n[l]; if (g < low) { low = g; best = l } }
        printf "%d %.3f", best, exp(low) }' "$csv")
best=${verdict% *} mean=${verdict#* }
device=$(build/clraster_bench --sphere 12 --frames 1 --warmup 0 --rounds 1 --no-ids ${device_args[@]+"${device_args[@]}"} \
  2>/dev/null | sed -n 's/.*"device":"\([^"]*\)".*/\1/p' || true)
mkdir -p "$bench_out"
cp "$csv" "$bench_out/micro.csv"
{
  echo "# Micro-triangle path: size limit by measurement"
  echo
  echo "Written by \`bash bench/micro.sh\` (bench/ab.sh turns, $pairs pairs per row, 1920x1080)${device:+ on $device}."
  echo "Each row: the same build with the micro path off against on at the limit; on/off < 1 is a gain."
  echo
  echo "| case | limit | off ms | on ms | on/off | pairs on faster | raster off / on | setup_emit off / on |"
  echo "|---|---|---|---|---|---|---|---|"
  awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s of %s | %s / %s | %s / %s |\n", $1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11 }' "$csv"
  echo
  if [[ "$best" == 0 ]]; then
    echo "Verdict: off (0). No limit's geometric mean of on/off over the cases is below 1."
  else
    echo "Verdict: limit $best (geometric mean of on/off over the cases $mean): set CLRASTER_MICRO_MAX=$best."
  fi
} >"$bench_out/micro.md"
echo "bench/micro.sh: $(tail -n 1 "$bench_out/micro.md")"
