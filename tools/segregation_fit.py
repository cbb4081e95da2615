#!/usr/bin/env python3
"""Fits K_d of the segregation theory (Kanehl (thesis) ch.5, eq 5.23) jointly to the per-kind
kernel density profiles (observable density_kde, eq 5.2) of one or several realisations of a
particle run with [[colloids.kind]].

  /usr/bin/python3 tools/segregation_fit.py RUN_DIR [RUN_DIR ...] --diffusivity D_1 [D_2]
                   [--d0 table|table/d|stokes-einstein|all] [--from-step S] [options]

Realisations. Each RUN_DIR is one realisation of the same scene (different run.seed): their
scenes must agree in every key but run.seed, run.steps and [output] (else one line naming the
first key that differs, exit 2), and their density_kde in kinds and bins. The run's scene gives
the channel (half width w = domain.size[1] / 2, walls at y = 0 and 2w), the kinds (radius,
count: mean fraction N pi a^2 / area in 2D, N 4/3 pi a^3 / volume in 3D) and the dimension d;
the centre speed v0 is the largest mean x velocity of velocity_profile (the mean over its
steady samples, below) averaged over the realisations, unless --centre-speed is given.
Profiles c_k(y) = 2w F_k(y) (normalised as the thesis does, int c dy = 2w).

Input layouts (docs/scenes.md, output.kde_window). Whole run (kde_window = 0): value and error
[kinds][bins], the profile and its block error as the run wrote them. Windows (kde_window > 0):
value [windows][kinds][bins] with step [windows] (the window's end); only the steady windows
enter: with --from-step S those ending after S, by default those from the steady-state onset on.
The onset is found from Delta(t) (Kanehl (thesis) eq 5.31; observable evolution of the same
file, value and each kind's by_kind, or computed from the windows by the same formula when the
run has no evolution) by the criterion of the windowed layout: a least-squares line through
Delta over a tail of the windows is flat when |slope| <= 2 sigma_slope (sigma from the
residuals); the onset is the first window whose tail (to the last window, at least K = max(4,
ceil(windows / 4)) windows) is flat for every curve and which itself lies within 2 sigma of the
tail's line. When not even the last K windows are flat, a warning and those windows
(--from-step chooses). The profile of a realisation is the mean over its
steady windows, its error the block error over them (each window one block: the error is too
small when the profile stays correlated over more than a window). Velocity and viscosity are
averaged over their samples after the steady onset (whole-run layout: their second half).

Combining. The realisations' profiles are averaged with equal weights (one scene: the same
statistics up to run length), the error of the mean from their errors, sqrt(sum sigma_r^2) / R.
Printed beside: the variance of that mean from the spread across the realisations over the one
from their errors, averaged over the fit bins (about 1 when the errors are right; below 1 by
chance, well above 1 when windows are correlated), and as a cross-check the fit's chi^2 with
per-bin errors from the spread (R - 1 dof each: t-distributed residuals, expected chi^2/dof =
(R - 1)/(R - 3) for R > 3). Errors estimated from few windows or realisations have the same
bias: chi^2/dof is about (n - 1)/(n - 3) for n blocks.

D_0 (--d0): only K_d D_0 enters the steady profiles, so K_d is relative to the D_0 taken.
"table": --diffusivity as given (Kanehl (thesis) Table 5.1's D per kind, in the order of
[[colloids.kind]]); "table/d": those divided by d (the thesis' tabulated D are d times its eq
4.51); "stokes-einstein": D_0 = kT / (6 pi eta a) with eta = rho nu, rho = fluid.density (unit
particle mass), kT = fluid.kT and nu from the runs' viscosity observable or --nu (the same
formula in 2D, where it is a convention only: Stokes' paradox); "all": the three. Conventions
with the same ratio of the kinds' D_0 (table and table/d) give the same profiles and chi^2,
their K_d differing by the D_0 ratio; a different ratio (Stokes-Einstein: D_0 ~ 1/a) changes
the shapes, and the chi^2 tells which one the profiles support.

The fit. For each trial K_d the continuum engine computes the steady profiles (narrows run of a
[continuum] model = "segregation" scene with K_c = 1, K_eta = --k-eta; observable
steady_density, by shooting; --jobs runs at a time). Data and model are compared over |y - w|
<= w - exclude (default: twice the largest radius, the wall layers the theory does not have)
at bins every 2 kernel widths (nearly independent), each kind with its own amplitude (fitted,
linear: the data's wall layers hold part of the mass), all kinds jointly with one K_d:
chi^2 = sum ((c - A_k m_k) / sigma)^2, dof = bins x kinds - kinds - 1. The engine solves on a
coarse grid in log K_d over --range, around its minimum and at the minimum +- 1 and 2 sigma
until those are covered (about 25 solves per D_0 ratio); between the solved points every fit
bin's model value is a cubic spline in log K_d, and chi^2 is scanned on 4001 points of log K_d
(then 4001 within 4 sigma of the minimum). K_d is the scan's minimum (its chi^2 then solved
exactly); the 1 sigma interval is where chi^2 reaches the minimum + max(1, chi^2/dof) on each
side (the profile likelihood: asymmetric intervals are kept; an end of --range reached is
reported as open, "<lo" or ">hi").

Output: the line "K_d = X +- Y (1σ [lo, hi]), chi2/dof = A/B, convention C" (the convention of
the smallest chi^2; Y half the interval), a table per convention, and c_L(0)/c_S(0) (two kinds:
the large kind's centre value over the small kind's, the mean of c over |y - w| <=
--centre-width, default the largest radius; mean over the realisations, error from their
scatter, or from the block errors for one realisation) with its significance above 1 in sigma
(Kanehl (thesis) sec 5.3.3: the larger kind enriches the centre more), the theory's ratio at
the fitted K_d and the ratio of uniform profiles in the width each kind's centre can reach,
(w - a_S) / (w - a_L) (> 1 without any segregation). --json FILE writes all numbers; --plot
[FILE] draws data (mean +- error) against the fitted theory (default
RUN_DIR/segregation_fit.png of the first RUN_DIR).
"""

