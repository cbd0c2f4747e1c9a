#!/usr/bin/env bash
# Every problem in problems/ runs as it is and writes the run contract's files.
set -eu
MF="$1"; ROOT="$2"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
for p in "$ROOT"/problems/*.yaml; do
  name="$(basename "$p" .yaml)"
  extra=()
  # Explicit dynamics runs take minutes to their end time (scripts/pd_*_study.py and the pd
  # tests run them in full): here the first 2% of it shows that they run as they are.
  if grep -qE '^analysis: (peridynamics|sph)' "$p"; then
    end="$(sed -n 's/^time: {end: \([^,}]*\).*/\1/p' "$p")"
    extra=(--set "time.end=$(awk -v e="$end" 'BEGIN { printf "%.6g", 0.02 * e }')")
  fi
  # A staged run: the preload in full, the explicit stage (the second) over 2% of its end time
  # and of its settle time.
  if grep -qE '^analysis: staged' "$p"; then
    for key in time settle; do
      value="$(sed -n "s/^    $key: {[a-z]*: *\([^,}]*\).*/\1/p" "$p" | head -1)"
      field="$([ $key = time ] && echo end || echo time)"
      [ -n "$value" ] && extra+=(--set "stages.1.$key.$field=$(awk -v e="$value" 'BEGIN { printf "%.6g", 0.02 * e }')")
    done
  fi
  "$MF" run "$p" --out "$WORK/$name" "${extra[@]}" > "$WORK/$name.log"
  for f in summary.json history.csv fields.h5 fields.xmf; do
    [ -s "$WORK/$name/$f" ] || { echo "FAIL: $name did not write $f"; exit 1; }
  done
  grep -q '"status": "completed"' "$WORK/$name/summary.json" || { echo "FAIL: $name status"; exit 1; }
  echo "ok: $name"
done
