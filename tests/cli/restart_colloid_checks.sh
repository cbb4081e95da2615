#!/usr/bin/env bash
# The restart state check of the colloid species (issue 35 item 1), one case per field and rule,
# each on 3 ranks: a checkpoint edited as a hostile user would (tests/hostile/edit_checkpoint.py
# rewrites the checksums, so only the state check can refuse it) is refused with exit 2, one
# line naming the file, the dataset and what is allowed, and nothing written (no log, no
# observables, no checkpoint). Rules: every field of a species of one row count before any rank
# reads (a short contact field deadlocked 2 and 3 ranks), every checksum verified whatever the row
# count, each field's step and time those of /parameters, the two stored scene texts one scene,
# radius and mass the scene's, box edges the scene's, centres between the walls, speeds within
# the run's limit, overlaps within the contact model's allowance (hard, spring, MD), unit
# quaternions, spring contacts exactly between touching bodies, no field silently reset.
source "$(dirname "$0")/common.bash"
edit=(/usr/bin/python3 "$src/tests/hostile/edit_checkpoint.py")

# Three small channels: hard and spring contacts of no-slip colloids, MD colloids.
cat > "$tmp/hard.toml" << 'TOML'
[run]
engine = "mpcd"
dimensions = 2
seed = 5
steps = 4
[domain]
size = [24.0, 12.0]
[fluid]
collision = "srd"
density = 5
dt = 0.1
[walls]
[colloids]
radius = 2.0
placement = "list"
positions = [[4.0, 6.0], [10.0, 6.0], [16.0, 3.0]]
coupling = "no-slip"
contacts = "hard"
[output]
every = 2
observables = ["temperature"]
progress = false
TOML
sed -e '/^coupling/d' -e '/^contacts/d' "$tmp/hard.toml" > "$tmp/md.toml"
sed -e 's/^placement = "list"/placement = "packing"\npacking_fraction = 0.6/' -e '/^positions/d' \
  -e 's/^contacts = "hard"/contacts = "spring"/' "$tmp/hard.toml" > "$tmp/spring.toml"
for s in hard md spring; do
  runs "$s: first run" "$narrows" run "$tmp/$s.toml" --out "$tmp/$s" > /dev/null 2>&1
done

n=0
# case NAME SCENE PATTERN EDIT...: the edited checkpoint of SCENE refused on 3 ranks.
case_() {
  local name=$1 s=$2 pattern=$3
  shift 3
  n=$((n + 1))
  local d=$tmp/c$n
  mkdir -p "$d"
  "${edit[@]}" "$tmp/$s/checkpoint-0000000004.h5" "$d/ck.h5" "$@" || check "$name: edited" false
  refused "$name" "ck.h5: $pattern" timeout 60 "${mpi[@]}" -n 3 "$narrows" run "$tmp/$s.toml" \
    --restart "$d/ck.h5" --set run.steps=6 --out "$d/out"
  check "$name: nothing written" '[ ! -e "$d/out" ] || [ -z "$(ls -A "$d/out")" ]'
}
C=/particles/colloids
K=/particles/contacts

# Row counts agreed before any rank reads; the checksum of a longer field still verified.
case_ "contacts: owner_id a row short" spring \
  "$K/owner_id/value has [0-9]* rows, $K/tangential_displacement/value has" drop $K/owner_id/value
case_ "contacts: partner_id a row more" spring \
  "$K/partner_id/value has [0-9]* rows, .*allowed: the same number of rows" \
  append $K/partner_id/value
case_ "contacts: partner_id a row more, checksum old" spring \
  "damaged checkpoint: $K/partner_id/value does not match its checksum" \
  append $K/partner_id/value nochecksum $K/partner_id/value
case_ "colloids: radius a row short" hard "$C/radius/value has 2 rows" drop $C/radius/value
# Step and time of every field those of /parameters.
case_ "step of a field" spring "$C/radius/step = 3 but /parameters/step = 4" \
  set $C/radius/step "" 3
case_ "/parameters/step" hard "/particles/fluid/position/step = 4 but /parameters/step = 2" \
  set /parameters/step "" 2
case_ "time of a field" hard "/particles/fluid/velocity/time = 0.2.* but /parameters/time" \
  set /particles/fluid/velocity/time "" 0.2
# The scene text edited, its canonical text not.
case_ "scene edited" hard "/parameters/scene has 'fluid.dt = 0.2' where /parameters/canonical_scene has 'fluid.dt = 0.1'" \
  replace /parameters/scene "dt = 0.1" "dt = 0.2"
# Radius and mass: the scene's.
case_ "radius x0.1" spring "$C/radius/value row 0 (colloid id 0) = 0.2.*allowed: 2, the radius the scene" \
  scale $C/radius/value 0.1
case_ "radius 1e-300" hard "$C/radius/value row 1 (colloid id 1) = 1e-300" set $C/radius/value 1 1e-300
case_ "mass 1e-300" hard "$C/mass/value row 0 (colloid id 0) = 1e-300; allowed: 62.83" \
  set $C/mass/value 0 1e-300
