#!/usr/bin/env bash
# Issue 18 item 7: every engine stops cleanly on SIGTERM at extreme parameter values that
# `check` accepts. For each case: start the run, wait until it runs (observables.h5 exists),
# send SIGTERM, and expect exit 0 within 20 s, the log line that says why, a checkpoint, and a
# restart from it that runs one step (kmc: one replica cannot finish at these rates, so the
# restart is stopped the same way and must say where it continued). On 2 ranks SIGTERM goes
# to one rank only (the stop is agreed collectively) and then to every rank (as SLURM does).
set -u
source "$(dirname "$0")/common.bash"
pids=()
trap 'for p in "${pids[@]}"; do kill -9 "$p" 2> /dev/null; done; rm -rf "$tmp"' EXIT
bound=20 # seconds from SIGTERM to exit

# Waits up to $bound s for PID $1; kills it if it is still running. Sets code and took (s).
wait_bounded() {
  local pid=$1 t0 i
  t0=$(date +%s%N)
  for ((i = 0; i < bound * 20; ++i)); do
    kill -0 "$pid" 2> /dev/null || break
    sleep 0.05
  done
  kill -9 "$pid" 2> /dev/null
  wait "$pid"
  code=$?
  took=$((($(date +%s%N) - t0) / 1000000))
}

