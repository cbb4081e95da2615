#!/usr/bin/env bash
# Scenes with [colloids]: every one in run/ runs briefly with finite observables; a colloid channel
# run on 2 ranks ends bitwise equal to 1 rank (fluid and colloids, compared by id in the final
# checkpoints); a restart (2 ranks to step 30, then 1 rank to 60) ends bitwise equal to the
# uninterrupted run; a checkpoint with the wrong colloid count is refused; placement = "file"
# reads the positions from a text file next to the scene, and a bad file is refused in one line.
# With unequal radii (radius_sd) the checkpoint stores each colloid's radius and mass, and the
# restart is bitwise equal too, also from a checkpoint without them (older format: drawn again).
set -u
source "$(dirname "$0")/common.bash"
same=$src/tests/cli/same_state.py
both="fluid:id,position,velocity colloids:id,position,velocity"
py=/usr/bin/python3

for scene in "$src"/run/*.toml; do
  grep -q '^\[colloids\]' "$scene" || continue
  name=$(basename "$scene" .toml)
  # Two samples each; the scenes of cluster size (over 300 000 fluid particles) take 20 steps.
  n=$("$narrows" info "$scene" | sed -n 's/^particles: \([0-9]*\) fluid.*/\1/p')
  steps=100
  [ "${n:-0}" -gt 300000 ] && steps=20
  runs --err "$tmp/$name.err" "$name: run" "$narrows" run "$scene" --set run.steps=$steps \
    --set output.every=$((steps / 2)) --set output.progress=false --out "$tmp/$name" > /dev/null
  check "$name: observables finite" '$py - "$tmp/$name/observables.h5" <<PY
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")["observables"]
for name in f:
    if f[name + "/step"].ndim == 0:
        continue  # a result of the whole run (colloid statistics: tests/cli/colloid_statistics.sh)
    # value, or every sampled dataset of a set of profiles (axial_fields: phi, velocity, ...)
    keys = ["value"] if "value" in f[name] else [k for k in f[name] if k not in ("step", "time", "bins")]
    for key in keys:
        v = f[name + "/" + key][()]
        assert v.shape[0] == 2 and np.all(np.isfinite(v)), (name, key, v)
PY'
done
# The density-wake tool on the wake scene's 100 steps (3 frames of every fluid particle).
runs "sedimentation.py --wake" $py "$src/tools/sedimentation.py" "$tmp/random_solvent_wake" \
  --skip 0 --blocks 3 --wake "$tmp/wake.png" > "$tmp/wake.txt"
check "sedimentation.py --wake reads the trajectory" \
  'grep -q "lane, ahead" "$tmp/wake.txt" && [ -s "$tmp/wake.png" ]'

cat > "$tmp/c.toml" <<'TOML'
[run]
dimensions = 2
seed = 12
steps = 60
[domain]
size = [24.0, 10.0]
[fluid]
collision = "srd"
density = 5
dt = 0.1
[walls]
[colloids]
radius = 1.5
count = 3
gravity = [0.02, 0.0]
[output]
every = 10
checkpoint_every = 30
progress = false
observables = ["momentum", "energy"]
TOML
runs "1 rank" "$narrows" run "$tmp/c.toml" --out "$tmp/one" > /dev/null 2>&1
runs "2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/c.toml" --out "$tmp/two" > /dev/null 2>&1
check "colloids stored in the checkpoint" '$py -c "import h5py,sys; f=h5py.File(sys.argv[1]); assert f[\"/particles/colloids/position/value\"].shape == (3, 2)" "$tmp/one/checkpoint-0000000060.h5"'
check "2 ranks bitwise equal to 1 rank (fluid and colloids)" \
  '$py "$same" "$tmp/one/checkpoint-0000000060.h5" "$tmp/two/checkpoint-0000000060.h5" $both'
runs "first part" "${mpi[@]}" -n 2 "$narrows" run "$tmp/c.toml" --set run.steps=30 --out "$tmp/part" > /dev/null 2>&1
runs --err "$tmp/err" "restart" "$narrows" run "$tmp/c.toml" --restart "$tmp/part" --out "$tmp/part" > /dev/null
check "restart (2 ranks to 30, 1 rank to 60) bitwise equal to the uninterrupted run" \
  '$py "$same" "$tmp/one/checkpoint-0000000060.h5" "$tmp/part/checkpoint-0000000060.h5" $both'
runs "first part on 1 rank" "$narrows" run "$tmp/c.toml" --set run.steps=30 --out "$tmp/part3" > /dev/null 2>&1
runs "restart on 3 ranks" "${mpi[@]}" -n 3 "$narrows" run "$tmp/c.toml" --restart "$tmp/part3" --out "$tmp/part3" > /dev/null 2>&1
check "restart (1 rank to 30, 3 ranks to 60: colloids handed to their slabs' owners) bitwise equal" \
  '$py "$same" "$tmp/one/checkpoint-0000000060.h5" "$tmp/part3/checkpoint-0000000060.h5" $both'
sed 's/count = 3/count = 2/' "$tmp/c.toml" > "$tmp/c2.toml"
refused "a scene with another colloid count" "colloids.count" \
  "$narrows" run "$tmp/c2.toml" --restart "$tmp/part/checkpoint-0000000030.h5" --out "$tmp/bad2"
