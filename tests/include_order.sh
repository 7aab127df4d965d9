#!/usr/bin/env bash
# include_order.sh — host/ is a house of rooms with one direction of arrows.
#
#   tests/include_order.sh SOURCE_DIR
#   tests/include_order.sh --plant SOURCE_DIR   the check must fail on a copy of
#                                               host/ where io includes api
#
# Rooms, lowest first: base io pipeline render api cli. A file in host/ROOM/
# may include "ROOM2/NAME.h" only where ROOM2 is ROOM or below it, and
# "kernels/NAME.h" (the host/device shared structs) from any room; a quoted
# include without a room, or one that climbs with "../", is refused, and so
# is any source file at host/'s top level or in a folder that is no room.
# Exit 1 with one line per offence; 0 when the house is in order.
set -euo pipefail
if [[ "${1:-}" == --plant ]]; then
  src="${2:?usage: include_order.sh --plant SOURCE_DIR}"
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  cp -r "$src/host" "$tmp/host"
  echo '#include "api/api_impl.h"' >>"$tmp/host/io/scene.h"
  if out=$(bash "$0" "$tmp" 2>&1); then
    echo "include_order: a planted include from io to api passed the check" >&2; exit 1
  fi
  grep -q 'host/io/scene.h:.*runs from io up to api' <<<"$out" || { echo "unexpected: $out" >&2; exit 1; }
  echo "include_order: the planted reverse include is caught: $out"
  exit 0
fi
src="${1:?usage: include_order.sh SOURCE_DIR}"
rooms=(base io pipeline render api cli)
declare -A rank
for i in "${!rooms[@]}"; do rank[${rooms[$i]}]=$i; done
shopt -s nullglob
fail=0
for f in "$src"/host/*; do
  [[ -f "$f" ]] && { echo "FAIL host/${f##*/}: source file at host/'s top level" >&2; fail=1; }
done
checked=0
for dir in "$src"/host/*/; do
  room=$(basename "$dir")
  if [[ -z "${rank[$room]+x}" ]]; then
    echo "FAIL host/$room/: not a room (${rooms[*]})" >&2; fail=1; continue
  fi
  for f in "$dir"*.cpp "$dir"*.h; do
    checked=$((checked + 1))
    while IFS=: read -r line target; do
      rel="host/$room/${f##*/}:$line"
      case "$target" in
        kernels/*) continue ;;
        ../* | */../*) echo "FAIL $rel: include \"$target\" climbs with ../" >&2; fail=1; continue ;;
        */*) ;;
        *) echo "FAIL $rel: include \"$target\" names no room" >&2; fail=1; continue ;;
      esac
      to=${target%%/*}
      if [[ -z "${rank[$to]+x}" ]]; then
        echo "FAIL $rel: include \"$target\": '$to' is not a room" >&2; fail=1
      elif ((rank[$to] > rank[$room])); then
        echo "FAIL $rel: include \"$target\" runs from $room up to $to" >&2; fail=1
      elif [[ ! -f "$src/host/$target" ]]; then
        echo "FAIL $rel: include \"$target\" names no file" >&2; fail=1
      fi
    done < <(grep -nE '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$f" | sed -E 's/^([0-9]+):.*"([^"]+)".*/\1:\2/')
  done
done
((checked > 0)) || { echo "include_order: no source files under $src/host" >&2; exit 2; }
((fail == 0)) && echo "include_order: $checked files in ${#rooms[@]} rooms, every include runs downwards"
exit "$fail"
