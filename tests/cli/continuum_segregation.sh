#!/usr/bin/env bash
# The segregation model of the continuum engine (Kanehl (thesis) ch.5) from the command line: check
# prints the model, the coupling matrix, the steady state and the time step; a run writes the
# fractions per kind (density [samples+1][cells][kinds]), Delta(t) (evolution) and the steady
# profile, keeps each kind's total; a restart from the checkpoint half-way continues bitwise; 2
# ranks give the bits of 1; bad input exits 2 with one line.
set -u
source "$(dirname "$0")/common.bash"

scene=$src/run/continuum_segregation_2d.toml
short=(--set continuum.time=20000.0 --set continuum.samples=20 --set continuum.cells=40)

runs "check" "$narrows" check "$scene" > "$tmp/check.out" 2>&1
check "check: the coupling matrix of eq 5.13 (a_S = 2, a_L = 4, 2D)" \
  'grep -q "^coupling matrix (eq 5.13): A_00 = 4, A_01 = 8.1, A_10 = 8.1, A_11 = 16" "$tmp/check.out"'
check "check: Peclet numbers 1 and 11.26" \
  'grep -q "^kind 0: .*Peclet .* = 1 (eq 5.1)" "$tmp/check.out" &&
   grep -q "^kind 1: .*Peclet .* = 11.26 (eq 5.1)" "$tmp/check.out"'
check "check: the steady state (large disks at the centre, small ones depleted)" \
  'grep -q "^steady state kind 0: phi(0) = 0.1993.*c(0)/c_mean = 0.797" "$tmp/check.out" &&
   grep -q "^steady state kind 1: phi(0) = 0.4224.*c(0)/c_mean = 1.69" "$tmp/check.out"'
check "check: time step and steps" 'grep -q "^time: 200000 in 251100 steps" "$tmp/check.out"'

runs "uninterrupted run" "$narrows" run "$scene" "${short[@]}" --set output.checkpoint_every=3080 \
  --out "$tmp/full" > /dev/null 2>&1
check "observables: density [21][40][2], evolution [21], steady_density [40][2]; totals kept" \
  '/usr/bin/python3 - "$tmp/full/observables.h5" <<PY
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")["observables"]
d = f["density/value"][()]
assert d.shape == (21, 40, 2), d.shape
assert f["evolution/value"].shape == (21,)
assert f["evolution/value"][0] == 0.0 and f["evolution/value"][-1] > 0.0
s = f["steady_density/value"][()]
assert s.shape == (40, 2), s.shape
m = d.mean(axis=1)
assert np.max(np.abs(m - 0.25)) < 1e-13, np.max(np.abs(m - 0.25))
assert d[-1, 20, 1] > 0.25 > d[-1, 20, 0]
PY'
check "checkpoints at 3080 and 6160 steps" \
  '[ -f "$tmp/full/checkpoint-0000003080.h5" ] && [ -f "$tmp/full/checkpoint-0000006160.h5" ]'

mkdir -p "$tmp/part"
cp "$tmp/full/checkpoint-0000003080.h5" "$tmp/part/"
runs "restart at T/2" "$narrows" run "$scene" "${short[@]}" --restart "$tmp/part" --out "$tmp/part" \
  > /dev/null 2>&1
runs "2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$scene" "${short[@]}" --out "$tmp/two" > /dev/null 2>&1
check "restart and 2 ranks: bitwise the uninterrupted run" '/usr/bin/python3 - "$tmp" <<PY
import sys, h5py, numpy as np
t = sys.argv[1]
for k in ("fraction_0", "fraction_1"):
    a = h5py.File(t + "/full/checkpoint-0000006160.h5", "r")["continuum/" + k][()]
    for other in ("/part/", "/two/"):
        b = h5py.File(t + other + "checkpoint-0000006160.h5", "r")["continuum/" + k][()]
        assert np.array_equal(a, b), (k, other)
fa = h5py.File(t + "/full/observables.h5", "r")["observables"]
fb = h5py.File(t + "/part/observables-0000003080.h5", "r")["observables"]
for k in ("density", "evolution"):
    assert fb[k]["value"].shape[0] == 10
    assert np.array_equal(fa[k]["value"][-10:], fb[k]["value"][()]), k
assert np.array_equal(fa["steady_density/value"][()], fb["steady_density/value"][()])
PY'

runs "bench --continuum" "$narrows" bench --continuum 200 > "$tmp/bench.txt" 2>&1
check "bench: cell-steps/s of the segregation model" \
  'grep -q "^continuum segregation 200 cells: .* cell-steps/s on one core" "$tmp/bench.txt"'

refused "flux with segregation" 'continuum.flux is not a key of continuum.model = "segregation"' \
  "$narrows" check "$scene" --set continuum.flux=burgers
refused "odd cells" "continuum.cells = 41 is out of range; allowed: an even integer" \
  "$narrows" check "$scene" --set continuum.cells=41
refused "fractions beyond close packing" \
  "continuum.kind\[1\].fraction = 0.6 is out of range; allowed: a number > 0 (mean area/volume fraction; all kinds together below max_packing = 0.82)" \
  "$narrows" check "$scene" --set 'continuum.kind=[{radius=2.0,fraction=0.25,diffusivity=0.001},{radius=4.0,fraction=0.6,diffusivity=0.001}]'
refused "three kinds" "continuum.kind: found .* allowed: one or two tables" \
  "$narrows" check "$scene" --set 'continuum.kind=[{radius=1.0,fraction=0.1,diffusivity=0.001},{radius=2.0,fraction=0.1,diffusivity=0.001},{radius=3.0,fraction=0.1,diffusivity=0.001}]'
refused "unknown kind key" "unknown key 'continuum.kind\[0\].mass'; allowed keys: radius, fraction, diffusivity" \
  "$narrows" check "$scene" --set 'continuum.kind=[{radius=2.0,fraction=0.25,diffusivity=0.001,mass=1.0}]'
refused "radius beyond the channel" "continuum.kind\[0\].radius = 50.0 is out of range" \
  "$narrows" check "$scene" --set 'continuum.kind=[{radius=50.0,fraction=0.25,diffusivity=0.001}]'
refused "negative k_d" "continuum.k_d = -1.0 is out of range; allowed: a number > 0" \
  "$narrows" check "$scene" --set continuum.k_d=-1.0
refused "dimensions 4" "continuum.dimensions = 4 is out of range; allowed: 2 or 3" \
  "$narrows" check "$scene" --set continuum.dimensions=4
refused "unknown shear" 'continuum.shear = "couette" is not known; allowed: "poiseuille", "viscous"' \
  "$narrows" check "$scene" --set 'continuum.shear="couette"'
refused "velocity with segregation" 'output.observables lists "velocity"' \
  "$narrows" check "$scene" --set 'output.observables=["velocity"]'
refused "k_d with jamming" 'continuum.k_d is a key of continuum.model = "segregation"' \
  "$narrows" check "$src/run/continuum_jamming_pulses.toml" --set continuum.k_d=2.0
refused "half_width with the conservation law" 'continuum.half_width is a key of continuum.model = "segregation"' \
  "$narrows" check "$src/run/continuum_burgers_riemann.toml" --set continuum.half_width=2.0

finish continuum_segregation
