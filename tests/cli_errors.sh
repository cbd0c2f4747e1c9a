#!/usr/bin/env bash
# Bad input: one clear message naming the key, a non-zero exit, and no result files left.
set -u
MF="$1"; ROOT="$2"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
fails=0
expect_error() { # expect_error "message fragment" args...
  local want="$1"; shift
  local out="$WORK/out"
  rm -rf "$out"
  msg="$("$MF" run "$@" --out "$out" 2>&1 >/dev/null)"; rc=$?
  if [ $rc -eq 0 ]; then echo "FAIL (exit 0): $*"; fails=$((fails+1)); return; fi
  if ! grep -qF -- "$want" <<<"$msg"; then echo "FAIL (message '$msg' lacks '$want'): $*"; fails=$((fails+1)); return; fi
  if [ -n "$(ls -A "$out" 2>/dev/null)" ]; then echo "FAIL (left files in $out): $*"; fails=$((fails+1)); return; fi
  echo "ok: $want"
}
P="$ROOT/problems/plate_tension.yaml"
expect_error "discretisation.spacing: expected a positive number, got -0.1" "$P" --set discretisation.spacing=-0.1
expect_error "material.E: expected a number, got steel" "$P" --set material.E=steel
expect_error "discretisation.colour: unknown key" "$P" --set discretisation.colour=red
expect_error "boundary[0].on: selects no part of the boundary" "$P" --set 'boundary.0.on={edge: bottom, box: [[5, 5], [6, 6]]}'
expect_error "boundary[1].on: no boundary piece is named 'roof'" "$P" --set boundary.1.on=roof
expect_error "cannot open the problem file" "$WORK/missing.yaml"
expect_error "--set boundary.x: 'x' indexes a list and must be a number" "$P" --set boundary.x=1
expect_error "--set name.foo: 'name' holds a single value" "$P" --set name.foo=1
expect_error "boundary[0].on.edges: expected a list of boundary names" "$P" --set 'boundary.0.on={edges: [{a: 1}]}'
expect_error "output.lines[1].name: another line is named 'y07'" "$P" --set 'output.lines.1.name=y07'
expect_error "output.lines[0].from: no sample point of the line lies in the body" "$P" --set 'output.lines.0.from=[5, 5]' --set 'output.lines.0.to=[6, 6]'
expect_error "geometry.holes[0].center: the hole 'hole0' does not cut the body" "$P" --set 'geometry.holes=[{center: [5, 5], radius: 0.1}]'
expect_error "geometry.holes[0].radius: the hole covers the whole body" "$P" --set 'geometry.holes=[{center: [0.5, 0.5], radius: 5}]'
expect_error "discretisation.refinement[0].spacing: puts about" "$P" --set 'discretisation.refinement=[{box: [[0, 0], [0.1, 0.1]], spacing: 1e-9}]'
expect_error "boundary[1].name: 'clamp' is used by boundary[0] already" "$P" --set boundary.1.name=clamp
expect_error "name: expected a name of letters, digits" "$P" --set name=a/b
expect_error "discretisation.quadrature.order: expected an integer from 2 to 10, got 1e30" "$P" --set discretisation.quadrature.order=1e30
printf 'name: x\nanalysis: elastic_static\n' > "$WORK/incomplete.yaml"
expect_error "model: required value is missing" "$WORK/incomplete.yaml"
# usage errors
"$MF" 2>/dev/null; [ $? -eq 2 ] && echo "ok: no command -> exit 2" || { echo "FAIL: no command"; fails=$((fails+1)); }
"$MF" check "$P" >/dev/null || { echo "FAIL: check on a good problem"; fails=$((fails+1)); }
[ $fails -eq 0 ] && echo "all bad inputs rejected" || exit 1
