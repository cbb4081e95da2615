#!/usr/bin/env bash
# The Table 6.1 channel's messages (issue 36 items 1-2): counted by tools/mpi_calls.c (PMPI,
# preloaded) on 3 ranks, every halo exchange of a step is one round of point-to-point messages
# ending in one MPI_Waitall, at most 9 per step (29 until 2026-12-04: an MPI_Alltoall of the
# row counts each, 21 of them for the spring sub-steps), and no MPI_Alltoall in a step; and the
# ghost shell that replaced the sub-steps' messages gives bitwise the run of one rank on 8
# uneven slabs (37-38 columns, narrower than the shell: ghosts from three ranks on each side),
# with contacts across the slab edges.
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3
same=$src/tests/cli/same_state.py
contacts=contacts:owner_id,partner_id,tangential_displacement
state="fluid:id,position,velocity colloids:id,position,velocity,angular_velocity_z,orientation_z $contacts"
# The Table 6.1 channel at half its length and 302 columns (uneven on 8 ranks), short; no
# observables within the steps counted (their sums are collectives of their own).
channel=(--set domain.size=[302.0,50.0] --set output.every=1000 --set output.checkpoint_every=0
  --set output.progress=false)

mpicc -shared -fPIC -O2 -o "$tmp/mpi_calls.so" "$src/tools/mpi_calls.c"
code=$?
check "mpi_calls.c builds (got $code)" '[ "$code" -eq 0 ]'
for steps in 10 30; do
  runs "3 ranks, $steps steps, MPI calls counted" env MPI_CALLS_OUT="$tmp/calls_$steps.txt" \
    "${mpi[@]}" -n 3 -x LD_PRELOAD="$tmp/mpi_calls.so" -x MPI_CALLS_OUT "$narrows" run \
    "$src/run/pulses_table6_1.toml" "${channel[@]}" --set run.steps=$steps \
    --out "$tmp/calls_run_$steps" > /dev/null 2>&1
done
# per step on the busiest rank: "kind calls" for each kind that changed
$py - "$tmp/calls_10.txt" "$tmp/calls_30.txt" 20 > "$tmp/per_step.txt" <<'PY'
import sys
def read(path):
    out = {}
    for line in open(path):
        f = line.split()
        out[int(f[0])] = {f[i]: int(f[i + 1]) for i in range(1, len(f), 3)}
    return out
a, b, steps = read(sys.argv[1]), read(sys.argv[2]), float(sys.argv[3])
assert len(a) == 3 and len(b) == 3, "three ranks each"
for kind in b[0]:
    print(kind, max((b[r][kind] - a[r][kind]) / steps for r in b))
PY
code=$?
check "per-step counts read (got $code)" '[ "$code" -eq 0 ]'
per_step() { sed -n "s/^$1 //p" "$tmp/per_step.txt"; }
echo "per step on the busiest of 3 ranks: $(tr '\n' ' ' < "$tmp/per_step.txt")"
exchanges=$(per_step waitall)
check "halo exchanges per step <= 9 (got '$exchanges')" \
  '$py -c "import sys; sys.exit(not 1 <= float(sys.argv[1]) <= 9)" "${exchanges:-0}"'
alltoall=$(per_step alltoall)
check "no MPI_Alltoall in a step (got '$alltoall')" '[ "$alltoall" = "0.0" ]'
collectives=$(per_step allreduce)
check "at most 1 MPI_Allreduce per step (got '$collectives')" \
  '$py -c "import sys; sys.exit(not float(sys.argv[1]) <= 1)" "${collectives:-9}"'
check "no MPI_Allgather in a step (got '$(per_step allgather)')" '[ "$(per_step allgather)" = "0.0" ]'

# 1 rank and 8 ranks (oversubscribed) bitwise, contacts across slab edges.
runs "1 rank" "$narrows" run "$src/run/pulses_table6_1.toml" "${channel[@]}" --set run.steps=30 \
  --out "$tmp/one" > /dev/null 2>&1
runs "8 ranks" "${mpi[@]}" -n 8 "$narrows" run "$src/run/pulses_table6_1.toml" "${channel[@]}" \
  --set run.steps=30 --out "$tmp/eight" > /dev/null 2>&1
check "8 ranks bitwise equal to 1 rank (fluid, colloids, contacts)" \
  '$py "$same" "$tmp/one/checkpoint-0000000030.h5" "$tmp/eight/checkpoint-0000000030.h5" $state'
$py - "$tmp/one/checkpoint-0000000030.h5" 8 302 > "$tmp/across.txt" <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
ranks, columns = int(sys.argv[2]), int(sys.argv[3])
ids = f["/particles/colloids/id/value"][:]
x = dict(zip(ids, f["/particles/colloids/position/value"][:, 0]))
owner = f["/particles/contacts/owner_id/value"][:]
partner = f["/particles/contacts/partner_id/value"][:]
first = [r * columns // ranks for r in range(ranks + 1)]
slab = lambda v: np.searchsorted(first, v % columns, side="right") - 1
print(sum(1 for o, p in zip(owner, partner) if p in x and slab(x[o]) != slab(x[p])))
PY
across=$(cat "$tmp/across.txt")
check "contacts between colloids of different slabs at the end (got '$across')" \
  '[ "${across:-0}" -ge 5 ]'
finish halo_exchanges