# stopped NAME OUT SIGNAL-TARGETS COMMAND...: runs COMMAND --out OUT in the background, sends
# SIGTERM once it runs, and checks the clean stop. SIGNAL-TARGETS: "self" (the command's PID)
# or "one"/"all" ranks (children of mpirun).
stopped() {
  local name=$1 out=$2 target=$3
  shift 3
  "$@" --out "$out" > "$tmp/$name.out" 2> "$tmp/$name.err" &
  local pid=$!
  pids+=("$pid")
  check "$name: the run starts" 'wait_for "$out/observables.h5" 120'
  sleep 1
  local victims=$pid
  if [ "$target" != self ]; then
    local ranks
    read -ra ranks <<< "$(ps -o pid= --ppid "$pid" | tr '\n' ' ')"
    victims=${ranks[*]}
    [ "$target" = one ] && victims=${ranks[0]}
  fi
  # shellcheck disable=SC2086
  kill -TERM $victims
  wait_bounded "$pid"
  echo "$name: stopped $took ms after SIGTERM"
  check "$name: exit 0 after SIGTERM (got $code; $(head -c 300 "$tmp/$name.err"))" '[ "$code" -eq 0 ]'
  check "$name: stopped within $bound s (took $took ms)" '[ "$took" -lt $((bound * 1000)) ]'
  check "$name: log line says why it stopped" \
    'grep -q "received SIGTERM: stopped after .*checkpoint-[0-9]\{10\}.h5 written; exit 0" "$out/log.txt"'
  check "$name: nothing on stderr" '[ ! -s "$tmp/$name.err" ] || { cat "$tmp/$name.err"; false; }'
  last=$(sed -n "s/.*checkpoint \(.*checkpoint-[0-9]\{10\}.h5\) written; exit 0.*/\1/p" "$out/log.txt")
  check "$name: the checkpoint exists" '[ -n "$last" ] && [ -s "$last" ]'
  step=$((10#$(echo "${last:-checkpoint-0.h5}" | sed 's/.*checkpoint-\([0-9]*\).h5/\1/')))
}

# restarted NAME OUT COMMAND...: COMMAND --restart OUT one step beyond $step continues it.
restarted() {
  local name=$1 out=$2
  shift 2
  runs "$name: one-step restart" "$@" --restart "$out" --set run.steps=$((step + 1)) \
    --out "$out" > "$tmp/$name.re" 2>&1
  check "$name: the restart continued the checkpoint" \
    'grep -q "restarted from .* at step $step" "$tmp/$name.re"'
}
# extreme NAME SCENE SETS...: check accepts the scene, SIGTERM stops its run cleanly, and the
# checkpoint restarts.
extreme() {
  local name=$1 scene=$2
  shift 2
  runs "$name: the scene passes check" "$narrows" check "$scene" "$@" > /dev/null
  stopped "$name" "$tmp/$name" self "$narrows" run "$scene" "$@"
  restarted "$name" "$tmp/$name" "$narrows" run "$scene" "$@"
}

# ---- mpcd: 2.56e6 particles in 16 x 16 cells, kT = 1e6 (check's limit: above it the
# runaway-speed invariant, |v| <= 1e4, would stop the run at its first observation), mean free
# path 1e6 cells (check's limit), the largest run.steps.
cat > "$tmp/mpcd.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 2
seed = 1
steps = 9999999999
[domain]
size = [16.0, 16.0]
[fluid]
collision = "srd"
density = 1e4
dt = 1000.0
kT = 1e6
[output]
every = 1000000
progress = false
TOML
extreme mpcd "$tmp/mpcd.toml"
refused "mpcd: kT = 1e10 is refused by check" "fluid.kT = 1e+10 gives thermal speeds" \
  "$narrows" check "$tmp/mpcd.toml" --set fluid.kT=1e10 --set fluid.dt=1e-3

# ---- mpcd on 2 ranks: SIGTERM to one rank only, then to both ranks
stopped mpcd_2ranks_one "$tmp/mpcd2" one "${mpi[@]}" -n 2 "$narrows" run "$tmp/mpcd.toml"
restarted mpcd_2ranks_one "$tmp/mpcd2" "${mpi[@]}" -n 2 "$narrows" run "$tmp/mpcd.toml"
stopped mpcd_2ranks_all "$tmp/mpcd3" all "${mpi[@]}" -n 2 "$narrows" run "$tmp/mpcd.toml"

# ---- mpcd with colloids: the largest md_substeps, colloids of mass 1e300, the largest
# run.steps (density 10: one step at md_substeps = 10000 takes a fraction of a second)
colloid_sets=(--set colloids.md_substeps=10000 --set colloids.mass=1e300
  --set run.steps=9999999999 --set output.every=1000000)
extreme mpcd_colloids "$src/run/colloids_conservation.toml" "${colloid_sets[@]}"

# ---- lgca: FHP-III on 4096 x 4096 sites at d = 0.999, the largest run.steps
cat > "$tmp/lgca.toml" <<'TOML'
[run]
engine = "lgca"
seed = 7
steps = 9999999999
[lattice]
model = "fhp-iii"
size = [4096, 4096]
density = 0.999
[output]
every = 1000000000
progress = false
TOML
extreme lgca "$tmp/lgca.toml"

# ---- lgca with a moving colloid: mass 1e-300 (the disc takes any momentum), radius 60,
# averages over 1e5 lags
lc_sets=(--set colloid.mass=1e-300 --set colloid.radius=60.0 --set colloid.max_lag=100000
  --set run.steps=9999999999)
extreme lgca_colloid "$src/run/lgca_colloid_moving.toml" "${lc_sets[@]}"

# ---- kmc: the issue's case, family 2 with a huge c. c = 1e300 makes a rate infinite and is
# refused; 1e150 is the largest decade check accepts (rates up to 1e300) once kmc.max_tries is
# lifted to 1e308. A replica never ends, so the restart is stopped the same way.
kmc_sets=(--set kmc.parameters.c=1e150 --set kmc.max_tries=1e308)
scene_k="$src/run/kmc_family2_shock.toml"
refused "kmc: c = 1e300 is refused" "infinite\|inf expected tries" \
  "$narrows" check "$scene_k" --set kmc.parameters.c=1e300 --set kmc.max_tries=1e308
runs "kmc extreme scene passes check" "$narrows" check "$scene_k" "${kmc_sets[@]}" > /dev/null
stopped kmc "$tmp/kmc" self "$narrows" run "$scene_k" "${kmc_sets[@]}"
stopped kmc_restart "$tmp/kmc" self "$narrows" run "$scene_k" "${kmc_sets[@]}" --restart "$tmp/kmc"
check "kmc: the restart continued the checkpoint" \
  'grep -q "restarted from .*checkpoint-0000000000.h5 with 0 of 64 replicas done" "$tmp/kmc/log-0000000000.txt"'

# ---- kmc: a lattice that cannot move (all sites empty) after a warm-up of 1e14: the snapshot
# interval of the observed time 1 is below the resolution of t. Used to take the same snapshot
# for ever without asking for stop signals; now a runtime error at once.
cat > "$tmp/frozen.toml" <<'TOML'
[run]
engine = "kmc"
seed = 3
[kmc]
length = 1000
boundary = "periodic"
rates = { "10->01" = 1.0 }
initial = { kind = "product", probabilities = [1.0, 0.0, 0.0] }
time = 1.0
warmup = 1e14
replicas = 4
max_tries = 1e308
TOML
runs "kmc frozen lattice passes check" "$narrows" check "$tmp/frozen.toml" > /dev/null
"$narrows" run "$tmp/frozen.toml" --out "$tmp/frozen" > /dev/null 2> "$tmp/frozen.err" &
pid=$!
pids+=("$pid")
wait_bounded "$pid"
check "kmc frozen lattice: exit 3 within $bound s (got $code after $took ms)" '[ "$code" -eq 3 ]'
check "kmc frozen lattice: says why" 'grep -q "snapshot interval .* cannot advance the time" "$tmp/frozen.err"'

# ---- lgca dhumieres-1d (no checkpoints): 4e8 steps per replica; SIGTERM ends it at once with
# exit 0 and a line saying that nothing was written.
"$narrows" run "$src/run/lgca_dhumieres_fig1.toml" --set run.steps=400000000 --out "$tmp/dh" \
  > "$tmp/dh.out" 2> "$tmp/dh.err" &
pid=$!
pids+=("$pid")
check "dhumieres: the run starts" 'wait_for "$tmp/dh/log.txt" 60'
sleep 1
kill -TERM "$pid"
wait_bounded "$pid"
echo "dhumieres: stopped $took ms after SIGTERM"
check "dhumieres: exit 0 after SIGTERM (got $code)" '[ "$code" -eq 0 ]'
check "dhumieres: stopped within $bound s (took $took ms)" '[ "$took" -lt $((bound * 1000)) ]'
check "dhumieres: log line says nothing was written" \
  'grep -q "stopped by a signal before every curve was measured.*no result is written; exit 0" "$tmp/dh/log.txt"'

finish "stop at extremes"
