#!/usr/bin/env bash
# Every lgca scene in run/ passes `check` and runs briefly with its observables; 2 ranks write
# the 1-rank numbers; a restart (on another rank count) ends in the same lattice as the
# uninterrupted run; tools/lgca_plot.py draws the output (fields, shear wave, VACF); bad lattice
# and tagged keys exit 2 with one line.
set -u
source "$(dirname "$0")/common.bash"

for scene in "$src"/run/lgca*.toml; do
  name=$(basename "$scene" .toml)
  small=(--set run.steps=40 --set output.every=10)
  # scenes with a tagged VACF complete 4 curves of 10 lags (the 1D one per replica)
  if grep -q '^\[tagged\]' "$scene"; then
    small+=(--set tagged.max_lag=10)
  fi
  one_d=0
  grep -q 'dhumieres-1d' "$scene" && one_d=1
  colloid=0
  grep -q '^\[colloid\]' "$scene" && colloid=1
  runs "$name: check" "$narrows" check "$scene" > "$tmp/$name.check" 2>&1
  runs "$name: run" "$narrows" run "$scene" "${small[@]}" --out "$tmp/$name" > "$tmp/$name.out" 2>&1
  check "$name: Loop time line" \
    'grep -q "^Loop time of .* on 1 ranks for 40 steps with .* sites (.* site-updates/s)$" "$tmp/$name/log.txt"'
  if [ "$one_d" -eq 0 ]; then
    check "$name: final checkpoint" '[ -f "$tmp/$name/checkpoint-0000000040.h5" ]'
  fi
  if [ "$colloid" -eq 1 ]; then
    check "$name: colloid momentum line" 'grep -q "momentum conserved exactly" "$tmp/$name/log.txt"'
  fi
  runs "$name: 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$scene" "${small[@]}" --out "$tmp/$name-2" > /dev/null 2>&1
  check "$name: 2 ranks write the 1-rank observables and lattice" '/usr/bin/python3 - "$tmp/$name" "$tmp/$name-2" <<PY
import sys, h5py, numpy as np
a = h5py.File(sys.argv[1] + "/observables.h5", "r")["observables"]
b = h5py.File(sys.argv[2] + "/observables.h5", "r")["observables"]
assert sorted(a) == sorted(b) and len(a) > 0, (list(a), list(b))
for k in a:
    assert np.array_equal(a[k]["value"][()], b[k]["value"][()]), k
    assert np.array_equal(a[k]["step"][()], b[k]["step"][()]), k
if "shear_wave" in a:
    assert a["shear_wave/value"].shape == (5,), a["shear_wave/value"].shape
if "vacf" in a:
    z, e, lags = a["vacf/value"][()], a["vacf/error"][()], a["vacf/lags"][()]
    assert z.shape == (11,) and lags.shape == (11,) and z[0] == 1.0, (z.shape, z[0])
    assert np.all(np.isfinite(e)) and abs(z[1]) < 1, (z, e)
if "velocity" in a:
    v = a["velocity/value"]
    assert v.ndim == 4 and v.shape[0] == 4 and v.shape[3] == 2, v.shape
    assert a["density/value"].shape == v.shape[:3]
import os
if os.path.exists(sys.argv[1] + "/checkpoint-0000000040.h5"):
    ca = h5py.File(sys.argv[1] + "/checkpoint-0000000040.h5", "r")
    cb = h5py.File(sys.argv[2] + "/checkpoint-0000000040.h5", "r")
    assert np.array_equal(ca["particles/lattice/state/value"][()], cb["particles/lattice/state/value"][()])
    if "colloid" in ca:
        for k in ("momentum", "omega", "position", "angle"):
            assert np.array_equal(ca["colloid"][k][()], cb["colloid"][k][()]), k
PY'
done

# The plot tool draws both kinds of output.
for name in lgca_shear_wave lgca_channel lgca_vacf_tail lgca_dhumieres_fig1 lgca_colloid_held \
  lgca_colloid_held_light lgca_colloid_moving; do
  runs "$name: tools/lgca_plot.py" /usr/bin/python3 "$src/tools/lgca_plot.py" \
    "$tmp/$name/observables.h5" --first 5 --png "$tmp/$name.png" > "$tmp/$name.plot" 2>&1
  check "$name: tools/lgca_plot.py writes a PNG" '[ -s "$tmp/$name.png" ]'
done

