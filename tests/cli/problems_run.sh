#!/usr/bin/env bash
# Every problem in problems/ runs as it is and writes the run contract's files; the plane implicit
# ones run a second time with finite elements, and where reference/calculix_plastic holds the
# problem's converged CalculiX curves both runs follow them (scripts/compare.py: within 2% of
# the largest value at every recorded point, 1% where the table says so, and the first-yield
# load within 1% where the elastic stress is bounded); the thick perforated plate's too
# (tests/reference/solid3d_vs_calculix.py).
#   problems_run.sh MESHFREE ROOT [K/N]   # K/N: only the K-th of N shards (K from 1)
# The shards are balanced by each problem's measured seconds here (tests/cli/problem_seconds.txt,
# from a whole run: its line "name: N s"), the longest first onto the least loaded shard; a problem
# not in the table counts 10 s.
set -eu
MF="$1"; ROOT="$2"; SHARD="${3:-1/1}"
K="${SHARD%/*}"; N="${SHARD#*/}"
[[ "$SHARD" =~ ^[1-9][0-9]*/[1-9][0-9]*$ ]] && [ "$K" -le "$N" ] ||
  { echo "problems_run.sh: expected K/N with 1 <= K <= N, got '$SHARD'"; exit 2; }
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
compared="$(/usr/bin/python3 "$ROOT/scripts/compare.py" --list)"
mine="$(for p in "$ROOT"/problems/*.yaml; do
  name="$(basename "$p" .yaml)"
  cost="$(awk -v n="$name" '$1 == n { print $2 }' "$ROOT/tests/cli/problem_seconds.txt")"
  echo "${cost:-10} $name"
done | sort -k1,1nr -k2,2 | awk -v n="$N" -v k="$K" '{
  best = 1; for (s = 2; s <= n; s++) if (load[s] < load[best]) best = s
  load[best] += $1; if (best == k) print $2 }')"
for name in $mine; do
  p="$ROOT/problems/$name.yaml"
  started=$SECONDS
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
  # The 3D problems checked against CalculiX C3D20R take 10 to 15 min on one thread over their
  # whole curves (tests/reference/solid3d_vs_calculix.py and punch_3d_vs_calculix.py run them
  # whole): here their first 5 increments of the same schedule, to first yield.
  first=5
  case "$name" in
    thick_perforated_plate) extra=(--set "steps.0.load_factor=0.025" --set "steps.0.increments=$first") ;;
    punch_block_3d) extra=(--set "steps.0.load_factor=250" --set "steps.0.increments=$first") ;;
  esac
  runs=("$name")
  # Every plane implicit problem also runs with finite elements, on a mesh gmsh makes from its
  # own geometry where it gives no mesh file (3D bodies are meshfree only; a file that adapts
  # its cloud gives the finite elements the adapted cloud's boxes as gmsh's size field).
  grep -qE '^analysis: (elastic_static|elastoplastic_static)' "$p" &&
    ! grep -qE '^model: \{type: solid_3d' "$p" && runs+=("$name:fem")
  for run in "${runs[@]}"; do
    out="$WORK/${run/:/_}"
    method=()
    [ "$run" != "$name" ] && method=(--set discretisation.method=fem --set discretisation.adapt=off)
    boxes="$WORK/$name/adapted_refinement.yaml"
    if [ "$run" != "$name" ] && [ -f "$boxes" ]; then
      want="$(sed -n 's/.*"refinement_boxes": \([0-9]*\).*/\1/p' "$WORK/$name/summary.json")"
      [ "$(grep -c '{box:' "$boxes")" = "$want" ] ||
        { echo "FAIL: $name: adapted_refinement.yaml does not hold its $want boxes"; exit 1; }
      method+=(--set "discretisation.refinement=$(cat "$boxes")")
    fi
    "$MF" run "$p" --out "$out" "${extra[@]}" "${method[@]}" > "$out.log" ||
      { tail -5 "$out.log"; echo "FAIL: $run exited with an error"; exit 1; }
    for f in summary.json history.csv fields.h5 fields.xmf; do
      [ -s "$out/$f" ] || { echo "FAIL: $run did not write $f"; exit 1; }
    done
    grep -q '"status": "completed"' "$out/summary.json" || { echo "FAIL: $run status"; exit 1; }
    if [ "$run" != "$name" ]; then
      grep -qE '"method": "FE Q8 on (a structured mesh|a gmsh mesh of the geometry)' "$out/summary.json" ||
        { echo "FAIL: $run did not mesh its geometry: $(grep '"method"' "$out/summary.json")"; exit 1; }
    fi
    echo "ok: $run"
  done
  if grep -qx "$name" <<< "$compared"; then
    /usr/bin/python3 "$ROOT/scripts/compare.py" "$name" --meshfree-dir "$WORK/$name" \
      --fem-dir "$WORK/${name}_fem" --out "$WORK/compare" --check 0.02 --check-first-yield 0.01 \
      > "$WORK/compare.log" 2>&1 ||
      { cat "$WORK/compare.log"; echo "FAIL: $name does not follow CalculiX"; exit 1; }
    grep "largest difference" "$WORK/compare.log"
  fi
  # The thick perforated plate's curve against CalculiX's C3D20R curve over the increments run:
  # the force within 1% at each.
  if [ "$name" = thick_perforated_plate ]; then
    /usr/bin/python3 "$ROOT/tests/reference/solid3d_vs_calculix.py" "$MF" "$ROOT" \
      --run-dir "$WORK/$name" --increments "$first" > "$WORK/calculix_3d.log" 2>&1 ||
      { cat "$WORK/calculix_3d.log"; echo "FAIL: $name does not follow CalculiX"; exit 1; }
    tail -1 "$WORK/calculix_3d.log"
  fi
  # The 3D punch block's patch displacement against CalculiX's over the increments run.
  if [ "$name" = punch_block_3d ]; then
    /usr/bin/python3 "$ROOT/tests/reference/punch_3d_vs_calculix.py" "$MF" "$ROOT" \
      --run-dir "$WORK/$name" --increments "$first" --mean-within 0.01 > "$WORK/punch_3d.log" 2>&1 ||
      { cat "$WORK/punch_3d.log"; echo "FAIL: $name does not follow CalculiX"; exit 1; }
    tail -1 "$WORK/punch_3d.log"
  fi
  echo "$name: $((SECONDS - started)) s"
done
