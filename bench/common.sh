# common.sh — sourced by the bench scripts that write results: where they go,
# and the check for gnuplot (installed by scripts/bootstrap.sh, never here).
#
# bench_args NAME ARGS...: takes `--out DIR` and `--update-docs` out of ARGS
# and sets bench_out to DIR, to docs/bench with --update-docs, or else to
# $BENCH_OUT or build/bench; bench_rest holds the other arguments in order.
# Only --update-docs (or a DIR naming it) rewrites the tracked docs/bench.
bench_args() {
  local name=$1 given=""
  shift
  bench_out="${BENCH_OUT:-build/bench}"
  bench_rest=()
  while (($#)); do
    case "$1" in
      --out)
        [[ $# -ge 2 && -n "$2" ]] || { echo "$name: --out needs a folder" >&2; exit 2; }
        [[ -z "$given" ]] || { echo "$name: give one of --out and --update-docs" >&2; exit 2; }
        bench_out=$2 given=--out
        shift 2
        ;;
      --update-docs)
        [[ -z "$given" ]] || { echo "$name: give one of --out and --update-docs" >&2; exit 2; }
        bench_out=docs/bench given=--update-docs
        shift
        ;;
      *)
        bench_rest+=("$1")
        shift
        ;;
    esac
  done
  echo "$name: results go to $bench_out/"
}

# need_gnuplot NAME: fails with one line when gnuplot is missing.
need_gnuplot() {
  command -v gnuplot >/dev/null ||
    { echo "$1: gnuplot not found; install gnuplot-nox (scripts/bootstrap.sh does)" >&2; exit 1; }
}
