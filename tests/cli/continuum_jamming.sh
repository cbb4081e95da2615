#!/usr/bin/env bash
# The jamming model of the continuum engine (Kanehl (thesis) ch.6) from the command line: check
# prints the friction fit, the unstable band of eq 6.11 and the time step; a run writes density
# (phi) and velocity (v) and conserves the mass; a restart from the checkpoint half-way continues
# bitwise; 2 ranks give the bits of 1; tools/jamming_plot.py draws the run; bad input exits 2
# with one line.
set -u
source "$(dirname "$0")/common.bash"

scene=$src/run/continuum_jamming_pulses.toml
short=(--set continuum.time=40.0 --set continuum.samples=20 --set continuum.cells=256)

runs "check" "$narrows" check "$scene" > "$tmp/check.out" 2>&1
check "check: the fit of Table 6.2 (mu = 1)" \
  'grep -q "^friction: .*0.0413 \[1 + tanh((0.762 - phi) / 0.0025)\]" "$tmp/check.out"'
# The band edge and the critical drive printed by check against the linearised PDE computed
# here (issue 33 item 2): v_ss of Table 6.2 (mu = 1) written out, the 2x2 matrix of a mode e^{ikx}
# about the uniform state (xi' by a central difference), its eigenvalues by numpy, the edge where
# the larger real part changes sign (brentq) and the drive where long waves (k = 1e-3) turn
# unstable. check prints phi, the edge and the drive to 6 digits: agreement within 1e-5
# relative (measured 4e-6 for the edge, from phi's rounding; the O(k^2) of
# the long-wave limit at k = 1e-3 is ~1e-6).
check "check: the unstable band of eq 6.11 and the stability boundary at phi = 0.75" \
  '/usr/bin/python3 - "$tmp/check.out" <<PY
import re, sys
import numpy as np
from scipy.optimize import brentq
text = open(sys.argv[1]).read()
m = re.search(r"^stability \(eq 6.11\) of phi = ([0-9.]+), .*unstable band 0 < k < ([0-9.]+) ", text, re.M)
b = re.search(r"^stability boundary .* unstable to long waves for drive < ([0-9.]+) ", text, re.M)
assert m and b, "stability lines missing"
phi0, edge, drive_c = float(m.group(1)), float(m.group(2)), float(b.group(1))
dv, dphi, phic, e1, e2, phiq = 0.0413, 0.0025, 0.762, 2.56, -3.24, 0.845
def vss(p):
    step = dv * (1 + np.tanh((phic - p) / dphi))
    return step + (e1 + e2 * p if p < phic else (e1 + e2 * phic) / (phic - phiq) ** 2 * (p - phiq) ** 2)
def rate(k, sigma, D=1.0):
    xi = lambda p: sigma / vss(p)
    v0, h = vss(phi0), 1e-6
    s_phi = -(xi(phi0 + h) - xi(phi0 - h)) / (2 * h) * v0
    a = np.array([[-1j * k * v0 - D * k * k, -1j * k * phi0], [s_phi, -1j * k * v0 - xi(phi0)]])
    return np.linalg.eigvals(a).real.max()
ref_edge = brentq(lambda k: rate(k, 1.0), 0.1, 5.0, xtol=1e-12)
ref_drive = brentq(lambda s: rate(1e-3, s), 0.5, 3.0, xtol=1e-12)
print("band edge", edge, "reference", ref_edge, "; critical drive", drive_c, "reference", ref_drive)
assert abs(edge - ref_edge) < 1e-5 * ref_edge, (edge, ref_edge)
assert abs(drive_c - ref_drive) < 1e-5 * ref_drive, (drive_c, ref_drive)
PY'
# The step count follows from the time step it prints (steps x dt = time, to one step), not a
# number copied from an earlier output (the scene's cells change it).
check "check: time step and steps" '/usr/bin/python3 - "$tmp/check.out" <<PY
import re, sys
text = open(sys.argv[1]).read()
dt = float(re.search(r"^time step: dt = ([0-9.e+-]+) ", text, re.M).group(1))
m = re.search(r"^time: ([0-9.e+-]+) in ([0-9]+) steps", text, re.M)
t, n = float(m.group(1)), int(m.group(2))
assert t == 400.0 and abs(n * dt - t) <= dt, (t, n, dt)
PY'

