#!/usr/bin/env bash
# tools/segregation_fit.py recovers a known K_d (issue 22, acceptance 4): a synthetic
# density_kde of a 2D channel like run/segregation_2d.toml (w = 20, kinds a = 4 x 20 and
# a = 2 x 40 in 100 x 40) is the engine's steady profile at K_d = 3 with 2 % Gaussian noise per
# bin (fixed seed) and those errors; the fit must give K_d within 2 % and its stated error must
# cover the truth within 3 sigma. Bad input exits 2 with one line.
set -u
source "$(dirname "$0")/common.bash"

fit=$src/tools/segregation_fit.py
mkdir -p "$tmp/run"
cat > "$tmp/truth.toml" <<TOML
[run]
engine = "continuum"
[continuum]
model = "segregation"
half_width = 20.0
cells = 400
centre_speed = 0.1
k_d = 3.0
time = 1e-9
samples = 1
[[continuum.kind]]
radius = 4.0
fraction = $(/usr/bin/python3 -c 'import math; print(20 * math.pi * 16 / 4000)')
diffusivity = 0.002
[[continuum.kind]]
radius = 2.0
fraction = $(/usr/bin/python3 -c 'import math; print(40 * math.pi * 4 / 4000)')
diffusivity = 0.003
[output]
observables = ["steady_density"]
TOML
runs "the true profile" "$narrows" run "$tmp/truth.toml" --out "$tmp/truth" > /dev/null 2>&1
runs "synthetic density_kde" /usr/bin/python3 - "$tmp" <<'PY'
import sys, h5py, numpy as np
t = sys.argv[1]
g = h5py.File(t + "/truth/observables.h5", "r")["observables/steady_density"]
ym, phi = g["bins"][()], g["value"][()]
y = (np.arange(320) + 0.5) * 0.125                      # bins of eps = 0.5 over [0, 40]
p = np.stack([np.interp(y - 20.0, ym, phi[:, i]) for i in range(2)])
p /= p.sum(axis=1, keepdims=True) * 0.125              # normalised to 1 per kind
rng = np.random.default_rng(2201)
err = 0.02 * p
value = p + err * rng.standard_normal(p.shape)
scene = """[run]
engine = "mpcd"
dimensions = 2
steps = 1
[domain]
size = [100.0, 40.0]
[colloids]
kde_width = 0.5
[[colloids.kind]]
radius = 4.0
count = 20
[[colloids.kind]]
radius = 2.0
count = 40
"""
with h5py.File(t + "/run/observables.h5", "w") as f:
    f["parameters/scene"] = scene.encode()
    k = f.create_group("observables/density_kde")
    k["value"], k["error"], k["bins"], k["width"] = value, err, y, [0.5]
PY
runs "fit" /usr/bin/python3 "$fit" "$tmp/run" --diffusivity 0.002 0.003 --centre-speed 0.1 \
  --narrows "$narrows" > "$tmp/fit.out" 2>&1
cat "$tmp/fit.out"
check "K_d within 2 % of 3 and within 3 sigma" '/usr/bin/python3 - "$tmp/fit.out" <<PY
import re, sys
k, e = map(float, re.search(r"^K_d = (\S+) \+- (\S+)", open(sys.argv[1]).read(), re.M).groups())
assert abs(k - 3.0) < 0.02 * 3.0, k
assert abs(k - 3.0) < 3 * e, (k, e)
PY'

refused "no density_kde" "observables.h5: not found" \
  /usr/bin/python3 "$fit" "$tmp/none" --diffusivity 0.002 0.003 --narrows "$narrows"
refused "one diffusivity for two kinds" "--diffusivity: 1 values for 2 kinds" \
  /usr/bin/python3 "$fit" "$tmp/run" --diffusivity 0.002 --centre-speed 0.1 --narrows "$narrows"
refused "no v0" "no velocity_profile for v0; allowed: --centre-speed V0" \
  /usr/bin/python3 "$fit" "$tmp/run" --diffusivity 0.002 0.003 --narrows "$narrows"

finish segregation_fit
