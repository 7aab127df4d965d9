#!/usr/bin/env bash
# oclgrind_check.sh — runs part of the kernel unit tests under Oclgrind and
# fails on any error it reports (out-of-bounds access, data race, invalid
# instruction), not only on a failed assertion.
#
#   tests/oclgrind_check.sh TESTS_BINARY LANES PART
#
# LANES (1 or 16) picks the kernels' work shape (CLRASTER_LANES). The parts
# together are the small crafted kernel tests (no differential or watertight
# scenes, nor resolve's prefetch test, a 125,000-triangle grid whose
# prefetch only PoCL's build has); each test case is in exactly one part, so
# CTest runs them side by side. The one-pixel-per-work-item shape is
# interpreted work-item by work-item, much slower, so there the
# 20,000-triangle binning test is left out. The few larger cases take their
# smallest sizes that reach the same paths when the device is Oclgrind
# (test::underOclgrind; docs/testing.md, "Oclgrind", lists them).
#   geometry           transform, near-plane clipping, setup, the scan (and binning, LANES 16)
#   raster             the raster kernels: fill rule, z-test, MSAA, hierarchical, float edges, the micro path
#   resolve            resolve and the shading modes
#   texture_lines_aov  texture sampling, lines and wireframe, the AOV kernel
set -euo pipefail
binary="$1"
lanes="$2"
part="$3"
case "$part" in
  geometry)
    filter="[transform],[setup],[scan],[clip]~[differential]~[watertight]"
    [[ "$lanes" == 16 ]] && filter="$filter,[bin]"
    ;;
  raster) filter="[raster]~[differential]" ;;
  resolve) filter="[resolve]~[prefetch],[shade]~[aa]" ;;
  texture_lines_aov) filter="[texture]~[cli],[lines],[aov]~[cli]" ;;
  *) echo "oclgrind_check.sh: unknown part '$part' (geometry, raster, resolve, texture_lines_aov)" >&2; exit 2 ;;
esac
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
# 48 KB of local memory, as the GPUs clraster targets have (NVIDIA's per-block
# limit): the one-pixel span kernel needs more than OpenCL's 32 KB minimum
# (docs/limits.md, "Span tables").
CLRASTER_LANES="$lanes" oclgrind --data-races --local-mem-size 49152 --log "$log" "$binary" "$filter"
if [[ -s "$log" ]]; then
  echo "oclgrind reported errors (CLRASTER_LANES=$lanes, $part):" >&2
  head -n 60 "$log" >&2
  exit 1
fi
echo "oclgrind: no errors (CLRASTER_LANES=$lanes, $part)"
