#!/usr/bin/env bash
# Every problem in problems/ runs as it is and writes the run contract's files.
set -eu
MF="$1"; ROOT="$2"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
for p in "$ROOT"/problems/*.yaml; do
  name="$(basename "$p" .yaml)"
  "$MF" run "$p" --out "$WORK/$name" > "$WORK/$name.log"
  for f in summary.json history.csv fields.h5 fields.xmf; do
    [ -s "$WORK/$name/$f" ] || { echo "FAIL: $name did not write $f"; exit 1; }
  done
  grep -q '"status": "completed"' "$WORK/$name/summary.json" || { echo "FAIL: $name status"; exit 1; }
  echo "ok: $name"
done
