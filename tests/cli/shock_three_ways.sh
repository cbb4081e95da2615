#!/usr/bin/env bash
# tools/shock_three_ways.sh (issue 22 acceptance 5), a SMOKE TEST only: the one command at its
# --tiny size (kmc L = 100, a 6-colloid chain for 1000 steps) writes the PNG and the table, and
# every speed and diffusion constant in the table is a finite number. It does not check the
# physics (the tiny runs are far too short for that); the shock's speed against the continuum
# is checked by tests/cli/continuum_scenes.sh and validation.KmcAgainstContinuum.*.
set -u
source "$(dirname "$0")/common.bash"

runs --err "$tmp/err.txt" "one command, tiny" bash "$src/tools/shock_three_ways.sh" --tiny \
  --out "$tmp/report" --narrows "$narrows" > "$tmp/out.txt"
check "PNG written" '[ -s "$tmp/report/shock_three_ways.png" ]'
check "table written" '[ -s "$tmp/report/shock_three_ways.txt" ]'
check "the table: three ways, finite speeds and diffusion constants" '/usr/bin/python3 - "$tmp/report/shock_three_ways.txt" <<PY
import math, re, sys
rows = [l for l in open(sys.argv[1]) if l.startswith("| ") and not l.startswith("| source")]
cells = [[c.strip() for c in l.strip().strip("|").split("|")] for l in rows]
names = [c[0] for c in cells]
for want in ("kmc", "continuum engine", "colloid chain, mpcd", "colloid chain, continuum engine"):
    assert any(n.startswith(want) for n in names), (want, names)
numbers = 0
for c in cells:
    for v in c[1:]:
        for x in v.split():
            if x == "+-":
                continue
            assert math.isfinite(float(x)), (c, x)
            numbers += 1
assert numbers >= 14, numbers
PY'
refused "bad option" "unknown option '--bogus'" bash "$src/tools/shock_three_ways.sh" --bogus

finish shock_three_ways
