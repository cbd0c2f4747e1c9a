#!/usr/bin/env bash
# Checkpoints that are not the run's own are refused: a restart from a foreign checkpoint (another
# spacing, its header made to match this problem's), a truncated one, one with a flipped bit in
# its particles' displacements, one written by another version of meshfree, and one whose time
# lies after the run's end (its checksum made to match) each exit 2 with one line naming what differs, and leave the folder as it was (no
# failed/, no staging folder, the checkpoint's files untouched). A run or a restart into a folder
# that a live run holds is refused the same way, and writes nothing there.
set -u
MF="$1"; ROOT="$2"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
D="$ROOT/problems/pd_disk_impact.yaml"
EVERY=(--set output.checkpoint_interval=1.0e-5)
fails=0
check() { # check "what" condition...
  local what="$1"; shift
  if "$@"; then echo "ok: $what"; else echo "FAIL: $what"; fails=$((fails+1)); fi
}
source "$(dirname "${BASH_SOURCE[0]}")/checkpoint_support.sh"
listing() { (cd "$1" && find . | sort && find . -type f | sort | xargs md5sum); }
# h5edit FILE python-statements: edits a state file with h5py; fnv(bytes) is meshfree's checksum
# of an array (tests/cli/fuzz_support.py).
h5edit() {
  /usr/bin/python3 - "$@" "$(dirname "${BASH_SOURCE[0]}")" <<'EOF'
import sys
import h5py, numpy as np
sys.path.insert(0, sys.argv[3])
from fuzz_support import fnv
def put(f, name, values):  # a dataset replaced, with its checksum
    values = np.asarray(values, dtype=f[name].dtype)
    del f[name]
    f.create_dataset(name, data=values)
    f[name].attrs.create("fnv1a64", fnv(values.tobytes()), dtype="u8")
f = h5py.File(sys.argv[1], "r+")
exec(sys.argv[2])
f.close()
EOF
}
# refused WHAT DIR EXPECTED [meshfree arguments]: a restart from DIR exits 2 with one line holding
# EXPECTED, and DIR is as it was.
refused() {
  local what="$1" dir="$2" expected="$3"; shift 3
  local before; before="$(listing "$dir")"
  local msg; msg="$("$MF" run "$D" --restart "$dir" "${EVERY[@]}" "$@" 2>&1 >/dev/null)"; local rc=$?
  check "$what: exit 2" [ $rc -eq 2 ]
  check "$what: one line" [ "$(wc -l <<<"$msg")" -eq 1 ]
  check "$what: naming what differs" grep -qF -- "$expected" <<<"$msg"
  [ "$(wc -l <<<"$msg")" -eq 1 ] && grep -qF -- "$expected" <<<"$msg" || echo "  got: $msg"
  check "$what: the folder is as it was" [ "$(listing "$dir")" = "$before" ]
}

# The run's own checkpoint, and one of the same problem at another spacing.
OWN="$WORK/own"
kill_after_checkpoint "$OWN" "$MF" run "$D" --out "$OWN" "${EVERY[@]}"
[ "$(generation "$OWN")" -ge 2 ] || { echo "FAIL: no checkpoint to start from"; exit 1; }
G="$(generation "$OWN")"
OTHER="$WORK/other"
kill_after_checkpoint "$OTHER" "$MF" run "$D" --out "$OTHER" "${EVERY[@]}" \
  --set discretisation.spacing=0.0006
copy() { rm -rf "$WORK/$1"; mkdir -p "$WORK/$1"; cp -a "$2/checkpoint" "$WORK/$1/"; echo "$WORK/$1"; }

# Another spacing, as given: the settings differ.
refused "a checkpoint of another spacing" "$(copy spacing "$OTHER")" \
  "discretisation.spacing changed since the checkpoint"
# Another spacing whose header claims this problem (its settings and identity copied from this
# run's checkpoint, checksums and all): the particle count differs.
F="$(copy foreign "$OTHER")"
FG="$(generation "$F")"
h5edit "$F/checkpoint/state-$FG.0.h5" "
own = h5py.File('$OWN/checkpoint/state-$G.0.h5', 'r')
for name in ('meta.settings', 'meta.identity'):
    del f[name]
    own.copy(own[name], f, name)"
refused "a foreign checkpoint with this problem's header" "$F" "checkpoint holds "
msg="$("$MF" run "$D" --restart "$F" "${EVERY[@]}" 2>&1 >/dev/null)"
check "... the counts named: its particles and this run's" \
  grep -qE "checkpoint holds [0-9]+ particles, this run has 3487" <<<"$msg"

