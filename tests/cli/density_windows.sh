#!/usr/bin/env bash
# The segregation observables of a particle run in time (output.kde_window): a channel with two
# colloid kinds writes density_kde per window, evolution (Delta of Kanehl (thesis) eq 5.31) and
# colloid_velocity_profile in the agreed layout; the windows are consistent with the whole-run
# averages (density_kde and colloid_velocity_profile with kde_window = 0 over the same samples)
# and Delta recomputed from the windows; the log ends with the steady-state line; 1, 2 and 3
# ranks write the windows bitwise equal; a run stopped at step 60 (inside a window) and
# restarted writes bitwise the windows of the uninterrupted run; bad values of the key are
# refused with one line, exit 2.
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3

cat > "$tmp/w.toml" <<'TOML'
[run]
dimensions = 2
seed = 4
steps = 200
[domain]
size = [40.0, 16.0]
[fluid]
collision = "srd"
density = 5
dt = 0.1
[walls]
[body_force]
value = [0.01, 0.0]
[colloids]
placement = "random"
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
kde_window = 20
checkpoint_every = 60
checkpoint_keep = 5
progress = false
observables = ["temperature", "density_kde", "evolution", "colloid_velocity_profile"]
TOML
names='("density_kde", "evolution", "colloid_velocity_profile")'
runs --err "$tmp/err1" "1 rank" "$narrows" run "$tmp/w.toml" --out "$tmp/one" > "$tmp/log1"
check "the windows have the agreed layout and agree with Delta recomputed from them" '$py - "$tmp/one/observables.h5" <<PY
import sys, h5py, numpy as np
o = h5py.File(sys.argv[1], "r")["observables"]
k, e, v = o["density_kde"], o["evolution"], o["colloid_velocity_profile"]
steps = 20 + 20 * np.arange(1, 10)  # windows (20, 40], ..., (180, 200]
y = k["bins"][()]
for g in (k, e, v):
    assert list(g["step"][()]) == list(steps), g["step"][()]
    assert np.allclose(g["time"][()], 0.1 * steps, rtol=0, atol=1e-12)
f = k["value"][()]
assert f.shape == (9, 2, 128) and y.shape == (128,) and "error" not in k, f.shape
assert list(k["samples"][()]) == [3] + [2] * 8, k["samples"][()]  # 20, 30, 40; then 2 each
assert list(k["counts"][()]) == [4, 2] and k["width"][0] == 0.5
# each window integrates to 1 up to the error of the midpoint rule over a few kernels (h = eps / 4)
assert np.allclose(f.sum(axis=2) * (y[1] - y[0]), 1.0, atol=1e-2), f.sum(axis=2) * (y[1] - y[0])
c = (k["counts"][()][None, :, None] * f).sum(axis=1)
delta = ((c - c[0]) ** 2).sum(axis=1) / (c[0] ** 2).sum()
by_kind = ((f - f[0]) ** 2).sum(axis=2) / (f[0] ** 2).sum(axis=1)
assert e["value"].shape == (9,) and e["value"][0] == 0.0 and np.all(e["value"][1:] > 0)
assert np.allclose(e["value"][()], delta, rtol=1e-12, atol=0), (e["value"][()], delta)
assert e["by_kind"].shape == (9, 2) and np.allclose(e["by_kind"][()], by_kind, rtol=1e-12, atol=0)
assert v["value"].shape == (9, 2, 128) and v["weight"].shape == (9, 2, 128)
w = v["weight"][()]
assert np.all(np.isnan(v["value"][()][w == 0])) and np.all(np.isfinite(v["value"][()][w > 0]))
PY'
check "the log gives the cost of the windows" 'grep -q "^kde windows: .* ms per sample on rank 0 .* ms per window closed .*; 9 windows of 20 steps" "$tmp/log1"'
check "the log ends with the steady-state line" 'grep -q "^evolution: \(steady\|NOT steady\) after 9 windows: Delta = .* over the last 4 windows" "$tmp/log1" || { grep evolution "$tmp/log1"; false; }'
# The same samples averaged over the whole run (kde_window = 0, steps 20..180): density_kde is
# the sample-weighted mean of the first eight windows, the velocity profile their
# weight-weighted mean.
runs --err "$tmp/err0" "kde_window = 0 over the same samples" "$narrows" run "$tmp/w.toml" \
  --set output.kde_window=0 --set run.steps=180 --set 'output.observables=["density_kde", "colloid_velocity_profile"]' --out "$tmp/whole" > /dev/null
check "the windows merge to the whole-run averages" '$py - "$tmp/one/observables.h5" "$tmp/whole/observables.h5" <<PY
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r")["observables"] for p in sys.argv[1:])
n = a["density_kde/samples"][:8]
f = (a["density_kde/value"][:8] * n[:, None, None]).sum(axis=0) / n.sum()
assert b["density_kde/value"].shape == (2, 128) and b["density_kde/samples"][0] == n.sum()
assert np.allclose(f, b["density_kde/value"][()], rtol=1e-12, atol=1e-14)
w, v = a["colloid_velocity_profile/weight"][:8], a["colloid_velocity_profile/value"][:8]
assert b["colloid_velocity_profile/value"].shape == (1, 2, 128), b["colloid_velocity_profile/value"].shape
assert list(b["colloid_velocity_profile/step"][()]) == [180]
W = w.sum(axis=0)
with np.errstate(invalid="ignore"):
    V = np.nansum(w * v, axis=0) / W
