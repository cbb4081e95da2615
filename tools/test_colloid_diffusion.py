#!/usr/bin/python3
"""ctest tools.colloid_diffusion: tools/colloid_diffusion.py on a short no-slip colloid scene
(Kanehl (thesis) §4.4.2, eq 4.50-4.51): one density-matched disc, a = 2, in a periodic box
l = 10a, MPC-AT+a, n = 10, dt = 0.05, T = 8e4 t0 (1.6e6 steps, about 2 CPU minutes), nu
measured in a Poiseuille slit of the same fluid (a few seconds). Checks, each against the
tool's own error (the engine's spread of 10 block integrals of D(t), and nu's spread of 64
blocks) at 3 sigma, with caps on those errors so that an inflated error cannot pass:
  - the errors: sigma_D / D <= 0.06, sigma_nu / nu <= 0.03 (measured 0.038 and 0.013);
  - Stokes-Einstein for the periodic box with the measured nu (Hasimoto (1959), leading order):
    |D / D_SE - 1| <= 3 sigma (measured 1.090 +- 0.043);
  - the thesis' Table 5.1 is d times its own eq 4.51: in the dimensionless mobility D eta / kT
    at l = 20a, |D / (table / d) - 1| <= 3 sigma (measured 1.036 +- 0.041), while the table
    as printed is excluded, |D / table - 1| > 3 sigma (measured 0.518 +- 0.021);
  - M <U^2> / (d kT) within 0.1 of 1 (measured 1.006).
Broken on purpose: the SE formula without the periodic-box term -1.3105 gives D / D_SE =
0.469 +- 0.019 (fails); the colloid's radius 20 % small in the scene 1.314 +- 0.042, table / d
1.166 +- 0.037, M <U^2> / (d kT) 1.607 (three fail); its mass 20 % large M <U^2> / (d kT) =
0.824 (fails; D does not depend on the mass); D's error tripled fails the cap.
Usage: test_colloid_diffusion.py NARROWS [--reuse DIR]  (--reuse: analyse an earlier run)."""

import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from selftest import check, summary  # noqa: E402

ARGS = ["--dim", "2", "--radius", "2", "--box-over-a", "10", "--density", "10", "--dt", "0.05",
        "--time", "80000", "--every", "2", "--tmax", "40", "--measure-nu", "--seed", "1"]


def main():
    if len(sys.argv) not in (2, 4):
        print(__doc__)
        return 2
    reuse = sys.argv[3] if len(sys.argv) == 4 and sys.argv[2] == "--reuse" else None
    with tempfile.TemporaryDirectory() as tmp:
        out = reuse or os.path.join(tmp, "diffusion")
        js = os.path.join(tmp, "d.json")
        cmd = [sys.executable, os.path.join(HERE, "colloid_diffusion.py"), *ARGS,
               "--narrows", sys.argv[1], "--out", out, "--json", js]
        if reuse:
            cmd.append("--analyse-only")
        done = subprocess.run(cmd, capture_output=True, text=True)
        print(done.stdout, end="")
        check("colloid_diffusion.py exits 0", done.returncode == 0, done.stderr[-800:])
        if done.returncode != 0:
            return summary()
        with open(js) as f:
            r = json.load(f)
    D, sD, nu, snu = r["D"], r["D_error"], r["nu"], r["nu_error"]
    check("error of D at most 6 % (an inflated error cannot pass)", 0 < sD <= 0.06 * D, (D, sD))
    check("error of nu at most 3 %", 0 < snu <= 0.03 * nu, (nu, snu))
    x, s = r["ratio_SE"], r["ratio_SE_error"]
    check(f"Stokes-Einstein with the measured nu: D / D_SE = {x:.3f} +- {s:.3f} within 3 sigma "
          "of 1", abs(x - 1) <= 3 * s, (x, s))
    x, s = r["ratio_table_over_d"], r["ratio_table_over_d_error"]
    check(f"the thesis' Table 5.1 / d: D / (table / d) = {x:.3f} +- {s:.3f} within 3 sigma of 1",
          abs(x - 1) <= 3 * s, (x, s))
    x, s = r["ratio_table"], r["ratio_table_error"]
    check(f"the table as printed (d x eq 4.51) excluded: D / table = {x:.3f} +- {s:.3f} more "
          "than 3 sigma from 1", abs(x - 1) > 3 * s, (x, s))
    check(f"equipartition M <U^2> / (d kT) = {r['kinetic']:.3f} within 0.1 of 1",
          abs(r["kinetic"] - 1) <= 0.1, r["kinetic"])
    return summary()


if __name__ == "__main__":
    sys.exit(main())
