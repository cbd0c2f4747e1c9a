#!/usr/bin/env bash
# Hostile inputs (tracker issue 28): each ends in one line on stderr with its cause, the exit
# status of the run contract (2: refused as input, nothing written; 1: the run failed, its reason
# in failed/summary.json), within a time limit: no endless run, no crash, no hang.
set -u
MF="$1"; ROOT="$2"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
fails=0
bad() { echo "FAIL ($1): ${*:2}"; fails=$((fails+1)); }

# outcome VERB WANT_RC "fragment" args...: runs `meshfree VERB args` (run: into $WORK/out) with a
# time limit, and checks the exit status, that stderr is one line holding the fragment, and for
# exit 2 that nothing was written.
outcome() {
  local verb="$1" want="$2" frag="$3"; shift 3
  rm -rf "$WORK/out"
  local extra=(); [ "$verb" = run ] && extra=(--out "$WORK/out")
  timeout 120 "$MF" "$verb" "$@" "${extra[@]}" >/dev/null 2>"$WORK/err"; rc=$?
  # Log lines ("[meshfree] ...": progress, warnings) are not the failure's line.
  msg="$(grep -v '^\[meshfree\]' "$WORK/err")"
  if [ "$rc" != "$want" ]; then bad "exit $rc, not $want; '$msg'" "$verb" "$@"; return 1; fi
  if [ "$(printf '%s\n' "$msg" | wc -l)" -ne 1 ]; then bad "not one line: '$msg'" "$verb" "$@"; return 1; fi
  if ! grep -qF -- "$frag" <<<"$msg"; then bad "message '$msg' lacks '$frag'" "$verb" "$@"; return 1; fi
  if [ "$want" = 2 ] && [ -n "$(ls -A "$WORK/out" 2>/dev/null)" ]; then bad "left files" "$verb" "$@"; return 1; fi
  echo "ok: $frag"
}
# The same through `meshfree run` and `meshfree check`: check refuses what run refuses.
refused() { outcome check 2 "$@" && outcome run 2 "$@"; }

P="$ROOT/problems/plate_tension.yaml"
Q="$ROOT/problems/plate_plastic_thesis.yaml"
C="$ROOT/problems/pd_cantilever_3d.yaml"
W="$ROOT/problems/pd_cantilever_random_load.yaml"
T="$ROOT/problems/sph_taylor_bar.yaml"

# Endless runs from accepted values: every count a run will perform is bounded before it starts.
refused "time.end: 1e+29 s in time steps of" "$C" --set time.end=1e29
refused "days a run may take" "$T" --set time.end=1e29
refused "functions[0].duration: " "$W" --set functions.0.duration=1e-300
refused "steps[0].increments: " "$Q" --set steps.0.increments=1000000
# A staged run's explicit stage (SPH, peridynamics) is bounded the same way, by check and by run
# before its preload runs, and named by its key path.
S="$ROOT/problems/staged_strip_blast.yaml"
M="$ROOT/problems/staged_pmma_impact.yaml"
refused "stages[1].time.end: 1e+29 s in time steps of" "$S" --set 'stages[1].time.end=1e29'
refused "stages[1].time.end: 1e+29 s in time steps of" "$M" --set 'stages[1].time.end=1e29'
refused "stages[1].output.fields_interval: field frames: about 5.3e+06" "$S" \
  --set 'stages[1].time.end=1' --set 'stages[1].output.fields_interval=1e-20'
refused "stages[1].output.checkpoint_interval: 1e-20 s: about" "$M" \
  --set 'stages[1].time.end=3' --set 'stages[1].output.fields_interval=1' \
  --set 'stages[1].output.checkpoint_interval=1e-20'
for key in history_interval fields_interval checkpoint_interval; do
  msg="$(timeout 120 "$MF" check "$S" --set "stages[1].output.$key=1e-20" 2>&1 >/dev/null)"; rc=$?
  n=$(grep -cF "warning: stages[1].output.$key: 1e-20 s is below the time step" <<<"$msg")
  if [ $rc -eq 0 ] && [ "$n" -eq 1 ]; then
    echo "ok: stages[1].output.$key=1e-20 is clamped to every step, with one warning naming the stage"
  else bad "exit $rc, $n warnings, '$msg'" "stages[1].output.$key=1e-20"; fi
