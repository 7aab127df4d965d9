#!/usr/bin/env bash
# views.sh — many views in one `clraster render --views` run against one `clraster render` process per view.
#
#   bash bench/views.sh [SCENE]
#
# Builds clraster in build/ (configuring it when there is none), writes a views file of VIEWS cameras on a
# circle around the scene (the built-in scene without SCENE), then times, REPEATS times each and alternating:
#   one run     clraster render SCENE --views views.json -o one/out_%04d.png
#   separate    VIEWS processes clraster render SCENE -o sep/out_NNNN.png
#               --eye ... --target ..., one after the other
# Both write every PNG (through the same temp-file + rename writer) and use a warm PoCL kernel cache. It
# checks that the two sets of images are identical, and prints the median wall time of each, the ratio and the
# per-view times. Environment: VIEWS (default 100), REPEATS (3), SIZE (1280x720).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

views="${VIEWS:-100}"
repeats="${REPEATS:-3}"
size="${SIZE:-1280x720}"
scene=("$@")
export POCL_CACHE_DIR="$PWD/build/pocl-cache"
fail() { echo "bench/views.sh: $*" >&2; exit 1; }

# Step 1: build, and a private copy of the binary (a rebuild meanwhile cannot
# change what is measured).
[[ -f build/CMakeCache.txt ]] || cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target clraster >/dev/null || fail "build failed"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp build/clraster "$work/clraster"

# Step 2: the cameras, on a circle around the scene's centre, as a views file
# and as command lines with the same numbers.
awk -v n="$views" -v dir="$work" 'BEGIN {
  pi = 3.14159265358979
  printf "{\"views\": [\n" > (dir "/views.json")
  for (i = 0; i < n; ++i) {
    a = 2 * pi * i / n
    eye = sprintf("%.4f,%.4f,%.4f", 8 * cos(a), 3.5 + sin(3 * a), 8 * sin(a))
    printf "  {\"eye\": [%s], \"target\": [0, -0.6, 0]}%s\n", eye, (i + 1 < n ? "," : "") > (dir "/views.json")
    print eye > (dir "/eyes.txt")
  }
  printf "]}\n" > (dir "/views.json")
}'
mkdir "$work/one" "$work/sep"

# Step 3: the timings, alternating the two ways.
now() { date +%s.%N; }
one_run() {
  "$work/clraster" render "${scene[@]}" --views "$work/views.json" -o "$work/one/out_%04d.png" --size "$size" \
    --stats >"$work/stats.json" || fail "the --views run failed"
}
separate_runs() {
  local i=0 eye
  while read -r eye; do
    "$work/clraster" render "${scene[@]}" -o "$(printf '%s/sep/out_%04d.png' "$work" "$i")" --size "$size" \
      --eye "$eye" --target 0,-0.6,0 || fail "separate run $i failed"
    i=$((i + 1))
  done <"$work/eyes.txt"
}
one_s=() sep_s=()
for ((r = 1; r <= repeats; ++r)); do
  start=$(now); one_run; end=$(now)
  one_s+=("$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')")
  start=$(now); separate_runs; end=$(now)
  sep_s+=("$(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.3f", b - a }')")
  echo "bench/views.sh: repetition $r: one run ${one_s[-1]} s, separate runs ${sep_s[-1]} s"
done

# Step 4: the same images both ways, then the report.
for f in "$work"/sep/out_*.png; do
  cmp -s "$f" "$work/one/$(basename "$f")" || fail "$(basename "$f") differs between the two ways"
done
count=$(ls "$work"/one | wc -l)
[[ "$count" == "$views" ]] || fail "the --views run wrote $count files, not $views"
median() { printf '%s\n' "$@" | sort -n | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }'; }
one_med=$(median "${one_s[@]}")
sep_med=$(median "${sep_s[@]}")
echo "bench/views.sh: $views views of ${scene[*]:-the built-in scene} at $size, median of $repeats," \
  "$(nproc) cores, $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1)"
awk -v n="$views" -v o="$one_med" -v s="$sep_med" 'BEGIN {
  printf "  %-22s %7.2f s  (%6.1f ms per view)\n", "one --views run:", o, 1000 * o / n
  printf "  %-22s %7.2f s  (%6.1f ms per view)\n", n " separate runs:", s, 1000 * s / n
  printf "  ratio separate / one: %.2f\n", s / o
}'
echo "  last --views run's stats: $(cat "$work/stats.json")"
