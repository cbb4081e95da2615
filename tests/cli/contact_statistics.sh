#!/usr/bin/env bash
# The contact network of the spring contacts (issue 31 items 2 and 5) through the command line:
# contact_statistics (overlap histograms, sliding fractions, coordination per kind) and the
# trajectory's /contacts are bitwise the same on 1 and 3 ranks, with contacts straddling slab
# edges counted once; the histograms add up to the contacts and agree with the trajectory's
# network; hard contacts are refused for the observable. The drive's target: a body force that
# acts on fluid and colloids runs bitwise as the same force given as colloids.gravity, and the
# combinations that make no sense are refused in one line.
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3

cat > "$tmp/s.toml" <<'TOML'
[run]
dimensions = 2
seed = 23
steps = 200
[domain]
size = [30.0, 12.0]
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
placement = "random"
gravity = [0.0, -1.0]
[[colloids.kind]]
radius = 1.6
count = 16
[[colloids.kind]]
radius = 1.2
count = 12
[colloids.spring]
kn = 2500
kt = 2500
mu_cc = 0.5
mu_cw = 0.3
substeps = 10
[output]
every = 50
trajectory_every = 100
trajectory_subsample = 1000
checkpoint_every = 0
progress = false
observables = ["contact_statistics"]
TOML

runs "1 rank" "$narrows" run "$tmp/s.toml" --out "$tmp/one" > /dev/null 2>&1
runs "3 ranks" "${mpi[@]}" -n 3 "$narrows" run "$tmp/s.toml" --out "$tmp/three" > /dev/null 2>&1
cat > "$tmp/same.py" <<'PY'
import sys, h5py, numpy as np
a, b = sys.argv[1:3]
def datasets(path, group):
    out = {}
    with h5py.File(path, "r") as f:
        f[group].visititems(lambda n, o: out.__setitem__(n, o[()]) if isinstance(o, h5py.Dataset) else None)
    return out
for file, group in (("observables.h5", "observables/contact_statistics"), ("trajectory.h5", "contacts")):
    x, y = datasets(f"{a}/{file}", group), datasets(f"{b}/{file}", group)
    if sorted(x) != sorted(y):
        sys.exit(f"{file} {group}: datasets {sorted(x)} and {sorted(y)}")
    for k in x:
        if x[k].dtype != y[k].dtype or x[k].shape != y[k].shape or x[k].tobytes() != y[k].tobytes():
            sys.exit(f"{file} /{group}/{k} differs")
PY
cat > "$tmp/meaningful.py" <<'PY'
# The comparison means something: contacts between colloids and with the walls at every sample,
# some straddling a slab edge of the 3 ranks (x = 10 or 20, to within a radius: the grid shifts);
# the histograms and `beyond` add up to the contacts and to the trajectory's network of the same
# step; the coordination of each kind is its colloids' partners over their number.
import sys, h5py, numpy as np
run = sys.argv[1]
with h5py.File(f"{run}/observables.h5", "r") as f:
    g = f["observables/contact_statistics"]
    value, contacts, beyond = g["value"][()], g["contacts"][()], g["beyond"][()]
    coordination, step, bins = g["coordination"][()], g["step"][()], g["bins"][()]
assert value.shape[1:] == (2, 100) and len(bins) == 100, value.shape
assert np.all(contacts[1:, 0] > 0) and np.all(contacts[1:, 1] > 0), contacts
assert np.array_equal(value.sum(axis=2) + beyond, contacts), (value.sum(axis=2), beyond, contacts)
assert coordination.shape[1] == 2, coordination.shape
with h5py.File(f"{run}/trajectory.h5", "r") as f:
    c = f["contacts"]
    tstep, first, count, ids = c["step"][()], c["first"][()], c["count"][()], c["ids"][()]
    x = f["particles/colloids/position/value"][()]
    cid = f["particles/colloids/id"][()]
straddle = 0
checked = 0
for t, s in enumerate(tstep):
    if s not in step:  # (the frame of step 0; samples from step 50 on)
        continue
    k = list(step).index(s)
    checked += 1
    rows = ids[first[t]:first[t] + count[t]]
    walls = rows[:, 1] < 0
    assert walls.sum() == contacts[k, 1] and (~walls).sum() == contacts[k, 0], (s, rows)
    # coordination from the network: each colloid-colloid contact counts for both colloids
    kind = np.where(cid < 16, 0, 1)
    n = np.zeros(len(cid))
    for o, p in rows[~walls]:
        n[o] += 1
        n[p] += 1
    want = [n[kind == q].mean() for q in (0, 1)]
    assert np.allclose(coordination[k], want, rtol=0, atol=1e-12), (coordination[k], want)
    for o, p in rows[~walls]:
        xo, xp = x[t, o, 0], x[t, p, 0]
        lo, hi = min(xo, xp), max(xo, xp)
        if hi - lo < 15 and any(lo < e < hi for e in (10.0, 20.0)):
            straddle += 1
