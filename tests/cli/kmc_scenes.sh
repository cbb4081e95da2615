#!/usr/bin/env bash
# Every kmc scene in run/ passes `check` without warnings and runs briefly; the observables
# file has the kmc series with their shapes; 2 ranks give the same numbers as 1; a bad kmc key
# exits 2 with one line; a preset whose rates miss its conditions warns with the residual.
set -u
source "$(dirname "$0")/common.bash"

# same A B: the observables of runs A and B exist, have the same series and are bitwise equal.
same() {
  /usr/bin/python3 - "$1/observables.h5" "$2/observables.h5" <<'PY'
import sys, h5py, numpy as np
a, b = (h5py.File(p, "r")["observables"] for p in sys.argv[1:3])
assert sorted(a) == sorted(b) and len(a) > 0, (sorted(a), sorted(b))
for k in a:
    assert np.array_equal(a[k]["value"][()], b[k]["value"][()]), k
PY
}

short=(--set kmc.length=40 --set kmc.time=50 --set kmc.warmup=5 --set kmc.replicas=3)
for scene in "$src"/run/*kmc*.toml "$src"/run/tasep*.toml; do
  [ -e "$scene" ] || continue
  name=$(basename "$scene" .toml)
  runs "$name: check" "$narrows" check "$scene" > "$tmp/$name.check" 2>&1
  check "$name: no warning" '! grep -q "^warning" "$tmp/$name.check"'
  extra=()
  shock=0
  if grep -q 'kind = "shock"' "$scene"; then
    extra=(--set 'kmc.initial={kind="shock",site=20}' --set kmc.samples=5)
    shock=1
  fi
  short_run=("${short[@]}" "${extra[@]}")
  runs "$name: run" "$narrows" run "$scene" "${short_run[@]}" --out "$tmp/$name" > "$tmp/$name.out" 2>&1
  check "$name: Loop time line" 'grep -q "^Loop time of .* events/s)" "$tmp/$name/log.txt"'
  check "$name: observables" '/usr/bin/python3 - "$tmp/$name/observables.h5" <<PY
import sys, h5py
f = h5py.File(sys.argv[1], "r")["observables"]
L = 40
c = f["current/value"].shape
d = f["density_profile/value"].shape
assert c[0] == 1 and c[1] in (L - 1, L), c
assert d == (1, L, 3), d
assert f["current_error/value"].shape == c
assert f["current_mean/value"].shape == (1,)
if $shock:
    assert f["shock_position/value"].shape == (6,), f["shock_position/value"].shape
    assert f["shock_position_variance/value"].shape == (6,)
PY'
  runs "$name: 2 ranks run" "${mpi[@]}" -n 2 "$narrows" run "$scene" "${short_run[@]}" \
    --out "$tmp/$name-2" > /dev/null 2>&1
  check "$name: 2 ranks give the 1-rank observables bitwise" 'same "$tmp/$name" "$tmp/$name-2"'
done

refused "bad rate key" 'kmc.rates."w99"' \
  "$narrows" check "$src/run/tasep_open.toml" --set 'kmc.rates={"10->01"=1.0,"w99"=1.0}'

# Off the shock manifold (h3 raised by 0.1): check still exits 0 but warns with the residual.
runs "off-manifold preset: check" "$narrows" check "$src/run/kmc_family2_shock.toml" \
  --set 'kmc.parameters.h3=1.0' > "$tmp/off.out" 2>&1
check "off-manifold preset: warns about eq 2.109 with residual 0.1" \
  'grep -q "^warning: shock manifold .*(eq 2.109) does not hold: residual 0.1$" "$tmp/off.out"'
runs "off-manifold preset: run" "$narrows" run "$src/run/kmc_family2_shock.toml" "${short[@]}" --set 'kmc.parameters.h3=1.0' \
  --set 'kmc.initial={kind="shock",site=20}' --out "$tmp/off" > /dev/null 2>&1
check "off-manifold preset: the run log has the warning" \
  'grep -q "^warning: .*eq 2.109" "$tmp/off/log.txt"'

# tools/kmc_plot.py: the plots are written, and the coarse-grained charge profile of the
# family 1 shock follows the solution of the hydrodynamic equation (eq 2.60, solved by the
# continuum engine, which kmc_plot.py runs): at the last time
# it is at least 4 times closer to it than to the initial profile it moved away from.
runs "family 1 shock run" "$narrows" run "$src/run/kmc_family1_shock.toml" --out "$tmp/hydro" \
  > /dev/null 2>&1
runs "kmc_plot.py" /usr/bin/python3 "$src/tools/kmc_plot.py" "$tmp/hydro/observables.h5" \
  --narrows "$narrows" > "$tmp/hydro.txt" 2>&1
check "kmc_plot.py writes the PNG" '[ -s "$tmp/hydro/kmc.png" ]'
check "charge profile follows eq 2.60" '/usr/bin/python3 - "$tmp/hydro.txt" <<PY
import re, sys
last = [l for l in open(sys.argv[1]) if l.startswith("t = ")][-1]
dist, still = map(float, re.search(r"hydrodynamic\| / jump = ([0-9.]+) \(\|measured - initial\| / jump = ([0-9.]+)", last).groups())
print(last.strip())
assert dist < still / 4, (dist, still)
PY'
runs "family 1 product run" "$narrows" run "$src/run/kmc_family1_product.toml" \
  --set kmc.replicas=4 --set kmc.time=200.0 --out "$tmp/prod" > /dev/null 2>&1
runs "kmc_plot.py --png" /usr/bin/python3 "$src/tools/kmc_plot.py" "$tmp/prod/observables.h5" \
  --png "$tmp/prod.png" > /dev/null 2>&1
check "kmc_plot.py current against density" '[ -s "$tmp/prod.png" ]'

finish kmc_scenes
