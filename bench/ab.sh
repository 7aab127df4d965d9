#!/usr/bin/env bash
# ab.sh — two builds of clraster on one benchmark case, frame turns alternated.
#
#   bash bench/ab.sh [-n PAIRS] DIR_A DIR_B [clraster_bench arguments]
#
# DIR_A and DIR_B each hold a built clraster_bench (a build folder, or a copy of one); the arguments name the
# case as clraster_bench takes them (default: the built-in scene at 1920x1080), and --no-ids --serve are added
# (so --shade MODE, which only --serve takes, compares another shading mode). Both builds load the case once,
# in two processes side by side, then take turns (clraster_bench --serve): PAIRS pairs of turns (default 40)
# in ABBA order (A B, B A, A B, ...), each turn --warmup untimed frames (default 1) and --frames timed ones
# (default 3) while the other process waits. Turns of a few frames put both builds in the same spell of a
# shared, noisy host, where alternating whole runs needs many more pairs to resolve a change of a few per
# cent. Prints per build the median over its turns of the frame and of each kernel stage, then in how many
# pairs B's frame, and each stage, was lower. An A/A run (the same folder twice) shows the host's spread;
# trust only a difference beyond it. Frames follow the other build's frame rather than their own, so the
# caches hold less of their data than in clraster_bench's own runs: compare the two builds here, not these
# times with the suite's. Each build runs from a private copy, with its own PoCL kernel cache, and PoCL's
# workers pinned (POCL_AFFINITY=1, as bench/run.sh).
# AB_ARGS_A and AB_ARGS_B (words, split on spaces) go to one build only: the same build twice with
# AB_ARGS_A=--no-layout compares the scene's layout with the file's order.
set -euo pipefail

fail() { echo "bench/ab.sh: $*" >&2; exit 1; }
pairs=40
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

# Step 2: both servers, each loading the case and its kernels.
for build in A B; do
  mkfifo "$work/$build.in" "$work/$build.out"
  extra="AB_ARGS_$build"
  # shellcheck disable=SC2086 # (words on purpose)
  POCL_CACHE_DIR="$work/$build/cache" "$work/$build/clraster_bench" --warmup 1 --frames 3 "$@" ${!extra:-} --no-ids --serve \
    <"$work/$build.in" >"$work/$build.out" 2>"$work/$build.err" &
done
exec {to_a}>"$work/A.in" {from_a}<"$work/A.out" {to_b}>"$work/B.in" {from_b}<"$work/B.out"
trap '' PIPE  # a server that stopped fails its write, reported below
line=
ask() {  # BUILD REQUEST: sends REQUEST (none: only reads) and reads the server's reply into line
  local to=$to_a from=$from_a
  [[ $1 == B ]] && to=$to_b from=$from_b
  if [[ -n $2 ]]; then echo "$2" >&"$to" 2>/dev/null || { cat "$work/$1.err" >&2; fail "build $1: clraster_bench --serve stopped"; }; fi
  IFS= read -r -u "$from" line || { cat "$work/$1.err" >&2; fail "build $1: clraster_bench --serve stopped"; }
}
for build in A B; do
  ask "$build" ""
  [[ $line == ready ]] || fail "build $build: clraster_bench --serve said '$line', not ready"
done

# Step 3: the pairs of turns, each turn one line "build frame=ms stage=ms ...".
turn() {  # BUILD
  ask "$1" turn
  echo "$1 $line" >>"$work/results"
}
for ((i = 0; i < pairs; ++i)); do
  if ((i % 2 == 0)); then turn A; turn B; else turn B; turn A; fi
done
exec {to_a}>&- {to_b}>&-
wait

# Step 4: medians per build, and the pairs in which B was lower.
awk -v pairs="$pairs" '
  function median(list, n,    v, i, j, t) {
    split(list, v, " ")
    for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (v[j] + 0 < v[i] + 0) { t = v[i]; v[i] = v[j]; v[j] = t }
    return n % 2 ? v[(n + 1) / 2] : (v[n / 2] + v[n / 2 + 1]) / 2
  }
  {
    b = $1; ++turns[b]
    for (f = 2; f <= NF; ++f) { split($f, kv, "="); names[kv[1]] = 1; values[b, kv[1]] = values[b, kv[1]] " " kv[2]; last[b, kv[1]] = kv[2] }
    if (turns["A"] == turns["B"]) for (s in names) lower[s] += last["B", s] + 0 < last["A", s] + 0
  }
  END {
    n = 0
    for (s in names) if (s != "frame") sorted[++n] = s
    for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (sorted[j] < sorted[i]) { t = sorted[i]; sorted[i] = sorted[j]; sorted[j] = t }
    for (b = 0; b < 2; ++b) {
      build = b ? "B" : "A"
      line = sprintf("%s frame %.3f ms", build, median(values[build, "frame"], turns[build]))
      for (i = 1; i <= n; ++i) line = line sprintf(", %s %.3f", sorted[i], median(values[build, sorted[i]], turns[build]))
      print line
    }
    line = sprintf("B lower: frame %d", lower["frame"])
    for (i = 1; i <= n; ++i) line = line sprintf(", %s %d", sorted[i], lower[sorted[i]])
    printf "%s of %d pairs\n", line, pairs
  }' "$work/results"
