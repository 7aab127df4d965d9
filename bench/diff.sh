#!/usr/bin/env bash
# diff.sh — clraster.torch's speed on the nvdiffrast sample ports: forward
# and backward time per iteration of pose, cube and earth at 256x256 and
# 512x512, the split per operation (forward/backward ms and their ratio),
# and instanced rasterize of 8 views against one, per image.
#
#   bash bench/diff.sh [BUILD_DIR] [diff_bench.py arguments]
#
# Needs the Python module built in BUILD_DIR (default build) and
# python3-torch. Wall-clock times on a shared machine are noisy: compare
# within one run, and repeat it.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$(cd "${1:-$here/../build}" && pwd)"
shift $(($# > 0 ? 1 : 0))
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$build/pocl-cache}"
PYTHONPATH="$build/python" exec /usr/bin/python3 "$here/diff_bench.py" "$@"
