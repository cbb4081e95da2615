#!/usr/bin/env bash
# A restart continues the checkpoint's own scene (issues 16, 17, 18), for every engine:
# - one table: a change in each top-level section of one scene per engine (mpcd, lgca, kmc) is
#   refused with one line naming the key (or the section added or deleted), exit 2, nothing
#   written; run.steps and output.* changes are accepted;
# - a deleted section/key is refused naming it (the [walls] bug of main 941882a);
# - a run made with --set continues with the same --set, or with no scene file at all
#   (--restart DIR), but not from the scene file without the --set;
# - a fresh run into a folder with a run's checkpoints needs --overwrite;
# - a restart with no steps left writes nothing (exit 0 at the end, exit 2 before it);
# - a checkpoint written before /parameters/canonical_scene existed (main 0aac96f) restarts,
#   its /parameters/scene canonicalised, and refuses a changed key the same way;
# - a checkpoint write that fails (zero fluid particles, an HDF5 error) leaves no .tmp;
# - a checkpoint refused on one rank only (an out-of-range particle id) ends every rank with one
#   line and exit 2, on 2 and 3 ranks (main hung on 2).
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3

cat > "$tmp/mpcd.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 2
seed = 5
steps = 4
[domain]
size = [12.0, 8.0]
[fluid]
collision = "srd"
density = 5
dt = 0.5
[body_force]
value = [0.001, 0.0]
[walls]
slip = false
[thermostat]
kind = "layers"
[output]
every = 2
progress = false
TOML
grep -v -e '^\[walls\]' -e '^slip' "$tmp/mpcd.toml" > "$tmp/mpcd-nowalls.toml"
grep -v -e '^\[thermostat\]' -e '^kind' "$tmp/mpcd.toml" > "$tmp/mpcd-at.toml" # at+a: no thermostat

cat > "$tmp/lgca.toml" <<'TOML'
[run]
engine = "lgca"
seed = 11
steps = 4
[lattice]
model = "fhp-saturated"
size = [32, 32]
density = 0.3
initial = "equilibrium"
walls = true
[colloid]
position = [16.0, 16.0]
radius = 2.5
mass = 100.0
max_lag = 2
displacement_lag = 2
displacement_every = 1
[output]
every = 2
progress = false
observables = ["colloid_vacf"]
TOML
grep -v '^walls' "$tmp/lgca.toml" > "$tmp/lgca-nowalls.toml"

cat > "$tmp/kmc.toml" <<'TOML'
[run]
engine = "kmc"
seed = 3
steps = 0
[kmc]
length = 50
boundary = "open"
rates = { "10->01" = 1.0 }
left = { "0->1" = 0.3 }
right = { "1->0" = 0.7 }
initial = { kind = "product", probabilities = [0.7, 0.3, 0.0] }
time = 20.0
warmup = 5.0
replicas = 2
[output]
progress = false
TOML
grep -v '^left' "$tmp/kmc.toml" > "$tmp/kmc-noleft.toml"

for e in mpcd lgca kmc; do
  "$narrows" run "$tmp/$e.toml" --out "$tmp/$e" > /dev/null 2> "$tmp/err"
  check "$e: first run exits 0" '[ $? -eq 0 ]'
done

# engine | --set(s) that change one top-level section | the key the refusal names
while IFS='|' read -r e sets key; do
  [ -n "$e" ] || continue
  out="$tmp/x-$e-${sets%%=*}"
  args=()
  for set in $sets; do args+=(--set "$set"); done
  refused "$e: --set $sets refused naming $key" "$e.toml: $key = .* but checkpoint .*; allowed: the checkpoint's scene" \
    "$narrows" run "$tmp/$e.toml" "${args[@]}" --set run.steps=8 --restart "$tmp/$e" --out "$out"
  check "$e: --set $sets: nothing written" '[ ! -e "$out" ]'
done <<'TABLE'
mpcd|run.seed=6|run.seed
mpcd|domain.size=[14.0,8.0]|domain.size
mpcd|fluid.dt=0.25|fluid.dt
mpcd|body_force.value=[0.002,0.0]|body_force.value
mpcd|walls.virtual_particles=false|walls.virtual_particles
mpcd|thermostat.kind=monte-carlo|thermostat.kind
mpcd|colloids.count=1 colloids.radius=1.0|\[colloids\]
lgca|run.seed=12|run.seed
lgca|lattice.density=0.4|lattice.density
lgca|colloid.mass=90.0|colloid.mass
lgca|tagged.max_lag=2|\[tagged\]
kmc|run.seed=4|run.seed
kmc|kmc.time=30.0|kmc.time
TABLE

