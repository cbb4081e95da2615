#!/usr/bin/env bash
# The observable axial_fields (Kanehl (thesis) eq 6.1) through the command line: a short run of
# polydisperse no-slip disks in a driven channel writes /observables/axial_fields/{phi, velocity,
# fluid_velocity} [T][bins], bins, step, time, bitwise the same on 1, 2 and 3 ranks (28 cells:
# uneven slabs on 3 ranks), and so are the trajectory's voronoi_fraction frames; the channel mean of phi is the colloid area over the channel area; the trajectory frames hold each
# colloid's voronoi_fraction; the log gives the cost per sample; the same in 3D (volume
# fraction, 1 and 3 ranks); bad axial_bin values and a scene without colloids are refused in one
# line.
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3
same=$src/tests/cli/same_state.py
fields="/observables/axial_fields/phi /observables/axial_fields/velocity /observables/axial_fields/fluid_velocity /observables/axial_fields/bins /observables/axial_fields/step /observables/axial_fields/time"

cat > "$tmp/s.toml" <<'TOML'
[run]
dimensions = 2
seed = 31
steps = 60
[domain]
size = [28.0, 12.0]
[fluid]
collision = "at+a"
density = 6
dt = 0.1
[body_force]
value = [0.02, 0.0]
[walls]
virtual_particles = true
[colloids]
coupling = "no-slip"
contacts = "spring"
radius = 1.4
radius_sd = 0.15
count = 16
placement = "random"
gravity = [0.02, 0.0]
[colloids.spring]
kn = 2500
kt = 2500
mu_cc = 0.5
mu_cw = 0.5
substeps = 15
[output]
every = 20
trajectory_every = 30
axial_bin = 3.5
progress = false
observables = ["axial_fields", "momentum"]
TOML
runs --err "$tmp/err1" "1 rank" "$narrows" run "$tmp/s.toml" --out "$tmp/one" > "$tmp/log1"
check "the log gives the cost per sample" 'grep -q "axial_fields: .* ms per sample" "$tmp/log1"'
for p in 2 3; do
  runs "$p ranks" "${mpi[@]}" -n $p "$narrows" run "$tmp/s.toml" --out "$tmp/r$p" > /dev/null 2>&1
  check "$p ranks: axial_fields bitwise equal to 1 rank" \
    '$py "$same" "$tmp/one/observables.h5" "$tmp/r$p/observables.h5" $fields'
  check "$p ranks: trajectory voronoi_fraction bitwise equal to 1 rank" \
    '$py "$same" "$tmp/one/trajectory.h5" "$tmp/r$p/trajectory.h5" /particles/colloids/voronoi_fraction/value'
done
cat > "$tmp/layout.py" <<'PY'
import math, sys, h5py, numpy as np
with h5py.File(sys.argv[1] + "/observables.h5", "r") as f:
    g = f["/observables/axial_fields"]
    phi, v, vf = g["phi"][:], g["velocity"][:], g["fluid_velocity"][:]
    bins, step = g["bins"][:], g["step"][:]
    assert phi.shape == (3, 8) == v.shape == vf.shape, (phi.shape, v.shape, vf.shape)
    assert np.allclose(bins, 1.75 + 3.5 * np.arange(8)), bins
    assert list(step) == [20, 40, 60], step
    assert np.all(np.isfinite(phi)) and np.all(phi > 0) and np.all(np.isfinite(vf)), phi
with h5py.File(sys.argv[1] + "/trajectory.h5", "r") as f:
    c = f["/particles/colloids"]
    r = c["radius"][:]
    phi_i = c["voronoi_fraction/value"][:]
    assert phi_i.shape == (3, 16), phi_i.shape
    assert np.all(phi_i > 0) and np.all(phi_i < 1), phi_i
# The channel mean of phi: the colloids' area over the channel's (sum of 8 bins: 1e-15).
want = math.pi * np.sum(r * r) / (28.0 * 12.0)
assert np.allclose(phi.mean(axis=1), want, rtol=1e-12, atol=0), (phi.mean(axis=1), want)
PY
check "layout, bins, steps, channel mean, trajectory field" '$py "$tmp/layout.py" "$tmp/one"'

refused "axial_bin not dividing the length" \
  "output.axial_bin = 3.0 does not divide domain.size\[0\] = 28.0 into whole bins; allowed with \"axial_fields\": a width at most domain.size\[0\] that divides it (e.g. 3.11" \
  "$narrows" check "$tmp/s.toml" --set output.axial_bin=3.0
refused "axial_bin longer than the channel" "output.axial_bin = 56.0 is longer than the channel, domain.size\[0\] = 28.0; allowed" \
  "$narrows" check "$tmp/s.toml" --set output.axial_bin=56.0
refused "axial_bin 0" "output.axial_bin = 0.*allowed: a number > 0" \
  "$narrows" check "$tmp/s.toml" --set output.axial_bin=0.0
# 3D: power cells of the balls in the slit, the volume fraction; 1 and 3 ranks bitwise.
three=(--set run.dimensions=3 --set 'domain.size=[28.0,12.0,6.0]' --set run.steps=40
  --set 'body_force.value=[0.02,0.0,0.0]' --set 'colloids.gravity=[0.02,0.0,0.0]')
runs "3D, 1 rank" "$narrows" run "$tmp/s.toml" "${three[@]}" --out "$tmp/one3" > /dev/null 2>&1
runs "3D, 3 ranks" "${mpi[@]}" -n 3 "$narrows" run "$tmp/s.toml" "${three[@]}" --out "$tmp/r3d" \
  > /dev/null 2>&1
check "3D: 3 ranks bitwise equal to 1 rank" \
  '$py "$same" "$tmp/one3/observables.h5" "$tmp/r3d/observables.h5" $fields'
cat > "$tmp/mean3.py" <<'PY'
import math, sys, h5py, numpy as np
with h5py.File(sys.argv[1] + "/observables.h5", "r") as f:
    phi = f["/observables/axial_fields/phi"][:]
with h5py.File(sys.argv[1] + "/trajectory.h5", "r") as f:
    r = f["/particles/colloids/radius"][:]
want = 4 / 3 * math.pi * np.sum(r**3) / (28.0 * 12.0 * 6.0)
assert phi.shape == (2, 8) and np.allclose(phi.mean(axis=1), want, rtol=1e-12, atol=0), (phi, want)
PY
check "3D: the channel mean of phi is the colloid volume over the slit's" '$py "$tmp/mean3.py" "$tmp/one3"'
sed '/^\[colloids/,/^substeps/d' "$tmp/s.toml" > "$tmp/fluid.toml"
refused "no colloids" "lists \"axial_fields\", which follows colloids; allowed only with \[colloids\]" \
  "$narrows" check "$tmp/fluid.toml"
# Not listed: any axial_bin the [output] accepts is left alone.
runs "not listed: axial_bin is not checked against the length" "$narrows" check "$tmp/s.toml" \
  --set 'output.observables=["momentum"]' --set output.axial_bin=3.0 > /dev/null
finish "axial fields"
