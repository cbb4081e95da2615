#!/usr/bin/python3
"""Test of tools/segregation_fit.py (Kanehl (thesis) ch.5: K_d of eq 5.23 from density_kde).

Usage: /usr/bin/python3 tools/test_segregation_fit.py NARROWS_BINARY

Synthetic realisations of one particle scene (2D, w = 20, a_L = 4 x 8 and a_S = 2 x 32: area
fractions 0.251 each) whose density_kde is the continuum engine's own steady profile (scene
written here, 80 cells, K_d = 5 with Table 5.1's 2D D, v0 = 0.1, K_eta = 1.51) plus Gaussian
noise of a known size, different per realisation (sigma of c = 2w F: 0.02 to 0.05 for the mean
of a run), in both layouts of docs/scenes.md (output.kde_window):
a) windows: 4 realisations of 40 windows, a transient relaxing from the uniform start over ~1.5
   windows, evolution (eq 5.31) written for three and left for the tool to compute for one;
   --d0 all. Checks: the table K_d within 3 of its 1 sigma half widths (log K_d) of 5;
   chi2/dof within 3 sqrt(2/dof) of 1; K_d(table/d) = d K_d(table) (the same D_0 ratio,
   to 1e-9); Stokes-Einstein's chi^2 larger by > 9 (3 sigma; the data carry Table 5.1's D
   ratio 1.41, not its 2; measured + 34)
   and the one line naming the table convention; the steady onset after the first 3 windows
   (where the transient, 1 - exp(-i / 1.5) of the steady profile, stands out of the noise of
   Delta) and before the last quarter;
   c_L(0)/c_S(0) within 3 sigma of the noiseless profile's and > 1 by >= 5 sigma (the issue's
   criterion met).
b) whole run (value and error [kinds][bins]): the same 4 realisations, --d0 table and then --d0
   table/d as separate runs of the tool: K_d within 3 half widths of 5, and the two K_d in the
   ratio d = 2, and their interval ends too, to 1e-3 (the two fits solve at different K_d D_0,
   so they differ by the spline's interpolation and the scan's step, 8 sigma / 4000 ~ 1e-4 in
   log K_d here; measured 2e-5). The 1 sigma half width (log K_d) equals the Fisher sigma of
   the same model (amplitudes and log K_d; derivative from two more continuum solves at K_d
   e^{+-0.02}) with the known errors, times sqrt(max(1, chi2/dof)), to 10 % (the chi^2 is not
   quite a parabola over +-1 sigma and the data are one noisy draw).
c) one windowed realisation with --from-step S: the windows used are those ending after S;
   the error of c_L(0)/c_S(0) from the block errors.
e) whole-run realisations whose block errors understate their noise by 2: the default
   --errors scaled finds the variance ratio ~4 and scales the errors (chi2/dof ~1), --errors
   blocks does not (chi2/dof ~4); the mirrored fit (default) has half the bins of --no-mirror.
d) one-line errors, exit 2: a realisation of another scene (kind 1's count differs: the key is
   named), a realisation whose density_kde lacks a kind, stokes-einstein without viscosity.
Prints FAIL lines and "N passed, M failed"; exit 1 on any failure. ~45 s.
"""

import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import narrows_h5  # noqa: E402
from selftest import check, summary  # noqa: E402

W = 20.0
KINDS = [(4.0, 8), (2.0, 32)]  # (radius, count), scene order: large first
D_TABLE = [0.000973, 0.00137]  # Kanehl (thesis) Table 5.1, 2D, a = 4 and a = 2
K_D = 5.0
V0 = 0.1
NU = 2.5
BINS = 400
KDE_WIDTH = 0.25
CELLS = 80