# What may change: run.steps (kmc: kmc.replicas) and output.*.
for e in mpcd lgca; do
  "$narrows" run "$tmp/$e.toml" --set run.steps=6 --set output.every=3 --set output.checkpoint_keep=3 \
    --restart "$tmp/$e" --out "$tmp/$e" > /dev/null 2> "$tmp/err"
  check "$e: run.steps and output.* may change on a restart" '[ $? -eq 0 ] || { cat "$tmp/err"; false; }'
done
"$narrows" run "$tmp/kmc.toml" --set kmc.replicas=3 --set output.checkpoint_keep=3 \
  --restart "$tmp/kmc" --out "$tmp/kmc" > /dev/null 2> "$tmp/err"
check "kmc: kmc.replicas and output.* may change on a restart" '[ $? -eq 0 ] || { cat "$tmp/err"; false; }'

# A deleted section or key is refused, naming it.
refused "mpcd: [walls] deleted" "mpcd-nowalls.toml: \[walls\] = absent but checkpoint .* has present" \
  "$narrows" run "$tmp/mpcd-nowalls.toml" --set run.steps=8 --restart "$tmp/mpcd" --out "$tmp/y1"
refused "lgca: lattice.walls deleted" "lattice.walls = (not set: the default false) but checkpoint .* has true" \
  "$narrows" run "$tmp/lgca-nowalls.toml" --set run.steps=8 --restart "$tmp/lgca" --out "$tmp/y2"
refused "kmc: kmc.left deleted" 'kmc.left."0->1" = (not set) but checkpoint .* has 0.3' \
  "$narrows" run "$tmp/kmc-noleft.toml" --set kmc.replicas=4 --restart "$tmp/kmc" --out "$tmp/y3"
check "deleted keys: nothing written" '[ ! -e "$tmp/y1" ] && [ ! -e "$tmp/y2" ] && [ ! -e "$tmp/y3" ]'

