#!/usr/bin/env bash
# No-slip colloids with spring contacts (issue 21 items 1-2) through the command line: settling
# colloids in a driven channel run on 1 and 2 ranks to bitwise the same final checkpoint
# (fluid, colloids, contact history), in 2D and 3D; a restart 2 -> 1 ranks continues bitwise; the log and
# `narrows info` name the contact model; scenes with bad spring keys are refused in one line.
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3
same=$src/tests/cli/same_state.py
contacts=contacts:owner_id,partner_id,tangential_displacement
state="fluid:id,position,velocity colloids:id,position,velocity,angular_velocity_z,orientation_z $contacts"
state3="fluid:id,position,velocity colloids:id,position,velocity,angular_velocity_x,angular_velocity_y,angular_velocity_z,orientation_z $contacts"

cat > "$tmp/s.toml" <<'TOML'
[run]
dimensions = 2
seed = 23
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
contacts = "spring"
radius = 1.6
count = 14
placement = "random"
gravity = [0.0, -1.0]
[colloids.spring]
kn = 2500
kt = 2500
mu_cc = 0.5
mu_cw = "inf"
substeps = 10
[output]
every = 50
checkpoint_every = 100
progress = false
observables = ["momentum", "energy"]
TOML
cat > "$tmp/touching.py" <<'PY'
import sys, h5py # (a checkpoint without contacts has no such species)
with h5py.File(sys.argv[1], "r") as f:
    if not any(p < 2**62 for p in f["/particles/contacts/partner_id/value"][:]):
        sys.exit("no contact between colloids at the end: little compared")
PY
check "narrows info names the springs" '"$narrows" info "$tmp/s.toml" | grep -q "linear springs and Coulomb friction.*mu_cw inf"'
runs --err "$tmp/err1" "1 rank" "$narrows" run "$tmp/s.toml" --out "$tmp/one" > "$tmp/log1"
check "the log counts the spring contacts" 'grep -q "spring contacts: [1-9].* contact updates" "$tmp/log1"'
runs "2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/s.toml" --out "$tmp/two" > /dev/null 2>&1
check "2 ranks bitwise equal to 1 rank (fluid, colloids, contacts)" \
  '$py "$same" "$tmp/one/checkpoint-0000000200.h5" "$tmp/two/checkpoint-0000000200.h5" $state && $py "$tmp/touching.py" "$tmp/one/checkpoint-0000000200.h5"'
runs "first half on 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/s.toml" --set run.steps=100 --out "$tmp/p21" > /dev/null 2>&1
check "the restart is mid-contact" '$py -c "import h5py,sys; assert len(h5py.File(sys.argv[1])[\"/particles/contacts/owner_id/value\"]) > 0" "$tmp/p21/checkpoint-0000000100.h5"'
runs "restart on 1 rank" "$narrows" run "$tmp/s.toml" --restart "$tmp/p21" --out "$tmp/p21" > /dev/null 2>&1
check "restart 2 -> 1 ranks bitwise equal to the uninterrupted run" \
  '$py "$same" "$tmp/one/checkpoint-0000000200.h5" "$tmp/p21/checkpoint-0000000200.h5" $state && $py "$tmp/touching.py" "$tmp/one/checkpoint-0000000200.h5"'

# 3D: spheres settling in a driven channel, 1 and 2 ranks bitwise (16 of them, a full layer on
# the wall, so that contacts between colloids last to the end in any noise realisation: with 8
# there were none left at step 200 in some).
sed -e 's/^dimensions = 2/dimensions = 3/' -e 's/^size = \[30.0, 12.0\]/size = [16.0, 8.0, 8.0]/' \
    -e 's/^value = \[0.01, 0.0\]/value = [0.01, 0.0, 0.0]/' -e 's/^radius = 1.6/radius = 1.5/' \
    -e 's/^count = 14/count = 16/' -e 's/^gravity = \[0.0, -1.0\]/gravity = [0.0, -1.0, 0.0]/' \
    -e 's/^density = 8/density = 5/' -e 's/^mu_cw = "inf"/mu_cw = 0.3/' "$tmp/s.toml" > "$tmp/s3.toml"
runs "3D on 1 rank" "$narrows" run "$tmp/s3.toml" --out "$tmp/one3" > /dev/null 2>&1
runs "3D on 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/s3.toml" --out "$tmp/two3" > /dev/null 2>&1
check "3D: 2 ranks bitwise equal to 1 rank (fluid, colloids, contacts)" \
  '$py "$same" "$tmp/one3/checkpoint-0000000200.h5" "$tmp/two3/checkpoint-0000000200.h5" $state3 && $py "$tmp/touching.py" "$tmp/one3/checkpoint-0000000200.h5"'

# Scenes the spring contacts cannot run.
bad() { sed "$1" "$tmp/s.toml" > "$tmp/bad.toml"; }
bad 's/contacts = "spring"/contacts = "hard"/'
refused "[colloids.spring] without spring contacts" 'colloids.spring.*only with colloids.contacts = "spring"' \
  "$narrows" check "$tmp/bad.toml"
bad 's/coupling = "no-slip"/coupling = "md"/'
refused "spring contacts with MD colloids" 'colloids.contacts = "spring".*allowed with coupling = "md": "none"' \
  "$narrows" check "$tmp/bad.toml"
bad 's/mu_cc = 0.5/mu_cc = -0.5/'
refused "a negative friction coefficient" 'colloids.spring.mu_cc.*a number >= 0, or "inf"' \
  "$narrows" check "$tmp/bad.toml"
bad 's/mu_cw = "inf"/mu_cw = "infinite"/'
refused "a friction coefficient that is not a number" 'colloids.spring.mu_cw.*"inf"' \
  "$narrows" check "$tmp/bad.toml"
bad 's/substeps = 10/substeps = 1/'
refused "too few sub-steps for the springs" 'colloids.spring.substeps = 1: .*radians per sub-step; allowed: at most 0.25, i.e. substeps >= ' \
  "$narrows" check "$tmp/bad.toml"
bad 's/^kt = 2500/kt = 2500\ndamping = 1.25/'
refused "an unknown spring key" "unknown key 'colloids.spring.damping'" "$narrows" check "$tmp/bad.toml"
bad 's/^kn = 2500/kn = 0/'
refused "kn = 0" 'colloids.spring.kn' "$narrows" check "$tmp/bad.toml"
# The contact kernel's benchmark (issue 21 acceptance 6): figures printed, and the packing with
# its velocities written for LAMMPS; a path that cannot be written is refused in one line.
runs "bench --dem" "$narrows" bench --dem 2000 --steps 2 --dem-data "$tmp/dem.data" \
  > "$tmp/dem.txt" 2>&1
check "bench --dem prints contact updates/s" \
  'grep -q "^dem: 20 sub-steps in .* contact updates/s" "$tmp/dem.txt"'
check "the LAMMPS data file holds 2000 atoms and their velocities" \
  'grep -q "^2000 atoms$" "$tmp/dem.data" && [ "$(awk "/^Atoms/{f=1;next} /^Velocities/{f=0} f && NF==7" "$tmp/dem.data" | wc -l)" -eq 2000 ] && [ "$(awk "/^Velocities/{f=1;next} f && NF==7" "$tmp/dem.data" | wc -l)" -eq 2000 ]'
refused "bench --dem beyond 1e8 disks" "command line: --dem .*allowed: a number of disks" \
  "$narrows" bench --dem 1e9
refused "bench --dem-data into a missing folder" "command line: --dem-data" \
  "$narrows" bench --dem 2000 --steps 1 --dem-data "$tmp/no/such/dir/p.data"
finish "spring scenes"
