#!/usr/bin/env bash
# Every engine stops on SIGTERM at the same point of its step (the one loop, run/drive.hpp): after
# the step in which the signal arrived, with a checkpoint of that step, exit 0 and the line
# "received SIGTERM: stopped after ..., checkpoint ... written; exit 0". --restart then continues
# the run to the same final state, bit for bit, as a run that got no signal (same_state.py on
# the final checkpoints). One case per engine: mpcd, lgca, kmc (a step is a round of replicas)
# and continuum, which also stops on 2 ranks with the signal sent to one rank only (the ranks
# agree on the step collectively).
set -u
source "$(dirname "$0")/common.bash"
same=$src/tests/cli/same_state.py
pids=()
trap 'for p in "${pids[@]}"; do kill -9 "$p" 2> /dev/null; done; rm -rf "$tmp"' EXIT
bound=30 # seconds from SIGTERM to exit

# stopped NAME TARGET COMMAND...: runs COMMAND --out $tmp/NAME in the background, sends SIGTERM
# once its loop runs (TARGET self: the command; one: its first child, a rank under mpirun),
# and checks the clean stop. Sets `at` to what the stop line says it stopped after (a step, or
# the replicas done) and `last` to the checkpoint it names.
stopped() {
  local name=$1 target=$2 out=$tmp/$1
  shift 2
  "$@" --out "$out" > "$tmp/$name.out" 2> "$tmp/$name.err" &
  local pid=$!
  pids+=("$pid")
  check "$name: the run starts" 'wait_for "$out/observables.h5" 60'
  sleep 1
  local victim=$pid
  [ "$target" = one ] && victim=$(ps -o pid= --ppid "$pid" | head -n 1)
  kill -TERM $victim
  local i
  for ((i = 0; i < bound * 20; ++i)); do
    kill -0 "$pid" 2> /dev/null || break
    sleep 0.05
  done
  kill -9 "$pid" 2> /dev/null
  wait "$pid"
  code=$?
  check "$name: exit 0 after SIGTERM (got $code; $(head -c 300 "$tmp/$name.err"))" \
    '[ "$code" -eq 0 ]'
  check "$name: the stop line" \
    'grep -q "^received SIGTERM: stopped after .*, checkpoint .*checkpoint-[0-9]\{10\}.h5 written; exit 0 (continue with --restart .*)$" "$out/log.txt"'
  at=$(sed -n "s/^received SIGTERM: stopped after \(step \)\?\([0-9]*\).*/\2/p" "$out/log.txt")
  last=$(sed -n "s/^received SIGTERM: .*, checkpoint \(.*checkpoint-[0-9]\{10\}.h5\) written.*/\1/p" \
    "$out/log.txt")
  check "$name: the checkpoint of the step it stopped after (${at:-?}: ${last:-none})" \
    '[ -n "$at" ] && [ "$last" = "$out/$(printf "checkpoint-%010d.h5" "$at")" ] && [ -s "$last" ]'
  [ -n "$at" ] || at=0
}

# continued NAME FINAL SPECS -- COMMAND...: COMMAND --restart continues $tmp/NAME, COMMAND alone
# runs without a signal into $tmp/NAME-straight; their checkpoints at step FINAL hold the same
# state (same_state.py SPECS).
continued() {
  local name=$1 final=$2 specs=() out=$tmp/$1
  shift 2
  while [ "$1" != -- ]; do
    specs+=("$1")
    shift
  done
  shift
  runs "$name: --restart continues it" "$@" --restart "$out" --out "$out" > "$tmp/$name.re" 2>&1
  check "$name: the restart started where it stopped" \
    'grep -q "^restarted from .*$(printf "checkpoint-%010d.h5" "$at")" "$tmp/$name.re"'
  runs "$name: the run without a signal" "$@" --out "$out-straight" > /dev/null 2>&1
  local file
  file=$(printf "checkpoint-%010d.h5" "$final")
  check "$name: restarted and straight runs end in the same state (bitwise, $file)" \
    '/usr/bin/python3 "$same" "$out-straight/$file" "$out/$file" "${specs[@]}"'
}

# ---- mpcd: an SRD fluid in a channel driven by a body force, 40000 particles
cat > "$tmp/mpcd.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 2
seed = 5
steps = 1000000000
[domain]
size = [100.0, 40.0]
[fluid]
collision = "srd"
dt = 0.5
[body_force]
value = [0.001, 0.0]
[walls]
slip = false
[output]
every = 50
progress = false
TOML
stopped mpcd self "$narrows" run "$tmp/mpcd.toml"
continued mpcd $((at + 7)) fluid:position,velocity -- \
  "$narrows" run "$tmp/mpcd.toml" --set run.steps=$((at + 7))

# ---- lgca: FHP-III shear wave on 512 x 512 sites
cat > "$tmp/lgca.toml" <<'TOML'
[run]
engine = "lgca"
seed = 7
steps = 1000000000
[lattice]
model = "fhp-iii"
size = [512, 512]
density = 0.3
initial = "shear-wave"
amplitude = 0.05
[output]
every = 100
observables = ["shear_wave"]
progress = false
TOML
stopped lgca self "$narrows" run "$tmp/lgca.toml"
continued lgca $((at + 9)) /particles/lattice/state/value -- \
  "$narrows" run "$tmp/lgca.toml" --set run.steps=$((at + 9))

# ---- kmc: open TASEP, a step is a round of replicas (one per rank); the unfinished round is
# dropped on SIGTERM
kmc=(--set kmc.length=400 --set kmc.time=3000 --set kmc.warmup=100 --set output.progress=false)
stopped kmc self "$narrows" run "$src/run/tasep_open.toml" "${kmc[@]}" --set kmc.replicas=100000
continued kmc $((at + 2)) /kmc/counters /kmc/mean /kmc/m2 -- \
  "$narrows" run "$src/run/tasep_open.toml" "${kmc[@]}" --set kmc.replicas=$((at + 2))

# ---- continuum: the Burgers shock (500000 steps); its end is continuum.time, which a restart
# keeps: both runs go to the end
burgers=(--set continuum.time=100000.0 --set continuum.samples=4 --set output.checkpoint_every=0
  --set output.progress=false)
stopped continuum self "$narrows" run "$src/run/continuum_burgers_riemann.toml" "${burgers[@]}"
final=$(sed -n 's/^time: .* in \([0-9]*\) steps.*/\1/p' "$tmp/continuum/log.txt")
check "continuum: stopped before its last step ($at of ${final:-?})" \
  '[ -n "$final" ] && [ "$at" -lt "$final" ]'
continued continuum "${final:-0}" /continuum/density -- \
  "$narrows" run "$src/run/continuum_burgers_riemann.toml" "${burgers[@]}"

# ---- continuum on 2 ranks (every rank advances the same cells), SIGTERM to one rank only: the
# ranks agree on the step to stop after
stopped continuum_2ranks one "${mpi[@]}" -n 2 "$narrows" run \
  "$src/run/continuum_burgers_riemann.toml" "${burgers[@]}"

finish "stop every engine"
