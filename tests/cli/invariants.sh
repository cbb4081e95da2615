#!/usr/bin/env bash
# A broken runtime invariant ends a run with exit code 3 and one line on stderr naming the step,
# the rank and what broke, on 1 rank and on 3 (uneven slabs). The fault: a constant force so
# strong that after one step every particle is faster than the allowed 10^4 (the runaway-speed
# branch; every branch, NaN, outside the channel and momentum drift included, fires in
# tests/mpi/test_invariants.cpp, which injects the faults directly).
set -u
source "$(dirname "$0")/common.bash"

cat > "$tmp/runaway.toml" <<'TOML'
[run]
dimensions = 2
steps = 20
[domain]
size = [13.0, 6.0]
[fluid]
collision = "srd"
dt = 0.5
[body_force]
kind = "constant"
value = [30000.0, 0.0]
[output]
every = 1
progress = false
TOML
exits 3 "runaway speed on 1 rank" "$narrows" run "$tmp/runaway.toml" --out "$tmp/one" \
  > /dev/null 2> "$tmp/one.err"
check "1 rank: one line on stderr" '[ "$(grep -c . "$tmp/one.err")" -eq 1 ]'
check "1 rank: the line names step 1, rank 0 and the speed bound" \
  'grep -q "invariant broken at step 1 on rank 0: particle id [0-9]* has position .* and velocity 15[0-9.]* along axis 0 (allowed: finite, |v| <= 10000)" "$tmp/one.err" || { cat "$tmp/one.err"; false; }'
exits 3 "runaway speed on 3 ranks" "${mpi[@]}" -n 3 "$narrows" run "$tmp/runaway.toml" \
  --out "$tmp/three" > /dev/null 2> "$tmp/three.err"
check "3 ranks: the line names step 1, a rank and the speed bound" \
  'grep -q "invariant broken at step 1 on rank [0-2]: particle id [0-9]* has .*(allowed: finite, |v| <= 10000)" "$tmp/three.err" || { cat "$tmp/three.err"; false; }'
check "3 ranks: one line on stderr" '[ "$(grep -c . "$tmp/three.err")" -eq 1 ]'
# The same scene with a force that keeps the speeds bounded runs to the end (exit 0): the fault
# above is the force, not the scene.
runs "a bounded force runs" "$narrows" run "$tmp/runaway.toml" --set 'body_force.value=[0.001,0.0]' \
  --out "$tmp/fine" > /dev/null 2>&1
finish "invariants"
