#!/usr/bin/env bash
# The limit-cycle area of the travelling-wave equations (Kanehl (thesis) eq 6.13-6.14, fig 6.14
# right, 6.18 a) as tools/jamming_waves.py finds it, at the wave speed c = -2.8 of fig 6.18 b:
# the area borders the Hopf point of eq 6.21 (solved here by bisection of (v0 - c)^2 = D xi0,
# independently of the tool) and ends at a homoclinic line on one side of it; the fixed point
# of fig 6.18 b (q = 2.228, where the thesis shows a limit cycle) lies inside, and a fixed
# point 3e-5 beyond the homoclinic line has no cycle (the trajectory leaves), one 3e-5 inside
# has one. About 20 s (vectorised RK4 over z = 300).
set -u
source "$(dirname "$0")/common.bash"

check "c = -2.8: Hopf point, homoclinic line, and the fig 6.18 b fixed point inside the area" \
  '/usr/bin/python3 - "$src/tools" <<PY
import sys
sys.path.insert(0, sys.argv[1])
import numpy as np
import jamming_plot, jamming_waves
m = jamming_plot.Model("1")
c = -2.8
# eq 6.21 written out: the trace (v0 - c) / D - xi0 / (v0 - c) vanishes
dv, dphi, phic, e1, e2, phiq = 0.0413, 0.0025, 0.762, 2.56, -3.24, 0.845
e3 = (e1 + e2 * phic) / (phic - phiq) ** 2
vss = lambda p: dv * (1 + np.tanh((phic - p) / dphi)) + (e1 + e2 * p if p < phic else e3 * (p - phiq) ** 2)
f = lambda p: (vss(p) - c) ** 2 - 1.0 / vss(p)
a, b = 0.755, 0.7645
assert f(a) * f(b) < 0
for _ in range(80):
    mid = 0.5 * (a + b)
    a, b = (mid, b) if f(a) * f(mid) > 0 else (a, mid)
hopf = 0.5 * (a + b)
area = jamming_waves.cycle_region(m, [c], 0.735, 0.795, 300.0)
print("area:", area, "Hopf (test):", hopf)
assert len(area) == 1, area
_, ph, hom = area[0]
assert abs(ph - hopf) < 1e-6, (ph, hopf)
assert hom is not None and 1e-5 < abs(hom - ph) < 0.04, (ph, hom)
fps = m.fixed_points(c, 2.228)
assert len(fps) == 3, fps
mid = fps[1]
print(f"fig 6.18 b fixed point phi0 = {mid:.5f}; area between {ph:.5f} and {hom:.5f}")
assert min(ph, hom) < mid < max(ph, hom), (mid, ph, hom)
side = np.sign(hom - ph)
st = jamming_waves.has_cycle(m, np.array([c, c]), np.array([hom - side * 3e-5, hom + side * 3e-5]), 300.0)
assert list(st) == [1, 0], st
PY'

finish jamming_waves
