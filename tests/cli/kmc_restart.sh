#!/usr/bin/env bash
# Checkpoint and restart of the kmc engine. A checkpoint holds the running sums over the
# finished replicas, so a continuation gives the numbers of an uninterrupted run bit for bit:
# from an intermediate checkpoint, with kmc.replicas raised on restart, on 2 ranks after 1,
# and after SIGTERM (which drops the unfinished round of replicas and exits 0). A restart
# that changes the model, lowers kmc.replicas below the replicas done, or points at a
# checkpoint of another engine exits 2 with one line.
set -u
source "$(dirname "$0")/common.bash"

scene=$src/run/tasep_open.toml
short=(--set kmc.length=200 --set kmc.time=500 --set kmc.warmup=50)

# Every observable of run A equals that of run B, bitwise.
same() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r")["observables"] for p in sys.argv[1:3])
assert sorted(a) == sorted(b), (sorted(a), sorted(b))
for k in a:
    assert np.array_equal(a[k]["value"][()], b[k]["value"][()]), k
PY
}

runs "uninterrupted run" "$narrows" run "$scene" "${short[@]}" --set kmc.replicas=6 --set output.checkpoint_every=2 \
  --out "$tmp/full" > /dev/null 2>&1
check "checkpoints after 4 and 6 replicas (2 kept)" \
  '[ -f "$tmp/full/checkpoint-0000000004.h5" ] && [ -f "$tmp/full/checkpoint-0000000006.h5" ]'

# Continue from the checkpoint after 4 replicas.
mkdir -p "$tmp/part"
cp "$tmp/full/checkpoint-0000000004.h5" "$tmp/part/"
runs "restart from 4 of 6 replicas" "$narrows" run "$scene" "${short[@]}" --set kmc.replicas=6 --restart "$tmp/part" \
  --out "$tmp/part" > /dev/null 2>&1
check "restart: log says where it started" \
  'grep -q "^restarted from .*checkpoint-0000000004.h5 with 4 of 6 replicas done" "$tmp/part/log-0000000004.txt"'
check "restart from 4 of 6 replicas: bitwise the uninterrupted numbers" \
  'same "$tmp/full/observables.h5" "$tmp/part/observables-0000000004.h5"'

# 3 replicas on 1 rank, then raised to 6 on 2 ranks.
runs "3 replicas on 1 rank" "$narrows" run "$scene" "${short[@]}" --set kmc.replicas=3 \
  --out "$tmp/grow" > /dev/null 2>&1
runs "3 replicas then 3 more on 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$scene" "${short[@]}" --set kmc.replicas=6 --restart "$tmp/grow" \
  --out "$tmp/grow" > /dev/null 2>&1
check "3 replicas then 3 more on 2 ranks: bitwise the uninterrupted numbers" \
  'same "$tmp/full/observables.h5" "$tmp/grow/observables-0000000003.h5"'

# SIGTERM during a long run: the unfinished round is dropped, the finished replicas are kept.
# (Long enough that the engine is still running a second after it started: about 5 s on one
# idle core.)
long=(--set kmc.length=2000 --set kmc.time=16000 --set kmc.warmup=100 --set kmc.replicas=40
  --set output.progress=false)
"$narrows" run "$scene" "${long[@]}" --out "$tmp/sig" > "$tmp/sig.out" 2>&1 &
pid=$!
for ((i = 0; i < 3000; ++i)); do
  compgen -G "$tmp/sig/log.txt" > /dev/null && break
  sleep 0.01
done
sleep 1
kill -TERM "$pid"
wait "$pid"
code=$?
check "SIGTERM: exit 0 (got $code)" '[ "$code" -eq 0 ]'
check "SIGTERM: log line with the replicas done" \
  'grep -q "^received SIGTERM: stopped after [0-9]* of 40 replicas, checkpoint" "$tmp/sig/log.txt"'
done_at=$(sed -n 's/^received SIGTERM: stopped after \([0-9]*\) of 40.*/\1/p' "$tmp/sig/log.txt")
check "SIGTERM: stopped before the end (after ${done_at:-?} replicas)" \
  '[ -n "$done_at" ] && [ "$done_at" -lt 40 ]'
runs "SIGTERM: restart to the end" "$narrows" run "$scene" "${long[@]}" --restart "$tmp/sig" --out "$tmp/sig" > /dev/null 2>&1
runs "uninterrupted long run on 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$scene" "${long[@]}" \
  --out "$tmp/nosig" > /dev/null 2>&1
from=$(printf '%010d' "${done_at:-0}")
check "SIGTERM then restart: bitwise a 2-rank uninterrupted run" \
  'same "$tmp/nosig/observables.h5" "$tmp/sig/observables-$from.h5"'

# Refused restarts: exit 2, one line naming the key.
refused "changed rate" 'kmc.left."0->1" = 0.4 but checkpoint .* has 0.3' \
  "$narrows" run "$scene" "${short[@]}" --set kmc.replicas=6 --set 'kmc.left={"0->1"=0.4}' \
  --restart "$tmp/full/checkpoint-0000000004.h5" --out "$tmp/r1"
refused "fewer replicas than done" 'checkpoint-0000000004.h5: at step 4 and kmc.replicas = 3: nothing to run; allowed: kmc.replicas above 4' \
  "$narrows" run "$scene" "${short[@]}" --set kmc.replicas=3 --restart "$tmp/full/checkpoint-0000000004.h5" \
  --out "$tmp/r2"
refused "pair correlations added on restart" 'output.observables lists "pair_correlation" but checkpoint .* lacks its running sums' \
  "$narrows" run "$scene" "${short[@]}" --set kmc.replicas=6 \
  --set 'output.observables=["current","density_profile","pair_correlation"]' \
  --restart "$tmp/full/checkpoint-0000000004.h5" --out "$tmp/r3"
cat > "$tmp/mpcd.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 2
steps = 5
[domain]
size = [8.0, 4.0]
[fluid]
collision = "srd"
dt = 0.5
[output]
progress = false
TOML
runs "mpcd run" "$narrows" run "$tmp/mpcd.toml" --out "$tmp/mpcd" > /dev/null 2>&1
refused "mpcd checkpoint for a kmc scene" 'run.engine = "kmc" but checkpoint .* has "mpcd"' \
  "$narrows" run "$scene" "${short[@]}" --restart "$tmp/mpcd" --out "$tmp/r4"
refused "kmc checkpoint for an mpcd scene" 'run.engine = "mpcd" but checkpoint .* has "kmc"' \
  "$narrows" run "$tmp/mpcd.toml" --restart "$tmp/full" --out "$tmp/r5"
check "refused restarts wrote nothing" \
  '[ ! -e "$tmp/r1" ] && [ ! -e "$tmp/r2" ] && [ ! -e "$tmp/r3" ] && [ ! -e "$tmp/r4" ] && [ ! -e "$tmp/r5" ]'

finish kmc_restart
