#!/usr/bin/env bash
# sanitize.sh — builds the host code and tests with AddressSanitizer and
# UndefinedBehaviorSanitizer in their own build folder and runs every test
# case there; any report fails the run.
#
#   tests/sanitize.sh SOURCE_DIR BUILD_DIR
#
# Leak checking is off: the OpenCL runtime and the tests' shared context are
# deliberately not torn down at exit. The test cases tagged [rlimit] run the
# CLI under an address-space limit (ulimit -v), which AddressSanitizer's
# shadow memory (terabytes of reserved address space) cannot start under:
# they run in the plain build only, and this script says how many it leaves.
set -euo pipefail
source_dir="$1"
build_dir="$2"
cmake -S "$source_dir" -B "$build_dir" -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer" >/dev/null
cmake --build "$build_dir" -j "$(nproc)" --target clraster clraster_tests
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
echo "sanitize: $("$build_dir/tests/clraster_tests" "[rlimit]" --list-test-names-only | grep -c .) test cases" \
  "tagged [rlimit] run in the plain build only (an address-space limit leaves ASan no room)"
"$build_dir/tests/clraster_tests" "~[rlimit]"
