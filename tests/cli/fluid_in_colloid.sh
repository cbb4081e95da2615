#!/usr/bin/env bash
# Issue 18 item 6: a restarted mpcd state with a fluid particle inside a colloid where no run
# can have put it (its WCA force beyond the range at which a run stops) is refused with one line
# naming the file, /particles/fluid/position/value, the fluid id and the colloid id, exit 2, on
# 1 and 3 ranks, writing nothing. The checkpoint is rewritten with a valid checksum, so only the
# state check can see it. A particle as deep as thermal motion takes one (0.8 radius, about
# 40 kT) restarts, and so does an ordinary checkpoint of run/colloids_conservation.toml.
set -u
source "$(dirname "$0")/common.bash"
move="/usr/bin/python3 $src/tests/hostile/move_fluid_particle.py"
scene="$src/run/colloids_conservation.toml"

runs "colloids_conservation: 20 steps" "$narrows" run "$scene" --set run.steps=20 --out "$tmp/c" > /dev/null
good=$tmp/c/checkpoint-0000000020.h5
runs "the ordinary checkpoint restarts" "$narrows" run "$scene" --restart "$good" \
  --set run.steps=25 --out "$tmp/ok" > /dev/null
runs "the ordinary checkpoint restarts on 3 ranks" "${mpi[@]}" -n 3 "$narrows" run "$scene" \
  --restart "$good" --set run.steps=25 --out "$tmp/ok3" > /dev/null

# At a colloid's centre, and at 0.3 radius (pair energy ~1e7 kT): refused, on 1 and 3 ranks.
for at in "17 0 0.0" "1234 2 0.3"; do
  read -r row crow frac <<< "$at"
  ids=$($move "$good" "$tmp/in.h5" "$row" "$crow" "$frac")
  check "fluid row $row moved into colloid row $crow" '[ -n "$ids" ]'
  read -r fid cid <<< "$ids"
  for n in 1 3; do
    refused "fluid id $fid at $frac radius from colloid $cid, $n ranks" \
      "in.h5: /particles/fluid/position/value: fluid particle id $fid at .* lies inside colloid id $cid at distance .*pair energy .* kT; allowed: a state a run can reach" \
      timeout 120 "${mpi[@]}" -n $n "$narrows" run "$scene" --restart "$tmp/in.h5" \
      --set run.steps=25 --out "$tmp/r$n"
    check "fluid inside colloid, $n ranks: nothing written" '[ ! -e "$tmp/r$n" ]'
  done
done

# Thermally reachable: 0.8 radius (4 ((1/0.8)^12 - (1/0.8)^6 + 1/4) = 44 kT) restarts.
$move "$good" "$tmp/near.h5" 17 1 0.8 > /dev/null
runs "a fluid particle at 0.8 radius restarts" "$narrows" run "$scene" --restart "$tmp/near.h5" \
  --set run.steps=25 --out "$tmp/near" > /dev/null
finish "fluid in colloid"