SCENE = """[run]
engine = "mpcd"
dimensions = 2
seed = {seed}
steps = {steps}

[domain]
size = [40.0, 40.0]

[fluid]
collision = "at+a"
density = 10
dt = 0.05
kT = 1.0

[body_force]
value = [0.0005, 0.0]
acts_on = "fluid"

[walls]
virtual_particles = true

[colloids]
coupling = "no-slip"
contacts = "hard"
placement = "random"
kde_width = {kde_width}
statistics_from = 0

[[colloids.kind]]
radius = {a0}
count = {n0}

[[colloids.kind]]
radius = {a1}
count = {n1}

[output]
every = 100
kde_window = {window}
observables = ["velocity_profile", "density_kde", "evolution"{visc}]
"""


def fractions():
    return [n * math.pi * a * a / (2 * W * 2 * W) for a, n in KINDS]


def truth(narrows, tmp, k_d=K_D):
    """The steady phi [cells][kinds] of the continuum engine at k_d, and its cell centres."""
    text = ('[run]\nengine = "continuum"\n[continuum]\nmodel = "segregation"\ndimensions = 2\n'
            f"half_width = {W}\ncells = {CELLS}\ncentre_speed = {V0}\nk_c = 1.0\nk_eta = 1.51\n"
            f"k_d = {k_d!r}\ntime = 1e-9\nsamples = 1\n")
    for (a, _), f, d in zip(KINDS, fractions(), D_TABLE):
        text += f"[[continuum.kind]]\nradius = {a}\nfraction = {f!r}\ndiffusivity = {d}\n"
    text += '[output]\nobservables = ["steady_density"]\nprogress = false\n'
    path = os.path.join(tmp, "truth.toml")
    with open(path, "w") as f:
        f.write(text)
    subprocess.run([narrows, "run", path, "--out", os.path.join(tmp, "truth"), "--overwrite"],
                   check=True, capture_output=True)
    s = narrows_h5.open_run(os.path.join(tmp, "truth")).series("steady_density")
    return s.bins, s.value


def delta(f):
    return np.sum((f - f[0]) ** 2, axis=-1) / np.sum(f[0] ** 2)


def write_run(path, seed, c_steady, y, sigma, rng, windows=None, evolution=True, kinds=None,
              counts=None, viscosity=True):
    """A synthetic run: density_kde = c_steady / 2w + noise (sigma on c for the run's mean),
    whole-run layout when windows is None, else that many windows with a transient."""
    kinds = KINDS if kinds is None else kinds
    counts = [n for _, n in kinds] if counts is None else counts
    window = 0 if windows is None else 1000
    steps = 40000
    scene = SCENE.format(seed=seed, steps=steps, kde_width=KDE_WIDTH, a0=kinds[0][0],
                         n0=counts[0], a1=kinds[1][0], n1=counts[1], window=window,
                         visc=', "viscosity"' if viscosity else "")
    os.makedirs(path, exist_ok=True)
    t = np.arange(100, steps + 1, 100)
    vel = np.zeros((len(t), BINS, 2))
    vel[:, :, 0] = V0 * (1 - ((y - W) / W) ** 2)
    series = {"velocity_profile": {"step": t, "time": 0.05 * t, "value": vel, "bins": y}}
    if viscosity:
        series["viscosity"] = {"step": t, "time": 0.05 * t,
                               "value": NU + 0.01 * rng.standard_normal(len(t))}
    nk = c_steady.shape[0]
    results = {}
    if windows is None:
        value = (c_steady + sigma * rng.standard_normal(c_steady.shape)) / (2 * W)
        results["density_kde"] = {"step": steps, "time": 0.05 * steps, "value": value,
                                  "error": np.full(c_steady.shape, sigma / (2 * W)), "bins": y,
                                  "width": [KDE_WIDTH], "counts": counts, "samples": [400]}
    else:
        i = np.arange(windows)
        relax = 1 - np.exp(-i / 1.5)
        c = 1 + relax[:, None, None] * (c_steady - 1)[None]
        c = c + sigma * math.sqrt(windows) * rng.standard_normal((windows,) + c_steady.shape)
        value = c / (2 * W)
        ws = (i + 1) * window
        series["density_kde"] = {"step": ws, "time": 0.05 * ws, "value": value, "bins": y,
                                 "width": [KDE_WIDTH], "counts": counts,
                                 "samples": np.full(windows, 10)}
        if evolution:
            total = np.tensordot(value, np.asarray(counts, float), axes=([1], [0]))
            series["evolution"] = {"step": ws, "time": 0.05 * ws, "value": delta(total),
                                   "by_kind": np.stack([delta(value[:, k]) for k in
                                                        range(nk)], axis=1)}
    narrows_h5.write_observables(os.path.join(path, "observables.h5"), series=series,
                                 results=results, scene=scene)