done
# A staged run bounds its explicit stage before the preload and again as the stage starts: the
# clamped interval is still said once (the tunnel: its preload takes seconds).
rm -rf "$WORK/out"
msg="$(timeout 300 "$MF" run "$ROOT/problems/staged_tunnel_blast.yaml" --out "$WORK/out" \
  --set 'stages[1].time.end=1e-5' --set 'stages[1].output.history_interval=1e-20' 2>&1 >/dev/null)"; rc=$?
n=$(grep -cF "warning: stages[1].output.history_interval: 1e-20 s is below the time step" <<<"$msg")
if [ $rc -eq 0 ] && [ "$n" -eq 1 ]; then
  echo "ok: a staged run says a clamped interval of its explicit stage once"
else bad "exit $rc, $n warnings" "staged run, stages[1].output.history_interval=1e-20"; fi
# An output interval below the time step is clamped to every step, with a warning, and the run
# ends (the catch-up loops once added 1e-20 until it passed t, which never happens).
for key in history_interval fields_interval checkpoint_interval; do
  rm -rf "$WORK/out"
  msg="$(timeout 120 "$MF" run "$C" --out "$WORK/out" --set time.end=2e-3 --set "output.$key=1e-20" 2>&1 >/dev/null)"; rc=$?
  if [ $rc -eq 0 ] && grep -qF "output.$key: 1e-20 s is below the time step" <<<"$msg"; then
    echo "ok: output.$key=1e-20 runs every step and ends"
  else bad "exit $rc, '$msg'" "output.$key=1e-20"; fi
done

# Crashes: an SPH region without particles; a write that fails under a file-size limit.
refused "regions[0]: holds no particle" "$T" --set 'regions.0.circle.center=[1, 1]'
# 16 MB leaves room for MPI's start-up files; each case writes more than that in frames.
for case in "$Q --set steps.0.increments=40" "$T --set time.end=2e-5 --set output.fields_interval=1e-9" \
            "$C --set time.end=0.05 --set output.fields_interval=1e-6"; do
  rm -rf "$WORK/out"
  # shellcheck disable=SC2086
  (trap '' XFSZ; ulimit -f 16384; timeout 120 "$MF" run $case --out "$WORK/out" >/dev/null 2>"$WORK/err"); rc=$?
  msg="$(grep -v '^\[meshfree\]' "$WORK/err")"
  if [ "$rc" = 1 ] && grep -qi "file too large" <<<"$msg" && [ "$(wc -l <<<"$msg")" -eq 1 ] &&
     grep -q '"status": "failed"' "$WORK/out/failed/summary.json"; then
    echo "ok: a failed write under ulimit -f exits 1: ${case%% *}"
  else bad "exit $rc, '$msg'" "ulimit -f 8: $case"; fi
done

# Runs side by side: a run started without mpirun keeps no MPI session folder (each such process
# named the same /tmp/ompi.<host>.<uid>/jf.0/1/0, and one ending removed it while another made it).
# With TMPDIR a file no such folder can be made, and the run still works; eight runs at once end 0.
if TMPDIR="$P" timeout 120 "$MF" run "$P" --out "$WORK/tmpdir_file" >/dev/null 2>"$WORK/err"; then
  echo "ok: a run with TMPDIR a file works (no MPI session folder)"
else bad "exit $?, '$(tail -3 "$WORK/err")'" "TMPDIR=$P"; fi
pids=()
for i in 1 2 3 4 5 6 7 8; do
  timeout 120 "$MF" run "$P" --out "$WORK/side_$i" >/dev/null 2>"$WORK/side_$i.err" & pids+=($!)
done
failed=0
for pid in "${pids[@]}"; do wait "$pid" || failed=$((failed+1)); done
[ $failed -eq 0 ] && echo "ok: eight runs started at once all end 0" ||
  bad "$failed of 8 failed: '$(cat "$WORK"/side_*.err | grep -v '^\[meshfree\]' | head -3)'" "runs side by side"

# Silent or faked outcomes.
outcome run 1 "run failed: the motion became non-finite" "$C" --set 'boundary.1.traction=[0, 0, -1e300]' --set time.end=0.05 &&
  grep -q "the load 'end_shear' is" <<<"$msg" && grep -q '"status": "failed"' "$WORK/out/failed/summary.json" ||
  bad "the non-finite message names the load and summary.json says failed" "traction 1e300"
# A collapsing SPH state (a region 1e20 kg/m^3 dense, as the input fuzzer made it): its CFL step
# falls to 4e-24 s in one step; the run stops there, naming the particle, instead of stepping for
# ever at a frozen time.
outcome run 1 "run failed: the CFL step fell to" "$ROOT/problems/sph_bar_impact.yaml" \
  --set regions.1.density=1e20 --set time.end=2e-6
