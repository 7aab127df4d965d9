#!/usr/bin/env bash
# ab.sh — two builds of clraster on one benchmark case, in alternated pairs.
#
#   bash bench/ab.sh [-n PAIRS] DIR_A DIR_B [clraster_bench arguments]
#
# DIR_A and DIR_B each hold a built clraster_bench (a build folder, or a copy
# of one); the arguments name the case as clraster_bench takes them (default:
# the built-in scene at 1920x1080), and --no-ids --rounds 1 are added. Runs
# PAIRS pairs (default 8) in ABBA order (A B, B A, A B, ...), so that a
# slower spell of the shared host falls on both builds alike, and prints per
# build the median over its runs of the frame (clr_ms) and of each kernel
# stage, then in how many pairs B's frame was lower. On the 2-core
# development machine two runs of one build differ by 5-10% in a stage's
# median and more in slow spells, so a change of a few per cent needs eight
# or ten pairs, and an A/A run (the same folder twice) shows the spread.
# Each build runs from a private copy, with its own PoCL kernel cache, and
# PoCL's workers pinned (POCL_AFFINITY=1, as bench/run.sh).
set -euo pipefail

fail() { echo "bench/ab.sh: $*" >&2; exit 1; }
pairs=8
if [[ "${1:-}" == "-n" ]]; then
  [[ "${2:-}" =~ ^[1-9][0-9]*$ ]] || fail "-n needs a positive number of pairs"
  pairs=$2
  shift 2
fi
[[ $# -ge 2 ]] || fail "usage: bash bench/ab.sh [-n PAIRS] DIR_A DIR_B [clraster_bench arguments]"
dir_a=$1 dir_b=$2
shift 2
for dir in "$dir_a" "$dir_b"; do
  [[ -x "$dir/clraster_bench" ]] || fail "no $dir/clraster_bench"
done

# Step 1: private copies (a rebuild meanwhile cannot change what is measured).
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/A/cache" "$work/B/cache"
cp "$dir_a/clraster_bench" "$work/A/"
cp "$dir_b/clraster_bench" "$work/B/"
export POCL_AFFINITY="${POCL_AFFINITY:-1}"

# Step 2: the pairs, each run one line "build clr_ms stage=ms ...".
run() {  # BUILD ARGS...: one run of the case, its line appended to results
  local build=$1 json frame stages
  shift
  json=$(POCL_CACHE_DIR="$work/$build/cache" "$work/$build/clraster_bench" "$@" --no-ids --rounds 1 2>"$work/err") ||
    { cat "$work/err" >&2; fail "build $build: clraster_bench failed"; }
  json=$(tail -n 1 <<<"$json")
  frame=$(sed -n 's/.*"clr_ms":\([0-9.]*\).*/\1/p' <<<"$json")
  stages=$(sed -n 's/.*"stage_ms":{\([^}]*\)}.*/\1/p' <<<"$json" | tr -d '"' | tr ',:' ' =')
  [[ -n "$frame" ]] || fail "build $build: no clr_ms in the bench's output"
  echo "$build $frame $stages" >>"$work/results"
}
for ((i = 0; i < pairs; ++i)); do
  if ((i % 2 == 0)); then first=A second=B; else first=B second=A; fi
  run "$first" "$@"
  run "$second" "$@"
done

# Step 3: medians per build, and the pairs B won.
awk -v pairs="$pairs" '
  function median(list, n,    v, i, j, t) {
    split(list, v, " ")
    for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (v[j] + 0 < v[i] + 0) { t = v[i]; v[i] = v[j]; v[j] = t }
    return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
  }
  {
    b = $1; ++runs[b]; frames[b] = frames[b] " " $2; last[b] = $2
    for (f = 3; f <= NF; ++f) { split($f, kv, "="); names[kv[1]] = 1; stage[b, kv[1]] = stage[b, kv[1]] " " kv[2] }
    if (runs["A"] == runs["B"]) won += last["B"] < last["A"]
  }
  END {
    n = 0
    for (s in names) sorted[++n] = s
    for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (sorted[j] < sorted[i]) { t = sorted[i]; sorted[i] = sorted[j]; sorted[j] = t }
    for (b = 0; b < 2; ++b) {
      build = b ? "B" : "A"
      line = sprintf("%s frame %.3f ms", build, median(frames[build], runs[build]))
      for (i = 1; i <= n; ++i) line = line sprintf(", %s %.3f", sorted[i], median(stage[build, sorted[i]], runs[build]))
      print line
    }
    printf "B frame lower in %d of %d pairs\n", won, pairs
  }' "$work/results"