assert np.allclose(W, b["colloid_velocity_profile/weight"][0], rtol=1e-12, atol=0)
assert np.allclose(V[W > 0], b["colloid_velocity_profile/value"][0][W > 0], rtol=1e-10, atol=1e-14)
assert np.all(np.isnan(b["colloid_velocity_profile/value"][0][W == 0]))
PY'
bitwise() { # FILE_A FILE_B ROWS_FROM: the windows of B are bitwise rows ROWS_FROM.. of A
  $py - "$1" "$2" "$3" <<PY
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r")["observables"] for p in sys.argv[1:3])
r = int(sys.argv[3])
for name in $names:
    for key in a[name]:
        x, y = a[name][key][()], b[name][key][()]
        if a[name][key].attrs.get("per_sample", 0) or key in ("value", "step", "time"):
            x = x[r:r + len(y)]
        assert x.shape == y.shape and np.array_equal(np.atleast_1d(x).view(np.uint8), np.atleast_1d(y).view(np.uint8)), (name, key, r)
PY
}
runs --err "$tmp/err2" "2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/w.toml" --out "$tmp/two" > /dev/null
runs --err "$tmp/err3" "3 ranks" "${mpi[@]}" -n 3 "$narrows" run "$tmp/w.toml" --out "$tmp/three" > /dev/null
check "2 ranks write the windows bitwise equal to 1 rank" 'bitwise "$tmp/one/observables.h5" "$tmp/two/observables.h5" 0'
check "3 ranks write the windows bitwise equal to 1 rank" 'bitwise "$tmp/one/observables.h5" "$tmp/three/observables.h5" 0'
# Stopped at 70, inside the window (60, 80] (its sums in the checkpoint), and restarted on 2
# ranks; restarted on 3 ranks from the checkpoint at 120, where (100, 120] just closed.
runs "first part to 70, 1 rank" "$narrows" run "$tmp/w.toml" --set run.steps=70 --out "$tmp/part" > /dev/null 2>&1
runs --err "$tmp/err4" "restart at 70, 2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$tmp/w.toml" --restart "$tmp/part" --out "$tmp/part" > "$tmp/log4"
check "first part: the windows closed by step 70 are the run's" 'bitwise "$tmp/one/observables.h5" "$tmp/part/observables.h5" 0'
check "restart inside a window: the continuation's windows are bitwise the run's" 'bitwise "$tmp/one/observables.h5" "$tmp/part/observables-0000000070.h5" 2'
runs "join_observables.py on the chain" $py "$src/tools/join_observables.py" "$tmp/part" > /dev/null
check "the joined chain holds bitwise the windows of the uninterrupted run" 'bitwise "$tmp/one/observables.h5" "$tmp/part/observables-joined.h5" 0 && $py -c "import h5py,sys; assert h5py.File(sys.argv[1])[\"observables/evolution/value\"].shape == (9,)" "$tmp/part/observables-joined.h5"'
check "the continuation's steady line sees the whole chain" 'grep -q "^evolution: .* after 9 windows" "$tmp/log4"'
mkdir -p "$tmp/chain" && cp "$tmp/one/checkpoint-0000000120.h5" "$tmp/chain/"
runs --err "$tmp/err5" "restart from the run's checkpoint at 120, 3 ranks" "${mpi[@]}" -n 3 "$narrows" run "$tmp/w.toml" --restart "$tmp/chain" --out "$tmp/chain" > /dev/null
check "restart at a window's end: the continuation's windows are bitwise the run's" 'bitwise "$tmp/one/observables.h5" "$tmp/chain/observables-0000000120.h5" 5'
refused "kde_window not a multiple of output.every" "output.kde_window = 25 is not a multiple of output.every = 10" \
  "$narrows" check "$tmp/w.toml" --set output.kde_window=25
refused "negative kde_window" "output.kde_window" "$narrows" check "$tmp/w.toml" --set output.kde_window=-10
refused "kde_window without density_kde" "output.kde_window = 20 windows density_kde, which output.observables does not list" \
  "$narrows" check "$tmp/w.toml" --set 'output.observables=["colloid_velocity_profile"]'
refused "evolution without windows" 'output.observables lists "evolution", Delta(t) of the density_kde windows, without them' \
  "$narrows" check "$tmp/w.toml" --set output.kde_window=0
refused "kde_window with another engine" 'output.kde_window = 10 windows the mpcd colloid profiles; allowed with run.engine = "lgca": 0' \
  "$narrows" check "$src/run/lgca_channel.toml" --set output.kde_window=10 --set output.every=10
finish density_windows
