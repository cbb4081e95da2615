#!/usr/bin/python3
"""Test of tools/vss_fit.py (Kanehl (thesis) eq 6.4, Table 6.2, fig 6.8). No narrows binary.

1. Pulls: 60 synthetic data sets drawn from eq 6.4 with Table 6.2's mu = 1 parameters at 46
   values of phi (0.70-0.84 every 0.005, and every 0.001 across the jump at phi_c = 0.762), each
   point with its own error sigma_i (0.002-0.008, drawn once) and Gaussian noise of that size.
   Each is fitted from a start away from the truth (dv x1.2, dphi x1.3, phi_c x1.025 = 0.781,
   e1 and e2 x0.9, phi_q x1.02). For each parameter the pull (fit - true) / reported error must
   have mean within 0.45 of 0 (3.5 standard errors of a mean of 60 unit pulls: the fit of the
   narrow tanh may be slightly biased; measured |mean| <= 0.31) and standard deviation in [0.7,
   1.35] (3.5 standard errors of the std of 60 unit pulls about 1): the reported errors are the
   fit's real scatter. chi^2 / dof averaged over the sets within 0.15 of 1 (its standard error is
   sqrt(2 / (40 * 60)) = 0.03).
2. One run's v_ss from colloid_positions that wrap around the periodic x (the mean displacement
   over the time after --transient, known exactly here): to 1e-12; the block error finite.
   Without colloid_positions, from axial_fields: the bins' velocities weighted by their phi, a
   bin without colloids (NaN) left out: to 1e-12.
3. The command line: `fit TABLE.csv` (as tools/sweep.py --collect writes it: mu_cc, phi, v_ss,
   v_ss_error, 3 repeats per phi) writes the JSON (narrows' own table with Table 6.2's column
   beside, e3 from continuity) and the PNG; a table without v_ss: exit 2, one line.
Prints FAIL lines and "N passed, M failed"; exit 1 on any failure.
"""

import csv
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import narrows_h5  # noqa: E402
from selftest import check, summary  # noqa: E402
from continuum_run import find_narrows  # noqa: E402
import vss_fit  # noqa: E402




TRUE = np.array(vss_fit.TABLE_6_2["1"])
PHI = np.unique(np.round(np.concatenate([np.arange(0.70, 0.8401, 0.005),
                                          np.arange(0.752, 0.7721, 0.001)]), 4))


def pulls():
    rng = np.random.default_rng(2026)
    sigma = rng.uniform(0.002, 0.008, len(PHI))
    start = TRUE * np.array([1.2, 1.3, 1.025, 0.9, 0.9, 1.02])
    out, chi, bound = [], [], 0
    for _ in range(60):
        v = vss_fit.eq_6_4(PHI, *TRUE) + rng.normal(0.0, sigma)
        p, err, cov, chi2, dof, at_bound = vss_fit.fit(PHI, v, sigma, start)
        out.append((p - TRUE) / err)
        chi.append(chi2 / dof)
        bound += bool(at_bound)
    out = np.array(out)
    for i, name in enumerate(vss_fit.NAMES):
        m, s = out[:, i].mean(), out[:, i].std(ddof=1)
        print(f"pull of {name}: mean {m:+.3f}, std {s:.3f}")
        check(f"pull of {name}: mean within 0.45 of 0", abs(m) < 0.45, m)
        check(f"pull of {name}: std in [0.7, 1.35]", 0.7 <= s <= 1.35, s)
    check("chi2/dof averages 1 within 0.15", abs(np.mean(chi) - 1) < 0.15, np.mean(chi))
    check("data that fix every parameter: no fit ends at a bound", bound == 0, bound)
    # data without a jump (a straight decline): the width is not fixed by them and the fit
    # says so instead of returning a negative width
    line = 2.0 - 2.5 * PHI
    p, err, cov, chi2, dof, at_bound = vss_fit.fit(PHI, line + rng.normal(0, sigma), sigma, start)
    check("no jump in the data: every parameter within its physical range, the unfixed ones "
          "named", p[1] > 0 and p[0] >= 0 and PHI.min() <= p[2] <= PHI.max() and
          (p[0] < 0.01 or len(at_bound) > 0), (p, at_bound))
    e3 = (TRUE[3] + TRUE[4] * TRUE[2]) / (TRUE[2] - TRUE[5]) ** 2
    check("eq 6.4 is continuous at phi_c (e3 of Table 6.2)",
          abs(vss_fit.eq_6_4(TRUE[2] - 1e-12, *TRUE) - vss_fit.eq_6_4(TRUE[2], *TRUE)) < 1e-9 and
          abs(vss_fit.eq_6_4(0.9, *TRUE) - (TRUE[0] * (1 + np.tanh((TRUE[2] - 0.9) / TRUE[1])) +
                                           e3 * (0.9 - TRUE[5]) ** 2)) < 1e-12)