# Restart: 20 steps on 2 ranks, then on to 40 on 1 rank = 40 steps straight on 1 rank.
scene=$src/run/lgca_shear_wave.toml
runs "restart: first part" "${mpi[@]}" -n 2 "$narrows" run "$scene" --set run.steps=20 --out "$tmp/rs" > /dev/null 2>&1
runs "restart: continuation" "$narrows" run "$scene" --set run.steps=40 --restart "$tmp/rs" --out "$tmp/rs" > /dev/null 2>&1
check "restart: log and observables of the continuation carry its first step" \
  '[ -f "$tmp/rs/log-0000000020.txt" ] && [ -f "$tmp/rs/observables-0000000020.h5" ]'
runs "restart: straight run" "$narrows" run "$scene" --set run.steps=40 --out "$tmp/straight" \
  > /dev/null 2>&1
check "restart: bitwise the uninterrupted lattice and shear wave" '/usr/bin/python3 - "$tmp" <<PY
import sys, h5py, numpy as np
t = sys.argv[1]
a = h5py.File(t + "/rs/checkpoint-0000000040.h5", "r")["particles/lattice/state/value"][()]
b = h5py.File(t + "/straight/checkpoint-0000000040.h5", "r")["particles/lattice/state/value"][()]
assert np.array_equal(a, b)
s = h5py.File(t + "/straight/observables.h5", "r")["observables/shear_wave/value"][()]
r1 = h5py.File(t + "/rs/observables.h5", "r")["observables/shear_wave/value"][()]
r2 = h5py.File(t + "/rs/observables-0000000020.h5", "r")["observables/shear_wave/value"][()]
assert np.array_equal(np.concatenate([r1, r2]), s), (len(r1), len(r2), len(s))
PY'
exits 2 "restart with another density" "$narrows" run "$scene" --set run.steps=60 \
  --set lattice.density=0.4 --restart "$tmp/rs" --out "$tmp/rs" > /dev/null 2> "$tmp/mismatch.err"
exits 2 "restart with another scene" "$narrows" run "$src/run/lgca_channel.toml" \
  --set run.steps=60 --restart "$tmp/rs" --out "$tmp/rs2" > /dev/null 2> "$tmp/mismatch2.err"
check "restart with another scene: one line" '[ "$(grep -c . "$tmp/mismatch2.err")" -eq 1 ]'

# Restart of the colloid: its momentum, angular velocity, centre, angle and averages come back
# from the checkpoint. A 600-step run on 2 ranks writes a checkpoint at step 300; continued from
# it on 1 rank, the run ends in the same lattice, colloid and colloid observables.
for cname in lgca_colloid_held lgca_colloid_moving; do
  # a 64 x 64 copy of the scene with a disc started at U = (0.3, 0.1) (a restart takes no
  # --set of scene keys other than run.steps and output.*)
  cscene=$tmp/$cname-small.toml
  sed -e 's/^size = .*/size = [64, 64]/' -e 's/^every = .*/every = 100/' \
    -e 's/^max_lag = .*/max_lag = 50/' -e 's/^displacement_lag = .*/displacement_lag = 200/' \
    -e 's/^displacement_every = .*/displacement_every = 10/' \
    -e 's/^position = .*/position = [60.0, 30.0]\nvelocity = [0.3, 0.1]/' \
    "$src/run/$cname.toml" > "$cscene"
  runs "$cname restart: straight run on 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$cscene" --set run.steps=600 \
    --set output.checkpoint_every=300 --out "$tmp/cstraight-$cname" > /dev/null 2>&1
  runs "$cname restart: continuation on 1 rank" "$narrows" run "$cscene" --set run.steps=600 \
    --restart "$tmp/cstraight-$cname/checkpoint-0000000300.h5" --out "$tmp/crs-$cname" \
    > /dev/null 2>&1
  check "$cname restart: bitwise the uninterrupted lattice and colloid" '/usr/bin/python3 - "$tmp" "$cname" <<PY
import sys, h5py, numpy as np
t, n = sys.argv[1], sys.argv[2]
a = h5py.File(t + "/crs-" + n + "/checkpoint-0000000600.h5", "r")
b = h5py.File(t + "/cstraight-" + n + "/checkpoint-0000000600.h5", "r")
k = "particles/lattice/state/value"
assert np.array_equal(a[k][()], b[k][()])
for q in ("momentum", "omega", "position", "angle", "correlations/layout", "correlations/values"):
    assert np.array_equal(a["colloid"][q][()], b["colloid"][q][()]), q
