#!/usr/bin/env bash
# Several colloid kinds and the colloid statistics: a channel with two kinds ([[colloids.kind]])
# writes colloid_vacf, colloid_diffusion, colloid_msd, colloid_angular_vacf and density_kde,
# which open with h5py with the documented shapes and known relations (D is (1/d) times the
# running trapezoid integral of C, the MSD is 0 at lag 0, MD colloids do not rotate, each kind's
# kernel density integrates to 1); 2 ranks write them bitwise equal to 1 rank; a restart with two
# kinds (1 rank to 60, 2 ranks to 120) ends bitwise equal to the uninterrupted run, radius and
# mass included, and its statistics continue the sums of the checkpoint (bitwise those of the
# uninterrupted run when continued from its own checkpoint) and join_observables.py copies
# them into the joined file; no-slip colloids of two kinds spin (angular VACF) with the same
# statistics on 1 and 2 ranks; tools/colloid_plot.py draws them; mixing the one-kind keys with the kinds is
# refused.
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3

cat > "$tmp/k.toml" <<'TOML'
[run]
dimensions = 2
seed = 4
steps = 120
[domain]
size = [40.0, 16.0]
[fluid]
collision = "srd"
density = 5
dt = 0.1
[walls]
[colloids]
placement = "random"
max_lag = 20
correlation_every = 2
statistics_from = 20
kde_width = 0.5
[[colloids.kind]]
radius = 1.5
count = 4
[[colloids.kind]]
radius = 2.5
count = 2
mass = 150.0
[output]
every = 10
checkpoint_every = 60
progress = false
observables = ["temperature", "colloid_vacf", "colloid_diffusion", "colloid_msd",
               "colloid_angular_vacf", "density_kde"]
TOML
runs --err "$tmp/err1" "1 rank" "$narrows" run "$tmp/k.toml" --out "$tmp/one" > /dev/null
runs --err "$tmp/err2" "2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/k.toml" --out "$tmp/two" > /dev/null
check "the statistics open with h5py, with their shapes and relations" '$py - "$tmp/one/observables.h5" <<PY
import sys, h5py, numpy as np
o = h5py.File(sys.argv[1], "r")["observables"]
lags = 20 // 2 + 1
for name in ("colloid_vacf", "colloid_diffusion", "colloid_msd", "colloid_angular_vacf"):
    g = o[name]
    assert g["value"].shape == (lags,) and g["error"].shape == (lags,), name
    assert g["value_by_kind"].shape == (2 * lags,), name
    assert g["kinds"][0] == 2 and g["samples"][0] == 51, (name, g["samples"][0])  # steps 20..120 by 2
    assert np.all(np.isfinite(g["value"][()])) and np.all(np.isfinite(g["error"][1:])), name
t = o["colloid_vacf/lags"][()]
assert np.allclose(t, 0.2 * np.arange(lags)), t
c, d = o["colloid_vacf/value"][()], o["colloid_diffusion/value"][()]
integral = np.concatenate([[0.0], np.cumsum(0.5 * (c[1:] + c[:-1]) * 0.2)]) / 2
assert np.allclose(d, integral, rtol=1e-12, atol=0), (d, integral)
ck = o["colloid_vacf/value_by_kind"][()].reshape(2, lags)
assert np.all(ck[:, 0] > 0), ck[:, 0]
assert o["colloid_msd/value"][0] == 0.0 and np.all(o["colloid_msd/value"][1:] > 0)
assert np.all(o["colloid_angular_vacf/value"][()] == 0.0)  # MD colloids do not rotate
k = o["density_kde"]
y, f = k["bins"][()], k["value"][()]
assert f.shape == (2, 128) and k["error"].shape == (2, 128) and y.shape == (128,), f.shape
assert k["samples"][0] == 11 and list(k["counts"][()]) == [4, 2], (k["samples"][0], k["counts"][()])
assert np.allclose(f.sum(axis=1) * (y[1] - y[0]), 1.0, atol=2e-3), f.sum(axis=1) * (y[1] - y[0])
PY'
check "2 ranks write the statistics bitwise equal to 1 rank" '$py - "$tmp/one/observables.h5" "$tmp/two/observables.h5" <<PY
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r")["observables"] for p in sys.argv[1:])
for name in ("colloid_vacf", "colloid_diffusion", "colloid_msd", "colloid_angular_vacf", "density_kde"):
    for key in a[name]:
        x, y = a[name][key][()], b[name][key][()]
        assert x.shape == y.shape and np.array_equal(np.atleast_1d(x).view(np.uint8), np.atleast_1d(y).view(np.uint8)), (name, key)
PY'
runs "first part, 1 rank" "$narrows" run "$tmp/k.toml" --set run.steps=60 --out "$tmp/part" > /dev/null 2>&1
runs --err "$tmp/err3" "restart, 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/k.toml" --restart "$tmp/part" --out "$tmp/part" > /dev/null
check "two kinds: restart (1 rank to 60, 2 ranks to 120) bitwise equal, radius and mass too" '$py - "$tmp/one/checkpoint-0000000120.h5" "$tmp/part/checkpoint-0000000120.h5" <<PY
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r")["particles"] for p in sys.argv[1:])
for species, keys in (("fluid", ("position", "velocity")), ("colloids", ("position", "velocity", "radius", "mass"))):
    oa, ob = np.argsort(a[species + "/id/value"][()]), np.argsort(b[species + "/id/value"][()])
    for key in keys:
        x, y = a[species][key]["value"][()][oa], b[species][key]["value"][()][ob]
        assert np.array_equal(x.view(np.uint64), y.view(np.uint64)), (species, key)