# A run made with --set: the same --set, or no scene file, continues; the file alone is refused.
while IFS='|' read -r e scene set key more; do
  [ -n "$e" ] || continue
  "$narrows" run "$tmp/$scene.toml" --set "$set" --out "$tmp/s-$e" > /dev/null 2> "$tmp/err"
  check "$e: run with --set $set exits 0" '[ $? -eq 0 ] || { cat "$tmp/err"; false; }'
  "$narrows" run "$tmp/$scene.toml" --set "$set" --set "$more" --restart "$tmp/s-$e" --out "$tmp/s-$e" \
    > /dev/null 2> "$tmp/err"
  check "$e: restart with the same --set exits 0" '[ $? -eq 0 ] || { cat "$tmp/err"; false; }'
  more2=${more%=*}=$((${more#*=} * 2))
  abs=$(realpath "$narrows")
  (cd "$tmp" && "$abs" run --restart "s-$e" --set "$more2" > /dev/null 2> "$tmp/err")
  check "$e: restart with no scene file exits 0" '[ $? -eq 0 ] || { cat "$tmp/err"; false; }'
  check "$e: ... and continued the checkpoint's scene in its folder" \
    'grep -q "^restarted from" "$tmp/s-$e/log-$(printf %010d "${more#*=}").txt"'
  refused "$e: restart from the file without --set $set" "$scene.toml: $key = .* but checkpoint" \
    "$narrows" run "$tmp/$scene.toml" --set "$more2" --restart "$tmp/s-$e" --out "$tmp/s2-$e"
done <<'TABLE'
mpcd|mpcd-at|fluid.collision=at+a|fluid.collision|run.steps=8
lgca|lgca|lattice.density=0.4|lattice.density|run.steps=8
kmc|kmc|kmc.time=30.0|kmc.time|kmc.replicas=4
TABLE
refused "run without a scene file needs --restart" "run needs a scene file, or --restart DIR" \
  "$narrows" run --out "$tmp/z"
refused "--restart ''" "command line: --restart ''; allowed: a non-empty path" \
  "$narrows" run "$tmp/mpcd.toml" --restart '' --out "$tmp/z"
refused "--out ''" "command line: --out ''; allowed: a non-empty path" \
  "$narrows" run "$tmp/mpcd.toml" --out ''

# A fresh run into a folder with a run's checkpoints: refused unless --overwrite.
sum=$(md5sum "$tmp/mpcd"/checkpoint-*.h5)
refused "fresh run into a run's folder" "holds the checkpoints of a run .*--overwrite" \
  "$narrows" run "$tmp/mpcd.toml" --set run.steps=2 --out "$tmp/mpcd"
check "... left its checkpoints untouched" '[ "$(md5sum "$tmp/mpcd"/checkpoint-*.h5)" = "$sum" ]'
"$narrows" run "$tmp/mpcd.toml" --set run.steps=2 --overwrite --out "$tmp/mpcd" > /dev/null 2>&1
check "--overwrite: exit 0, only the new run's checkpoint is left" \
  '[ $? -eq 0 ] && [ "$(cd "$tmp/mpcd" && ls checkpoint-*)" = checkpoint-0000000002.h5 ]'

# No steps left: nothing to run, nothing written.
before=$(ls "$tmp/lgca")
"$narrows" run "$tmp/lgca.toml" --set run.steps=6 --restart "$tmp/lgca" --out "$tmp/lgca" > /dev/null 2> "$tmp/err"
code=$?
check "restart at run.steps: exit 0 (got $code)" '[ "$code" -eq 0 ]'
check "restart at run.steps: one line saying so" \
  '[ "$(grep -c . "$tmp/err")" -eq 1 ] && grep -q "nothing to run, nothing written" "$tmp/err"'
refused "restart beyond run.steps" "at step 6 and run.steps = 5: nothing to run" \
  "$narrows" run "$tmp/lgca.toml" --set run.steps=5 --restart "$tmp/lgca" --out "$tmp/lgca"
check "no-step restarts wrote nothing" '[ "$(ls "$tmp/lgca")" = "$before" ]'

# A checkpoint of the old format: no /parameters/canonical_scene, the scene text as written.
mkdir -p "$tmp/old"
$py - "$tmp/lgca/checkpoint-0000000006.h5" "$tmp/old/checkpoint-0000000006.h5" <<'PY'
import shutil, sys, h5py
shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "r+") as f:
    del f["parameters/canonical_scene"]
PY
refused "old-format checkpoint: a changed key" "lattice.density = 0.35 but checkpoint .* has 0.3" \
  "$narrows" run "$tmp/lgca.toml" --set lattice.density=0.35 --set run.steps=8 --restart "$tmp/old" --out "$tmp/old"
"$narrows" run "$tmp/lgca.toml" --set run.steps=8 --restart "$tmp/old" --out "$tmp/old" > /dev/null 2> "$tmp/err"
code=$?
check "old-format checkpoint restarts (exit $code)" '[ "$code" -eq 0 ] || { cat "$tmp/err"; false; }'

# A failed checkpoint write (HDF5 cannot address an empty dataset) leaves no .tmp behind.
"$narrows" run "$tmp/mpcd.toml" --set fluid.density=1e-9 --out "$tmp/empty" > /dev/null 2>&1
code=$?
check "no fluid particles: not exit 0 (got $code)" '[ "$code" -ne 0 ]'
check "no fluid particles: no checkpoint .tmp left" '! ls "$tmp/empty" 2> /dev/null | grep -q "\.tmp$"'

# Refusal is collective: an out-of-range id read by one rank only. The edited dataset gets its
# checksum recomputed (io/row_hash.hpp: the sum over rows of row_hash(row, id)), so the
# refusal comes from the id range check (mpcd/restart_checks.cpp), not from the checksum.
"$narrows" run "$tmp/mpcd.toml" --set walls.slip=true --out "$tmp/ids" > /dev/null 2>&1
$py - "$tmp/ids/checkpoint-0000000004.h5" "$tmp/bad-id.h5" <<'PY'
import shutil, sys, h5py, numpy as np
shutil.copy(sys.argv[1], sys.argv[2])
def row_hashes(ids):  # io::row_hash of rows 0..n-1, one 64-bit word each, mod 2^64
    with np.errstate(over="ignore"):
        h = (np.arange(len(ids), dtype=np.uint64) + np.uint64(1)) * np.uint64(0x9e3779b97f4a7c15)
        h = (h ^ ids.astype(np.uint64)) * np.uint64(0xd6e8feb86659fd93)
        h ^= h >> np.uint64(32)
        h *= np.uint64(0xd6e8feb86659fd93)
        return h ^ (h >> np.uint64(32))
with h5py.File(sys.argv[2], "r+") as f:
    d = f["particles/fluid/id/value"]
    ids = d[...]
    stored = int(np.asarray(d.attrs["checksum"]).ravel()[0])
    assert int(row_hashes(ids).sum(dtype=np.uint64)) == stored, "row_hash.hpp changed"
    ids[len(ids) - 1] = 10**9  # the last row: read by the last rank
    d[...] = ids
    d.attrs["checksum"] = np.array([row_hashes(ids).sum(dtype=np.uint64)], dtype=np.uint64)
PY
for n in 2 3; do
  refused "out-of-range id on $n ranks" \
    "bad-id.h5: /particles/fluid/id/value row [0-9]* holds id 1000000000; allowed: 0 to [0-9]*$" \
    timeout 120 "${mpi[@]}" -n "$n" "$narrows" run "$tmp/mpcd.toml" --set walls.slip=true \
    --set run.steps=8 --restart "$tmp/bad-id.h5" --out "$tmp/b$n"
  check "out-of-range id on $n ranks: nothing written" '[ ! -e "$tmp/b$n" ]'
done

finish restart_same_scene
