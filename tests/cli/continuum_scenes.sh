#!/usr/bin/env bash
# The continuum engine from the command line: check prints the scheme and time step, the run
# writes density and shock_position, the shock of run/continuum_burgers_riemann.toml moves at
# the Rankine-Hugoniot speed; a restart from the checkpoint half-way continues bitwise (the
# final cell averages and every later sample equal those of the uninterrupted run), a changed
# checkpoint is refused by its checksum, 2 ranks
# give the numbers of 1; tools/shock_report.py puts a kmc shock against it; bad input exits 2
# with one line and writes nothing.
set -u
source "$(dirname "$0")/common.bash"

scene=$src/run/continuum_burgers_riemann.toml

runs "check" "$narrows" check "$scene" > "$tmp/check.out" 2>&1
check "check: prints the time step and steps" \
  'grep -q "^time step: dt = 0.2 (CFL 0.4" "$tmp/check.out" && grep -q "^time: 400 in 2000 steps" "$tmp/check.out"'

runs "uninterrupted run" "$narrows" run "$scene" --set output.checkpoint_every=1000 --out "$tmp/full" \
  > /dev/null 2>&1
check "observables: density [41][800] and shock_position [41]" '/usr/bin/python3 - "$tmp/full/observables.h5" <<PY
import sys, h5py
f = h5py.File(sys.argv[1], "r")["observables"]
assert f["density/value"].shape == (41, 800), f["density/value"].shape
assert f["density/bins"].shape == (800,)
assert f["shock_position/value"].shape == (41,)
PY'
check "log: shock speed 0.5 (Rankine-Hugoniot 0.5)" \
  'grep -q "^shock: at x = 300.* speed 0.5 (Rankine-Hugoniot 0.5)" "$tmp/full/log.txt"'
check "log: Loop time line" 'grep -q "^Loop time of .* for 2000 steps with 800 cells" "$tmp/full/log.txt"'
check "checkpoints at 1000 and 2000 steps" \
  '[ -f "$tmp/full/checkpoint-0000001000.h5" ] && [ -f "$tmp/full/checkpoint-0000002000.h5" ]'

# Restart at T/2 (step 1000 of 2000) and continue.
mkdir -p "$tmp/part"
cp "$tmp/full/checkpoint-0000001000.h5" "$tmp/part/"
runs "restart at T/2" "$narrows" run "$scene" --restart "$tmp/part" --out "$tmp/part" > /dev/null 2>&1
check "restart: bitwise the uninterrupted run (final state, later samples)" '/usr/bin/python3 - "$tmp" <<PY
import sys, h5py, numpy as np
t = sys.argv[1]
a = h5py.File(t + "/full/checkpoint-0000002000.h5", "r")["continuum/density"][()]
b = h5py.File(t + "/part/checkpoint-0000002000.h5", "r")["continuum/density"][()]
assert np.array_equal(a, b)
fa = h5py.File(t + "/full/observables.h5", "r")["observables"]
fb = h5py.File(t + "/part/observables-0000001000.h5", "r")["observables"]
for k in ("density", "shock_position"):
    n = fb[k]["value"].shape[0]
    assert n == 20, n
    assert np.array_equal(fa[k]["value"][-n:], fb[k]["value"][()]), k
    assert np.array_equal(fa[k]["time"][-n:], fb[k]["time"][()]), k
PY'
# A checkpoint whose cell averages were changed after writing fails its checksum (io/row_hash).
cp "$tmp/full/checkpoint-0000001000.h5" "$tmp/damaged.h5"
/usr/bin/python3 -c 'import sys, h5py; f = h5py.File(sys.argv[1], "r+"); f["continuum/density"][400] += 1e-12' \
  "$tmp/damaged.h5"
refused "restart from a changed checkpoint" "damaged.h5.*/continuum/density does not match its checksum" \
  "$narrows" run "$scene" --restart "$tmp/damaged.h5" --out "$tmp/damaged"
check "changed checkpoint: nothing written" '[ ! -e "$tmp/damaged" ]'
refused "restart with another flux" "continuum.flux" \
  "$narrows" run "$scene" --set continuum.flux=tasep --restart "$tmp/part/checkpoint-0000001000.h5" --out "$tmp/other"

