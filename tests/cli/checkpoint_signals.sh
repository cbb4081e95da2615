#!/usr/bin/env bash
# Stopping a run: SIGTERM (1 rank) and SIGUSR1 (2 ranks under mpirun, which forwards it) end
# the run after the current step with a checkpoint, exit code 0 and a log line saying so, and
# the checkpoint restarts. kill -9 while a checkpoint is being written leaves the previous
# checkpoint intact: a restart from the directory uses it.
set -u
source "$(dirname "$0")/common.bash"
pids=()
trap 'for p in "${pids[@]}"; do kill -9 "$p" 2> /dev/null; done; rm -rf "$tmp"' EXIT

# Waits (up to $2 s) until the file pattern $1 matches something.
wait_for() {
  local i
  for ((i = 0; i < $2 * 100; ++i)); do
    compgen -G "$1" > /dev/null && return 0
    sleep 0.01
  done
  return 1
}

# A long run: 40000 particles, a million steps (never reached).
cat > "$tmp/long.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 2
steps = 1000000
[domain]
size = [100.0, 40.0]
[fluid]
collision = "srd"
dt = 0.5
[output]
every = 50
progress = false
TOML

stop_test() { # name, signal, launcher...
  local name=$1 sig=$2 out="$tmp/$1"
  shift 2
  "$@" "$narrows" run "$tmp/long.toml" --out "$out" > "$tmp/$name.out" 2> "$tmp/$name.err" &
  local pid=$!
  pids+=("$pid")
  wait_for "$out/observables.h5" 30 # the loop is running
  sleep 0.5
  kill -"$sig" "$pid"
  local t0=$SECONDS
  wait "$pid"
  local code=$?
  check "$name: exit 0 after SIG$sig (got $code)" '[ "$code" -eq 0 ]'
  check "$name: stopped within a few seconds" '[ $((SECONDS - t0)) -le 10 ]'
  check "$name: log line says why it stopped" 'grep -q "received SIG$sig: stopped after step [0-9]*, checkpoint .*checkpoint-[0-9]\{10\}.h5 written; exit 0" "$out/log.txt"'
  check "$name: nothing on stderr" '[ ! -s "$tmp/$name.err" ]'
  local step
  step=$(sed -n "s/.*stopped after step \([0-9]*\).*/\1/p" "$out/log.txt")
  check "$name: checkpoint of that step exists" '[ -s "$out/$(printf "checkpoint-%010d.h5" "$step")" ]'
  runs "$name: restart from the checkpoint" "$@" "$narrows" run "$tmp/long.toml" --restart "$out" \
    --set run.steps=$((step + 3)) --out "$out" > "$tmp/$name.re" 2>&1
  check "$name: the checkpoint restarts" 'grep -q "restarted from .* at step $step" "$tmp/$name.re"'
}
stop_test sigterm_1rank TERM
stop_test sigusr1_2ranks USR1 "${mpi[@]}" -n 2

# kill -9 while a checkpoint is written: 2 million particles (80 MB per checkpoint), one every
# step. Once one is complete, kill the run the moment the next temporary file appears.
cat > "$tmp/big.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 2
steps = 1000000
[domain]
size = [500.0, 400.0]
[fluid]
collision = "srd"
dt = 0.5
sort_every = 0
[output]
every = 1000
checkpoint_every = 1
progress = false
TOML
"$narrows" run "$tmp/big.toml" --out "$tmp/big" > "$tmp/big.out" 2>&1 &
pid=$!
pids+=("$pid")
wait_for "$tmp/big/checkpoint-*.h5" 120
sleep 0.2
wait_for "$tmp/big/checkpoint-*.h5.tmp" 60
kill -9 "$pid"
wait "$pid" 2> /dev/null
code=$?
check "kill -9 ends the run (status 137, got $code)" '[ "$code" -eq 137 ]'
check "the killed run left a temporary file (killed mid-write)" 'compgen -G "$tmp/big/checkpoint-*.h5.tmp" > /dev/null'
newest=$(cd "$tmp/big" && ls checkpoint-*.h5 | tail -1)
step=$((10#$(echo "$newest" | sed "s/checkpoint-\([0-9]*\).h5/\1/")))
runs "restart from the directory after kill -9" "$narrows" run "$tmp/big.toml" --restart "$tmp/big" \
  --set run.steps=$((step + 1)) --set output.checkpoint_every=0 --out "$tmp/big" > "$tmp/big.re" 2>&1
check "restart after kill -9 uses the newest complete checkpoint" \
  'grep -q "restarted from .*$newest at step $step" "$tmp/big.re"'
check "the restart cleaned the temporary file up" '! compgen -G "$tmp/big/checkpoint-*.h5.tmp" > /dev/null'
finish "checkpoint signals"