case_ "mass 1e300" md "$C/mass/value row 2 (colloid id 2) = 1.0*e+300" set $C/mass/value 2 1e300
# Speeds within the run's limit (1e300 hung a hard-contact run).
case_ "velocity 1e300" hard "$C/velocity/value (colloid id 0) component 0 = 1.0*e+300; allowed: |v| <= 10000" \
  set $C/velocity/value 0,0 1e300
case_ "spin 1e300" hard "$C/angular_velocity_z/value (colloid id 1) = 1.0*e+300; allowed: |omega| r <= 10000" \
  set $C/angular_velocity_z/value 1 1e300
# Inside the scene's box, between the walls.
case_ "box edges edited" hard "$C/box/edges\[0\] = 40; allowed: 24, the scene's domain.size\[0\]" \
  set $C/box/edges 0 40 set $C/position/value 0,0 30
case_ "centre on a wall" hard "$C/position/value (colloid id 2) component 1 = 0 (radius 2); allowed: a centre between the walls" \
  set $C/position/value 2,1 0
case_ "MD centre on a wall" md "$C/position/value (colloid id 2) component 1 = 0 (radius 2); allowed: a centre between the walls" \
  set $C/position/value 2,1 0
case_ "hard colloid in a wall" hard "component 1 = 1 (radius 2) overlaps a wall; allowed: hard contacts keep" \
  set $C/position/value 2,1 1
# Overlaps within the contact model's allowance.
case_ "hard: on another's centre" hard "colloid ids 0 and 1 overlap.*allowed: hard contacts allow none" \
  set $C/position/value 1,0 4.0
case_ "MD: on another's centre" md "colloid ids 0 and 1 overlap.*allowed: MD colloids allow a 48-24 pair force below" \
  set $C/position/value 1,0 4.0 set $C/position/value 1,1 6.0
case_ "spring: all at one point" spring "overlap: centres 0 apart.*allowed: spring contacts allow overlaps with each centre outside" \
  fill $C/position/value 6
# Unit quaternions; no field reset when it is missing.
case_ "orientation not unit" hard "$C/orientation_\* row 0 is not a unit quaternion" \
  set $C/orientation_w/value 0 0.5
case_ "orientation deleted" hard "missing dataset $C/orientation_w/value; allowed: a checkpoint of colloid contacts holds" \
  delete $C/orientation_w delete $C/orientation_x delete $C/orientation_y delete $C/orientation_z
case_ "orientation_w deleted" hard "missing dataset $C/orientation_w/value" delete $C/orientation_w
case_ "radius deleted" hard "missing dataset $C/radius/value but $C/mass/value is there" delete $C/radius
case_ "angular_velocity_z deleted" hard "missing dataset $C/angular_velocity_z/value but $C/orientation_w/value is there" \
  delete $C/angular_velocity_z
# Contacts exactly between the touching bodies.
case_ "contact between distant colloids" spring "holds a contact of colloid ids 0 and 13: .*which do not touch" \
  set $K/partner_id/value 0 13
case_ "wall contact far from the wall" spring "holds a contact of colloid id 1 and the wall y = L_y: .*which do not touch" \
  set $K/owner_id/value 2 1
case_ "contact group deleted" spring "no contact row of colloid id 0 and colloid id 2, which overlap" delete $K
case_ "contact rows removed" spring "no contact row of colloid id .*, which overlap" \
  drop $K/owner_id/value drop $K/partner_id/value drop $K/tangential_displacement/value
# An old checkpoint (no checksums) gets the same value checks.
case_ "no checksums: mass 1e-300" hard "$C/mass/value row 0 (colloid id 0) = 1e-300" \
  set $C/mass/value 0 1e-300 strip
case_ "no checksums: contact between distant colloids" spring "which do not touch" \
  set $K/partner_id/value 0 13 strip

# The untouched checkpoints restart on 3 ranks.
for s in hard md spring; do
  runs "$s: untouched checkpoint restarts on 3 ranks" timeout 60 "${mpi[@]}" -n 3 "$narrows" run \
    "$tmp/$s.toml" --restart "$tmp/$s" --set run.steps=6 --out "$tmp/$s" > /dev/null 2>&1
done
# Item 4: a rank that alone finds a broken invariant inside a step ends the run with exit 3 and
# its one line, without Open MPI's MPI_ABORT notice or "Data unpack would read past end of
# buffer" (mpirun without --quiet). A colloid at 5000 (within the speed limit) runs into the fluid.
loud=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && loud+=(--allow-run-as-root)
"${edit[@]}" "$tmp/md/checkpoint-0000000004.h5" "$tmp/fast.h5" set $C/velocity/value 1,0 5000
exits 3 --err "$tmp/err3" "exit 3 on 3 ranks" timeout 60 "${loud[@]}" -n 3 "$narrows" run \
  "$tmp/md.toml" --restart "$tmp/fast.h5" --set run.steps=6 --out "$tmp/fast" > /dev/null
check "exit 3 on 3 ranks: one line, narrows' own" \
  '[ "$(grep -c . "$tmp/err3")" -eq 1 ] && grep -q "^narrows: invariant broken" "$tmp/err3" || { cat "$tmp/err3"; false; }'
echo "restart cases: $n refused"
finish restart_colloid_checks
