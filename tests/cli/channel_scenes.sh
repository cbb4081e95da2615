#!/usr/bin/env bash
# Every MPCD scene in run/ passes `check`; each channel scene (with [walls]) runs briefly and
# writes the viscosity series, a velocity profile that plot_profile.py turns into a PNG, and a
# log with the Poiseuille Ma/Re line; 2 ranks give the same viscosity numbers as 1.
set -u
source "$(dirname "$0")/common.bash"

for scene in "$src"/run/*.toml; do
  grep -q 'engine = "\(kmc\|lgca\|continuum\)"' "$scene" && continue
  name=$(basename "$scene" .toml)
  runs "$name: check" "$narrows" check "$scene" > "$tmp/$name.check" 2>&1
  grep -q '^\[walls\]' "$scene" || continue
  grep -q '^\[colloids\]' "$scene" && continue # run by colloid_scenes.sh
  short=(--set domain.size=$(grep -q 'dimensions = 3' "$scene" && echo '[8,6,4]' || echo '[8,6]')
         --set run.steps=200 --set output.every=50 --set output.progress=false)
  runs "$name: run" "$narrows" run "$scene" "${short[@]}" --out "$tmp/$name" > /dev/null 2>&1
  check "$name: Poiseuille line in the log" 'grep -q "Poiseuille channel: u0 = \|viscosity: no kinetic" "$tmp/$name/log.txt"'
  check "$name: viscosity series" '/usr/bin/python3 - "$tmp/$name/observables.h5" <<PY
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")["observables"]
v = f["viscosity/value"][()]
assert v.shape == (4,), v.shape
assert np.all(np.isfinite(v)), v
PY'
  runs "$name: plot_profile.py" /usr/bin/python3 "$src/tools/plot_profile.py" "$tmp/$name" \
    > "$tmp/$name.plot" 2>&1
  check "$name: plot" '[ -s "$tmp/$name/profile.png" ]'
  runs "$name: 2 ranks run" "${mpi[@]}" -n 2 "$narrows" run "$scene" "${short[@]}" \
    --out "$tmp/$name-2" > /dev/null 2>&1
  check "$name: 2 ranks give the 1-rank viscosity series" '/usr/bin/python3 - "$tmp/$name/observables.h5" "$tmp/$name-2/observables.h5" <<PY
import sys, h5py, numpy as np
a = h5py.File(sys.argv[1], "r")["observables/viscosity/value"][()]
b = h5py.File(sys.argv[2], "r")["observables/viscosity/value"][()]
assert np.allclose(a, b, rtol=1e-12, atol=0), (a, b)
PY'
done
finish "channel scenes"