# 2 ranks: the same numbers.
runs "2 ranks" "${mpi[@]}" -n 2 "$narrows" run "$scene" --out "$tmp/two" > /dev/null 2>&1
check "2 ranks: bitwise the 1-rank run" '/usr/bin/python3 - "$tmp" <<PY
import sys, h5py, numpy as np
t = sys.argv[1]
a = h5py.File(t + "/full/observables.h5", "r")["observables/density/value"][()]
b = h5py.File(t + "/two/observables.h5", "r")["observables/density/value"][()]
assert np.array_equal(a, b)
PY'

# tools/shock_report.py: the family 2 shock of run/kmc_family2_shock.toml against the continuum
# engine: one PNG and the table; the continuum shock moves at Rankine-Hugoniot (0.5 %), the kmc
# shock's mean within 3 standard errors of it.
runs "kmc family 2 shock" "$narrows" run "$src/run/kmc_family2_shock.toml" --out "$tmp/f2" > /dev/null 2>&1
runs "shock_report.py" /usr/bin/python3 "$src/tools/shock_report.py" "$tmp/f2/observables.h5" \
  --narrows "$narrows" > "$tmp/report.txt" 2>&1
check "shock_report.py: PNG and table" '[ -s "$tmp/f2/shock_report.png" ] && [ -s "$tmp/f2/shock_report.txt" ]'
check "shock_report.py: continuum at Rankine-Hugoniot, kmc within 3 errors" '/usr/bin/python3 - "$tmp/report.txt" <<PY
import re, sys
text = open(sys.argv[1]).read()
print(text)
kmc, err = map(float, re.search(r"\| kmc [^|]*\| ([-0-9.e]+) \+- ([0-9.e]+) \|", text).groups())
cont = float(re.search(r"\| continuum engine [^|]*\| ([-0-9.e]+) \|", text).group(1))
rh = float(re.search(r"\| Rankine-Hugoniot [^|]*\| ([-0-9.e]+) \|", text).group(1))
assert abs(cont - rh) < 0.005 * abs(rh), (cont, rh)
assert abs(kmc - rh) < 3 * err, (kmc, err, rh)
PY'

runs "bench --continuum" "$narrows" bench --continuum 1000 > "$tmp/bench.txt" 2>&1
check "bench: cell-steps/s of burgers and family1" \
  '[ "$(grep -cE "^continuum (burgers|family1) 1000 cells: .* cell-steps/s on one core" "$tmp/bench.txt")" -eq 2 ]'

# Bad input: one line naming the file, the key, what was found and what is allowed; no output.
refused "unknown flux" 'continuum.flux = "lwr" is not known; allowed: "burgers".*continuum_burgers_riemann.toml' \
  "$narrows" run "$scene" --set continuum.flux=lwr --out "$tmp/bad1"
check "unknown flux: nothing written" '[ ! -e "$tmp/bad1" ]'
refused "tasep density out of range" 'continuum_burgers_riemann.toml: continuum.initial.left = 1.5 is out of range; allowed: a particle density from 0 to 1' \
  "$narrows" check "$scene" --set continuum.flux=tasep --set continuum.initial.left=1.5
refused "family2 without parameters" "missing required key 'continuum.parameters'" \
  "$narrows" check "$scene" --set continuum.flux=family2 --set continuum.initial.left=0.5
refused "cfl too large" "continuum.cfl = 0.9 is out of range; allowed: a number > 0 and <= 0.5" \
  "$narrows" check "$scene" --set continuum.cfl=0.9
refused "reservoirs with periodic" "continuum.reservoirs needs continuum.boundary = \"open\"" \
  "$narrows" check "$scene" --set continuum.boundary=periodic --set 'continuum.reservoirs=[1.0,0.0]'
refused "initial key of another kind" "unknown key 'continuum.initial.values' for kind = \"riemann\"" \
  "$narrows" check "$scene" --set 'continuum.initial={kind="riemann",left=1.0,right=0.0,values=[1.0,2.0]}'

finish continuum_scenes