r, m = a["colloids/radius/value"][()][oa], a["colloids/mass/value"][()][oa]
assert list(r) == [1.5] * 4 + [2.5] * 2, r
assert np.allclose(m[:4], 5 * np.pi * 1.5**2, rtol=1e-14) and list(m[4:]) == [150.0, 150.0], m
PY'
check "the continuation's statistics hold the samples of the whole chain" '$py -c "import h5py,sys; assert h5py.File(sys.argv[1])[\"observables/colloid_vacf/samples\"][0] == 51" "$tmp/part/observables-0000000060.h5"'
runs "join_observables.py on the chain" $py "$src/tools/join_observables.py" "$tmp/part" > /dev/null
check "the joined file holds the chain's statistics and the joined series" '$py -c "
import h5py, sys
o = h5py.File(sys.argv[1])[\"observables\"]
assert o[\"colloid_vacf/samples\"][0] == 51 and o[\"density_kde/value\"].shape == (2, 128)
assert o[\"temperature/value\"].shape == (12,)" "$tmp/part/observables-joined.h5"'
# The same scene (run.steps too, so the same blocks) continued from the uninterrupted run's
# checkpoint at 60 on 2 ranks: the statistics of the chain are bitwise those of the run.
mkdir -p "$tmp/chain" && cp "$tmp/one/checkpoint-0000000060.h5" "$tmp/chain/"
runs --err "$tmp/err4" "restart from the run's checkpoint at 60, 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/k.toml" --restart "$tmp/chain" --out "$tmp/chain" > /dev/null
check "the chain's statistics (restart at 60) are bitwise the uninterrupted run's" '$py - "$tmp/one/observables.h5" "$tmp/chain/observables-0000000060.h5" <<PY
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r")["observables"] for p in sys.argv[1:])
for name in ("colloid_vacf", "colloid_diffusion", "colloid_msd", "colloid_angular_vacf", "density_kde"):
    for key in a[name]:
        x, y = a[name][key][()], b[name][key][()]
        assert x.shape == y.shape and np.array_equal(np.atleast_1d(x).view(np.uint8), np.atleast_1d(y).view(np.uint8)), (name, key)
PY'
runs "colloid_plot.py" $py "$src/tools/colloid_plot.py" "$tmp/one" --png "$tmp/c.png" > "$tmp/plot.txt"
check "colloid_plot.py fits a plateau per kind and draws a PNG: $(head -c 300 "$tmp/plot.txt")" \
  'grep -q "^kind 1: D = .* +- .* (plateau over t in \[1.33333, 2\])" "$tmp/plot.txt" && grep -q "kind 0: density_kde integrates to 1.00" "$tmp/plot.txt" && [ -s "$tmp/c.png" ]'
runs "a run without the statistics" "$narrows" run "$tmp/k.toml" --set run.steps=10 \
  --set 'output.observables=["temperature"]' --out "$tmp/none" > /dev/null 2>&1
exits 2 "colloid_plot.py without the statistics" $py "$src/tools/colloid_plot.py" "$tmp/none" > /dev/null 2>&1
# No-slip colloids of two kinds spin: the angular VACF at lag 0 is positive for each kind, and
# 2 ranks write the statistics bitwise equal to 1 rank.
ns=(--set colloids.coupling=no-slip --set colloids.contacts=hard --set fluid.collision=at+a
    --set fluid.dt=0.05 --set run.steps=60 --set colloids.statistics_from=0)
runs --err "$tmp/err5" "no-slip kinds, 1 rank" "$narrows" run "$tmp/k.toml" "${ns[@]}" --out "$tmp/ns1" > /dev/null
runs --err "$tmp/err6" "no-slip kinds, 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/k.toml" "${ns[@]}" --out "$tmp/ns2" > /dev/null
check "no-slip kinds: the colloids spin and 2 ranks give the 1-rank statistics bitwise" '$py - "$tmp/ns1/observables.h5" "$tmp/ns2/observables.h5" <<PY
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r")["observables"] for p in sys.argv[1:])
w = a["colloid_angular_vacf/value_by_kind"][()].reshape(2, -1)
assert np.all(w[:, 0] > 0), w[:, 0]
for name in ("colloid_vacf", "colloid_angular_vacf", "density_kde"):
    for key in a[name]:
        x, y = a[name][key][()], b[name][key][()]
        assert np.array_equal(np.atleast_1d(x).view(np.uint8), np.atleast_1d(y).view(np.uint8)), (name, key)
PY'
refused "one-kind radius beside [[colloids.kind]]" "colloids.radius = 2 cannot be mixed with \[\[colloids.kind\]\]" \
  "$narrows" check "$tmp/k.toml" --set colloids.radius=2
finish colloid_statistics
