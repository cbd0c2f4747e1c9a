#!/usr/bin/env bash
# Results are never lost or faked: a good result in the output folder survives a run that fails
# late, a run killed with SIGKILL, a full disk (a file-size limit stands in for it) and planted
# links; files the code did not write are never removed; an output folder that is not a
# directory is refused before anything runs.
set -u
MF="$1"; ROOT="$2"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
P="$ROOT/problems/plate_tension.yaml"
B="$ROOT/problems/pd_pmma_beam_impact.yaml"
OUT="$WORK/out"
fails=0
check() { # check "what" condition...
  local what="$1"; shift
  if "$@"; then echo "ok: $what"; else echo "FAIL: $what"; fails=$((fails+1)); fi
}
digest() { (cd "$OUT" && find . -maxdepth 1 -type f | sort | xargs md5sum); }
good_result() { # the first run's files, unchanged
  [ "$(digest)" = "$GOOD" ]
}

# A completed run, and a file of the user's beside it.
"$MF" run "$P" --out "$OUT" >/dev/null || { echo "FAIL: the first run"; exit 1; }
echo "measured by hand" > "$OUT/line_experiment.csv"
GOOD="$(digest)"
check "a completed run lists its files in the manifest, with size and inode" \
  grep -qxE "history.csv	[0-9]+	$(stat -c %i "$OUT/history.csv")" "$OUT/.meshfree-manifest"

# A run that fails late (a linear solve that did not solve the system).
msg="$("$MF" run "$P" --out "$OUT" -- -pc_type none 2>&1 >/dev/null)"; rc=$?
check "a late failure exits 1" [ $rc -eq 1 ]
check "a late failure says why on stderr" grep -qF "linear solve did not solve the system" <<<"$msg"
check "a late failure leaves the previous result as it was" good_result
check "a late failure keeps its files under failed/" grep -q '"status": "failed"' "$OUT/failed/summary.json"
check "no staging folder is left after a failure" [ -z "$(ls -d "$OUT"/.meshfree-staging-* 2>/dev/null)" ]

# A run killed with SIGKILL after a few history rows (history.csv grows as the run goes).
OMP_NUM_THREADS=1 "$MF" run "$B" --out "$OUT" --set time.end=1e-2 >/dev/null 2>&1 &
pid=$!
rows() { cat "$OUT"/.meshfree-staging-*/history.csv 2>/dev/null | wc -l; }
for _ in $(seq 200); do
  [ "$(rows)" -ge 4 ] && break
  sleep 0.1
done
kill -9 $pid; wait $pid 2>/dev/null
check "a killed run leaves the previous result as it was" good_result
check "a killed run leaves its staging folder" [ -n "$(ls -d "$OUT"/.meshfree-staging-* 2>/dev/null)" ]
check "a killed run's history is on disk up to the kill" [ "$(rows)" -ge 4 ]
said="$("$MF" run "$P" --out "$OUT" 2>&1)"
check "the next run says what the killed run's folder was" grep -qF "the unfinished files of an earlier run" <<<"$said"
check "the next run removes it" [ -z "$(ls -d "$OUT"/.meshfree-staging-* 2>/dev/null)" ]
check "a completed run removes an earlier run's failed/" [ ! -e "$OUT/failed" ]
check "the user's file is kept" grep -qx "measured by hand" "$OUT/line_experiment.csv"

# A staged run killed in its explicit stage keeps the history of both stages up to the kill.
S="$ROOT/problems/staged_pmma_impact.yaml"
OMP_NUM_THREADS=1 "$MF" run "$S" --out "$WORK/staged" >/dev/null 2>&1 &
pid=$!
staged_rows() { awk -F, 'NR > 1 && $2 == 1' "$WORK"/staged/.meshfree-staging-*/history.csv 2>/dev/null | wc -l; }
for _ in $(seq 600); do
  [ "$(staged_rows)" -ge 3 ] && break
  sleep 0.1
done
kill -9 $pid; wait $pid 2>/dev/null
check "a killed staged run's history holds the preload's rows" \
  [ "$(awk -F, 'NR > 1 && $2 == 0' "$WORK"/staged/.meshfree-staging-*/history.csv | wc -l)" -ge 2 ]
check "... and the explicit stage's up to the kill" [ "$(staged_rows)" -ge 3 ]

# A file the previous run wrote and this one does not (a line dropped) goes; the user's stays.
"$MF" run "$P" --out "$OUT" --set 'output.lines=[{name: y07, from: [0, 0.7], to: [1, 0.7], points: 41}]' >/dev/null
check "a result the new run does not write again is removed" [ ! -e "$OUT/line_top.csv" ]
check "a file no manifest lists is kept" [ -f "$OUT/line_experiment.csv" ]

# Links planted under the names the run writes are replaced, never followed.
echo "victim" > "$WORK/victim"
rm -f "$OUT/history.csv" "$OUT/summary.json.partial"
ln -s "$WORK/victim" "$OUT/history.csv"
ln -s "$WORK/victim" "$OUT/summary.json.partial"
"$MF" run "$P" --out "$OUT" >/dev/null
check "a planted link's target is not written" grep -qx "victim" "$WORK/victim"
check "the link is replaced by the result" [ -f "$OUT/history.csv" ] && [ ! -L "$OUT/history.csv" ]