runs "uninterrupted run" "$narrows" run "$scene" "${short[@]}" --set output.checkpoint_every=1360 \
  --out "$tmp/full" > /dev/null 2>&1
check "observables: density and velocity [21][256], mass conserved" '/usr/bin/python3 - "$tmp/full/observables.h5" <<PY
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")["observables"]
assert f["density/value"].shape == (21, 256), f["density/value"].shape
assert f["velocity/value"].shape == (21, 256)
m = f["density/value"][()].mean(axis=1)
assert np.max(np.abs(m - m[0])) < 1e-13, np.max(np.abs(m - m[0]))
PY'
check "checkpoints at 1360 and 2720 steps" \
  '[ -f "$tmp/full/checkpoint-0000001360.h5" ] && [ -f "$tmp/full/checkpoint-0000002720.h5" ]'

mkdir -p "$tmp/part"
cp "$tmp/full/checkpoint-0000001360.h5" "$tmp/part/"
runs "restart at T/2" "$narrows" run "$scene" "${short[@]}" --restart "$tmp/part" --out "$tmp/part" \
  > /dev/null 2>&1
runs "2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$scene" "${short[@]}" --out "$tmp/two" > /dev/null 2>&1
check "restart and 2 ranks: bitwise the uninterrupted run" '/usr/bin/python3 - "$tmp" <<PY
import sys, h5py, numpy as np
t = sys.argv[1]
for k in ("density", "velocity"):
    a = h5py.File(t + "/full/checkpoint-0000002720.h5", "r")["continuum/" + k][()]
    for other in ("/part/", "/two/"):
        b = h5py.File(t + other + "checkpoint-0000002720.h5", "r")["continuum/" + k][()]
        assert np.array_equal(a, b), (k, other)
fa = h5py.File(t + "/full/observables.h5", "r")["observables"]
fb = h5py.File(t + "/part/observables-0000001360.h5", "r")["observables"]
for k in ("density", "velocity"):
    assert fb[k]["value"].shape[0] == 10
    assert np.array_equal(fa[k]["value"][-10:], fb[k]["value"][()]), k
PY'

runs "tools/jamming_plot.py" /usr/bin/python3 "$src/tools/jamming_plot.py" "$tmp/full" > "$tmp/plot.out" 2>&1
check "jamming_plot: PNG and the three fixed points of fig 6.18 b (saddle, focus source, saddle)" \
  '[ -s "$tmp/full/jamming.png" ] && [ "$(grep -c "^fixed point" "$tmp/plot.out")" -eq 3 ] &&
   grep -q "0.7625.*focus source" "$tmp/plot.out"'

runs "bench --continuum" "$narrows" bench --continuum 1000 > "$tmp/bench.txt" 2>&1
check "bench: point-steps/s of the jamming model" \
  'grep -q "^continuum jamming 1000 points: .* point-steps/s on one core" "$tmp/bench.txt"'

refused "flux with jamming" 'continuum.flux is a key of continuum.model = "conservation-law"' \
  "$narrows" check "$scene" --set continuum.flux=burgers
refused "unknown mu" 'continuum.mu = "2" is not known; allowed: "infinity", "1", "1/2", "0"' \
  "$narrows" check "$scene" --set 'continuum.mu="2"'
refused "odd cells" "continuum.cells = 511 is out of range; allowed: an even integer" \
  "$narrows" check "$scene" --set continuum.cells=511
refused "open boundary" 'continuum.boundary = "open" is not known; allowed: "periodic"' \
  "$narrows" check "$scene" --set continuum.boundary=open
refused "mean out of range" "continuum.initial.mean = 1.5 is out of range" \
  "$narrows" check "$scene" --set 'continuum.initial={kind="random",mean=1.5,amplitude=0.0}'
refused "shock_position with jamming" 'output.observables lists "shock_position"' \
  "$narrows" check "$scene" --set 'output.observables=["shock_position"]'
refused "drive with the conservation law" 'continuum.drive is a key of continuum.model = "jamming"' \
  "$narrows" check "$src/run/continuum_burgers_riemann.toml" --set continuum.drive=2.0

finish continuum_jamming
