#!/usr/bin/env bash
# Slabs balanced by work (issue 36 item 3): a no-slip channel with spring contacts whose colloids
# sit in the first half of the box, on 3 ranks with equal slabs and with the slabs moved
# every 10 steps (threshold 1: they move at nearly every check, fluid, colloids and contacts
# migrating to the new owners), ends in bitwise the same state (fluid, colloids, contact
# history) and the same observables (those summed in fixed point); so do the slabs balanced by
# measured busy time (moved by each rank's work per busy second, so where they go depends on the
# machine; the state must not); a restart from equal slabs on 3 ranks, balanced on 4 ranks,
# continues bitwise; the log gives the counted work's and the busy time's max/mean.
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3
same=$src/tests/cli/same_state.py
state="fluid:id,position,velocity colloids:id,position,velocity,angular_velocity_z,orientation_z contacts:owner_id,partner_id,tangential_displacement"
end=checkpoint-0000000120.h5

cat > "$tmp/s.toml" <<'TOML'
[run]
dimensions = 2
seed = 36
steps = 120
[domain]
size = [48.0, 12.0]
[fluid]
collision = "at+a"
density = 8
dt = 0.05
[body_force]
value = [0.01, 0.0]
[walls]
virtual_particles = true
[colloids]
coupling = "no-slip"
contacts = "spring"
radius = 1.6
placement = "list"
positions = [[2.5, 2.0], [6.0, 2.0], [9.5, 2.0], [13.0, 2.0], [16.5, 2.0], [20.0, 2.0],
             [2.5, 5.5], [6.0, 5.5], [9.5, 5.5], [13.0, 5.5], [16.5, 5.5], [20.0, 5.5]]
gravity = [0.0, -1.0]
[colloids.spring]
kn = 2500
kt = 2500
mu_cc = 0.5
mu_cw = 0.5
substeps = 10
[output]
every = 30
progress = false
observables = ["momentum", "colloid_positions"] # (the energy is a floating sum in rank order)
TOML
cat > "$tmp/touching.py" <<'PY'
import sys, h5py # contacts between colloids at the end, so that their history was compared
with h5py.File(sys.argv[1], "r") as f:
    if not any(p < 2**62 for p in f["/particles/contacts/partner_id/value"][:]):
        sys.exit("no contact between colloids at the end: little compared")
PY
cat > "$tmp/same_observables.py" <<'PY'
import sys, h5py, numpy as np # every dataset under /observables bit for bit (the scenes differ)
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
names = []
a["/observables"].visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
assert names, "no observables"
for n in names:
    x, y = a["/observables/" + n][()], b["/observables/" + n][()]
    if x.shape != y.shape or x.tobytes() != y.tobytes():
        sys.exit("observables differ: /observables/" + n)
PY
balanced=(--set domain.balance=work --set domain.balance_every=10 --set domain.balance_threshold=1.0)

runs "3 ranks, equal slabs" "${mpi[@]}" -n 3 "$narrows" run "$tmp/s.toml" --out "$tmp/none" \
  > /dev/null 2>&1
runs "3 ranks, slabs balanced every 10 steps" "${mpi[@]}" -n 3 "$narrows" run "$tmp/s.toml" \
  "${balanced[@]}" --out "$tmp/work" > /dev/null 2>&1
check "the log gives the counted work of equal slabs" \
  'grep -q "^counted work: max/mean [0-9.]* over the ranks .*equal slabs" "$tmp/none/log.txt"'
check "the balanced slabs are uneven at the start" \
  'grep "slabs balanced by counted work: first columns" "$tmp/work/log.txt" | grep -vq "columns 0 16 32 of 48"'
check "the slabs moved mid-run" 'grep -q "slabs moved [1-9][0-9]* times" "$tmp/work/log.txt"'
check "balanced: counted max/mean below that of equal slabs" \
  '[ "$(sed -n "s/^counted work: max\/mean \([0-9.]*\).*/\1/p" "$tmp/work/log.txt")" \< "$(sed -n "s/^counted work: max\/mean \([0-9.]*\).*/\1/p" "$tmp/none/log.txt")" ]'
check "3 ranks: balanced bitwise equal to equal slabs (fluid, colloids, contacts)" \
  '$py "$same" "$tmp/none/$end" "$tmp/work/$end" $state && $py "$tmp/touching.py" "$tmp/none/$end"'
check "3 ranks: balanced, the same observables (momentum, colloid positions)" \
  '$py "$tmp/same_observables.py" "$tmp/none/observables.h5" "$tmp/work/observables.h5"'

runs "3 ranks, slabs balanced by busy time every 10 steps" "${mpi[@]}" -n 3 "$narrows" run \
  "$tmp/s.toml" --set domain.balance=time --set domain.balance_every=10 \
  --set domain.balance_threshold=1.0 --out "$tmp/time" > /dev/null 2>&1
check "by time: the slabs moved mid-run, and the log gives the busy time per check" \
  'grep -q "^busy time every 10 steps: .*slabs moved [1-9][0-9]* times" "$tmp/time/log.txt" && grep -q "^busy time max/mean per check (step: value, \* slabs moved): 10: " "$tmp/time/log.txt"'
check "3 ranks: balanced by time bitwise equal to equal slabs (fluid, colloids, contacts)" \
  '$py "$same" "$tmp/none/$end" "$tmp/time/$end" $state'
check "3 ranks: balanced by time, the same observables" \
  '$py "$tmp/same_observables.py" "$tmp/none/observables.h5" "$tmp/time/observables.h5"'

runs "first half on 3 ranks, equal slabs" "${mpi[@]}" -n 3 "$narrows" run "$tmp/s.toml" \
  --set run.steps=60 --out "$tmp/half" > /dev/null 2>&1
runs "restart on 4 ranks, balanced" "${mpi[@]}" -n 4 "$narrows" run "$tmp/s.toml" \
  "${balanced[@]}" --restart "$tmp/half" --out "$tmp/half" > /dev/null 2>&1
check "the restart balanced its slabs" 'grep -q "slabs moved [1-9]" "$tmp/half"/log-*.txt'
check "restart 3 -> 4 ranks balanced: bitwise equal to the uninterrupted run" \
  '$py "$same" "$tmp/none/$end" "$tmp/half/$end" $state'
finish "work balance"