def tool(args, tmp, name):
    out = os.path.join(tmp, name + ".json")
    r = subprocess.run([sys.executable, os.path.join(HERE, "segregation_fit.py")] + args +
                       ["--json", out, "--cells", str(CELLS), "--range", "0.1", "1000"],
                       capture_output=True, text=True)
    got = None
    if r.returncode == 0:
        with open(out) as f:
            got = json.load(f)
    return r, got


def fisher_sigma(narrows, tmp, y, err):  # err: the one error of every fit bin
    """sigma of log K_d from the Fisher matrix of the fit's model (amplitude A_k per kind, one
    log K_d) at the true K_d, over the fit bins (|y - w| <= w - 2 a_L, every 2 kernel widths)
    with the error err in each; the derivative by central differences at +- 0.02."""
    keep = np.nonzero(np.abs(y - W) <= W - 2 * KINDS[0][0])[0][::int(round(2 * KDE_WIDTH /
                                                                            (y[1] - y[0])))]
    m = {}
    for h in (-0.02, 0.02):
        ym, phi = truth(narrows, tmp, K_D * math.exp(h))
        m[h] = np.stack([np.interp(y[keep] - W, ym, phi[:, k]) / phi[:, k].mean()
                         for k in range(len(KINDS))])
    ym, phi = truth(narrows, tmp)
    m0 = np.stack([np.interp(y[keep] - W, ym, phi[:, k]) / phi[:, k].mean()
                   for k in range(len(KINDS))])
    du = (m[0.02] - m[-0.02]) / 0.04
    nk, nb = m0.shape
    jac = np.zeros((nk * nb, 1 + nk))
    jac[:, 0] = du.ravel()
    for k in range(nk):
        jac[k * nb:(k + 1) * nb, 1 + k] = m0[k]
    wgt = np.full(nk * nb, 1.0 / err ** 2)
    cov = np.linalg.inv(jac.T @ (wgt[:, None] * jac))
    return math.sqrt(cov[0, 0]), keep


def half_log(res):
    return 0.5 * (math.log(res["hi"]) - math.log(res["lo"]))


