#!/usr/bin/env bash
# The restart state check of the colloids, part of issue 35 item 1 (tests/cli/restart_checks.bash),
# on 3 ranks: radius and mass the scene's (x0.1, 1e-300, 1e300; a mass of 1e-300 ended in
# bad_alloc), speeds and spins within the run's speed limit (1e300 hung a hard-contact run), box
# edges the scene's, centres between the walls and hard colloids off them. And item 4: a rank
# that alone finds a broken invariant ends the run with exit 3 and one line, without Open MPI's.
source "$(dirname "$0")/common.bash"
source "$(dirname "$0")/restart_checks.bash"

# Radius and mass: the scene's.
case_ "radius x0.1" hard "$C/radius/value row 0 (colloid id 0) = 0.2.*allowed: 2, the radius the scene" \
  scale $C/radius/value 0.1
case_ "radius 1e-300" hard "$C/radius/value row 1 (colloid id 1) = 1e-300" set $C/radius/value 1 1e-300
case_ "mass 1e-300" hard "$C/mass/value row 0 (colloid id 0) = 1e-300; allowed: 62.83" \
  set $C/mass/value 0 1e-300
case_ "mass 1e300" md "$C/mass/value row 2 (colloid id 2) = 1.0*1e+300" set $C/mass/value 2 1e300
# Speeds within the run's limit (1e300 hung a hard-contact run).
case_ "velocity 1e300" hard "$C/velocity/value (colloid id 0) component 0 = 1.0*1e+300; allowed: |v| <= 10000" \
  set $C/velocity/value 0,0 1e300
case_ "spin 1e300" hard "$C/angular_velocity_z/value (colloid id 1) = 1.0*1e+300; allowed: |omega| r <= 10000" \
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

# Item 4: a rank that alone finds a broken invariant inside a step ends the run with exit 3 and
# its one line, without Open MPI's MPI_ABORT notice or "Data unpack would read past end of
# buffer" (mpirun without --quiet). A colloid at 5000 (within the speed limit) runs into the fluid.
checkpoint_of md
loud=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && loud+=(--allow-run-as-root)
"${edit[@]}" "$tmp/md/checkpoint-0000000004.h5" "$tmp/fast.h5" set $C/velocity/value 1,0 5000
exits 3 --err "$tmp/err3" "exit 3 on 3 ranks" timeout 60 "${loud[@]}" -n 3 "$narrows" run \
  "$tmp/md.toml" --restart "$tmp/fast.h5" --set run.steps=6 --out "$tmp/fast" > /dev/null
check "exit 3 on 3 ranks: one line, narrows' own" \
  '[ "$(grep -c . "$tmp/err3")" -eq 1 ] && grep -q "^narrows: invariant broken" "$tmp/err3" || { cat "$tmp/err3"; false; }'

untouched hard md
echo "restart cases: $n refused"
finish restart_colloid_checks