import argparse
import concurrent.futures
import itertools
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

import narrows_h5
from continuum_run import find_narrows
from narrows_h5 import NarrowsDataError

CONVENTIONS = ("table", "table/d", "stokes-einstein")
IGNORED = ("run.seed", "run.steps")  # and every key of [output]


# One rank without mpirun: Open MPI's singleton start spawns a daemon unless told not to
# (isolated); isolated singletons share one session directory, which concurrent solves must not
# (MPI-IO's shared-file files collide there), so each solve gets its own. Other MPIs ignore
# these; a user's own settings are kept.
def singleton_env(work):
    env = dict(os.environ)
    for key, value in (("OMPI_MCA_ess_singleton_isolated", "1"), ("OMPI_MCA_pml", "ob1"),
                       ("OMPI_MCA_orte_tmpdir_base", work)):
        env.setdefault(key, value)
    return env


class InputError(Exception):
    """A bad command line (bad data raise narrows_h5.NarrowsDataError)."""


# ---- reading one realisation ---------------------------------------------------------------


def flat_keys(d, prefix=""):
    """{dotted key: value} of a scene dict; arrays of tables as key[i]."""
    out = {}
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(flat_keys(v, key + "."))
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for i, x in enumerate(v):
                out.update(flat_keys(x, f"{key}[{i}]."))
            out[key + ".length"] = len(v)
        else:
            out[key] = v
    return out


def physics_keys(scene):
    return {k: v for k, v in flat_keys(scene).items()
            if k not in IGNORED and not k.startswith("output.")}


def line_flat(t, y):
    """(|slope| <= 2 sigma_slope of the least-squares line through (t, y), the first point
    within 2 sigma of that line), sigma from the residuals."""
    t = np.asarray(t, float)
    y = np.asarray(y, float)
    tc = t - t.mean()
    sxx = float(np.sum(tc * tc))
    if sxx <= 0:
        return True, True
    slope = float(np.sum(tc * (y - y.mean()))) / sxx
    res = y - y.mean() - slope * tc
    sigma = math.sqrt(float(np.sum(res * res)) / max(len(t) - 2, 1))
    return abs(slope) <= 2.0 * sigma / math.sqrt(sxx), abs(res[0]) <= 2.0 * sigma


def delta_curves(c, counts):
    """Delta(t) of eq 5.31 against the first window: the total (sum_k N_k c_k) and each kind.
    c: [windows][kinds][bins] on equal bins (the bin width cancels)."""
    def delta(f):
        return np.sum((f - f[0]) ** 2, axis=-1) / np.sum(f[0] ** 2)
    total = np.tensordot(c, np.asarray(counts, float), axes=([1], [0]))
    return [delta(total)] + [delta(c[:, k, :]) for k in range(c.shape[1])]


def steady_onset(steps, curves, path):
    """Index of the first steady window: the first whose tail (to the last window, at least K
    windows) is flat for every curve and which itself lies within 2 sigma of the tail's line
    (a short transient at the start of a long tail hardly tilts the line); None when not even
    the last K windows are flat."""
    n = len(steps)
    k = max(4, math.ceil(n / 4))
    if n < k:
        raise NarrowsDataError(path, f"density_kde has {n} windows, too few to find the steady "
                               "state (4 at least)", "--from-step S")
    for s in range(n - k + 1):
        tests = [line_flat(steps[s:], y[s:]) for y in curves]
        if all(flat for flat, _ in tests) and (s == n - k or all(on for _, on in tests)):
            return s
    return None