SCENE = """[run]
dimensions = 2
seed = 5
steps = 100

[domain]
size = [{L}, 50.0]

[colloids]
packing_fraction = 0.75

[colloids.spring]
mu_cc = 1.0
mu_cw = 1.0
"""


def one_run(tmp):
    L, T, N = 200.0, 81, 30
    rng = np.random.default_rng(3)
    t = np.linspace(0.0, 40.0, T)
    speed = rng.uniform(0.1, 0.5, N)  # each colloid its own speed: several wraps of x
    x0 = rng.uniform(0, L, N)
    wobble = 0.3 * np.sin(t[:, None] * 1.7 + np.arange(N))
    x = (x0 + speed * t[:, None] * 40 + wobble) % L
    pos = np.stack([x, rng.uniform(0, 50, (T, N))], axis=2)
    path = os.path.join(tmp, "run")
    os.makedirs(path)
    series = {"colloid_positions": {"step": np.arange(T, dtype=np.int64), "time": t, "value": pos,
                                    "bins": np.arange(N, dtype=np.int64)}}
    narrows_h5.write_observables(os.path.join(path, "observables.h5"), series=series,
                                 scene=SCENE.format(L=L))
    keep = t >= 10.0
    tk, wk = t[keep], wobble[keep]
    want = np.mean((speed * 40 * (tk[-1] - tk[0]) + wk[-1] - wk[0]) / (tk[-1] - tk[0]))
    done = subprocess.run([sys.executable, os.path.join(HERE, "vss_fit.py"), "run", path,
                           "--transient", "10"], capture_output=True, text=True)
    check("run: exit 0", done.returncode == 0, done.stderr)
    if done.returncode:
        return
    with open(os.path.join(path, "vss.json")) as f:
        r = json.load(f)
    check("run: v_ss of colloids wrapping around x", abs(r["v_ss"] - want) < 1e-12 * abs(want),
          (r["v_ss"], want))
    check("run: phi, mu from the scene", r["phi"] == 0.75 and r["mu_cc"] == 1.0, r)
    check("run: finite block error", np.isfinite(r["v_ss_error"]) and r["v_ss_error"] >= 0, r)


def axial(tmp):
    """v_ss from axial_fields: bins weighted by phi, a bin without colloids (NaN) left out."""
    T, X = 40, 10
    t = np.arange(T) * 1.0
    phi = np.tile(np.linspace(0.5, 0.9, X), (T, 1))
    v = np.tile(np.linspace(0.4, 0.1, X), (T, 1))
    v[8, 4], phi[8, 4] = np.nan, 0.0
    want = np.sum(np.nan_to_num(v[5:]) * phi[5:]) / np.sum(phi[5:])
    path = os.path.join(tmp, "axial")
    os.makedirs(path)
    series = {"axial_fields": {"step": np.arange(T, dtype=np.int64), "time": t, "phi": phi,
                               "velocity": v, "fluid_velocity": v, "bins": np.arange(X) + 0.5}}
    narrows_h5.write_observables(os.path.join(path, "observables.h5"), series=series,
                                 scene=SCENE.format(L=10.0))
    r = vss_fit.run_vss(path, transient=5.0)
    check("run: v_ss from axial_fields, weighted by phi", abs(r["v_ss"] - want) < 1e-12 and
          r["source"] == "axial_fields", (r["v_ss"], want))