outcome run 1 "accepted up to 0.001" "$P" -- -ksp_type cg -pc_type jacobi -ksp_rtol 0.5

# Messages: quoted values cut and on one line; FIFOs, devices and folders named.
{ grep -v '^analysis:' "$P"; printf 'analysis: '; head -c 2000000 /dev/zero | tr '\0' x; echo; } > "$WORK/long.yaml"
refused "analysis: expected one of" "$WORK/long.yaml"
[ ${#msg} -lt 400 ] && echo "ok: a 2 MB value is cut" || bad "${#msg} characters" "2 MB value"
refused "got 'a\\nb'" "$P" --set 'discretisation.method="a\nb"'
mkfifo "$WORK/fifo.yaml" "$WORK/fifo.msh" "$WORK/fifo.csv"
refused "fifo.yaml: is a FIFO, device or socket, not a problem file" "$WORK/fifo.yaml"
refused "discretisation.fem.mesh: " "$P" --set discretisation.method=fem --set "discretisation.fem.mesh=$WORK/fifo.msh"
refused "functions[0].file: " "$W" --set "functions.0.file=$WORK/fifo.csv"
refused "/dev/zero: is a FIFO, device or socket, not a problem file" /dev/zero
refused "problems: is a folder, not a problem file" "$ROOT/problems"
refused "discretisation.spacing: expected at most the body's size (1 x 1), got 1000000000" "$P" --set discretisation.spacing=1e9
refused "--set .name: an empty key in the path" "$P" --set .name=x
refused "boundary[1].edges: no boundary piece is named 'roof'" "$P" --set 'boundary[1].edges=roof'
refused "boundary[1].tracton: unknown key (known here: " "$P" --set 'boundary.1={name: pull, edges: [right], tracton: [1, 0]}'
grep -qF "pressure" <<<"$msg" && grep -qF "did you mean 'traction'?" <<<"$msg" || bad "'$msg' lacks pressure or the near miss" "tracton"
"$MF" check "$P" --set 'boundary[1].traction=[2, 0]' >/dev/null 2>&1 && echo "ok: boundary[1].traction accepted" || bad "refused" "boundary[1].traction"
"$MF" run "$P" --out /proc/meshfree-out >/dev/null 2>"$WORK/err"; rc=$?
[ $rc -eq 2 ] && [ "$(grep -vc '^\[meshfree\]' "$WORK/err")" -eq 1 ] && grep -qF -- "--out /proc/meshfree-out" "$WORK/err" &&
  echo "ok: an unusable --out is exit 2" || bad "exit $rc, '$(cat "$WORK/err")'" "--out /proc/meshfree-out"
outcome run 1 "bogus" "$P" -- -ksp_type bogus

# A peridynamic body of 14 million particles (the disk-impact target 16 m tall, as the input
# fuzzer once made it): check reports estimates within seconds instead of building 8e8 bonds.
msg="$(timeout 20 "$MF" check "$ROOT/problems/pd_disk_impact.yaml" \
  --set "geometry.box.size=[0.0105, 0.0105, 16]" 2>&1)"; rc=$?
[ $rc -eq 0 ] && grep -qF "too many to build for a check" <<<"$msg" &&
  echo "ok: check of a 14-million-particle body reports estimates" ||
  bad "exit $rc, '$(tail -2 <<<"$msg")'" check pd_disk_impact 16 m tall

# The OpenMP wait policy is set before libgomp starts (the executable's preinit array), not by the
# program running itself again: passive by default, the user's own policy kept.
policy() { env "$@" OMP_DISPLAY_ENV=true "$MF" --help 2>&1 | grep -o "OMP_WAIT_POLICY = '[A-Z]*'"; }
[ "$(policy)" = "OMP_WAIT_POLICY = 'PASSIVE'" ] && echo "ok: OpenMP waits passively" ||
  bad "wait policy '$(policy)', not PASSIVE" --help
[ "$(policy OMP_WAIT_POLICY=active)" = "OMP_WAIT_POLICY = 'ACTIVE'" ] &&
  echo "ok: the user's OMP_WAIT_POLICY is kept" || bad "OMP_WAIT_POLICY=active not kept" --help

[ $fails -eq 0 ] && echo "every hostile input ends in one line" || exit 1