def read_realisation(run_dir, from_step):
    run = narrows_h5.open_run(run_dir)
    g = run.series("density_kde")
    scene = run.scene()
    kinds = scene.get("colloids", {}).get("kind")
    if not kinds:
        raise NarrowsDataError(run.path, "the scene has no [[colloids.kind]]",
                               "a run with one or two colloid kinds")
    if len(kinds) > 2:
        raise NarrowsDataError(run.path, f"{len(kinds)} colloid kinds", "one or two")
    w = float(scene["domain"]["size"][1]) / 2.0
    value = np.asarray(g["value"], float)
    out = {"path": run.path, "dir": run_dir, "scene": scene, "y": np.asarray(g.bins, float),
           "width": g.number("width"), "seed": scene.get("run", {}).get("seed")}
    # the colloids per kind as the run placed them (with placement = "packing" the scene's
    # counts are only the number ratio)
    out["counts"] = (np.asarray(g["counts"], float).ravel() if "counts" in g
                     else np.array([float(k.get("count", 0)) for k in kinds]))
    if value.ndim not in (2, 3) or value.shape[-2] != len(kinds):
        raise NarrowsDataError(run.path, f"/observables/density_kde/value of shape "
                               f"{list(value.shape)}: {value.shape[-2] if value.ndim >= 2 else 0}"
                               f" kinds for the {len(kinds)} [[colloids.kind]] of the scene",
                               "[kinds][bins] or [windows][kinds][bins], one row per kind")
    if value.shape[-1] != len(out["y"]):
        raise NarrowsDataError(run.path, "density_kde value and bins differ in length")
    since = None  # the step after which samples are steady (None: the second half)
    if value.ndim == 2:
        out["layout"] = "whole run"
        if from_step is not None:
            print(f"segregation_fit: warning: {run.path}: a whole-run density_kde (no windows); "
                  "--from-step does not apply to it", file=sys.stderr)
        out["c"] = 2 * w * value
        out["error"] = 2 * w * np.asarray(g["error"], float)
        out["windows"] = None
    else:
        steps = np.asarray(g.step, float)
        c = 2 * w * value
        if from_step is not None:
            first = int(np.searchsorted(steps, from_step, side="right"))
            how = f"--from-step {from_step:g}"
        else:
            if run.has("evolution"):
                e = run.series("evolution")
                if len(e.step) != len(steps) or np.any(e.step != steps):
                    raise NarrowsDataError(run.path, "evolution and density_kde have different "
                                           "steps", "the windows of one run")
                curves = [np.asarray(e.value, float)]
                if "by_kind" in e:
                    curves += list(np.asarray(e["by_kind"], float).T)
                source = "evolution"
            else:
                counts = [k.get("count", 1) for k in kinds]
                curves = delta_curves(c, counts)
                source = "Delta from the density_kde windows"
            first = steady_onset(steps, curves, run.path)
            if first is None:
                first = len(steps) - max(4, math.ceil(len(steps) / 4))
                print(f"segregation_fit: warning: {run.path}: not steady by the criterion "
                      f"(Delta of eq 5.31 over the last {len(steps) - first} windows has a slope "
                      "beyond 2 sigma); using those windows (--from-step S to choose)",
                      file=sys.stderr)
                how = f"the last {len(steps) - first} windows, NOT steady ({source})"
            else:
                how = f"steady from window {first} ({source})"
        used = c[first:]
        if len(used) < 2:
            raise NarrowsDataError(run.path, f"{len(used)} density_kde windows ({how})",
                                   "at least 2 (--from-step S)")
        out["layout"] = "windows"
        out["c"] = used.mean(axis=0)
        out["error"] = used.std(axis=0, ddof=1) / math.sqrt(len(used))
        since = steps[first - 1] if first > 0 else -math.inf
        out["windows"] = {"total": len(steps), "used": len(used), "first": first,
                          "from_step": float(since), "how": how}
    for k in range(len(kinds)):
        if not np.all(np.isfinite(out["c"][k])) or np.sum(out["c"][k]) <= 0:
            raise NarrowsDataError(run.path, f"density_kde of kind {k} (radius "
                                   f"{kinds[k]['radius']}) is empty or not finite",
                                   "a run whose every kind has colloids and samples")

    def steady_mean(name, key="value"):
        if not run.has(name):
            return None
        s = run.series(name)
        v = np.asarray(s[key], float)
        st = np.atleast_1d(np.asarray(s.step, float))
        if since is None or v.ndim == 0 or len(st) != len(v):
            rows = v[v.shape[0] // 2:] if v.ndim >= 1 and v.shape[0] > 1 else v
        else:
            rows = v[st > since] if np.any(st > since) else v[v.shape[0] // 2:]
        return rows.mean(axis=0) if np.ndim(rows) >= 1 else rows

    vel = steady_mean("velocity_profile")
    out["v0"] = None if vel is None else float(np.max(vel[..., 0] if vel.ndim > 1 else vel))
    nu = steady_mean("viscosity")
    out["nu"] = None if nu is None else float(np.mean(nu))
    return out


def check_same(runs):
    """Every realisation is the first one's scene but for the seed: one error line if not."""
    ref = runs[0]
    keys = physics_keys(ref["scene"])
    for r in runs[1:]:
        other = physics_keys(r["scene"])
        for key in sorted(set(keys) | set(other)):
            if keys.get(key, "(absent)") != other.get(key, "(absent)"):
                raise NarrowsDataError(r["path"], f"scene key {key} = "
                                       f"{other.get(key, '(absent)')!r}, but "
                                       f"{keys.get(key, '(absent)')!r} in {ref['path']}",
                                       "realisations of one scene, differing only in run.seed, "
                                       "run.steps and [output]")
        if r["c"].shape != ref["c"].shape or not np.allclose(r["y"], ref["y"]) \
                or r["width"] != ref["width"]:
            raise NarrowsDataError(r["path"], "density_kde bins or kernel width differ from "
                                   f"those of {ref['path']}", "realisations of one scene")


# ---- the continuum model -------------------------------------------------------------------


def steady(narrows, dims, w, kinds, d0, v0, k_d, k_eta, cells, work):
    """The steady fractions phi [cells][kinds] at the cell centres y [cells] (in [-w, w]) of
    the segregation model at K_d with D_0 = d0, or None when it has no steady state."""
    text = ("[run]\nengine = \"continuum\"\n[continuum]\nmodel = \"segregation\"\n"
            f"dimensions = {dims}\nhalf_width = {w!r}\ncells = {cells}\n"
            f"centre_speed = {v0!r}\nk_c = 1.0\nk_eta = {k_eta!r}\nk_d = {k_d!r}\n"
            "time = 1e-9\nsamples = 1\n")
    for k, d in zip(kinds, d0):
        text += (f"[[continuum.kind]]\nradius = {k['radius']!r}\nfraction = {k['fraction']!r}\n"
                 f"diffusivity = {d!r}\n")
    text += "[output]\nobservables = [\"steady_density\"]\nprogress = false\n"
    os.makedirs(work, exist_ok=True)
    scene = os.path.join(work, "fit.toml")
    with open(scene, "w") as f:
        f.write(text)
    out = os.path.join(work, "out")
    r = subprocess.run([narrows, "run", scene, "--out", out, "--overwrite"],
                       capture_output=True, text=True, env=singleton_env(work))
    if r.returncode != 0:
        raise InputError(f"narrows run of the segregation model at K_d = {k_d:g} failed: "
                         + (r.stderr.strip().splitlines() or ["?"])[-1])
    run = narrows_h5.open_run(out)
    if not run.has("steady_density"):
        return None  # none at this K_d (e.g. close packing reached): chi^2 = infinity
    g = run.series("steady_density")
    return np.asarray(g.bins, float), np.asarray(g.value, float)


class Model:
    """The steady profiles of one set of D_0 at u = log K_d: solved by the continuum engine
    (cached, --jobs at a time), and between the solved points a cubic spline in u of every fit
    bin's value (the profiles are smooth in u), so that chi^2 can be scanned densely."""

    def __init__(self, a, setup, d0, data, err, pool, work):
        self.a, self.setup, self.d0, self.pool, self.work = a, setup, d0, pool, work
        self.data, self.err = data, err
        self.cache = {}
        self.count = itertools.count()
        self._spline = None

    def _solve(self, u):
        s = self.setup
        got = steady(self.a.narrows, s["dims"], s["w"], s["kinds"], self.d0, s["v0"],
                     math.exp(u), self.a.k_eta, self.a.cells,
                     os.path.join(self.work, str(next(self.count))))
        if got is None:
            return None
        ym, phi = got
        c = phi / phi.mean(axis=0)  # normalised as the data: int c dy = 2w
        m = np.stack([np.interp(s["y_fit"], ym, c[:, i]) for i in range(c.shape[1])])
        return {"y": ym, "c": c, "m": m}

    def evaluate(self, us):
        """Solves at each u not solved yet; returns the exact chi^2 at each u."""
        us = [float(u) for u in us]
        todo = [u for u in dict.fromkeys(us) if u not in self.cache]
        for u, got in zip(todo, self.pool.map(self._solve, todo)):
            self.cache[u] = got
        if todo:
            self._spline = None
        return [self.chi2_at(u) for u in us]

    def chi2_at(self, u, err=None):
        got = self.cache[u]
        if got is None:
            return math.inf
        return amplitude_chi2(self.data, self.err if err is None else err, got["m"])[0]

    def solved(self):
        """The solved u with a steady state, sorted."""
        return np.array(sorted(u for u, g in self.cache.items() if g is not None))

    def scan(self, us):
        """chi^2 at each u from the spline through the solved profiles (inf outside them)."""
        from scipy.interpolate import CubicSpline
        known = self.solved()
        if self._spline is None and len(known) >= 2:
            self._spline = CubicSpline(known, np.stack([self.cache[u]["m"] for u in known]),
                                       axis=0)
        out = np.full(len(us), math.inf)
        if len(known) < 2:
            return out
        inside = (us >= known[0]) & (us <= known[-1])
        m = self._spline(us[inside])  # [points][kinds][bins]
        wgt = 1.0 / self.err ** 2
        amp = np.sum(wgt * self.data * m, axis=2) / np.sum(wgt * m * m, axis=2)
        out[inside] = np.sum(wgt * (self.data - amp[:, :, None] * m) ** 2, axis=(1, 2))
        return out


def amplitude_chi2(data, err, m):
    """chi^2 of data against A_k m_k with the best amplitude A_k of each kind, and the A_k."""
    wgt = 1.0 / err ** 2
    amp = np.sum(wgt * data * m, axis=1) / np.sum(wgt * m * m, axis=1)
    return float(np.sum(wgt * (data - amp[:, None] * m) ** 2)), amp


def crossing(us, cs, i, target, direction):
    """The u where chi^2 (scanned: us, cs) first exceeds target going from index i in
    direction (linear between the scan points), or None if it does not within the scan."""
    j = i
    while 0 <= j + direction < len(us):
        k = j + direction
        if cs[k] > target:
            if not math.isfinite(cs[k]):
                return us[j]
            return us[j] + (target - cs[j]) / (cs[k] - cs[j]) * (us[k] - us[j])
        j = k
    return None


def fit(model, lo, hi, dof):
    """Minimum of chi^2 in u = log K_d on [lo, hi] and its 1 sigma interval. Solves on a coarse
    grid (9 points), 5 more around its minimum, then at the minimum +- 1 and 2 sigma (the
    interval estimated so far, at least a quarter of the spacing of the points solved there)
    until the solved points cover 1.5 sigma on each side at <= 1.1 sigma spacing and the
    interval changed by < 10 %; the minimum and the interval from a scan of the spline's chi^2
    on 4001 points in log K_d, then on 4001 within 4 sigma of the minimum (asymmetric
    intervals kept); chi^2 at the minimum solved exactly."""
    grid = list(np.linspace(lo, hi, 9))
    values = model.evaluate(grid)
    i = int(np.argmin(values))
    if not math.isfinite(values[i]):
        raise InputError("no steady state of the segregation model for any K_d in --range "
                         f"{math.exp(lo):g} {math.exp(hi):g}")
    a, b = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    model.evaluate(np.linspace(a, b, 7)[1:-1])
    previous = None
    for _ in range(8):
        known = model.solved()
        span = (known[0], known[-1])
        for _ in range(2):  # over all solved points, then around the minimum found
            us = np.linspace(span[0], span[1], 4001)
            cs = model.scan(us)
            j = int(np.argmin(cs))
            best, cmin = us[j], cs[j]
            rise = max(1.0, cmin / dof) if dof > 0 else 1.0
            u_lo = crossing(us, cs, j, cmin + rise, -1)
            u_hi = crossing(us, cs, j, cmin + rise, 1)
            s_lo = best - (u_lo if u_lo is not None else lo)
            s_hi = (u_hi if u_hi is not None else hi) - best
            span = (max(known[0], best - 4 * s_lo), min(known[-1], best + 4 * s_hi))
        left, right = known[known < best], known[known > best]
        gap = max(best - left[-1] if len(left) else 0.0, right[0] - best if len(right) else 0.0)
        s_lo, s_hi = max(s_lo, gap / 4), max(s_hi, gap / 4)
        a, b = max(lo, best - 1.5 * s_lo), min(hi, best + 1.5 * s_hi)
        near = known[(known >= a - 1.1 * s_lo) & (known <= b + 1.1 * s_hi)]
        covered = (len(near) >= 4 and near[0] <= a + 1e-9 and near[-1] >= b - 1e-9 and
                   np.diff(near).max() <= 1.1 * max(s_lo, s_hi))
        steady = previous is not None and abs(s_lo / previous[0] - 1) < 0.1 and \
            abs(s_hi / previous[1] - 1) < 0.1
        if covered and steady:
            break
        previous = (s_lo, s_hi)
        model.evaluate([u for u in (best - 2 * s_lo, best - s_lo, best, best + s_hi,
                                    best + 2 * s_hi) if lo <= u <= hi])
    exact = model.evaluate([best])[0]  # the profile at the minimum itself
    rise = max(1.0, exact / dof) if dof > 0 else 1.0
    return {"u": best, "chi2": exact, "chi2_scan": cmin, "rise": rise,
            "lo": u_lo if u_lo is not None else lo, "hi": u_hi if u_hi is not None else hi,
            "open_lo": u_lo is None, "open_hi": u_hi is None, "solves": len(model.cache)}


# ---- main ----------------------------------------------------------------------------------


def centre_value(y, c, w, half):
    """Mean of c over |y - w| <= half (the interpolated value at y = w when half is 0)."""
    sel = np.abs(y - w) <= half
    if half <= 0 or np.count_nonzero(sel) == 0:
        return np.interp(w, y, c)
    return float(np.mean(c[sel]))


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run_dirs", nargs="+", metavar="RUN_DIR")
    p.add_argument("--diffusivity", type=float, nargs="+",
                   help="D per kind (Table 5.1's), for --d0 table and table/d")
    p.add_argument("--d0", default="table", choices=CONVENTIONS + ("all",))
    p.add_argument("--nu", type=float, help="kinematic viscosity for stokes-einstein "
                                            "(default: the runs' viscosity observable)")
    p.add_argument("--from-step", type=float, help="windowed runs: the windows ending after S")
    p.add_argument("--centre-speed", type=float)
    p.add_argument("--k-eta", type=float, default=1.51)
    p.add_argument("--range", type=float, nargs=2, default=[0.01, 1000.0],
                   metavar=("LO", "HI"), help="search interval of K_d")
    p.add_argument("--exclude", type=float, help="wall strip left out (default 2 max radius)")
    p.add_argument("--no-mirror", dest="mirror", action="store_false",
                   help="fit both halves as measured (default: each profile averaged with its "
                   "mirror image about the centre, one half fitted)")
    p.add_argument("--errors", choices=("scaled", "blocks"), default="scaled",
                   help="scaled (default): with >= 3 realisations whose spread exceeds their "
                   "block errors, the block errors scaled up by the pooled ratio; blocks: as "
                   "measured")
    p.add_argument("--centre-width", type=float,
                   help="half width of the centre average of c_L(0)/c_S(0) (default the "
                        "largest radius; 0: the value at the centre)")
    p.add_argument("--cells", type=int, default=400)
    p.add_argument("--jobs", type=int, default=4, help="continuum runs at a time")
    p.add_argument("--narrows", help="the narrows binary (default: $NARROWS, build/narrows, "
                                      "the PATH)")
    p.add_argument("--json", metavar="FILE", help="write every number to FILE")
    p.add_argument("--plot", nargs="?", const="", metavar="FILE",
                   help="draw the fit (default RUN_DIR/segregation_fit.png)")
    a = p.parse_args(argv)
    try:
        if a.diffusivity is not None and any(not d > 0 for d in a.diffusivity):
            raise InputError("--diffusivity: allowed: numbers > 0")
        if a.nu is not None and not a.nu > 0:
            raise InputError(f"--nu {a.nu:g}: allowed: a number > 0")
        if not 0 < a.range[0] < a.range[1]:
            raise InputError("--range LO HI: allowed: 0 < LO < HI")
        if a.jobs < 1:
            raise InputError(f"--jobs {a.jobs}: allowed: >= 1")
        conventions = list(CONVENTIONS) if a.d0 == "all" else [a.d0]
        a.narrows = find_narrows(a.narrows)
        runs = [read_realisation(d, a.from_step) for d in a.run_dirs]
        check_same(runs)
        ref = runs[0]
        scene = ref["scene"]
        dims = int(scene.get("run", {}).get("dimensions", 2))
        size = scene["domain"]["size"]
        w = float(size[1]) / 2.0
        volume = float(np.prod(size))
        kinds = []
        for k, n in zip(scene["colloids"]["kind"], ref["counts"]):
            r = float(k["radius"])
            body = math.pi * r * r if dims == 2 else 4.0 / 3.0 * math.pi * r ** 3
            kinds.append({"radius": r, "count": int(n), "fraction": n * body / volume})
        nk = len(kinds)
        if any(c in conventions for c in ("table", "table/d")):
            if a.diffusivity is None:
                raise InputError(f"--d0 {a.d0} needs --diffusivity, one D per kind")
            if len(a.diffusivity) != nk:
                raise InputError(f"--diffusivity: {len(a.diffusivity)} values for {nk} kinds; "
                                 "allowed: one D > 0 per kind, in the order of [[colloids.kind]]")
        if a.centre_speed is not None:
            v0, v0_from = a.centre_speed, "--centre-speed"
        else:
            missing = [r["path"] for r in runs if r["v0"] is None]
            if missing:
                raise NarrowsDataError(missing[0], "no velocity_profile for v0",
                                       "--centre-speed V0")
            v0 = float(np.mean([r["v0"] for r in runs]))
            v0_from = "velocity_profile"
        d0 = {}
        nu = nu_from = None
        if "table" in conventions or "table/d" in conventions:
            d0["table"] = list(a.diffusivity)
            d0["table/d"] = [d / dims for d in a.diffusivity]
        if "stokes-einstein" in conventions:
            if a.nu is not None:
                nu, nu_from = a.nu, "--nu"
            else:
                missing = [r["path"] for r in runs if r["nu"] is None]
                if missing:
                    raise narrows_h5.missing_observable(
                        missing[0], "viscosity", "--nu NU, or runs with the viscosity observable "
                        "(--d0 stokes-einstein needs nu)")
                nu, nu_from = float(np.mean([r["nu"] for r in runs])), "viscosity observable"
            fluid = scene.get("fluid", {})
            rho, kt = float(fluid.get("density", 10)), float(fluid.get("kT", 1.0))
            d0["stokes-einstein"] = [kt / (6 * math.pi * rho * nu * k["radius"]) for k in kinds]
        d0 = {c: d0[c] for c in conventions}
        for c in conventions:
            for k, d in zip(kinds, d0[c]):
                k.setdefault("d0", {})[c] = d

        # the fit region and the combined data
        y = ref["y"]
        exclude = a.exclude if a.exclude is not None else 2.0 * max(k["radius"] for k in kinds)
        stride = max(1, int(round(2.0 * ref["width"] / (y[1] - y[0])))) if len(y) > 1 else 1
        region = np.abs(y - w) <= w - exclude
        if a.mirror:
            # the channel is symmetric about its centre: each profile averaged with its mirror
            # image (bins (j + 1/2) h, so bin j mirrors bin n - 1 - j), one half fitted
            if not np.allclose(y[::-1], 2 * w - y, rtol=0, atol=1e-9 * w):
                raise NarrowsDataError(ref["path"], "density_kde bins not symmetric about the "
                                       "channel centre", "--no-mirror")
            for r in runs:
                r["c"] = 0.5 * (r["c"] + r["c"][:, ::-1])
                r["error"] = 0.5 * np.sqrt(r["error"] ** 2 + r["error"][:, ::-1] ** 2)
            region &= y >= w - 1e-9 * w
        keep = np.nonzero(region)[0][::stride]
        if len(keep) < 3:
            raise InputError(f"--exclude {exclude:g}: fewer than 3 bins left in the channel")
        cs = np.stack([r["c"][:, keep] for r in runs])
        es = np.stack([r["error"][:, keep] for r in runs])
        R = len(runs)
        data = cs.mean(axis=0)  # realisations of one scene: equal weights
        err = np.sqrt(np.sum(es ** 2, axis=0)) / R
        if np.any(~(err > 0)):
            raise NarrowsDataError(ref["path"], "density_kde errors of 0 (or not finite) in "
                                   "the fit region in every realisation", "runs with samples "
                                   "in every block or window (or a larger --exclude)")
        scatter = None
        if R >= 2:
            err_scatter = cs.std(axis=0, ddof=1) / math.sqrt(R)
            # pooled over the fit bins (sums, not a mean of ratios: a bin whose block errors
            # are near 0 in most realisations would dominate a mean)
            ratio2 = float(np.sum(err_scatter ** 2) / np.sum(err ** 2))
            scatter = {"variance_ratio": ratio2, "bins": int(data.size), "scaled": False}
            if a.errors == "scaled" and R >= 3 and ratio2 > 1:
                # the block errors miss correlations longer than a block (a cluster of large
                # colloids that stays off-centre for the whole run): scaled up by the pooled
                # spread of the realisations, sum over (kinds x bins) of R - 1 dof each
                err = err * math.sqrt(ratio2)
                scatter["scaled"] = True
        dof = data.size - nk - 1
        chi2_flat = amplitude_chi2(data, err, np.ones_like(data))[0]
        setup = {"dims": dims, "w": w, "kinds": kinds, "v0": v0, "y_fit": y[keep] - w}

        # one fit per ratio of the kinds' D_0 (conventions sharing it differ in K_d only)
        results = {}
        with tempfile.TemporaryDirectory() as work, \
                concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
            families = []
            for c in conventions:
                ratio = np.array(d0[c]) / d0[c][0]
                for fam in families:
                    if np.allclose(fam["ratio"], ratio, rtol=1e-9, atol=0):
                        fam["members"].append(c)
                        break
                else:
                    families.append({"ratio": ratio, "members": [c]})
            for n_fam, fam in enumerate(families):
                lead = fam["members"][0]
                model = Model(a, setup, d0[lead], data, err, pool,
                              os.path.join(work, f"f{n_fam}"))
                f = fit(model, math.log(a.range[0]), math.log(a.range[1]), dof)
                got = model.cache[f["u"]]
                if got is None:
                    raise InputError("no steady state of the segregation model at the fitted "
                                     f"K_d = {math.exp(f['u']):g}")
                _, amp = amplitude_chi2(data, err, got["m"])
                chi2_s = None
                if R >= 2:
                    chi2_s = amplitude_chi2(data, err_scatter, got["m"])[0]
                # the theory's profiles normalised as the data (int c dy = 2w over [-w, w])
                c_theory = got["c"]
                for c in fam["members"]:
                    scale = d0[lead][0] / d0[c][0]  # K_d D_0 is what the profiles fix
                    results[c] = {
                        "d0": d0[c], "k_d": math.exp(f["u"]) * scale,
                        "lo": math.exp(f["lo"]) * scale, "hi": math.exp(f["hi"]) * scale,
                        "open_lo": f["open_lo"], "open_hi": f["open_hi"],
                        "chi2": f["chi2"], "dof": dof, "rise": f["rise"],
                        "chi2_scatter": chi2_s, "amplitudes": amp.tolist(),
                        "same_profiles_as": lead if c != lead else None,
                        "theory_y": got["y"], "theory_c": c_theory, "theory_fit": got["m"],
                        "solves": f["solves"]}
        best_c = min(conventions, key=lambda c: (results[c]["chi2"], conventions.index(c)))

        # c_L(0) / c_S(0)
        half = a.centre_width if a.centre_width is not None else max(k["radius"] for k in kinds)
        ratio = None
        if nk == 2:
            big = int(np.argmax([k["radius"] for k in kinds]))
            small = 1 - big
            per = []
            for r in runs:
                cl = centre_value(y, r["c"][big], w, half)
                cs_ = centre_value(y, r["c"][small], w, half)
                per.append(cl / cs_)
            per = np.array(per)
            mean = float(per.mean())
            if R >= 2:
                sig = float(per.std(ddof=1) / math.sqrt(R))
                how = f"realisation scatter, {R} realisations"
            else:  # one realisation: the block errors (taken as correlated across the centre)
                r = runs[0]
                cl = centre_value(y, r["c"][big], w, half)
                cs_ = centre_value(y, r["c"][small], w, half)
                el = centre_value(y, r["error"][big], w, half)
                es_ = centre_value(y, r["error"][small], w, half)
                sig = mean * math.sqrt((el / cl) ** 2 + (es_ / cs_) ** 2)
                how = "block errors of one realisation"
            th = results[best_c]
            ty = th["theory_y"]
            theory = (centre_value(ty + w, th["theory_c"][:, big], w, half) /
                      centre_value(ty + w, th["theory_c"][:, small], w, half))
            base = (w - kinds[small]["radius"]) / (w - kinds[big]["radius"])
            ratio = {"value": mean, "error": sig, "per_realisation": per.tolist(),
                     "sigma_above_1": (mean - 1) / sig if sig > 0 else math.inf,
                     "error_from": how, "centre_half_width": half, "large_kind": big,
                     "theory": theory, "theory_convention": best_c, "uniform_accessible": base,
                     "sigma_above_uniform": (mean - base) / sig if sig > 0 else math.inf,
                     "issue_criterion_met": bool(R >= 4 and sig > 0 and (mean - 1) / sig >= 5)}
    except (InputError, NarrowsDataError) as e:
        return narrows_h5.report("segregation_fit", e)

    # ---- report ----
    def interval(res):
        lo = ("<" if res["open_lo"] else "") + f"{res['lo']:.5g}"
        hi = (">" if res["open_hi"] else "") + f"{res['hi']:.5g}"
        return f"[{lo}, {hi}]"

    b = results[best_c]
    print(f"K_d = {b['k_d']:.5g} +- {0.5 * (b['hi'] - b['lo']):.2g} (1σ {interval(b)}), "
          f"chi2/dof = {b['chi2']:.4g}/{b['dof']}, convention {best_c}")
    for c in conventions:
        res = results[c]
        print(f"convention {c}: D_0 = " + ", ".join(f"{d:.5g}" for d in res["d0"]) +
              " (kinds in scene order)" + (f"; the same profiles as {res['same_profiles_as']}"
                                           if res["same_profiles_as"] else ""))
        print(f"  K_d = {res['k_d']:.5g}, 1σ {interval(res)} (chi^2 + {res['rise']:.3g}), "
              f"K_d D_0 = " + ", ".join(f"{res['k_d'] * d:.4g}" for d in res["d0"]))
        print(f"  chi2/dof = {res['chi2']:.4g}/{res['dof']} = "
              f"{res['chi2'] / max(res['dof'], 1):.3g}"
              + ("" if res["chi2_scatter"] is None else
                 f"; with errors from the realisation scatter {res['chi2_scatter']:.4g}/"
                 f"{res['dof']} = {res['chi2_scatter'] / max(res['dof'], 1):.3g}"
                 + (f" (expected {(R - 1) / (R - 3):.3g})" if R > 3 else
                    " (expected value infinite for R <= 3)")))
        print("  amplitudes (data / theory over the fit region): " +
              ", ".join(f"{x:.4g}" for x in res["amplitudes"]))
    if len(results) > 1:
        print("chi^2 per convention: " + ", ".join(f"{c} {results[c]['chi2']:.4g}"
                                                   for c in conventions))
    print(f"uniform profiles (K_d -> infinity): chi^2 = {chi2_flat:.4g} (minus the fit's: "
          f"{chi2_flat - b['chi2']:.4g}, the evidence for segregation)")
    if ratio is not None:
        names = ("L", "S")
        print(f"c_{names[0]}(0)/c_{names[1]}(0) = {ratio['value']:.4g} +- {ratio['error']:.2g} "
              f"({ratio['error_from']}; mean of c over |y - w| <= {half:g}): "
              f"{ratio['sigma_above_1']:.3g} sigma above 1; theory at the fitted K_d "
              f"{ratio['theory']:.4g}; uniform in the reachable width (w - a_S)/(w - a_L) = "
              f"{ratio['uniform_accessible']:.4g} ({ratio['sigma_above_uniform']:.3g} sigma "
              "above it)")
        print("  issue criterion (>= 5 sigma above 1 over >= 4 realisations): " +
              ("met" if ratio["issue_criterion_met"] else "not met"))
    if scatter is not None:
        print(f"realisation scatter: variance of the mean from the {R} realisations' spread / "
              f"from their block errors = {scatter['variance_ratio']:.3g} (pooled over the "
              f"{scatter['bins']} fit bins; 1 when the block errors are right)" +
              ("; the errors of the fit are the block errors scaled by its square root "
               "(--errors scaled)" if scatter["scaled"] else ""))
    for r in runs:
        win = r["windows"]
        print(f"{r['dir']}: seed {r['seed']}, {r['layout']}" +
              ("" if win is None else f", {win['used']} of {win['total']} windows "
               f"({win['how']})"))
    print(f"fit: {len(keep)} bins per kind, |y - w| <= {w - exclude:g} (every {stride} bins), "
          f"{nk} kinds jointly, {R} realisations; K_c = 1, K_eta = {a.k_eta:g}")
    for i, k in enumerate(kinds):
        print(f"kind {i}: radius {k['radius']:g}, fraction {k['fraction']:.4g}, Peclet "
              f"a^3 v0 / (w^2 D_0) = " +
              ", ".join(f"{k['radius'] ** 3 * v0 / (w * w * d):.4g} ({c})"
                        for c, d in k["d0"].items()))
    print(f"channel: {dims}D, w = {w:g}, v0 = {v0:.5g} ({v0_from})" +
          ("" if nu is None else f", nu = {nu:.5g} ({nu_from})"))
    if b["open_lo"] or b["open_hi"]:
        print(f"warning: the 1σ interval reaches the end of --range {a.range[0]:g} "
              f"{a.range[1]:g}")

    if a.json:
        out = {"best": best_c, "realisations": [
            {"dir": r["dir"], "seed": r["seed"], "layout": r["layout"], "windows": r["windows"],
             "v0": r["v0"], "nu": r["nu"]} for r in runs],
            "dimensions": dims, "half_width": w, "v0": v0, "nu": nu, "kinds": kinds,
            "fit_bins": len(keep), "exclude": exclude, "stride": stride,
            "chi2_uniform": chi2_flat, "scatter": scatter, "centre_ratio": ratio,
            "conventions": {c: {k: v for k, v in res.items()
                                if k not in ("theory_y", "theory_c", "theory_fit")}
                            for c, res in results.items()}}
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)
    if a.plot is not None:
        plt = narrows_h5.pyplot()
        fig, ax = plt.subplots(figsize=(6, 4))
        yk = (y[keep] - w) / w
        for i, k in enumerate(kinds):
            line = ax.errorbar(yk, data[i], err[i], fmt="o", ms=3,
                               label=f"a = {k['radius']:g}, {R} run(s)")
            ax.plot(yk, b["amplitudes"][i] * b["theory_fit"][i], "-",
                    color=line[0].get_color(), label=f"a = {k['radius']:g}, theory")
        ax.set_xlabel("y / w")
        ax.set_ylabel("c (int c dy = 2w)")
        ax.set_title(f"K_d = {b['k_d']:.4g} ({best_c}), chi2/dof = {b['chi2']:.3g}/{b['dof']}")
        ax.legend(fontsize=8)
        fig.tight_layout()
        path = a.plot or os.path.join(a.run_dirs[0], "segregation_fit.png")
        fig.savefig(path, dpi=120)
        print(f"plot: {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
