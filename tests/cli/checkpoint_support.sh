# Shell helpers of the checkpoint tests (tests/cli/restart.sh, tests/cli/checkpoint_refusals.sh), sourced.
# generation DIR: the generation checkpoint.txt names (0 when there is none yet).
generation() { sed -n 's/^generation //p' "$1/checkpoint/checkpoint.txt" 2>/dev/null || echo 0; }
# kill_after_checkpoint OUT command...: starts a run (its output in $WORK/killed.log), kills it
# and any launcher's children with SIGKILL once its second checkpoint is in place.
kill_after_checkpoint() {
  local out="$1"; shift
  "$@" >"$WORK/killed.log" 2>&1 &
  local pid=$!
  for _ in $(seq 3000); do
    [ "$(generation "$out")" -ge 2 ] && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.01
  done
  pkill -9 -P $pid 2>/dev/null; kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
}
