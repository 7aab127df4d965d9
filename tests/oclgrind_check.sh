#!/usr/bin/env bash
# oclgrind_check.sh — runs the kernel unit tests under Oclgrind and fails on
# any error it reports (out-of-bounds access, data race, invalid
# instruction), not only on a failed assertion.
#
#   tests/oclgrind_check.sh TESTS_BINARY LANES
#
# LANES (1 or 16) picks the kernels' work shape (CLRASTER_LANES). The filter
# keeps to the small crafted kernel tests (no differential or watertight
# scenes, nor resolve's prefetch test, a 125,000-triangle grid whose
# prefetch only PoCL's build has), so a run stays short. The
# one-pixel-per-work-item shape is interpreted work-item by work-item, much
# slower, so there the 20,000-triangle binning test is left out too.
set -euo pipefail
binary="$1"
lanes="$2"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
filter="[transform],[setup],[scan],[raster]~[differential],[clip]~[differential]~[watertight],[resolve]~[prefetch],[shade]~[aa],[texture]~[cli],[lines],[aov]~[cli]"
[[ "$lanes" == 16 ]] && filter="$filter,[bin]"
CLRASTER_LANES="$lanes" oclgrind --data-races --log "$log" "$binary" "$filter"
if [[ -s "$log" ]]; then
  echo "oclgrind reported errors (CLRASTER_LANES=$lanes):" >&2
  head -n 60 "$log" >&2
  exit 1
fi
echo "oclgrind: no errors (CLRASTER_LANES=$lanes)"
