#!/usr/bin/env bash
# The v_ss parameters of the jamming model (Kanehl (thesis) eq 6.4) from the scene: the preset
# column of Table 6.2 (continuum.mu = "1"), the same six numbers given as continuum.vss, and
# the same numbers in a fit file (continuum.vss_fit, the JSON of tools/vss_fit.py) give bitwise
# the same run; the parameters used are in the log and in /parameters/continuum of
# observables.h5; a fit file's errors are recorded; every bad source is refused with one line
# naming the file and the key.
set -u
source "$(dirname "$0")/common.bash"

short=(--set continuum.time=20.0 --set continuum.samples=10 --set continuum.cells=128)
# The scene without its mu line (vss and vss_fit cannot be mixed with mu).
sed '/^mu = /d' "$src/run/continuum_jamming_pulses.toml" > "$tmp/bare.toml"
preset=$src/run/continuum_jamming_pulses.toml
table='{ delta_v = 0.0413, delta_phi = 0.0025, phi_c = 0.762, e1 = 2.56, e2 = -3.24, phi_q = 0.845 }'
cat > "$tmp/fit.json" <<JSON
{"delta_v": 0.0413, "delta_phi": 0.0025, "phi_c": 0.762, "e1": 2.56, "e2": -3.24,
 "phi_q": 0.845, "phi_c_error": 0.0015, "e1_error": 0.04, "source": "Table 6.2, mu = 1",
 "points": 41}
JSON

runs "preset run" "$narrows" run "$preset" "${short[@]}" --out "$tmp/preset" > "$tmp/preset.out" 2>&1
runs "vss run" "$narrows" run "$tmp/bare.toml" "${short[@]}" --set "continuum.vss=$table" \
  --out "$tmp/vss" > "$tmp/vss.out" 2>&1
runs "vss_fit run" "$narrows" run "$tmp/bare.toml" "${short[@]}" --set 'continuum.vss_fit="fit.json"' \
  --out "$tmp/file" > "$tmp/file.out" 2>&1
check "log: the parameters and where they came from" \
  'grep -q "v_ss parameters (eq 6.4) from Table 6.2, mu = 1: delta_v = 0.0413, delta_phi = 0.0025, phi_c = 0.762, e1 = 2.56, e2 = -3.24, phi_q = 0.845; e3 = " "$tmp/preset/log.txt" &&
   grep -q "v_ss parameters (eq 6.4) from continuum.vss: delta_v = 0.0413," "$tmp/vss/log.txt" &&
   grep -q "v_ss parameters (eq 6.4) from continuum.vss_fit = .*fit.json: delta_v = 0.0413, delta_phi = 0.0025, phi_c = 0.762 +- 0.0015, e1 = 2.56 +- 0.04, e2 = -3.24" "$tmp/file/log.txt"'
check "preset, vss and vss_fit: bitwise the same phi and v; /parameters/continuum" '/usr/bin/python3 - "$tmp" <<PY
import sys, h5py, numpy as np
t = sys.argv[1]
f = {k: h5py.File(t + "/" + k + "/observables.h5", "r") for k in ("preset", "vss", "file")}
for k in ("density", "velocity"):
    a = f["preset"]["observables/" + k + "/value"][()]
    assert a.shape == (11, 128), a.shape
    for other in ("vss", "file"):
        assert np.array_equal(a, f[other]["observables/" + k + "/value"][()]), (k, other)
want = dict(delta_v=0.0413, delta_phi=0.0025, phi_c=0.762, e1=2.56, e2=-3.24, phi_q=0.845)
for name, g in f.items():
    at = g["parameters/continuum"].attrs
    for k, x in want.items():
        assert at[k][0] == x, (name, k, at[k])
    assert abs(at["e3"][0] - (2.56 - 3.24 * 0.762) / (0.762 - 0.845) ** 2) < 1e-12
src = {k: g["parameters/continuum"].attrs["vss_source"] for k, g in f.items()}
src = {k: v.decode() if isinstance(v, bytes) else str(v) for k, v in src.items()}
assert src["preset"] == "Table 6.2, mu = 1" and src["vss"] == "continuum.vss", src
assert src["file"].endswith("fit.json"), src
at = f["file"]["parameters/continuum"].attrs
assert at["phi_c_error"][0] == 0.0015 and at["e1_error"][0] == 0.04 and "e2_error" not in at
PY'
runs "jamming_plot on a vss_fit run" /usr/bin/python3 "$src/tools/jamming_plot.py" "$tmp/file" \
  > "$tmp/plot.out" 2>&1
check "jamming_plot reads the parameters of the run" \
  'grep -q "^eq 6.11 at phi0 = 0.75 (vss delta_v = 0.0413, .*phi_q = 0.845.*unstable band 0 < k < 0.757" "$tmp/plot.out"'

# Refusals: one line naming the file, the key, what was found and what is allowed.
bare=("$narrows" check "$tmp/bare.toml")
refused "mu and vss" 'continuum.vss cannot be mixed with continuum.mu; allowed: exactly one of' \
  "$narrows" check "$preset" --set "continuum.vss=$table"
refused "vss and vss_fit" 'continuum.vss_fit cannot be mixed with continuum.vss' \
  "${bare[@]}" --set "continuum.vss=$table" --set 'continuum.vss_fit="fit.json"'
