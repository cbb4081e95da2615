#!/usr/bin/python3
"""Test of tools/segregation_theory.py (Kanehl (thesis) fig 5.3, eq 5.29, the D_0 conventions of
docs/segregation.md). Needs the narrows binary ($NARROWS or build/narrows).

1. The conventions: (ii) is (i) / d; Stokes-Einstein at the thesis' 2D nu = 3.22, rho = 50, a =
   2 is 1 / (6 pi 161 2) = 1.64757e-4 (by hand); the three centre speeds give Pe_S = a_S^3 v0 /
   (w^2 D_S) = 1 with Table 5.1's D_S ("table") and with the convention's own ("own"), and g w^2 /
   (2 nu) ("drive"); and with Stokes-Einstein the drive's Pe_S = 3 pi rho g a_S^4 for any nu.
2. The parser of `narrows check`: on a real check of the 2D mixture at phi_L / phi_S = 1 the
   parsed wall ratio of each kind equals K_c a^2 (2 v0 / w) phi(w) / (K_d D_0) from the parsed
   phi(w) (so the fields are read in the right order), c(0)/c_mean = phi(0) / mean; "none found"
   gives None.
3. Only K_c v0 / (K_d D_0) shapes the profiles: (i) and (ii) at their own Pe_S = 1 give the same
   steady state (to 1e-6, the shooting's Newton tolerance is 1e-13).
4. features(): a rising c_L peak and a wall ratio from a made-up row.
5. fig5_3 writes its PNG; the printed D_C / (K_d D_0) at phi = 0.5002 (grid point 122 of 200 at
   phi_M = 0.82) is 1 / S with S = (1 - phi)^2 / (1 - 0.1 phi) (gamma = 0.9 at c_L = c_S).
Prints FAIL lines and "N passed, M failed"; exit 1 on any failure.
"""

import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import segregation_theory as st  # noqa: E402
from continuum_run import find_narrows  # noqa: E402
from selftest import check, summary  # noqa: E402


def close(a, b, rel):
    return abs(a - b) <= rel * abs(b)


def main():
    narrows = find_narrows(None)
    # 1
    conv = st.conventions(2)
    check("(ii) = (i) / 2", close(conv[1][1], conv[0][1] / 2, 1e-15)
          and close(conv[1][2], conv[0][2] / 2, 1e-15))
    se = [c for c in conv if c[0].endswith("nu = 3.22")][0]
    check("Stokes-Einstein D_S at nu = 3.22", close(se[1], 1.64757e-4, 1e-5), se[1])
    check("Stokes-Einstein D_L = D_S / 2", close(se[2], se[1] / 2, 1e-15))
    for label, ds, dl, nu in conv:
        v = st.speeds(2, ds, nu)
        check(f"{label}: table Pe_S = 1", close(8 * v["table"] / (1600 * 0.00137), 1.0, 1e-14))
        check(f"{label}: own Pe_S = 1", close(8 * v["own"] / (1600 * ds), 1.0, 1e-14))
        check(f"{label}: drive", close(v["drive"], 1e-4 * 1600 / (2 * nu), 1e-14))
    pe = 8 * st.speeds(2, se[1], se[3])["drive"] / (1600 * se[1])
    check("drive Pe_S = 3 pi rho g a^4 with Stokes-Einstein", close(pe, 3 * math.pi * 50 * 1e-4
                                                                     * 16, 1e-12), pe)
    with tempfile.TemporaryDirectory() as work:
        # 2
        ds, dl = 0.00137, 0.000973
        v0 = st.speeds(2, ds, 3.98)["table"]
        got = st.steady(narrows, work, 2, v0, ds, dl, 1.0, 7.46)
        check("check parsed: two kinds", got is not None and sorted(got) == [0, 1], got)
        if got is not None and sorted(got) == [0, 1]:
            for k, (a, d) in enumerate(((2.0, ds), (4.0, dl))):
                phi0, phiw, peak, wall = got[k]
                want = a * a * (2 * v0 / 40.0) * phiw / (7.46 * d)
                check(f"kind {k}: wall ratio from phi(w)", close(wall, want, 2e-3), (wall, want))
                check(f"kind {k}: c(0)/c_mean = phi(0) / 0.25", close(peak, phi0 / 0.25, 1e-4))
            check("large disks peak at the centre", got[1][2] > 1.0 > got[0][2], got)
        check("none found -> None", st.parse_check("steady state: none found (x)") is None)
        # 3
        a = st.steady(narrows, work, 2, st.speeds(2, conv[0][1], 1)["own"], conv[0][1],
                      conv[0][2], 0.5, 7.46)
        b = st.steady(narrows, work, 2, st.speeds(2, conv[1][1], 1)["own"], conv[1][1],
                      conv[1][2], 0.5, 7.46)
        check("(i) and (ii) at their own Pe_S = 1: one steady state",
              a is not None and b is not None and
              all(close(b[k][j], a[k][j], 1e-6) for k in (0, 1) for j in range(4)), (a, b))
        # 4
        row = {"steady": [{0: (0, 0, 0.5, 3.1), 1: (0, 0, p, 9)} for p in
                          (2.0, 2.1, 2.2, 2.3, 2.4, 2.5)]}
        wall, rises, on = st.features(row)
        check("features: wall ratio and rising peaks", wall == 3.1 and rises and on)
        row["steady"][4][1] = (0, 0, 2.0, 9)
        check("features: a fall at 0.2 is not 'on to 0.08'", not st.features(row)[2])
        # 5
        out = os.path.join(work, "fig")
        r = subprocess.run([sys.executable, os.path.join(os.path.dirname(
            os.path.abspath(__file__)), "segregation_theory.py"), "fig5_3", "--out", out,
            "--narrows", narrows], capture_output=True, text=True)
        check("fig5_3 exits 0", r.returncode == 0, r.stderr)
        check("fig5_3 PNG", os.path.getsize(os.path.join(out, "fig5_3.png")) > 1000
              if os.path.exists(os.path.join(out, "fig5_3.png")) else False)
        line = [x for x in r.stdout.splitlines() if x.startswith("0.5002")]
        phi = 0.82 * 122 / 200
        want = (1 - 0.1 * phi) / (1 - phi) ** 2
        check("fig5_3: 1 / S at phi = 0.5002", len(line) == 1 and
              close(float(line[0].split()[1]), want, 1e-3), (line, want))
    return summary()


if __name__ == "__main__":
    sys.exit(main())