def main(argv):
    narrows = os.path.abspath(argv[1]) if len(argv) > 1 else os.environ.get("NARROWS")
    if not narrows:
        print("usage: test_segregation_fit.py NARROWS_BINARY")
        return 2
    os.environ["NARROWS"] = narrows
    rng = np.random.default_rng(32)
    with tempfile.TemporaryDirectory() as tmp:
        ym, phi = truth(narrows, tmp)
        y = (np.arange(BINS) + 0.5) * 2 * W / BINS
        c_steady = np.stack([np.interp(y - W, ym, phi[:, k]) / phi[:, k].mean()
                             for k in range(len(KINDS))])
        sigmas = [0.02, 0.03, 0.04, 0.05]
        seeds = [11, 12, 13, 14]
        # the noiseless c_L(0)/c_S(0) as the tool defines it: mean over |y - w| <= a_L
        centre = np.abs(y - W) <= KINDS[0][0]
        ratio_true = c_steady[0][centre].mean() / c_steady[1][centre].mean()

        # a) windows, 4 realisations, --d0 all
        dirs = []
        for n, (seed, s) in enumerate(zip(seeds, sigmas)):
            d = os.path.join(tmp, f"win{seed}")
            write_run(d, seed, c_steady, y, s, rng, windows=40, evolution=(n != 2))
            dirs.append(d)
        r, got = tool(dirs + ["--diffusivity"] + [str(d) for d in D_TABLE] + ["--d0", "all"],
                      tmp, "a")
        check("a: exit 0", r.returncode == 0, r.stderr.strip())
        if got:
            t = got["conventions"]["table"]
            print(f"a) windows, 4 realisations: K_d = {t['k_d']:.4f} [{t['lo']:.4f}, "
                  f"{t['hi']:.4f}] (true {K_D}), chi2/dof = {t['chi2']:.1f}/{t['dof']}; "
                  f"table/d {got['conventions']['table/d']['k_d']:.4f}; stokes-einstein "
                  f"{got['conventions']['stokes-einstein']['k_d']:.4f} chi2 "
                  f"{got['conventions']['stokes-einstein']['chi2']:.1f}; c_L/c_S = "
                  f"{got['centre_ratio']['value']:.4f} +- {got['centre_ratio']['error']:.4f} "
                  f"(true {ratio_true:.4f})")
            pull = abs(math.log(t["k_d"] / K_D)) / half_log(t)
            check("a: K_d within 3 sigma of the true one", pull <= 3, f"{pull:.2f} sigma")
            check("a: 1 sigma interval around K_d", t["lo"] < t["k_d"] < t["hi"], str(t))
            tol = 3 * math.sqrt(2.0 / t["dof"])
            check("a: chi2/dof about 1", abs(t["chi2"] / t["dof"] - 1) <= tol,
                  f"{t['chi2'] / t['dof']:.3f}, allowed 1 +- {tol:.3f}")
            td = got["conventions"]["table/d"]
            check("a: K_d(table/d) = d K_d(table)", abs(td["k_d"] / t["k_d"] - 2) < 1e-9 and
                  abs(td["lo"] / t["lo"] - 2) < 1e-9, f"{td['k_d'] / t['k_d']}")
            se = got["conventions"]["stokes-einstein"]
            d_se = [1.0 / (6 * math.pi * 10 * NU * a) for a, _ in KINDS]
            check("a: stokes-einstein D_0 = kT/(6 pi rho nu a)",
                  np.allclose(se["d0"], d_se, rtol=1e-3), f"{se['d0']} vs {d_se}")
            check("a: stokes-einstein fits worse", se["chi2"] > t["chi2"] + 9,
                  f"{se['chi2']:.1f} vs {t['chi2']:.1f}")
            check("a: one line names the table convention", got["best"] == "table" and
                  r.stdout.startswith("K_d = ") and "convention table" in
                  r.stdout.splitlines()[0], r.stdout.splitlines()[0])
            firsts = [x["windows"]["first"] for x in got["realisations"]]
            check("a: steady onset after the first windows of the transient, before the last "
                  "quarter", all(3 <= f <= 30 for f in firsts), str(firsts))
            cr = got["centre_ratio"]
            check("a: c_L(0)/c_S(0) within 3 sigma of the profile's",
                  abs(cr["value"] - ratio_true) <= 3 * cr["error"],
                  f"{cr['value']:.4f} +- {cr['error']:.4f} vs {ratio_true:.4f}")
            check("a: c_L(0)/c_S(0) > 1 by >= 5 sigma", cr["sigma_above_1"] >= 5 and
                  cr["issue_criterion_met"], f"{cr['sigma_above_1']:.2f}")
            sig = np.std(cr["per_realisation"], ddof=1) / 2
            check("a: ratio error is the realisation scatter", abs(cr["error"] - sig) < 1e-12)

        # b) whole run, --d0 table and --d0 table/d separately
        whole = []
        for seed, s in zip(seeds, sigmas):
            d = os.path.join(tmp, f"run{seed}")
            write_run(d, seed, c_steady, y, s, rng)
            whole.append(d)
        fits = {}
        for conv in ("table", "table/d"):
            r, got = tool(whole + ["--diffusivity"] + [str(d) for d in D_TABLE] +
                          ["--d0", conv], tmp, "b" + conv.replace("/", ""))
            check(f"b: {conv}: exit 0", r.returncode == 0, r.stderr.strip())
            if got:
                fits[conv] = got["conventions"][conv]
        if len(fits) == 2:
            t, td = fits["table"], fits["table/d"]
            print(f"b) whole run, 4 realisations: K_d = {t['k_d']:.4f} [{t['lo']:.4f}, "
                  f"{t['hi']:.4f}] (true {K_D}), chi2/dof = {t['chi2']:.1f}/{t['dof']}; "
                  f"table/d separately: {td['k_d']:.4f} [{td['lo']:.4f}, {td['hi']:.4f}]")
            pull = abs(math.log(t["k_d"] / K_D)) / half_log(t)
            check("b: K_d within 3 sigma of the true one", pull <= 3, f"{pull:.2f} sigma")
            tol = 3 * math.sqrt(2.0 / t["dof"])
            check("b: chi2/dof about 1", abs(t["chi2"] / t["dof"] - 1) <= tol,
                  f"{t['chi2'] / t['dof']:.3f}")
            # the whole-run errors are the sigmas given: the mean's is sqrt(sum sigma^2) / 4
            sig_f, _ = fisher_sigma(narrows, tmp, y, math.sqrt(sum(x * x for x in sigmas)) / 4)
            ratio = half_log(t) / (math.sqrt(t["rise"]) * sig_f)
            print(f"   1 sigma half width in log K_d {half_log(t):.5f}, Fisher "
                  f"{sig_f:.5f} x sqrt(max(1, chi2/dof)) = {math.sqrt(t['rise']) * sig_f:.5f}")
            check("b: 1 sigma interval = the Fisher sigma (x sqrt(max(1, chi2/dof)))",
                  abs(ratio - 1) < 0.1, f"ratio {ratio:.4f}")
            check("b: separate fits: K_d ratio = d", abs(td["k_d"] / t["k_d"] / 2 - 1) < 1e-3,
                  f"{td['k_d'] / t['k_d']:.6f}")
            check("b: separate fits: interval ratio = d",
                  abs(td["lo"] / t["lo"] / 2 - 1) < 1e-3 and abs(td["hi"] / t["hi"] / 2 - 1) <
                  1e-3, f"{td['lo'] / t['lo']:.5f} {td['hi'] / t['hi']:.5f}")

        # e) block errors that understate the noise by 2 (the realisations scatter twice as
        # much as their errors say, as runs whose profiles stay correlated longer than a
        # block): --errors scaled (default) scales them by the pooled spread (variance ratio
        # ~4: 2 kinds x 12 bins x 3 dof, so within [2.5, 6.5] at >3 sigma) and chi2/dof is ~1;
        # --errors blocks keeps them and chi2/dof is ~4; --no-mirror fits both halves.
        under = []
        for seed, s in zip(seeds, sigmas):
            d = os.path.join(tmp, f"under{seed}")
            write_run(d, 100 + seed, c_steady, y, s, rng)
            with narrows_h5.h5py.File(os.path.join(d, "observables.h5"), "r+") as f:
                f["observables/density_kde/error"][...] *= 0.5
            under.append(d)
        runs_e = {}
        for name, extra in (("scaled", []), ("blocks", ["--errors", "blocks"]),
                            ("both halves", ["--no-mirror"])):
            r, got = tool(under + ["--diffusivity"] + [str(d) for d in D_TABLE] + extra, tmp,
                          "e" + name.replace(" ", ""))
            check(f"e: {name}: exit 0", r.returncode == 0, r.stderr.strip())
            if got:
                runs_e[name] = got
        if len(runs_e) == 3:
            sc, bl, nm = (runs_e[k] for k in ("scaled", "blocks", "both halves"))
            t, tb = sc["conventions"]["table"], bl["conventions"]["table"]
            vr = sc["scatter"]["variance_ratio"]
            print(f"e) errors understated by 2: variance ratio {vr:.3f}; chi2/dof scaled "
                  f"{t['chi2']:.1f}/{t['dof']}, blocks {tb['chi2']:.1f}/{tb['dof']}; both "
                  f"halves dof {nm['conventions']['table']['dof']}")
            check("e: variance ratio ~4 and the errors scaled",
                  2.5 <= vr <= 6.5 and sc["scatter"]["scaled"], f"{vr:.3f}")
            tol = 3 * math.sqrt(2.0 / t["dof"])
            check("e: scaled: chi2/dof about 1", abs(t["chi2"] / t["dof"] - 1) <= tol,
                  f"{t['chi2'] / t['dof']:.3f}")
            check("e: blocks: chi2/dof about 4 (> 2: 2.4 sd below)", tb["chi2"] / tb["dof"] > 2 and
                  not bl["scatter"]["scaled"], f"{tb['chi2'] / tb['dof']:.3f}")
            check("e: mirrored: half the bins of --no-mirror",
                  abs((nm["conventions"]["table"]["dof"] + 3) / (t["dof"] + 3) - 2) < 0.2,
                  f"{t['dof']} vs {nm['conventions']['table']['dof']}")

        # c) one realisation, --from-step
        r, got = tool([dirs[0], "--diffusivity"] + [str(d) for d in D_TABLE] +
                      ["--from-step", "25500"], tmp, "c")
        check("c: exit 0", r.returncode == 0, r.stderr.strip())
        if got:
            win = got["realisations"][0]["windows"]
            check("c: windows ending after S", win["used"] == 15 and win["first"] == 25,
                  str(win))
            check("c: one realisation: block errors", "block errors" in
                  got["centre_ratio"]["error_from"])
            t = got["conventions"]["table"]
            pull = abs(math.log(t["k_d"] / K_D)) / half_log(t)
            print(f"c) one realisation, windows after step 25500: K_d = {t['k_d']:.4f} "
                  f"[{t['lo']:.4f}, {t['hi']:.4f}], chi2/dof = {t['chi2']:.1f}/{t['dof']}")
            check("c: K_d within 3 sigma of the true one", pull <= 3, f"{pull:.2f} sigma")

        # d) one-line errors
        other = os.path.join(tmp, "other")
        write_run(other, 15, c_steady, y, 0.03, rng, counts=[8, 30])
        r, _ = tool(whole[:2] + [other, "--diffusivity"] + [str(d) for d in D_TABLE], tmp, "d1")
        check("d: another scene: exit 2, one line naming the key",
              r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and
              "colloids.kind[1].count" in r.stderr and "other" in r.stderr, r.stderr)
        lacking = os.path.join(tmp, "lacking")
        write_run(lacking, 16, c_steady[:1], y, 0.03, rng)
        r, _ = tool([lacking, "--diffusivity"] + [str(d) for d in D_TABLE], tmp, "d2")
        check("d: a missing kind: exit 2, one line", r.returncode == 2 and
              len(r.stderr.strip().splitlines()) == 1 and "kinds" in r.stderr and
              "lacking" in r.stderr, r.stderr)
        novisc = os.path.join(tmp, "novisc")
        write_run(novisc, 17, c_steady, y, 0.03, rng, viscosity=False)
        r, _ = tool([novisc, "--d0", "stokes-einstein"], tmp, "d3")
        check("d: stokes-einstein without nu: exit 2, one line", r.returncode == 2 and
              len(r.stderr.strip().splitlines()) == 1 and "--nu" in r.stderr, r.stderr)
    return summary()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