# A full disk: a file-size limit makes a write fail (SIGXFSZ ignored: the write returns EFBIG).
# 16 MB leaves room for MPI's start-up files; the beam's fields pass it at about 0.3 ms.
"$MF" run "$P" --out "$OUT" >/dev/null
GOOD="$(digest)"
msg="$(trap '' XFSZ; ulimit -f 16384; "$MF" run "$B" --out "$OUT" --set time.end=6e-4 2>&1 >/dev/null)"; rc=$?
check "a write that fails exits 1" [ $rc -eq 1 ]
check "a write that fails says so and where" grep -qiE "file too large writing .*fields\.h5" <<<"$msg"
check "a write that fails leaves the previous result as it was" good_result

# An output folder that is a file is refused before the run.
echo "not a folder" > "$WORK/file"
msg="$("$MF" run "$P" --out "$WORK/file" 2>&1 >/dev/null)"; rc=$?
check "an output folder that is a file: exit 2" [ $rc -eq 2 ]
check "an output folder that is a file: one line naming it" grep -qF -- "--out $WORK/file: not a directory" <<<"$msg"
check "an output folder that is a file is not touched" grep -qx "not a folder" "$WORK/file"

# No link in the output folder is followed. A manifest planted as a link to a list naming a
# user's file: nothing is removed through it, and the run's own manifest replaces the link.
"$MF" run "$P" --out "$OUT" >/dev/null
echo "precious" > "$OUT/precious.txt"
printf 'precious.txt\n' > "$WORK/list"
rm -f "$OUT/.meshfree-manifest"; ln -s "$WORK/list" "$OUT/.meshfree-manifest"
"$MF" run "$P" --out "$OUT" >/dev/null; rc=$?
check "a planted manifest link: the run completes" [ $rc -eq 0 ]
check "... the user's file the list names is kept" grep -qx precious "$OUT/precious.txt"
check "... the list is not written" [ "$(cat "$WORK/list")" = "precious.txt" ]
check "... and the link is replaced by the run's manifest" \
  [ -f "$OUT/.meshfree-manifest" -a ! -L "$OUT/.meshfree-manifest" ]
# A manifest entry whose name is now another file than the one its run wrote (another inode).
printf 'precious.txt\t%s\t1\n' "$(stat -c %s "$OUT/precious.txt")" >>"$OUT/.meshfree-manifest"
"$MF" run "$P" --out "$OUT" >/dev/null
check "a manifest entry that is not the file its run wrote is not removed" \
  grep -qx precious "$OUT/precious.txt"
# failed/ planted as a link to a folder whose manifest lists its files exactly: a completed run
# removes an earlier run's failed/, but not through a link.
mkdir -p "$WORK/elsewhere"; echo "victim" > "$WORK/elsewhere/victim.csv"
printf 'victim.csv\t%s\t%s\n' $(stat -c '%s %i' "$WORK/elsewhere/victim.csv") \
  >"$WORK/elsewhere/.meshfree-manifest"
rm -rf "$OUT/failed"; ln -s "$WORK/elsewhere" "$OUT/failed"
"$MF" run "$P" --out "$OUT" >/dev/null
check "a failed/ link: the folder it points to keeps its files" \
  grep -qx victim "$WORK/elsewhere/victim.csv"
check "... and the link stays a link" [ -L "$OUT/failed" ]
# checkpoint/ planted as a link to a folder holding files under a checkpoint's names: a run
# writes no checkpoint through it and removes nothing there; a restart through it is refused.
D="$ROOT/problems/pd_disk_impact.yaml"
C="$WORK/linked"; mkdir -p "$C" "$WORK/target"
echo "generation 1" > "$WORK/target/checkpoint.txt"; echo "mine" > "$WORK/target/state-1.0.h5"
ln -s "$WORK/target" "$C/checkpoint"
target() { (cd "$WORK/target" && find . | sort && find . -type f | sort | xargs md5sum); }
T0="$(target)"
msg="$("$MF" run "$D" --out "$C" --set output.checkpoint_interval=1.0e-5 --set time.end=3.0e-5 2>&1)"; rc=$?
check "a checkpoint/ link: the run completes" [ $rc -eq 0 ]
check "... saying it writes no checkpoints" grep -qF "meshfree follows no link" <<<"$msg"
check "... nothing written into or removed from the link's target" [ "$(target)" = "$T0" ]
msg="$("$MF" run "$D" --restart "$C" 2>&1 >/dev/null)"; rc=$?
check "a restart through a checkpoint/ link: exit 2" [ $rc -eq 2 ]
check "... one line saying it is a link" \
  [ "$(wc -l <<<"$msg")" -eq 1 -a -n "$(grep -F "$C/checkpoint is a link" <<<"$msg")" ]
check "... and the link's target untouched" [ "$(target)" = "$T0" ]

[ $fails -eq 0 ] && echo "results kept safe in every case" || exit 1
