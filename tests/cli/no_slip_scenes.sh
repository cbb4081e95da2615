#!/usr/bin/env bash
# No-slip colloids with hard contacts (issue 20) through the command line: a channel under a
# pressure drive with settling colloids runs on 1, 2 and 3 ranks to bitwise the same final
# checkpoint (fluid, colloids and their angular velocities, compared by id); restarts 2 -> 1
# and 1 -> 3 ranks continue bitwise; fluid fast enough to cross several cells a step around
# colloids runs on 3 uneven slabs bitwise as on 1 rank; the run log counts the contacts; scenes
# the coupling cannot run are refused in one line naming the key.
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3
same=$src/tests/cli/same_state.py
state="fluid:id,position,velocity colloids:id,position,velocity,angular_velocity_z,orientation_w,orientation_z"

cat > "$tmp/n.toml" <<'TOML'
[run]
dimensions = 2
seed = 21
steps = 200
[domain]
size = [30.0, 12.0]
[fluid]
collision = "at+a"
density = 8
dt = 0.05
[body_force]
kind = "constant"
value = [0.01, 0.0]
[walls]
virtual_particles = true
[colloids]
coupling = "no-slip"
contacts = "hard"
radius = 1.6
count = 10
placement = "random"
gravity = [0.0, -0.1]
[output]
every = 50
checkpoint_every = 100
progress = false
observables = ["momentum", "energy"]
TOML
runs --err "$tmp/err1" "1 rank" "$narrows" run "$tmp/n.toml" --out "$tmp/one" > "$tmp/log1"
check "the log counts the contacts" 'grep -q "colloid contacts: [1-9][0-9]* colloid-colloid" "$tmp/log1"'
check "the colloids turned: orientation (cos t/2, 0, 0, sin t/2), a unit quaternion" '$py -c "import h5py,sys,numpy as np; g=h5py.File(sys.argv[1])[\"/particles/colloids\"]; w=g[\"orientation_w/value\"][:]; z=g[\"orientation_z/value\"][:]; assert np.allclose(w*w+z*z, 1.0) and np.abs(z).max() > 1e-3 and not g[\"orientation_x/value\"][:].any()" "$tmp/one/checkpoint-0000000200.h5"'
check "the colloids spin" '$py -c "import h5py,sys,numpy as np; f=h5py.File(sys.argv[1]); assert np.abs(f[\"/particles/colloids/angular_velocity_z/value\"][:]).max() > 1e-4" "$tmp/one/checkpoint-0000000200.h5"'
runs "2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/n.toml" --out "$tmp/two" > /dev/null 2>&1
check "2 ranks bitwise equal to 1 rank" \
  '$py "$same" "$tmp/one/checkpoint-0000000200.h5" "$tmp/two/checkpoint-0000000200.h5" $state'
runs "3 ranks" "${mpi[@]}" -n 3 "$narrows" run "$tmp/n.toml" --out "$tmp/three" > /dev/null 2>&1
check "3 ranks bitwise equal to 1 rank" \
  '$py "$same" "$tmp/one/checkpoint-0000000200.h5" "$tmp/three/checkpoint-0000000200.h5" $state'
runs "first half on 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/n.toml" --set run.steps=100 --out "$tmp/p21" > /dev/null 2>&1
runs "restart on 1 rank" "$narrows" run "$tmp/n.toml" --restart "$tmp/p21" --out "$tmp/p21" > /dev/null 2>&1
check "restart 2 -> 1 ranks bitwise equal to the uninterrupted run" \
  '$py "$same" "$tmp/one/checkpoint-0000000200.h5" "$tmp/p21/checkpoint-0000000200.h5" $state'
runs "first half on 1 rank" "$narrows" run "$tmp/n.toml" --set run.steps=100 --out "$tmp/p13" > /dev/null 2>&1
runs "restart on 3 ranks" "${mpi[@]}" -n 3 "$narrows" run "$tmp/n.toml" --restart "$tmp/p13" --out "$tmp/p13" > /dev/null 2>&1
check "restart 1 -> 3 ranks bitwise equal to the uninterrupted run" \
  '$py "$same" "$tmp/one/checkpoint-0000000200.h5" "$tmp/p13/checkpoint-0000000200.h5" $state'
check "trajectory-free run wrote no partial files" '! ls "$tmp/one" | grep -q "\.tmp$"'

# Fast fluid: SRD with dt = 2 moves particles up to ~8 cells a step, further than the colloids'
# own reach, so the region whose colloids a rank holds as ghosts is sized by the fluid's reach
# (fluid_reach). On 3 uneven slabs (11, 10, 10 columns) the run is bitwise that of 1 rank; with
# the reach set to zero it stops at step 6 ("fluid particle ... outside the region whose colloids
# this rank held"). Spring contacts: hard contacts widen the region by their own margin and hide it.
cat > "$tmp/fast.toml" <<'TOML'
[run]
dimensions = 2
seed = 5
steps = 100
[domain]
size = [31.0, 12.0]
[fluid]
collision = "srd"
density = 5
dt = 2.0
[walls]
virtual_particles = true
[colloids]
coupling = "no-slip"
contacts = "spring"
radius = 1.2
count = 24
mass = 400.0
placement = "random"
[colloids.spring]
kn = 100
kt = 100
substeps = 20
[output]
every = 100
checkpoint_every = 100
progress = false
observables = ["momentum"]
TOML
runs "fast fluid, 1 rank" "$narrows" run "$tmp/fast.toml" --out "$tmp/fast1" > /dev/null 2>&1
runs --err "$tmp/err_fast3" "fast fluid, 3 ranks" "${mpi[@]}" -n 3 "$narrows" run "$tmp/fast.toml" --out "$tmp/fast3" > /dev/null
check "fast fluid: 3 ranks bitwise equal to 1 rank" \
  '$py "$same" "$tmp/fast1/checkpoint-0000000100.h5" "$tmp/fast3/checkpoint-0000000100.h5" fluid:id,position,velocity colloids:id,position,velocity,angular_velocity_z'

# Scenes the coupling cannot run.
bad() { sed "$1" "$tmp/n.toml" > "$tmp/bad.toml"; }
bad 's/collision = "at+a"/collision = "random-maxwell"/'
refused "no-slip with a random solvent" 'colloids.coupling.*random-maxwell.*allowed with srd, at or at+a' \
  "$narrows" check "$tmp/bad.toml"
bad 's/contacts = "hard"/contacts = "none"/'
refused "no-slip without contacts in a channel" 'colloids.contacts.*could overlap.*allowed: contacts = "hard"' \
  "$narrows" check "$tmp/bad.toml"
bad 's/coupling = "no-slip"/coupling = "md"/'
refused "hard contacts with MD colloids" 'colloids.contacts = "hard".*allowed with coupling = "md": "none"' \
  "$narrows" check "$tmp/bad.toml"
bad 's/^count = 10/count = 10\nmd_substeps = 10/'
refused "an MD key with no-slip" 'colloids.md_substeps = 10 sets the MD coupling' \
  "$narrows" check "$tmp/bad.toml"
bad 's/dt = 0.05/dt = 0.4/'
refused "a step beyond the explicit coupling's stability" 'colloids.coupling.*factor f = .*allowed: f <= 0.5' \
  "$narrows" check "$tmp/bad.toml"
bad 's/coupling = "no-slip"/coupling = "slip"/'
refused "an unknown coupling" 'colloids.coupling' "$narrows" check "$tmp/bad.toml"
finish "no-slip scenes"