# A truncated state file.
T="$(copy truncated "$OWN")"
S="$T/checkpoint/state-$G.0.h5"
truncate -s $(( $(stat -c %s "$S") / 2 )) "$S"
refused "a truncated checkpoint" "$T" "not a readable checkpoint file"

# One bit of one displacement flipped (the file stays readable HDF5).
B="$(copy bitflip "$OWN")"
S="$B/checkpoint/state-$G.0.h5"
offset="$(/usr/bin/python3 -c "
import h5py; f = h5py.File('$S', 'r'); print(f['particles.u'].id.get_offset() + 8 * 1000 + 2)")"
/usr/bin/python3 -c "
f = open('$S', 'r+b'); f.seek($offset); b = f.read(1); f.seek($offset); f.write(bytes([b[0] ^ 0x10]))"
refused "a checkpoint with a flipped bit in particles.u" "$B" "'particles.u' does not match its checksum"

# A checkpoint of another version of meshfree (its version rewritten, checksum and all), refused
# naming both versions: this one is CMakeLists.txt's project version.
VERSION="$(sed -n 's/^project(meshfree VERSION \([0-9.]*\).*/\1/p' "$ROOT/CMakeLists.txt")"
check "the program's version is read from CMakeLists.txt" [ -n "$VERSION" ]
V="$(copy version "$OWN")"
h5edit "$V/checkpoint/state-$G.0.h5" "put(f, 'meta.version', list(b'0.0.9'))"
refused "a checkpoint of another version" "$V" \
  "the checkpoint was written by meshfree 0.0.9, this is meshfree $VERSION"
# ... and the version this one writes.
check "... the run's own checkpoint records this version" [ "$(/usr/bin/python3 -c "
import h5py; f = h5py.File('$OWN/checkpoint/state-$G.0.h5', 'r')
print(bytes(f['meta.version'][()].astype('u1')).decode())")" = "$VERSION" ]

# A time after the end (1e300), its checksum made to match.
L="$(copy late "$OWN")"
h5edit "$L/checkpoint/state-$G.0.h5" "put(f, 'meta.time', [1e300])"
refused "a checkpoint at t = 1e300" "$L" "time 1e+300 is not inside this run (0 to 0.0001)"
# ... and a header that no longer goes with the state it holds.
H="$(copy header "$OWN")"
h5edit "$H/checkpoint/state-$G.0.h5" "put(f, 'meta.time', [5.0e-5])"
refused "a checkpoint whose header has another time than its state" "$H" "a damaged checkpoint"

# The run's own checkpoint still restarts, to completion, from a folder moved elsewhere (its field
# parts are found in the folder read).
mv "$OWN" "$WORK/moved"
"$MF" run "$D" --restart "$WORK/moved" "${EVERY[@]}" >/dev/null 2>&1; rc=$?
check "the run's own checkpoint, moved to another folder, restarts and completes" [ $rc -eq 0 ]
check "... with its results" grep -q '"status": "completed"' "$WORK/moved/summary.json"

# A live run holds its folder: a restart into it and a plain run into it are refused, and write
# nothing there.
LIVE="$WORK/live"
"$MF" run "$D" --out "$LIVE" "${EVERY[@]}" >/dev/null 2>&1 &
first=$!
for _ in $(seq 3000); do [ "$(generation "$LIVE")" -ge 1 ] && break; sleep 0.01; done
kill -STOP $first
before="$(listing "$LIVE")"
msg="$("$MF" run "$D" --restart "$LIVE" "${EVERY[@]}" 2>&1 >/dev/null)"; rc=$?
check "a restart beside a live run: exit 2" [ $rc -eq 2 ]
check "... one line saying the folder is in use" \
  [ "$(wc -l <<<"$msg")" -eq 1 -a -n "$(grep -F -- "--restart $LIVE: in use by a run of meshfree that is still going" <<<"$msg")" ]
msg="$("$MF" run "$D" --out "$LIVE" --set time.end=3.0e-5 2>&1 >/dev/null)"; rc=$?
check "a plain run into a live run's folder: exit 2" [ $rc -eq 2 ]
check "... one line saying the folder is in use" \
  [ "$(wc -l <<<"$msg")" -eq 1 -a -n "$(grep -F -- "--out $LIVE: in use by a run of meshfree that is still going" <<<"$msg")" ]
check "... and the live run's folder is as it was (no failed/, no checkpoint touched)" \
  [ "$(listing "$LIVE")" = "$before" ]
kill -CONT $first; wait $first; rc=$?
check "the live run goes on and completes" [ $rc -eq 0 ]

echo "$fails failure(s)"
[ $fails -eq 0 ]
