#!/usr/bin/env bash
# comment_density.sh — comments are contracts and reasons, not logs.
#
#   tests/comment_density.sh SOURCE_DIR
#
# Fails (exit 1, one line per offence) if any kernels/*.cl or kernels/*.h has
# comment lines >= half its code lines, or if a comment in kernels/ or host/
# (whole-line or trailing) quotes a time in milliseconds. A comment line
# starts, after whitespace, with //, /*, */ or "* " (a lone * too; not *ptr);
# a code line is any other non-blank line. Prints every kernel file's counts.
set -euo pipefail
src="${1:?usage: comment_density.sh SOURCE_DIR}"
[[ -d "$src/kernels" ]] || { echo "comment_density: no kernels/ under $src" >&2; exit 2; }
comment_re='^[[:space:]]*(//|/\*|\*/|\*([[:space:]]|$))'
shopt -s nullglob
kernel_files=("$src"/kernels/*.cl "$src"/kernels/*.h)
((${#kernel_files[@]})) || { echo "comment_density: no kernel files under $src/kernels" >&2; exit 2; }
fail=0
for f in "${kernel_files[@]}"; do
  comments=$(grep -cE "$comment_re" "$f" || true)
  code=$(grep -vE "$comment_re" "$f" | grep -cE '[^[:space:]]' || true)
  printf '%-28s %4d comment / %4d code\n' "kernels/${f##*/}" "$comments" "$code"
  if ((2 * comments >= code)); then
    echo "FAIL kernels/${f##*/}: $comments comment lines >= half of $code code lines" >&2
    fail=1
  fi
done
for f in "$src"/kernels/* "$src"/host/*/*; do
  if hits=$(grep -nE "($comment_re|//|/\*).*[0-9][0-9.]* ?ms\b" "$f"); then
    while IFS= read -r hit; do
      echo "FAIL ${f#"$src"/}:${hit%%:*}: comment quotes a time in ms" >&2
    done <<<"$hits"
    fail=1
  fi
done
exit "$fail"