# Positions from a file (relative to the scene file; comments, blank lines and commas-free
# whitespace-separated numbers).
sed -e 's/^count = 3/placement = "file"\npositions_file = "pos.txt"/' "$tmp/c.toml" > "$tmp/f.toml"
printf '# x y\n4.5 5.0\n\n12.0 4.0   # second\n19.5 6.0\n' > "$tmp/pos.txt"
runs --err "$tmp/errf" "placement = file" "$narrows" run "$tmp/f.toml" --set run.steps=0 --out "$tmp/file" > /dev/null
check "placement = file puts the colloids at the file's positions" '$py -c "
import h5py, sys, numpy as np
p = h5py.File(sys.argv[1])[\"/particles/colloids/position/value\"][()]
assert np.array_equal(p, [[4.5, 5.0], [12.0, 4.0], [19.5, 6.0]]), p" "$tmp/file/checkpoint-0000000000.h5"'
printf '4.5 5.0\n12.0 x\n' > "$tmp/pos.txt"
refused "a position file with a word" 'colloids.positions_file (.*pos.txt:2): found "12.0 x"' \
  "$narrows" check "$tmp/f.toml"
printf '4.5 5.0\n12.0 10.0\n' > "$tmp/pos.txt"
refused "a position file with a colloid on the wall" 'pos.txt:2).*lies' "$narrows" check "$tmp/f.toml"
rm "$tmp/pos.txt"
refused "a missing position file" 'colloids.positions_file = "pos.txt": cannot open' \
  "$narrows" check "$tmp/f.toml"
# Unequal radii: radius 1.5, sd 0.2 (largest 2.1: the wall cut-off 1.0631 * 4.2 fits in 5).
sed 's/^radius = 1.5/radius = 1.5\nradius_sd = 0.2/' "$tmp/c.toml" > "$tmp/sd.toml"
runs "radius_sd: info" "$narrows" info "$tmp/sd.toml" > "$tmp/sd_info" 2>&1
check "info names the radius spread: $(grep MD: "$tmp/sd_info" | head -c 300)" \
  'grep -q "MD: 3 colloids (r 1.5 sd 0.2 truncated at 3 sd, drawn .* to .*, M .* to .*LJ wall (sigma_w 2 r_a" "$tmp/sd_info"'
runs "radius_sd: 1 rank" "$narrows" run "$tmp/sd.toml" --out "$tmp/sd_one" > /dev/null 2>&1
runs "radius_sd: first part on 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/sd.toml" --set run.steps=30 --out "$tmp/sd_part" > /dev/null 2>&1
check "radius_sd: radius and mass stored per colloid (unequal, M = n pi r^2)" '$py - "$tmp/sd_part/checkpoint-0000000030.h5" <<PY
import sys, h5py, numpy as np
c = h5py.File(sys.argv[1], "r")["particles/colloids"]
r, m = c["radius/value"][()], c["mass/value"][()]
assert r.shape == (3,) and m.shape == (3,), (r.shape, m.shape)
assert len(set(r)) == 3 and np.all(np.abs(r - 1.5) <= 0.6), r
assert np.allclose(m, 5 * np.pi * r**2, rtol=1e-14), (m, r)
PY'
cp "$tmp/sd_part/checkpoint-0000000030.h5" "$tmp/sd_old.h5"
runs --err "$tmp/err" "radius_sd: restart" "$narrows" run "$tmp/sd.toml" --restart "$tmp/sd_part" --out "$tmp/sd_part" > /dev/null
check "radius_sd: restart (2 ranks to 30, 1 rank to 60) bitwise equal to the uninterrupted run" \
  '$py "$same" "$tmp/sd_one/checkpoint-0000000060.h5" "$tmp/sd_part/checkpoint-0000000060.h5" $both'
check "radius_sd: restart keeps radius and mass bitwise" '$py - "$tmp/sd_one/checkpoint-0000000060.h5" "$tmp/sd_part/checkpoint-0000000060.h5" <<PY
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r")["particles/colloids"] for p in sys.argv[1:])
oa, ob = np.argsort(a["id/value"][()]), np.argsort(b["id/value"][()])
for f in ("radius", "mass"):
    assert np.array_equal(a[f + "/value"][()][oa].view(np.uint64), b[f + "/value"][()][ob].view(np.uint64)), f
PY'
# (as a checkpoint written before radius and mass were stored: it lacks the fields added after
# them too, the spin and the orientation, which MD colloids keep at rest and the identity)
runs "radius_sd: strip radius and mass from the checkpoint" $py -c "import h5py, sys
f = h5py.File(sys.argv[1], 'r+')
for n in ('radius', 'mass', 'angular_velocity_z', 'orientation_w', 'orientation_x',
          'orientation_y', 'orientation_z'):
    del f['particles/colloids/' + n]" "$tmp/sd_old.h5"
runs --err "$tmp/err" "radius_sd: restart from a checkpoint without radius and mass" \
  "$narrows" run "$tmp/sd.toml" --restart "$tmp/sd_old.h5" --out "$tmp/sd_old" > /dev/null
check "radius_sd: ... and is bitwise equal to the uninterrupted run" \
  '$py "$same" "$tmp/sd_one/checkpoint-0000000060.h5" "$tmp/sd_old/checkpoint-0000000060.h5" $both'
sed 's/^radius_sd = 0.2/radius_sd = 0.1/' "$tmp/sd.toml" > "$tmp/sd2.toml"
refused "a restart with another radius_sd" 'colloids.radius_sd = 0.1[0-9]* but checkpoint .* has 0.2' \
  "$narrows" run "$tmp/sd2.toml" --restart "$tmp/sd_part/checkpoint-0000000030.h5" --out "$tmp/sd_bad"
finish "colloid scenes"