refused "vss: missing key" "missing required key 'continuum.vss.phi_q'" \
  "${bare[@]}" --set 'continuum.vss={ delta_v = 0.0413, delta_phi = 0.0025, phi_c = 0.762, e1 = 2.56, e2 = -3.24 }'
refused "vss: unknown key" "unknown key 'continuum.vss.phi_j'; allowed keys: delta_v, delta_phi" \
  "${bare[@]}" --set "continuum.vss={ delta_v = 0.0413, delta_phi = 0.0025, phi_c = 0.762, e1 = 2.56, e2 = -3.24, phi_q = 0.845, phi_j = 1.0 }"
refused "vss: phi_q <= phi_c" 'continuum.vss.phi_q = 0.7 is out of range; allowed: phi_c = 0.762 < phi_q <= 1' \
  "${bare[@]}" --set 'continuum.vss={ delta_v = 0.0413, delta_phi = 0.0025, phi_c = 0.762, e1 = 2.56, e2 = -3.24, phi_q = 0.7 }'
refused "vss: not a number" 'continuum.vss.e1: found "big" (string); allowed: a finite number' \
  "${bare[@]}" --set 'continuum.vss={ delta_v = 0.0413, delta_phi = 0.0025, phi_c = 0.762, e1 = "big", e2 = -3.24, phi_q = 0.845 }'
refused "vss: non-finite" 'continuum.vss.e2 = -inf is out of range; allowed: a finite number' \
  "${bare[@]}" --set 'continuum.vss={ delta_v = 0.0413, delta_phi = 0.0025, phi_c = 0.762, e1 = 2.56, e2 = -inf, phi_q = 0.845 }'
refused "vss_fit: no file" 'continuum.vss_fit = "none.json": .*none.json: cannot open; allowed: the path' \
  "${bare[@]}" --set 'continuum.vss_fit="none.json"'
printf '{"delta_v": 0.0413, "delta_phi": 0.0025,,}' > "$tmp/broken.json"
refused "vss_fit: not JSON" 'continuum.vss_fit = "broken.json": .*broken.json is not valid JSON (.*parse error' \
  "${bare[@]}" --set 'continuum.vss_fit="broken.json"'
printf '{"delta_v": 0.0413, "delta_phi": NaN, "phi_c": 0.762, "e1": 2.56, "e2": -3.24, "phi_q": 0.845}' > "$tmp/nan.json"
refused "vss_fit: NaN" 'nan.json is not valid JSON (.*NaN and Infinity are not JSON)' \
  "${bare[@]}" --set 'continuum.vss_fit="nan.json"'
printf '{"delta_v": 0.0413, "delta_phi": 1e999, "phi_c": 0.762, "e1": 2.56, "e2": -3.24, "phi_q": 0.845}' > "$tmp/inf.json"
refused "vss_fit: overflow" 'inf.json is not valid JSON (.*number overflow parsing .1e999' \
  "${bare[@]}" --set 'continuum.vss_fit="inf.json"'
printf '{"delta_v": 0.0413, "delta_phi": 0.0025, "phi_c": 0.762, "e1": 2.56, "e2": -3.24}' > "$tmp/short.json"
refused "vss_fit: missing parameter" 'short.json has no key "phi_q"; allowed: the path' \
  "${bare[@]}" --set 'continuum.vss_fit="short.json"'
printf '{"delta_v": 0.0413, "delta_phi": "0.0025", "phi_c": 0.762, "e1": 2.56, "e2": -3.24, "phi_q": 0.845}' > "$tmp/text.json"
refused "vss_fit: a string" 'text.json: "delta_phi" is "0.0025" (string); allowed: a finite number' \
  "${bare[@]}" --set 'continuum.vss_fit="text.json"'
printf '{"delta_v": 0.0413, "delta_phi": 0.0025, "phi_c": 0.762, "e1": 2.56, "e2": -3.24, "phi_q": 0.75}' > "$tmp/order.json"
refused "vss_fit: phi_q <= phi_c" 'order.json: "phi_q" = 0.75 is out of range; allowed: phi_c = 0.762 < phi_q <= 1' \
  "${bare[@]}" --set 'continuum.vss_fit="order.json"'
printf '[0.0413, 0.0025, 0.762, 2.56, -3.24, 0.845]' > "$tmp/array.json"
refused "vss_fit: an array" 'array.json: found a JSON array at the top; allowed: the path' \
  "${bare[@]}" --set 'continuum.vss_fit="array.json"'
printf '{"delta_v": 0.0413, "delta_phi": 0.0025, "phi_c": 0.762, "e1": 2.56, "e2": -3.24, "phi_q": 0.845, "e2_error": -1}' > "$tmp/err.json"
refused "vss_fit: negative error" 'err.json: "e2_error" = -1 is out of range; allowed: a number >= 0' \
  "${bare[@]}" --set 'continuum.vss_fit="err.json"'
refused "vss with the conservation law" 'continuum.vss is a key of continuum.model = "jamming"' \
  "$narrows" check "$src/run/continuum_burgers_riemann.toml" --set "continuum.vss=$table"

finish continuum_jamming_vss