assert np.any(a["colloid/momentum"][()] != 0)
moved = not np.array_equal(a["colloid/position"][()], [60.0, 30.0])
assert moved == (n == "lgca_colloid_moving"), (n, a["colloid/position"][()])
PY'
  check "$cname restart: the colloid averages continue (observables bitwise the straight run)" \
    'grep -q "continue the averages of the checkpoint" "$tmp/crs-$cname/log-0000000300.txt" && /usr/bin/python3 - "$tmp" "$cname" <<PY
import sys, h5py, numpy as np
t, n = sys.argv[1], sys.argv[2]
a = h5py.File(t + "/crs-" + n + "/observables-0000000300.h5", "r")["observables"]
b = h5py.File(t + "/cstraight-" + n + "/observables.h5", "r")["observables"]
for g in ("colloid_vacf", "colloid_diffusion"):
    assert sorted(a[g]) == sorted(b[g]), (list(a[g]), list(b[g]))
    for k in a[g]:
        assert np.array_equal(a[g][k][()], b[g][k][()], equal_nan=True), (g, k)
assert a["colloid_vacf/error"][()][1] > 0  # ten blocks: a real comparison
PY'
done
# Another run.steps on the restart is a new averaging run (e.g. after an equilibration job).
runs "restart with another run.steps" "$narrows" run "$tmp/lgca_colloid_moving-small.toml" \
  --set run.steps=500 --restart "$tmp/cstraight-lgca_colloid_moving/checkpoint-0000000300.h5" \
  --out "$tmp/crs-new" > /dev/null 2>&1
check "restart with another run.steps: colloid averages start afresh" \
  'grep -q "start afresh (run.steps = 500" "$tmp/crs-new/log-0000000300.txt"'

# A checkpoint written before the centre and the averages were stored (momentum and omega
# only) still restarts a held disc; its averages start afresh.
mkdir -p "$tmp/oldfmt"
old=$tmp/oldfmt/checkpoint-0000000600.h5
cp "$tmp/crs-lgca_colloid_held/checkpoint-0000000600.h5" "$old"
runs "strip the centre and averages from a checkpoint" /usr/bin/python3 - "$old" <<PY
import sys, h5py
f = h5py.File(sys.argv[1], "r+")
for k in ("position", "angle", "correlations"):
    del f["colloid"][k]
PY
runs "held colloid restarts from a checkpoint without /colloid/position" "$narrows" run "$tmp/lgca_colloid_held-small.toml" --set run.steps=700 --restart "$old" \
  --out "$tmp/old-ckpt" > /dev/null 2> "$tmp/old-ckpt.err"
check "... and its averages start afresh" \
  'grep -q "start afresh" "$tmp/old-ckpt/log-0000000600.txt"'

# Bad input: exit 2, one line naming the key.
bad() {
  local label=$1 want=$2
  shift 2
  exits 2 "$label" "$narrows" check "$scene" "$@" > /dev/null 2> "$tmp/bad.err"
  check "$label: one line naming $want" \
    '[ "$(grep -c . "$tmp/bad.err")" -eq 1 ] && grep -qF "$want" "$tmp/bad.err"'
}
bad "density 1.5" "lattice.density" --set lattice.density=1.5
bad "odd size_y" "lattice.size[1]" --set 'lattice.size=[64,63]'
bad "unknown model" "lattice.model" --set lattice.model=fhp-iv
bad "unknown key" "lattice.colour" --set lattice.colour=3
bad "vacf without [tagged]" "[tagged]" --set 'output.observables=["vacf"]'
bad "replicas on an FHP model" "tagged.replicas" --set tagged.max_lag=10 --set tagged.replicas=2
bad "max_lag 0" "tagged.max_lag" --set tagged.max_lag=0
bad "dhumieres-1d without [tagged]" "[tagged]" --set lattice.model=dhumieres-1d \
  --set 'lattice.size=[64]' --set lattice.initial=equilibrium --set lattice.amplitude=0
bad "zero-momentum on FHP" "lattice.initial" --set lattice.initial=zero-momentum
bad "moving colloid with walls" "colloid.held" --set 'colloid.position=[10.0,10.0]' \
  --set colloid.held=false --set lattice.walls=true
bad "moving colloid smaller than 1/sqrt(3)" "colloid.radius" \
  --set 'colloid.position=[10.0,10.0]' --set colloid.held=false --set colloid.radius=0.55
bad "colloid.held not a boolean" "colloid.held" --set 'colloid.position=[10.0,10.0]' \
  --set colloid.held=3
bad "colloid without position" "colloid.position" --set colloid.radius=2.5
bad "amplitude too large" "lattice.amplitude" --set lattice.amplitude=0.9
bad "[fluid] in an lgca scene" "[fluid]" --set fluid.dt=0.1
finish lgca_scenes