def command_line(tmp):
    rng = np.random.default_rng(11)
    table = os.path.join(tmp, "table.csv")
    with open(table, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["point", "colloids.packing_fraction", "mu_cc", "phi", "v_ss", "v_ss_error"])
        i = 0
        for p in PHI:
            for _ in range(3):
                v = vss_fit.eq_6_4(p, *TRUE) + rng.normal(0, 0.005)
                w.writerow([i, p, 1.0, p, v, 0.005])
                i += 1
    prefix = os.path.join(tmp, "fit")
    done = subprocess.run([sys.executable, os.path.join(HERE, "vss_fit.py"), "fit", table,
                           "--out", prefix], capture_output=True, text=True)
    check("fit: exit 0", done.returncode == 0, done.stderr)
    if done.returncode:
        return
    with open(prefix + ".json") as f:
        res = json.load(f)["1"]
    check("fit: Table 6.2's column beside", res["table_6_2_column"] == "1" and
          res["table_6_2"]["phi_c"] == 0.762, res.get("table_6_2"))
    check("fit: 46 points of 3 repeats", res["points"] == len(PHI) and res["runs"] == 3 * len(PHI),
          (res["points"], res["runs"]))
    check("fit: phi_c within 4 errors", abs(res["phi_c"] - 0.762) < 4 * res["phi_c_error"],
          (res["phi_c"], res["phi_c_error"]))
    e3 = (res["e1"] + res["e2"] * res["phi_c"]) / (res["phi_c"] - res["phi_q"]) ** 2
    check("fit: e3 from continuity", abs(res["e3"] - e3) < 1e-12 * abs(e3) and res["e3_error"] > 0)
    check("fit: PNG", os.path.getsize(prefix + ".png") > 0)
    # the one-mu file is what the continuum jamming model reads (continuum.vss_fit = FILE)
    flat = prefix + "-mu1.json"
    with open(flat) as f:
        one = json.load(f)
    check("fit: the one-mu file holds the six eq 6.4 parameters flat",
          all(isinstance(one.get(k), float) for k in vss_fit.NAMES), sorted(one))
    scene = os.path.join(HERE, "..", "run", "continuum_jamming_pulses.toml")
    with open(scene) as f:
        text = f.read()
    check("fit: the jamming scene names its mu preset", 'mu = "1"\n' in text)
    copy = os.path.join(tmp, "jamming_fit.toml")
    with open(copy, "w") as f:
        f.write(text.replace('mu = "1"\n', f'vss_fit = "{flat}"\n'))
    done = subprocess.run([find_narrows(None), "check", copy], capture_output=True, text=True)
    check("fit: narrows takes the one-mu file as continuum.vss_fit and prints its phi_c",
          done.returncode == 0 and f"{one['phi_c']:.6g}"[:5] in done.stdout,
          (done.returncode, done.stdout[-400:], done.stderr))
    bad = os.path.join(tmp, "bad.csv")
    with open(bad, "w") as f:
        f.write("mu_cc,phi,speed\n1,0.7,0.3\n")
    done = subprocess.run([sys.executable, os.path.join(HERE, "vss_fit.py"), "fit", bad,
                           "--out", prefix], capture_output=True, text=True)
    check("fit: a table without v_ss: exit 2, one line naming the column",
          done.returncode == 2 and "'v_ss'" in done.stderr and
          len(done.stderr.strip().splitlines()) == 1, (done.returncode, done.stderr))


def main():
    for part in (pulls, one_run, axial, command_line):
        with tempfile.TemporaryDirectory() as tmp:
            try:
                part(tmp) if part is not pulls else part()
            except Exception as e:  # noqa: BLE001
                check(f"{part.__name__} ran to the end", False, f"{type(e).__name__}: {e}")
    return summary()


if __name__ == "__main__":
    sys.exit(main())