assert checked >= 2 and straddle > 0, (checked, "frames; no contact across x = 10 or 20")
PY
check "contact_statistics and /contacts: 3 ranks bitwise equal to 1 rank" \
  '$py "$tmp/same.py" "$tmp/one" "$tmp/three"'
check "contacts at every sample, across slab edges; counts add up; coordination per kind" \
  '$py "$tmp/meaningful.py" "$tmp/one"'

bad() { sed "$1" "$tmp/s.toml" > "$tmp/bad.toml"; }
bad 's/contacts = "spring"/contacts = "hard"/; /^\[colloids.spring\]/,/^substeps/d'
refused "contact_statistics with hard contacts" \
  'output.observables lists "contact_statistics" with colloids.contacts = "hard".*allowed only with colloids.contacts = "spring"' \
  "$narrows" check "$tmp/bad.toml"

# The drive: body_force.acts_on = "fluid+colloids" gives each colloid M value on top of its
# gravity, the same bits as writing the sum into colloids.gravity.
bad 's/^value = \[0.01, 0.0\]/value = [0.01, 0.0]\nacts_on = "fluid+colloids"/'
cp "$tmp/bad.toml" "$tmp/drive_key.toml"
bad 's/^gravity = \[0.0, -1.0\]/gravity = [0.01, -1.0]/'
cp "$tmp/bad.toml" "$tmp/drive_gravity.toml"
check "narrows check names the drive on the colloids" \
  '"$narrows" check "$tmp/drive_key.toml" | grep -q "the body force on the colloids too"'
runs "the drive by body_force.acts_on" "$narrows" run "$tmp/drive_key.toml" --set run.steps=100 \
  --set output.trajectory_every=0 --out "$tmp/key" > /dev/null 2>&1
runs "the drive by colloids.gravity" "$narrows" run "$tmp/drive_gravity.toml" --set run.steps=100 \
  --set output.trajectory_every=0 --out "$tmp/grav" > /dev/null 2>&1
runs "the fluid-only drive" "$narrows" run "$tmp/s.toml" --set run.steps=100 \
  --set output.trajectory_every=0 --out "$tmp/fluid_only" > /dev/null 2>&1
cat > "$tmp/colloids.py" <<'PY'
import sys, h5py
def state(p):
    with h5py.File(p, "r") as f:
        return [f[f"particles/{s}/{k}/value"][()].tobytes() for s in ("colloids", "fluid")
                for k in ("position", "velocity")]
a, b = state(sys.argv[1]), state(sys.argv[2])
sys.exit(0 if (a == b) == (sys.argv[3] == "same") else 1)
PY
check "acts_on = fluid+colloids bitwise equal to the force in colloids.gravity" \
  '$py "$tmp/colloids.py" "$tmp/key/checkpoint-0000000100.h5" "$tmp/grav/checkpoint-0000000100.h5" same'
check "and different from the drive on the fluid alone" \
  '$py "$tmp/colloids.py" "$tmp/key/checkpoint-0000000100.h5" "$tmp/fluid_only/checkpoint-0000000100.h5" different'
sed 's/^gravity = \[0.0, -1.0\]/gravity = [0.01, 0.0]/' "$tmp/drive_key.toml" > "$tmp/twice.toml"
check "check warns of a drive given twice" \
  '"$narrows" check "$tmp/twice.toml" 2>&1 | grep -q "the colloids feel the drive twice"'
bad 's/^value = \[0.01, 0.0\]/value = [0.01, 0.0]\nacts_on = "colloids"/'
refused "an unknown drive target" 'body_force.acts_on = "colloids" is not a known drive target; allowed: fluid, fluid+colloids' \
  "$narrows" check "$tmp/bad.toml"
cat > "$tmp/nocolloids.toml" <<'TOML'
[run]
dimensions = 2
steps = 10
[domain]
size = [20.0, 10.0]
[fluid]
collision = "srd"
dt = 0.1
[body_force]
value = [0.01, 0.0]
acts_on = "fluid+colloids"
TOML
refused "fluid+colloids without colloids" 'body_force.acts_on = "fluid.colloids" needs \[colloids\]' \
  "$narrows" check "$tmp/nocolloids.toml"
sed -e 's/^value = \[0.01, 0.0\]/kind = "sine"\namplitude = 0.01/' -e '/^\[walls\]/,/^virtual_particles/d' \
  "$tmp/nocolloids.toml" > "$tmp/sine.toml"
printf '[colloids]\ncoupling = "no-slip"\nradius = 1.5\ncount = 2\n' >> "$tmp/sine.toml"
refused "fluid+colloids with the sine force" 'body_force.acts_on = "fluid.colloids" cannot be combined with body_force.kind = "sine"' \
  "$narrows" check "$tmp/sine.toml"
finish "contact statistics"
