#!/usr/bin/env bash
# placement = "packing" (issue 21 item 3) through the command line: a bidisperse channel packed
# to phi = 0.78 runs on 1 and 2 ranks to bitwise the same checkpoint (every rank packs alike);
# the packing in the checkpoint has the scene's counts, its fraction, overlaps below 1 % of the
# small radius and no fluid particle inside a colloid; the log reports the packing; scenes the
# packing cannot make are refused in one line.
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3

cat > "$tmp/s.toml" <<'TOML'
[run]
dimensions = 2
seed = 5
steps = 20
[domain]
size = [40.0, 20.0]
[fluid]
collision = "at+a"
density = 5
dt = 0.05
[body_force]
value = [0.01, 0.0]
[walls]
virtual_particles = true
[colloids]
coupling = "no-slip"
contacts = "spring"
placement = "packing"
packing_fraction = 0.78
[[colloids.kind]]
radius = 1.5
count = 1
[[colloids.kind]]
radius = 2.1
count = 1
[output]
every = 10
trajectory_every = 20
progress = false
observables = ["momentum"]
TOML
runs --err "$tmp/err1" "1 rank" "$narrows" run "$tmp/s.toml" --out "$tmp/one" > "$tmp/log1"
check "the log reports the packing" 'grep -q "packing: 60 colloids at fraction 0.78[0-9]*, deepest overlap" "$tmp/log1"'
runs "2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/s.toml" --out "$tmp/two" > /dev/null 2>&1
cat > "$tmp/state.py" <<'PY'
import h5py, numpy as np, sys
f = h5py.File(sys.argv[1], "r")
for s in ["fluid", "colloids"]:
    p = f["/particles/" + s]
    o = np.argsort(p["id/value"][:])
    for k in ["position", "velocity"]:
        sys.stdout.buffer.write(p[k + "/value"][:][o].tobytes())
PY
$py "$tmp/state.py" "$tmp/one/checkpoint-0000000020.h5" > "$tmp/one.bin"
$py "$tmp/state.py" "$tmp/two/checkpoint-0000000020.h5" > "$tmp/two.bin"
check "2 ranks bitwise equal to 1 rank" '[ -s "$tmp/one.bin" ] && cmp -s "$tmp/one.bin" "$tmp/two.bin"'
# The packing as made (frame 0 of a trajectory) in a walled channel L x W, periodic in x: the
# positions, radii, the file, the smallest gap between two surfaces and between a surface and a wall.
cat > "$tmp/gaps.py" <<'PY'
import h5py, numpy as np
def packing(path, L, W):
    f = h5py.File(path, "r")
    c = f["/particles/colloids"]
    x, r = c["position/value"][0], c["radius"][:]
    d = x[:, None, :] - x[None, :, :]
    d[..., 0] -= L * np.round(d[..., 0] / L)
    gap = np.hypot(d[..., 0], d[..., 1]) - (r[:, None] + r[None, :])
    np.fill_diagonal(gap, np.inf)
    walls = np.minimum(x[:, 1] - r, W - x[:, 1] - r)
    return x, r, f, gap.min(), walls.min()
PY
cat > "$tmp/packed.py" <<'PY'
import sys, numpy as np
from gaps import packing
L, W = 40.0, 20.0
x, r, f, gap, walls = packing(sys.argv[1], L, W)
small, large = np.sum(r == 1.5), np.sum(r == 2.1)
assert small == 30 and large == 30, (small, large) # 0.78 L W / (pi (1.5^2 + 2.1^2)) = 29.8 each
phi = np.pi * np.sum(r * r) / (L * W)
assert abs(phi - 0.78) < 0.011, phi # within half a pair's area of the target
deepest = max(-gap, -walls, 0.0)
assert deepest < 0.01 * 1.5, deepest
p = f["/particles/fluid/position/value"][0]
inside = 0
for a in range(len(r)):
    e = p - x[a]
    e[:, 0] -= L * np.round(e[:, 0] / L)
    inside += np.sum(np.hypot(e[:, 0], e[:, 1]) < r[a])
assert inside == 0, inside
print("phi %.4f deepest overlap %.2e of the small radius, %d fluid particles" % (phi, deepest / 1.5, len(p)))
PY
check "the packing: counts, fraction, overlaps < 1 %, no fluid inside" '$py "$tmp/packed.py" "$tmp/one/trajectory.h5" > /dev/null'

# Rough hard spheres packed (run/segregation_fig5_6_2d.toml, Kanehl (thesis) fig 5.6: 398 disks
# at phi = 0.5 in the 200 x 80 channel): the packing leaves every surface apart (>= 1 % of the
# small radius from the others, >= 0.4 % from the walls), and the run goes on 2 and 3 ranks,
# bitwise as on 1. (Packed touching, a chain of collisions crossed the ghost colloids of a rank
# in the first step: on 2 or more ranks the run stopped at step 1, exit 3.)
hard=$src/run/segregation_fig5_6_2d.toml
short=(--set run.steps=4 --set output.every=4 --set output.checkpoint_every=0
  --set output.trajectory_every=4 --set output.kde_window=0 --set 'output.observables=["temperature"]')
runs --err "$tmp/herr1" "hard packing, 1 rank" "$narrows" run "$hard" "${short[@]}" --out "$tmp/h1" > /dev/null
for n in 2 3; do
  runs --err "$tmp/herr$n" "hard packing, $n ranks" "${mpi[@]}" -n $n "$narrows" run "$hard" \
    "${short[@]}" --out "$tmp/h$n" > /dev/null
done
cat > "$tmp/apart.py" <<'PY'
import sys
from gaps import packing
x, r, f, gap, walls = packing(sys.argv[1], 200.0, 80.0)
assert len(r) == 398 and gap >= 0.01 * 2.0 and walls >= 0.004 * 2.0, (gap, walls)
PY
check "hard packing: surfaces apart" '$py "$tmp/apart.py" "$tmp/h1/trajectory.h5"'
$py "$tmp/state.py" "$tmp/h1/checkpoint-0000000004.h5" > "$tmp/h1.bin"
for n in 2 3; do
  $py "$tmp/state.py" "$tmp/h$n/checkpoint-0000000004.h5" > "$tmp/h$n.bin"
  check "hard packing: $n ranks bitwise equal to 1 rank" '[ -s "$tmp/h1.bin" ] && cmp -s "$tmp/h1.bin" "$tmp/h$n.bin"'
done

bad() { sed "$1" "$tmp/s.toml" > "$tmp/bad.toml"; }
bad 's/packing_fraction = 0.78/packing_fraction = 0.9/'
refused "a fraction beyond random close packing" 'colloids.packing_fraction.*at most 0.84' "$narrows" check "$tmp/bad.toml"
bad 's/coupling = "no-slip"/coupling = "md"/; s/contacts = "spring"/contacts = "none"/'
refused "packing with MD colloids" 'colloids.placement = "packing".*allowed with coupling = "no-slip"' "$narrows" check "$tmp/bad.toml"
bad 's/placement = "packing"/placement = "random"/'
refused "packing_fraction without packing" 'colloids.packing_fraction = 0.78 is the target of placement = "packing"' "$narrows" check "$tmp/bad.toml"
bad '/packing_fraction = 0.78/d'
refused "packing without its fraction" 'colloids.packing_fraction' "$narrows" check "$tmp/bad.toml"
bad 's/radius = 2.1/radius = 10.5/'
refused "a colloid wider than the channel" 'does not fit across the channel' "$narrows" check "$tmp/bad.toml"
finish "packing scenes"
