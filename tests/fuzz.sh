#!/usr/bin/env bash
# fuzz.sh — builds tests/fuzz_load.cpp (libFuzzer, AddressSanitizer, UndefinedBehaviorSanitizer) with clang in
# a build folder of its own and runs the model loading path on hostile input. A crash, a sanitizer report, a
# leak, an input slower than 10 s or one that takes over 2 GiB fails the run; libFuzzer leaves the input in
# BUILD_DIR/artifacts.
#
#   tests/fuzz.sh SOURCE_DIR BUILD_DIR [SECONDS]
#
# SECONDS 0 (what CTest runs) replays tests/fuzz_corpus once: the seeds and every input that ever crashed or
# hung, a deterministic regression test. SECONDS > 0 fuzzes from there for that long (default 60), with the
# random seed FUZZ_SEED when set: run it by hand to look for new problems, then guard them and add the inputs
# to the corpus. CTest only replays: libFuzzer runs are not reproducible, and memory errors inside assimp that
# no single input reproduces would make a fuzzing test flaky. New inputs go to BUILD_DIR/corpus, which starts
# empty on every run.
set -euo pipefail
source_dir="$1"
build_dir="$2"
seconds="${3:-60}"
cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER="${CXX:-clang++}" -DCLRASTER_FUZZ=ON >/dev/null
cmake --build "$build_dir" --target fuzz_load -j "$(nproc)"
rm -rf "$build_dir/corpus" "$build_dir/scratch"
mkdir -p "$build_dir/corpus" "$build_dir/scratch" "$build_dir/artifacts"
export FUZZ_LOAD_TMPDIR="$build_dir/scratch"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1
export LSAN_OPTIONS="suppressions=$source_dir/tests/fuzz_lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
if [[ "$seconds" == 0 ]]; then
  limit=(-runs=0)
else
  limit=(-max_total_time="$seconds")
  [[ -n "${FUZZ_SEED:-}" ]] && limit+=(-seed="$FUZZ_SEED")
fi
"$build_dir/tests/fuzz_load" "${limit[@]}" -timeout=10 -rss_limit_mb=2048 \
  -dict="$source_dir/tests/fuzz_load.dict" -artifact_prefix="$build_dir/artifacts/" -print_final_stats=1 \
  "$build_dir/corpus" "$source_dir/tests/fuzz_corpus"
