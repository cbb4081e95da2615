#!/usr/bin/python3
"""The figures of shear-induced segregation in a particle run (Kanehl (thesis) ch.5: figs 5.4,
5.5 and 5.10): the evolution parameter Delta against the distance travelled, the steady colloid
velocity profiles, the viscosity profile eta(y) (eq 5.33 against eq 5.29) and eta(phi) of
uniform suspensions.

Usage (/usr/bin/python3 tools/segregation_plot.py COMMAND ...; each writes one PNG, --png PATH,
default RUN_DIR/segregation_<command>.png, and prints its numbers; --json prints them as one
JSON object instead):

  evolution RUN_DIR [RUN_DIR...] [--radius-over-w A_W ...] [--thesis-radius-over-w A_W ...]
  velocity  RUN_DIR [--from-step S] [--uniform RUN_DIR]
  viscosity RUN_DIR [--with RUN_DIR...] [--mirror] [--continuum STEADY.h5|auto]
            [--nu NU | --fluid-run RUN_DIR]
            [--diffusivity D_1 [D_2]] [--k-d K] [--k-eta K] [--shear poiseuille|viscous]
            [--degree D] [--force local|uniform] [--from-step S] [--uniform-steps FROM TO]
  fig54     RUN_DIR [RUN_DIR...] [--nu NU] [--from-step S] [--to-step S]

What the run must hold (the particle-side layout of issue 32): /observables/density_kde with
output.kde_window > 0 (value [windows][kinds][bins], step, time, bins, counts), evolution (value
[windows], by_kind [windows][kinds], time) and colloid_velocity_profile (value and weight
[windows][kinds][bins]); fig54 and the fluid's viscosity need velocity_profile (the fluid,
[T][bins][d]) or viscosity. The channel (half width w = domain.size[1] / 2, walls at y = 0 and
2w; y below is measured from the centre), the kinds (radius, count; the counts of density_kde
when it has them, as with placement = "packing"), the fluid density rho (particle mass 1) and the
drive g = body_force.value[0] come from the scene in /parameters/scene.

evolution (figs 5.5a, 5.10a). Delta (eq 5.31, value, and per kind, by_kind) against d / w,
where d = v_c (t - t_0) is the distance the colloids at the centre travel since the first
window (all windows are kde_window steps long, so the window ends are as good as their centres)
and v_c is the centre value of colloid_velocity_profile merged over kinds and windows with the
kernel weights (or, without it, the largest mean x velocity of the fluid's velocity_profile;
the output says which). Saturation: Delta(d) = Delta_inf (1 - exp(-d / d_tau)) by scipy's
curve_fit with every point's error the noise of the late windows (the residual scatter about
the least-squares line through the last K = max(4, ceil(windows / 4)) windows; errors scaled
by sqrt(chi^2/dof) when that exceeds 1); d_sat = 3 d_tau (Delta at 95 % of Delta_inf) +- 3
sigma(d_tau), in units of w. Steady (the criterion of the layout): the slope of that line is
within 2 of its standard errors of 0. Delta has a floor from sampling noise (c(y, 0) and c(y, t)
are averages over finite windows): printed as the mean of int (c_i - c_(i+1))^2 / int c_0^2 over
consecutive late windows, which is what noise alone adds to Delta in a steady state; Delta_inf
well above it is segregation.
Scaling to the thesis' channel. Shear-induced migration moves a colloid across the channel with
the current J ~ K_c a^2 gdot phi (eq 5.14; Kanehl (thesis) sec 5.3.1: "J ~ a^2"), so it takes
t ~ w^2 / (a^2 gdot) to cross w; with gdot ~ v_c / w the colloids at the centre travel
d = v_c t ~ w^3 / a^2 meanwhile: d / w ~ (w / a)^2, independent of the speed. Hence d / w at
the thesis' a / w is (d / w measured) x ((a/w)_run / (a/w)_thesis)^2. The thesis' own numbers
obey it in 2D: d_L ~ 100 w, d_S ~ 400 w at a_L / a_S = 2 (ratio 4 = 2^2, as sec 5.3.1 says;
with a_L / w = 0.1 and a_S / w = 0.05 both are d / w ~ (w / a)^2 with a prefactor of ~ 1);
in 3D (sec 5.4.1) d_L ~ 100 w, d_S ~ 500 w, ratio 5, "roughly" (there the Peclet numbers,
hence the share of diffusion, differ more between the kinds, PeL ~ 16, PeS ~ 1). The argument
is one of the shear-driven part of the current alone: diffusion (D_0, the Peclet number) sets
the steady Delta_inf and shifts d_sat when Pe is not large, so compare runs at the thesis' Pe.
(a/w)_run comes from --radius-over-w or the scene (a run whose kinds have one radius);
(a/w)_thesis from --thesis-radius-over-w or, by default, the run's radius over the thesis'
w = 40 b (Table 5.1: a_S = 2 b -> 0.05, a_L = 4 b -> 0.1, the same radius in cells as the
thesis).

velocity (figs 5.5b, 5.10b). Per kind v_x(y) of colloid_velocity_profile, the windows from
--from-step on (default: the last K windows, those of the steady criterion) merged with their
kernel weights, against the parabola v = v0 (1 - y^2 / w^2) + b of the uniform suspension:
least squares to the first window of the run (kinds merged), or to every window of --uniform.
The first window stands for the uniform suspension: start the statistics
(colloids.statistics_from) after the flow has developed (~ w^2 / nu) and keep kde_window short
against the migration (d_sat / v_c).

viscosity (fig 5.5c). eta(y) = -F(y) / gdot(y) (eq 5.33, integrated from the centre: F(y) =
int_0^y f dy', f the force per volume), gdot = dv_x/dy of the steady colloid velocity (kinds and
windows merged with their weights). Smoothing: on each half of the channel separately a
least-squares even polynomial v = sum_j c_j y^(2j), j = 0..degree/2, weighted with the kernel
weight sums (the number of samples behind each bin), differentiated exactly; the degree is
--degree, or by default the highest of 8, 6, 4, 2 whose fit falls monotonically from the centre
to the wall on that half (the shear stress -F(y) has one sign on each half, so gdot must too: a
fit whose gdot changes sign follows noise or layering, and gives eta < 0 or poles). Why: eq 5.33
divides by gdot, which vanishes at the centre; an even polynomial has gdot(0) = 0 and gdot odd,
so eta = F / gdot is a ratio of two odd functions and stays finite at the centre, where a finite
difference of noisy data would make eta swing wildly; a fit per half leaves each half its own
profile (a one-sided plug). The force f: with body_force.acts_on = "fluid" (the default) it acts
on the fluid particles only, which fill the fraction 1 - phi(y) of the slab at y, so f(y) = rho
g (1 - phi(y)); with "fluid+colloids" each colloid adds M g, so f = rho g (1 - phi) + g sum_k
(M_k / V_k) phi_k = rho g for density-matched colloids (--force local, the default: the momentum
balance of the run); --force uniform takes f = rho g, eq 5.33 as printed. phi(y) = sum_k N_k
F_k(y) V_k / (L_x [L_z]) is the local fraction of colloid centres (density_kde, the same
windows), as the continuum model's phi_i. eta_0 = eta_f (1 - phi/phi_M)^-2 at the mean phi (eq
5.29; the thesis' eta_0 of fig 5.5c), eta_f = rho nu: nu from --nu, or from --fluid-run (a run
without colloids: its viscosity observable or velocity_profile fit, see fig54); without either,
eta_0 is the measured viscosity of this suspension while still uniform (eq 4.49 on the fluid
velocity_profile samples of the first window, or --uniform-steps FROM TO; the output says
which). Against eq 5.29 with phi(y) of (a) the continuum engine's steady profiles (--continuum
FILE: an observables file with steady_density; auto: run narrows on a [continuum] model =
"segregation" scene from the run's kinds, as tools/segregation_fit.py builds it, with
centre_speed the v0 of the uniform parabola above and D_0 from --diffusivity, or Stokes-Einstein
kT / (6 pi rho nu a) with the pure fluid's nu (--nu, --fluid-run) as the thesis says it did (sec
5.2.4), in 2D too although the Stokes paradox leaves it no basis there: the model's default K_d
(7.46 2D, 0.61 3D) belongs to that convention (docs/segregation.md, "D_0: which convention");
--k-d, --k-eta, --shear pass on) and (b) phi(y) of the particles. Printed: the largest relative
difference |eta_5.33 / eta_5.29 - 1| over w/4 < |y| < w - 2 a_L (a_L the largest radius; away
from the centre, where both gdot and F vanish, and from the walls), for each eq 5.29 curve
(Kanehl (thesis) fig 5.5c; acceptance 3 of issue 32).

fig54 (fig 5.4). For each run the mean fraction phi (the kinds' volumes over the box) and the
effective viscosity of eq 4.49, nu_eff = g_eff w^2 / (2 v0): v0 from a least-squares parabola
v = a y (2w - y) + b through the fluid's velocity_profile averaged over the samples from
--from-step to --to-step (default: the second half of the run; the flow needs ~ w^2 / nu to
develop and the suspension should not have migrated yet), nu_eff = g_eff / (2 a), g_eff = g
(1 - phi) with acts_on = "fluid" (the force per volume over rho), g with "fluid+colloids"
(density-matched), and beside it the same with g as applied (eq 4.49 as printed, which the
thesis' fig 5.4 seems to use); the run's viscosity observable (its mean over those samples,
corrected the same way: it uses g) when it has no velocity_profile. Over the pure fluid's nu:
a run among them without colloids (their mean), or --nu. Against eq 5.29 with phi_M = 0.82 (2D) or 0.64
(3D) (--max-packing). Prints the table.

Bad input (missing observables, bad options): one line naming the file and what is missing,
exit 2.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import warnings

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import narrows_h5  # noqa: E402
from narrows_h5 import NarrowsDataError  # noqa: E402

TOOL = "segregation_plot"
THESIS_W = 40.0  # Kanehl (thesis) Table 5.1: w = 40 b in 2D and 3D


class InputError(Exception):
    """A bad command line (bad data raise narrows_h5.NarrowsDataError)."""


# ---- the run: scene, kinds, windows ----------------------------------------------------------


def body_volume(a, dims):
    return math.pi * a * a if dims == 2 else 4.0 / 3.0 * math.pi * a ** 3


def max_packing(dims):
    return 0.82 if dims == 2 else 0.64  # Kanehl (thesis) eq 5.29


class Channel:
    """What the scene of a run says about the channel, the fluid, the drive and the kinds."""

    def __init__(self, run, counts=None):
        s = run.scene()
        self.path = run.newest
        self.dims = int(s.get("run", {}).get("dimensions", 2))
        size = [float(x) for x in s["domain"]["size"]]
        self.size = size
        self.w = size[1] / 2.0
        self.cross = size[0] * (size[2] if self.dims == 3 else 1.0)  # L_x [L_z]
        self.volume = float(np.prod(size))
        fluid = s.get("fluid", {})
        self.rho = float(fluid.get("density", 10))
        self.kT = float(fluid.get("kT", 1.0))
        bf = s.get("body_force", {})
        self.g = float(bf.get("value", [0.0])[0]) if bf.get("kind", "constant") == "constant" \
            else 0.0
        self.acts_on = bf.get("acts_on", "fluid")
        col = s.get("colloids")
        self.kinds = []
        if col:
            if "kind" in col:
                raw = [(float(k["radius"]), k.get("count"), k.get("mass")) for k in col["kind"]]
            else:
                n = col.get("count", len(col.get("positions", [])) or None)
                raw = [(float(col["radius"]), n, col.get("mass"))]
            if counts is not None and len(counts) == len(raw):
                raw = [(a, int(n), m) for (a, _, m), n in zip(raw, counts)]
            elif col.get("placement") == "packing":
                phi = float(col["packing_fraction"])
                if len(raw) == 1:
                    raw = [(raw[0][0], round(phi * self.volume / body_volume(raw[0][0],
                                                                             self.dims)),
                            raw[0][2])]
                else:
                    factor = phi * self.volume / sum(n * body_volume(a, self.dims)
                                                     for a, n, _ in raw)
                    raw = [(a, round(n * factor), m) for a, n, m in raw]
            for a, n, m in raw:
                if n is None:
                    raise NarrowsDataError(self.path, "the number of colloids is neither in "
                                           "the scene nor in density_kde/counts",
                                           'a run with "density_kde" (placement = "file")')
                v = body_volume(a, self.dims)
                mass = float(m) if m is not None else self.rho * v
                self.kinds.append({"radius": a, "count": int(n), "volume": v,
                                   "density": mass / v,
                                   "fraction": int(n) * v / self.volume})
        self.phi = sum(k["fraction"] for k in self.kinds)

    def force_per_volume(self, phi_k):
        """f(y) of the momentum balance (see the docstring), phi_k [kinds][bins]."""
        phi = np.sum(phi_k, axis=0)
        f = self.rho * self.g * (1.0 - phi)
        if self.acts_on == "fluid+colloids":
            for k, p in zip(self.kinds, phi_k):
                f = f + self.g * k["density"] * p
        return f

    def mean_force_per_mass(self):
        """g_eff = (mean force per volume) / rho of a uniform suspension."""
        phi_k = np.array([[k["fraction"]] for k in self.kinds]) if self.kinds \
            else np.zeros((1, 1))
        return float(self.force_per_volume(phi_k)[0]) / self.rho


def windowed(series):
    """value [windows][kinds][bins] (a result of the whole run, [kinds][bins], as one window)."""
    v = np.asarray(series.value, float)
    return v[None] if v.ndim == 2 else v


def series_steps(series):
    step = np.atleast_1d(np.asarray(series.step))
    return step


def steady_window_count(n):
    return max(4, int(math.ceil(n / 4.0)))


def line_slope(x, y):
    """Least-squares line: slope, its standard error (from the residuals), residual sd."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    A = np.vstack([x, np.ones_like(x)]).T
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    r = y - A @ coef
    dof = max(len(x) - 2, 1)
    s2 = float(r @ r) / dof
    sxx = float(np.sum((x - x.mean()) ** 2))
    return float(coef[0]), math.sqrt(s2 / sxx) if sxx > 0 else math.inf, math.sqrt(s2)


def merge(value, weight):
    """Weight-merged profile over the first axis (NaN where the weight is 0)."""
    value = np.where(weight > 0, value, 0.0)
    ws = weight.sum(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(ws > 0, (value * weight).sum(axis=0) / ws, np.nan), ws


def pick_windows(steps, from_step):
    """Indices of the windows from from_step on (default: the last K of the steady criterion)."""
    n = len(steps)
    if from_step is None:
        return np.arange(n - min(n, steady_window_count(n)), n)
    idx = np.nonzero(steps >= from_step)[0]
    if len(idx) == 0:
        raise InputError(f"--from-step {from_step}: no window ends at or after it (last "
                         f"{int(steps[-1])})")
    return idx


def colloid_velocity(run):
    s = run.series("colloid_velocity_profile")
    weight = np.asarray(s["weight"], float)
    return {"value": windowed(s), "weight": weight[None] if weight.ndim == 2 else weight,
            "step": series_steps(s), "bins": np.asarray(s.bins, float)}


def density(run):
    s = run.series("density_kde")
    counts = s.get("counts")
    return {"value": windowed(s), "step": series_steps(s), "bins": np.asarray(s.bins, float),
            "counts": None if counts is None else np.ravel(counts)}


def open_channel(path):
    run = narrows_h5.open_run(path)
    counts = None
    if run.has("density_kde"):
        counts = run.series("density_kde").get("counts")
        counts = None if counts is None else np.ravel(counts)
    return run, Channel(run, counts)


def particle_phi(ch, dens, windows):
    """phi_k(y) [kinds][bins] of the colloid centres, density_kde merged over windows."""
    F = dens["value"][windows].mean(axis=0)  # each window normalised: equal weights
    return np.array([k["count"] * F[i] * k["volume"] / ch.cross
                     for i, k in enumerate(ch.kinds)])


# ---- fluid Poiseuille fit (eq 4.49) ----------------------------------------------------------


def poiseuille_nu(run, ch, from_step=None, to_step=None):
    """(nu_eff, v0, how, steps used): eq 4.49 with the force per volume over rho (see doc)."""
    g_eff = ch.mean_force_per_mass()
    if run.has("velocity_profile"):
        s = run.series("velocity_profile")
        step = np.asarray(s.step)
        sel = select_samples(step, from_step, to_step, s.path)
        v = np.asarray(s.value, float)[sel][..., 0].mean(axis=0)
        y = np.asarray(s.bins, float)
        q = y * (2.0 * ch.w - y)
        A = np.vstack([q, np.ones_like(q)]).T
        (a, b), *_ = np.linalg.lstsq(A, v, rcond=None)
        if not a > 0:
            raise NarrowsDataError(s.path, "velocity_profile: no Poiseuille flow along +x in "
                                   "the samples used", "a driven channel run")
        return g_eff / (2.0 * a), a * ch.w ** 2 + b, "velocity_profile fit", \
            (int(step[sel][0]), int(step[sel][-1]))
    if run.has("viscosity"):
        s = run.series("viscosity")
        step = np.asarray(s.step)
        sel = select_samples(step, from_step, to_step, s.path)
        nu = float(np.mean(np.asarray(s.value, float)[sel])) * g_eff / ch.g
        return nu, g_eff * ch.w ** 2 / (2 * nu), "viscosity observable", \
            (int(step[sel][0]), int(step[sel][-1]))
    raise narrows_h5.missing_observable(run.path, "velocity_profile",
                                        'a run with "velocity_profile" or "viscosity"')


def select_samples(step, from_step, to_step, path):
    step = np.asarray(step)
    lo = from_step if from_step is not None else step[len(step) // 2]
    hi = to_step if to_step is not None else step[-1]
    sel = np.nonzero((step >= lo) & (step <= hi))[0]
    if len(sel) == 0:
        raise InputError(f"{path}: no samples between steps {lo} and {hi}")
    return sel


def fluid_nu(args, ch_any):
    """(nu of the pure fluid, how) from --nu or --fluid-run, else (None, None)."""
    if getattr(args, "nu", None) is not None:
        return args.nu, "--nu"
    if getattr(args, "fluid_run", None):
        run, ch = open_channel(args.fluid_run)
        if ch.kinds:
            raise NarrowsDataError(run.newest, "--fluid-run has colloids",
                                   "a run without [colloids]")
        nu, _, how, _ = poiseuille_nu(run, ch, None, None)
        return nu, f"--fluid-run ({how})"
    return None, None


# ---- evolution (figs 5.5a, 5.10a) ------------------------------------------------------------


def saturation_fit(d, delta):
    """Delta = D_inf (1 - exp(-d / d_tau)) with the late-window noise; returns a dict."""
    from scipy.optimize import curve_fit

    n = len(d)
    k = min(n, steady_window_count(n))
    slope, slope_err, noise = line_slope(d[-k:], delta[-k:])
    out = {"windows": n, "late_windows": k, "late_slope": slope, "late_slope_error": slope_err,
           "steady": bool(abs(slope) <= 2.0 * slope_err), "noise": noise}
    sigma = np.full(n, noise if noise > 0 else max(1e-12, 1e-6 * np.max(np.abs(delta))))
    model = lambda x, a, tau: a * (1.0 - np.exp(-x / tau))  # noqa: E731
    late = float(np.mean(delta[-k:]))
    # the first guess: d_tau where Delta first passes 63 % of the late mean
    passed = np.nonzero(delta >= 0.632 * late)[0]
    tau0 = float(d[passed[0]]) if len(passed) and d[passed[0]] > 0 else float(d[-1]) / 3.0
    lo, hi = 1e-3 * d[1], 1e3 * d[-1]  # d_tau from well inside the first window to far beyond
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # an unresolved d_tau: infinite errors, said below
            p, cov = curve_fit(model, d, delta, p0=[late, min(max(tau0, 2 * lo), hi / 2)],
                               sigma=sigma, absolute_sigma=True, bounds=([-np.inf, lo],
                                                                         [np.inf, hi]),
                               max_nfev=20000)
    except (RuntimeError, ValueError) as e:
        out["fit_error"] = str(e)
        return out
    chi2 = float(np.sum(((delta - model(d, *p)) / sigma) ** 2))
    dof = max(n - 2, 1)
    scale = math.sqrt(max(1.0, chi2 / dof))
    err = np.sqrt(np.diag(cov)) * scale
    out.update({"delta_inf": float(p[0]), "delta_inf_error": float(err[0]),
                "d_tau": float(p[1]), "d_tau_error": float(err[1]),
                "d_sat": 3.0 * float(p[1]), "d_sat_error": 3.0 * float(err[1]),
                "chi2_dof": chi2 / dof,
                "resolved": bool(d[1] < 3.0 * p[1] < d[-1])})
    if 3.0 * p[1] <= d[1]:
        out["note"] = "saturated before the second window: d_sat unresolved (shorter kde_window)"
        out["d_tau_error"] = out["d_sat_error"] = math.inf  # only d_sat < d[1] is known
    elif 3.0 * p[1] >= d[-1]:
        out["note"] = "d_sat beyond the end of the run (an extrapolation)"
    return out


def noise_floor(run, ch):
    """The part of Delta that sampling noise alone gives: the mean over consecutive pairs of the
    last K windows of int (c_i - c_(i+1))^2 dy / int c_0^2 dy, c = sum_k N_k F_k of density_kde
    (in a steady state E[(c_i - c_0)^2] = bias^2 + 2 var = bias^2 + E[(c_i - c_(i+1))^2])."""
    if not run.has("density_kde"):
        return None
    dens = density(run)
    F = dens["value"]
    if F.shape[0] < 3:
        return None
    counts = np.array([k["count"] for k in ch.kinds], float)
    if F.shape[1] != len(counts):
        raise NarrowsDataError(run.path, f"density_kde has {F.shape[1]} kinds, the scene "
                               f"{len(counts)}", "the run's own observables")
    c = np.einsum("k,wkb->wb", counts, F)
    k = min(F.shape[0] - 1, steady_window_count(F.shape[0]))
    late = c[-k - 1:]
    den = float(np.sum(c[0] ** 2))
    return float(np.mean(np.sum(np.diff(late, axis=0) ** 2, axis=1)) / den) if den > 0 else None


def centre_speed(run, ch):
    """(v_c, how): colloid_velocity_profile at y = w merged over kinds and windows, else the
    largest mean x velocity of the fluid's velocity_profile."""
    if run.has("colloid_velocity_profile"):
        cv = colloid_velocity(run)
        W, K, B = cv["value"].shape
        v, ws = merge(cv["value"].reshape(W * K, B), cv["weight"].reshape(W * K, B))
        ok = ws > 0
        if not np.any(ok):
            raise NarrowsDataError(run.path, "colloid_velocity_profile has no weight anywhere")
        vc = float(np.interp(ch.w, cv["bins"][ok], v[ok]))
        return vc, "colloid_velocity_profile at the centre (kinds and windows merged)"
    if run.has("velocity_profile"):
        v = np.asarray(run.series("velocity_profile").value, float)[..., 0]
        return float(np.max(v.mean(axis=0))), "fluid velocity_profile maximum (no " \
            "colloid_velocity_profile)"
    raise narrows_h5.missing_observable(run.path, "colloid_velocity_profile",
                                        'a run with "colloid_velocity_profile" or '
                                        '"velocity_profile"')


def cmd_evolution(a):
    results = []
    for i, path in enumerate(a.run_dirs):
        run, ch = open_channel(path)
        ev = run.series("evolution", 'a run that lists "evolution" (density_kde with '
                        'output.kde_window > 0)')
        t = np.asarray(ev.time, float)
        delta = np.asarray(ev.value, float)
        if len(t) < 3:
            raise NarrowsDataError(ev.path, f"evolution has {len(t)} windows",
                                   "at least 3 (output.kde_window shorter than the run)")
        vc, how = centre_speed(run, ch)
        d = vc * (t - t[0]) / ch.w
        r = {"run": path, "v_c": vc, "v_c_from": how, "w": ch.w, "dimensions": ch.dims,
             "phi": ch.phi, "radii": [k["radius"] for k in ch.kinds]}
        r.update(saturation_fit(d, delta))
        r["noise_floor"] = noise_floor(run, ch)
        by = ev.get("by_kind")
        r["by_kind"] = []
        if by is not None:
            by = np.asarray(by, float)
            for k in range(by.shape[1]):
                fk = saturation_fit(d, by[:, k])
                r["by_kind"].append({key: fk.get(key) for key in
                                     ("delta_inf", "delta_inf_error", "d_sat", "d_sat_error",
                                      "steady", "resolved", "note")})
        a_w = pick(a.radius_over_w, i)
        one_radius = len({k["radius"] for k in ch.kinds}) == 1
        if a_w is None and one_radius:
            a_w = ch.kinds[0]["radius"] / ch.w
        a_th = pick(a.thesis_radius_over_w, i)
        if a_th is None and one_radius:
            a_th = ch.kinds[0]["radius"] / THESIS_W
        if a_w and a_th and "d_sat" in r:
            f = (a_w / a_th) ** 2
            r.update({"a_over_w": a_w, "thesis_a_over_w": a_th, "scale": f,
                      "d_sat_thesis": r["d_sat"] * f, "d_sat_thesis_error": r["d_sat_error"] * f})
        r["_d"], r["_delta"], r["_by"] = d, delta, by
        results.append(r)

    plt = narrows_h5.pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    for j, r in enumerate(results):
        c = f"C{j}"
        ax.plot(r["_d"], r["_delta"], "o", ms=3, color=c, label=os.path.basename(
            os.path.normpath(r["run"])) + f" (phi {r['phi']:.3g})")
        if r["_by"] is not None and r["_by"].shape[1] > 1:
            for k in range(r["_by"].shape[1]):
                ax.plot(r["_d"], r["_by"][:, k], "--", color=c, lw=0.8)
        if "d_tau" in r:
            x = np.linspace(0, r["_d"][-1], 200)
            ax.plot(x, r["delta_inf"] * (1 - np.exp(-x / r["d_tau"])), "-", color=c)
            ax.axvline(r["d_sat"], color=c, ls=":")
        if r.get("noise_floor") is not None:
            ax.axhline(r["noise_floor"], color=c, ls="-.", lw=0.6)
    ax.set_xlabel("d / w  (d = v_c t; dotted: d_sat, dash-dotted: noise floor)")
    ax.set_ylabel("Delta (eq 5.31)")
    ax.legend(fontsize=7)
    save(fig, a, results[0]["run"], "evolution")

    for r in results:
        for key in ("_d", "_delta", "_by"):
            r.pop(key)
    out = {"runs": results}
    if a.json:
        print(json.dumps(finite(out), indent=1))
        return 0
    for r in results:
        print(f"{r['run']}: {r['dimensions']}D, phi = {r['phi']:.4g}, radii {r['radii']}, "
              f"w = {r['w']:g}")
        print(f"  v_c = {r['v_c']:.5g} from the {r['v_c_from']}")
        if "d_sat" in r:
            print(f"  d_sat = 3 d_tau = {r['d_sat']:.4g} +- {r['d_sat_error']:.2g} w, Delta_inf "
                  f"= {r['delta_inf']:.4g} +- {r['delta_inf_error']:.2g} (chi^2/dof "
                  f"{r['chi2_dof']:.3g}, noise {r['noise']:.3g} from the last "
                  f"{r['late_windows']} windows)")
        else:
            print(f"  no saturation fit: {r.get('fit_error')}")
        if r.get("note"):
            print(f"  note: {r['note']}")
        if r.get("noise_floor") is not None:
            print(f"  Delta from sampling noise alone (consecutive late windows of density_kde): "
                  f"{r['noise_floor']:.3g}")
        print(f"  steady: {'yes' if r['steady'] else 'no'} (slope of Delta over the last "
              f"{r['late_windows']} windows {r['late_slope']:.3g} +- "
              f"{r['late_slope_error']:.2g} per w)")
        for k, b in enumerate(r["by_kind"]):
            if b.get("d_sat") is not None:
                print(f"  kind {k}: d_sat = {b['d_sat']:.4g} +- {b['d_sat_error']:.2g} w, "
                      f"Delta_inf = {b['delta_inf']:.4g}, steady "
                      f"{'yes' if b['steady'] else 'no'}")
        if "d_sat_thesis" in r:
            print(f"  at the thesis' a/w = {r['thesis_a_over_w']:.4g} (run: {r['a_over_w']:.4g}): "
                  f"d_sat = {r['d_sat_thesis']:.4g} +- {r['d_sat_thesis_error']:.2g} w (x "
                  f"{r['scale']:.4g} = (a/w run / a/w thesis)^2; thesis: d_L ~ 100 w, d_S ~ "
                  f"{'400' if r['dimensions'] == 2 else '500'} w)")
    return 0


def finite(x):
    """x with every non-finite float replaced by None (strict JSON)."""
    if isinstance(x, dict):
        return {k: finite(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [finite(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


def nan_list(x):
    """A list for JSON with None in place of NaN."""
    return [None if not np.isfinite(v) else float(v) for v in x]


def pick(values, i):
    if not values:
        return None
    return values[i] if len(values) > 1 else values[0]


def save(fig, a, run_dir, name):
    path = a.png or os.path.join(run_dir if os.path.isdir(run_dir) else
                                 os.path.dirname(run_dir) or ".", f"segregation_{name}.png")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    return path


# ---- velocity (figs 5.5b, 5.10b) -------------------------------------------------------------


def uniform_parabola(run, ch, first_only):
    """(v0, b): v = v0 (1 - y^2/w^2) + b through the colloid velocities (kinds merged) of the
    first window, or of every window."""
    cv = colloid_velocity(run)
    val, wt = cv["value"], cv["weight"]
    if first_only:
        val, wt = val[:1], wt[:1]
    W, K, B = val.shape
    v, ws = merge(val.reshape(W * K, B), wt.reshape(W * K, B))
    ok = ws > 0
    s = cv["bins"][ok] - ch.w
    A = np.vstack([1.0 - (s / ch.w) ** 2, np.ones_like(s)]).T * np.sqrt(ws[ok])[:, None]
    (v0, b), *_ = np.linalg.lstsq(A, v[ok] * np.sqrt(ws[ok]), rcond=None)
    return float(v0), float(b)


def steady_velocity(run, ch, from_step):
    cv = colloid_velocity(run)
    win = pick_windows(cv["step"], from_step)
    per_kind = []
    for k in range(cv["value"].shape[1]):
        per_kind.append(merge(cv["value"][win, k], cv["weight"][win, k]))
    allv, allw = merge(cv["value"][win].reshape(-1, len(cv["bins"])),
                       cv["weight"][win].reshape(-1, len(cv["bins"])))
    return cv["bins"] - ch.w, per_kind, (allv, allw), win, cv["step"]


def cmd_velocity(a):
    run, ch = open_channel(a.run_dir)
    s, per_kind, (allv, allw), win, steps = steady_velocity(run, ch, a.from_step)
    if a.uniform:
        urun, uch = open_channel(a.uniform)
        v0, b = uniform_parabola(urun, uch, False)
        uniform_from = f"--uniform {a.uniform} (every window)"
    else:
        v0, b = uniform_parabola(run, ch, True)
        uniform_from = "the first window of the run"
    ok = allw > 0
    centre = float(np.interp(0.0, s[ok], allv[ok]))
    out = {"run": a.run_dir, "windows": [int(steps[win[0]]), int(steps[win[-1]])],
           "uniform_from": uniform_from, "uniform_v0": v0, "uniform_wall": b,
           "uniform_centre": v0 + b, "steady_centre": centre,
           "steady_over_uniform": centre / (v0 + b) if v0 + b else None,
           "kinds": []}
    for k, (v, wk) in enumerate(per_kind):
        okk = wk > 0
        out["kinds"].append({"radius": ch.kinds[k]["radius"] if k < len(ch.kinds) else None,
                             "centre": float(np.interp(0.0, s[okk], v[okk])) if np.any(okk)
                             else None})
    plt = narrows_h5.pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    for k, (v, wk) in enumerate(per_kind):
        ax.plot(s / ch.w, v, "-", label=f"kind {k} (a = {out['kinds'][k]['radius']:g})")
    x = np.linspace(-1, 1, 201)
    ax.plot(x, v0 * (1 - x * x) + b, "-.", color="k", label="uniform suspension")
    ax.set_xlabel("y / w")
    ax.set_ylabel("colloid v_x")
    ax.legend(fontsize=8)
    save(fig, a, a.run_dir, "velocity")
    if a.json:
        print(json.dumps(finite(out), indent=1))
        return 0
    print(f"{a.run_dir}: steady windows ending at steps {out['windows'][0]}..{out['windows'][1]}"
          f" ({len(win)} windows, weight-merged)")
    for k, kk in enumerate(out["kinds"]):
        print(f"  kind {k} (a = {kk['radius']:g}): v_x at the centre {kk['centre']:.5g}")
    print(f"  uniform suspension ({uniform_from}): v = {v0:.5g} (1 - y^2/w^2) + {b:.3g}; steady "
          f"centre / uniform centre = {out['steady_over_uniform']:.4g}")
    return 0


# ---- viscosity (fig 5.5c) --------------------------------------------------------------------


AUTO_DEGREE = 8


def even_fit(s, v, wt, degree, w):
    """Weighted least-squares even polynomial in s/w; returns (v(s), dv/ds(s)) callables."""
    J = degree // 2
    x = s / w
    A = np.vstack([x ** (2 * j) for j in range(J + 1)]).T
    sw = np.sqrt(wt / wt.max())
    c, *_ = np.linalg.lstsq(A * sw[:, None], v * sw, rcond=None)

    def value(t):
        t = np.asarray(t, float) / w
        return sum(c[j] * t ** (2 * j) for j in range(J + 1))

    def slope(t):
        t = np.asarray(t, float) / w
        return sum(2 * j * c[j] * t ** (2 * j - 1) for j in range(1, J + 1)) / w

    return value, slope


def cumulative_from_centre(s, f):
    """F(s) = int_0^s f ds' on the grid s (ascending, through 0 by interpolation)."""
    f0 = float(np.interp(0.0, s, f))
    F = np.zeros_like(s)
    right = s > 0
    sr = np.concatenate([[0.0], s[right]])
    fr = np.concatenate([[f0], f[right]])
    F[right] = np.concatenate([[0.0], np.cumsum(0.5 * (fr[1:] + fr[:-1]) * np.diff(sr))])[1:]
    left = s < 0
    sl = np.concatenate([[0.0], s[left][::-1]])
    fl = np.concatenate([[f0], f[left][::-1]])
    F[left] = np.concatenate([[0.0], np.cumsum(0.5 * (fl[1:] + fl[:-1]) * np.diff(sl))])[1:][::-1]
    return F


def continuum_steady(a, ch, v0, nu_f, work):
    """phi(y) [bins] and y of the continuum model's steady profiles (total over kinds)."""
    if a.continuum != "auto":
        run = narrows_h5.open_run(a.continuum)
        g = run.series("steady_density", 'an observables file of a [continuum] model = '
                       '"segregation" run with "steady_density"')
        val = np.asarray(g.value, float)
        return np.asarray(g.bins, float), val.sum(axis=1) if val.ndim == 2 else val, \
            f"file {a.continuum}"
    from continuum_run import find_narrows

    narrows = find_narrows(a.narrows)
    if a.diffusivity:
        if len(a.diffusivity) != len(ch.kinds):
            raise InputError(f"--diffusivity: {len(a.diffusivity)} values for "
                             f"{len(ch.kinds)} kinds; allowed: one D_0 > 0 per kind")
        D = list(a.diffusivity)
        how_d = "--diffusivity"
    elif nu_f is not None:
        D = [ch.kT / (6 * math.pi * ch.rho * nu_f * k["radius"]) for k in ch.kinds]
        how_d = "Stokes-Einstein kT / (6 pi rho nu a)"
    else:
        raise InputError("--continuum auto needs D_0: --diffusivity D_1 [D_2], or --nu / "
                         "--fluid-run for Stokes-Einstein")
    text = ("[run]\nengine = \"continuum\"\n[continuum]\nmodel = \"segregation\"\n"
            f"dimensions = {ch.dims}\nhalf_width = {ch.w!r}\ncells = {a.cells}\n"
            f"centre_speed = {v0!r}\nshear = \"{a.shear}\"\n"
            "time = 1e-9\nsamples = 1\n")
    if a.k_d is not None:
        text += f"k_d = {a.k_d!r}\n"
    if a.k_eta is not None:
        text += f"k_eta = {a.k_eta!r}\n"
    for k, d in zip(ch.kinds, D):
        text += (f"[[continuum.kind]]\nradius = {k['radius']!r}\nfraction = {k['fraction']!r}\n"
                 f"diffusivity = {d!r}\n")
    text += "[output]\nobservables = [\"steady_density\"]\nprogress = false\n"
    scene = os.path.join(work, "steady.toml")
    with open(scene, "w") as f:
        f.write(text)
    out = os.path.join(work, "out")
    r = subprocess.run([narrows, "run", scene, "--out", out, "--overwrite"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise InputError("narrows run of the segregation model failed: "
                         + (r.stderr.strip().splitlines() or ["?"])[-1])
    run = narrows_h5.open_run(out)
    if not run.has("steady_density"):
        raise InputError("the segregation model has no steady state for this run's kinds "
                         "(close packing reached?)")
    g = run.series("steady_density")
    val = np.asarray(g.value, float)
    return np.asarray(g.bins, float), val.sum(axis=1), \
        f"narrows continuum run (v0 {v0:.4g}, D_0 {', '.join(f'{x:.4g}' for x in D)} " \
        f"from {how_d})"


def cmd_viscosity(a):
    run, ch = open_channel(a.run_dir)
    if not ch.kinds:
        raise NarrowsDataError(run.newest, "the scene has no colloids", "a suspension run")
    if ch.g == 0:
        raise NarrowsDataError(run.newest, "body_force.value[0] = 0 (or not constant): no "
                               "drive f for eq 5.33", "a pressure-driven channel run")
    phim = a.max_packing or max_packing(ch.dims)
    y_all, per_kind, (v, wt), win, steps = steady_velocity(run, ch, a.from_step)
    dens = density(run)
    dwin = pick_windows(dens["step"], int(steps[win[0]]) if a.from_step is None
                        else a.from_step)
    phi_k = particle_phi(ch, dens, dwin)
    s_d = dens["bins"] - ch.w
    # more realisations of the same scene (--with): velocities merged by their kernel weights,
    # the fractions averaged with equal weights
    for extra in a.with_runs or []:
        xrun, xch = open_channel(extra)
        xy, _, (xv, xwt), xwin, xsteps = steady_velocity(xrun, xch, a.from_step)
        xdens = density(xrun)
        if xy.shape != y_all.shape or xdens["bins"].shape != dens["bins"].shape or \
                not np.isclose(xch.w, ch.w) or len(xch.kinds) != len(ch.kinds):
            raise InputError(f"--with {extra}: another channel or other bins than {a.run_dir}")
        v, wt = merge(np.stack([v, xv]), np.stack([wt, xwt]))
        xdwin = pick_windows(xdens["step"], int(xsteps[xwin[0]]) if a.from_step is None
                             else a.from_step)
        phi_k = phi_k + particle_phi(xch, xdens, xdwin)
    phi_k = phi_k / (1 + len(a.with_runs or []))
    if a.mirror:
        # the channel is symmetric about its centre: each profile merged with its mirror image
        if not (np.allclose(y_all, -y_all[::-1]) and np.allclose(s_d, -s_d[::-1])):
            raise InputError(f"{a.run_dir}: bins not symmetric about the centre; drop --mirror")
        v, wt = merge(np.stack([v, v[::-1]]), np.stack([wt, wt[::-1]]))
        phi_k = 0.5 * (phi_k + phi_k[:, ::-1])
    phi_part = phi_k.sum(axis=0)

    if a.force == "uniform":
        f = np.full_like(s_d, ch.rho * ch.g)
    else:
        f = ch.force_per_volume(phi_k)
    F = cumulative_from_centre(s_d, f)
    a_l = max(k["radius"] for k in ch.kinds)
    s = y_all
    ok = (wt > 0) & np.isfinite(v)
    eta = np.full_like(s, np.nan)
    degrees = []
    for side in (s > 0, s < 0):
        m = ok & side
        top = a.degree or AUTO_DEGREE
        if np.count_nonzero(m) < top // 2 + 2:
            raise NarrowsDataError(run.path, "colloid_velocity_profile: too few bins with "
                                   f"colloids on one half for a degree-{top} fit")
        for deg in ([a.degree] if a.degree else range(AUTO_DEGREE, 0, -2)):
            _, slope = even_fit(np.abs(s[m]), v[m], wt[m], deg, ch.w)
            if np.all(slope(np.abs(s[m])) <= 0):  # v falls from the centre to the wall
                break
        degrees.append(deg)
        sd = np.abs(s[side])
        gd = slope(sd) * np.sign(s[side])  # dv/dy on this half
        with np.errstate(divide="ignore", invalid="ignore"):
            eta[side] = -np.interp(s[side], s_d, F) / gd
    eta[~ok] = np.nan

    nu_f, how_nu = fluid_nu(a, ch)
    if nu_f is not None:
        eta0 = ch.rho * nu_f * (1 - ch.phi / phim) ** -2
        how_eta0 = f"eq 5.29 at phi = {ch.phi:.4g}, eta_f = rho nu, nu = {nu_f:.5g} from {how_nu}"
    else:
        if a.uniform_steps:
            lo, hi = a.uniform_steps
        else:  # the samples of the first window
            st = dens["step"]
            hi = int(st[0])
            lo = hi - int(st[1] - st[0]) + 1 if len(st) > 1 else 0
        nu_s, _, how, rng = poiseuille_nu(run, ch, lo, hi)
        eta0 = ch.rho * nu_s
        how_eta0 = (f"measured: rho nu_eff of the uniform suspension, eq 4.49 ({how}, steps "
                    f"{rng[0]}..{rng[1]}); give --nu for eq 5.29's")
    v0u, bu = uniform_parabola(run, ch, True)
    curves = {}
    eta529_part = (1 - np.interp(s, s_d, phi_part) / phim) ** -2 / (1 - ch.phi / phim) ** -2
    eta529_part[~ok] = np.nan  # no colloid centres there (the wall layers)
    curves["particles"] = (eta529_part, "phi(y) of the particles (density_kde)")
    if a.continuum:
        with tempfile.TemporaryDirectory() as work:
            yc, phic, how_c = continuum_steady(a, ch, v0u + bu, nu_f, work)
        # the continuum's y is from the centre (walls at -w, w)
        eta529_c = (1 - np.interp(s, yc, phic) / phim) ** -2 / (1 - ch.phi / phim) ** -2
        curves["continuum"] = (eta529_c, "phi(y) of the continuum model: " + how_c)
    region = ok & (np.abs(s) > ch.w / 4) & (np.abs(s) < ch.w - 2 * a_l)
    out = {"run": a.run_dir, "windows": [int(steps[win[0]]), int(steps[win[-1]])],
           "phi": ch.phi, "max_packing": phim, "eta0": eta0, "eta0_from": how_eta0,
           "force": a.force, "acts_on": ch.acts_on, "degree": degrees,
           "eta_positive": bool(np.all(eta[np.isfinite(eta)] >= 0)),
           "region": [ch.w / 4, ch.w - 2 * a_l], "region_bins": int(np.count_nonzero(region)),
           "eta_centre_over_eta0": None, "compare": {}}
    eta_rel = eta / eta0
    inner = ok & (np.abs(s) > 0)
    if np.any(inner):
        j = np.argmin(np.where(inner, np.abs(s), np.inf))
        out["eta_centre_over_eta0"] = float(eta_rel[j])
    for name, (curve, how) in curves.items():
        if np.count_nonzero(region) == 0:
            diff = None
        else:
            diff = float(np.max(np.abs(eta_rel[region] / curve[region] - 1)))
        out["compare"][name] = {"from": how, "max_relative_difference": diff}

    out["profile"] = {"y": s.tolist(), "eta_over_eta0": nan_list(eta_rel),
                      "phi_particles": np.interp(s, s_d, phi_part).tolist()}
    for name, (curve, _) in curves.items():
        out["profile"][f"eq_5_29_{name}"] = nan_list(curve)
    plt = narrows_h5.pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(s / ch.w, eta_rel, "-", color="C0", label="eq 5.33 (colloid v_x)")
    for j, (name, (curve, how)) in enumerate(curves.items()):
        ax.plot(s / ch.w, curve, "--", color=f"C{j + 1}", label=f"eq 5.29, phi of the {name}")
    for x in (ch.w / 4, ch.w - 2 * a_l):
        for sg in (-1, 1):
            ax.axvline(sg * x / ch.w, color="0.7", lw=0.6)
    ax.set_xlabel("y / w")
    ax.set_ylabel("eta / eta_0")
    # log scale, clipped: eq 5.29 of the particles' layered phi(y) diverges where a layer
    # exceeds phi_M, and would hide the rest
    ax.set_yscale("log")
    finite_eta = np.asarray(eta_rel, float)[np.isfinite(eta_rel) & (np.asarray(eta_rel) > 0)]
    if finite_eta.size:
        ax.set_ylim(max(1e-2, 0.3 * finite_eta.min()), 30 * finite_eta.max())
    ax.legend(fontsize=7)
    save(fig, a, a.run_dir, "viscosity")
    if a.json:
        print(json.dumps(finite(out), indent=1))
        return 0
    out.pop("profile")
    print(f"{a.run_dir}: steady windows ending at steps {out['windows'][0]}..{out['windows'][1]},"
          f" phi = {ch.phi:.4g}, phi_M = {phim:g}")
    force = ("rho g (eq 5.33 as printed)" if a.force == "uniform"
             else f"local, acts_on = {ch.acts_on}")
    print(f"  force per volume: {force}; gdot from an even polynomial per half of degree "
          f"{degrees[0]} (y > 0), {degrees[1]} (y < 0)"
          + ("" if a.degree else " (auto: the highest <= 8 with v falling toward the walls)"))
    if not out["eta_positive"]:
        print("  warning: eta < 0 somewhere: the fitted v_x rises toward a wall even at degree "
              "2 (too noisy, or not a pressure-driven steady state)")
    print(f"  eta_0 = {eta0:.5g} ({how_eta0})")
    if out["eta_centre_over_eta0"] is not None:
        print(f"  eta / eta_0 next to the centre: {out['eta_centre_over_eta0']:.4g}")
    for name, c in out["compare"].items():
        d = c["max_relative_difference"]
        print(f"  eq 5.33 against eq 5.29 with {c['from']}: largest |relative difference| over "
              f"{out['region'][0]:.3g} < |y| < {out['region'][1]:.3g} = "
              f"{'n/a' if d is None else f'{d:.4g}'} ({out['region_bins']} bins)")
    return 0


# ---- fig 5.4 ---------------------------------------------------------------------------------


def cmd_fig54(a):
    rows, pure = [], []
    dims = None
    for path in a.run_dirs:
        run, ch = open_channel(path)
        if dims is not None and ch.dims != dims:
            raise InputError(f"{path}: a {ch.dims}D run among {dims}D runs")
        dims = ch.dims
        if ch.g == 0:
            raise NarrowsDataError(run.newest, "body_force.value[0] = 0", "a driven channel")
        nu, v0, how, rng = poiseuille_nu(run, ch, a.from_step, a.to_step)
        row = {"run": path, "phi": ch.phi, "nu_eff": nu, "v0": v0, "from": how,
               "steps": list(rng), "g_eff_over_g": ch.mean_force_per_mass() / ch.g}
        (pure if not ch.kinds else rows).append(row)
    phim = a.max_packing or max_packing(dims)
    if a.nu is not None:
        nu_f, how_f = a.nu, "--nu"
    elif pure:
        nu_f = float(np.mean([p["nu_eff"] for p in pure]))
        how_f = f"mean of {len(pure)} run(s) without colloids"
    else:
        raise InputError("no pure-fluid viscosity: give a run without colloids among the runs, "
                         "or --nu")
    for r in rows:
        r["eta_over_eta_f"] = r["nu_eff"] / nu_f
        # eq 4.49 with the force as applied (on the fluid particles only, g per particle): what
        # the thesis' formula gives when read as printed
        r["eta_over_eta_f_applied_g"] = r["eta_over_eta_f"] / r["g_eff_over_g"]
        r["eq_5_29"] = (1 - r["phi"] / phim) ** -2
        r["ratio"] = r["eta_over_eta_f"] / r["eq_5_29"]
        r["ratio_applied_g"] = r["eta_over_eta_f_applied_g"] / r["eq_5_29"]
    rows.sort(key=lambda r: r["phi"])
    plt = narrows_h5.pyplot()
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.plot([r["phi"] for r in rows], [r["eta_over_eta_f"] for r in rows], "o",
            label="runs (eq 4.49, force per volume)")
    if any(r["g_eff_over_g"] != 1 for r in rows):
        ax.plot([r["phi"] for r in rows], [r["eta_over_eta_f_applied_g"] for r in rows], "s",
                mfc="none", label="runs (eq 4.49, g as applied)")
    x = np.linspace(0, max([r["phi"] for r in rows] + [0.1]) * 1.1, 200)
    x = x[x < phim * 0.98]
    ax.plot(x, (1 - x / phim) ** -2, "-", label=f"eq 5.29, phi_M = {phim:g}")
    ax.set_xlabel("phi")
    ax.set_ylabel("eta / eta_f")
    ax.legend()
    save(fig, a, a.run_dirs[0], "fig54")
    out = {"dimensions": dims, "max_packing": phim, "nu_f": nu_f, "nu_f_from": how_f,
           "runs": rows}
    if a.json:
        print(json.dumps(finite(out), indent=1))
        return 0
    print(f"{dims}D, pure fluid nu = {nu_f:.5g} ({how_f}), phi_M = {phim:g}")
    print(f"{'phi':>7} {'nu_eff':>9} {'eta/eta_f':>9} {'eq 5.29':>8} {'ratio':>6} "
          f"{'g applied':>9} {'ratio':>6}  run (source, steps, g_eff/g)")
    for r in rows:
        print(f"{r['phi']:7.4f} {r['nu_eff']:9.5g} {r['eta_over_eta_f']:9.4g} "
              f"{r['eq_5_29']:8.4g} {r['ratio']:6.3f} {r['eta_over_eta_f_applied_g']:9.4g} "
              f"{r['ratio_applied_g']:6.3f}  {r['run']} ({r['from']}, "
              f"{r['steps'][0]}..{r['steps'][1]}, {r['g_eff_over_g']:.3g})")
    print("  eta/eta_f: eq 4.49 with the mean force per volume over rho (g_eff); 'g applied': "
          "with g itself, eq 4.49 as printed")
    return 0


# ---- command line ----------------------------------------------------------------------------


def parser():
    p = argparse.ArgumentParser(prog="segregation_plot.py",
                                description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True)

    def common(q):
        q.add_argument("--png", help="the PNG (default RUN_DIR/segregation_<command>.png)")
        q.add_argument("--json", action="store_true", help="print the numbers as JSON")
        q.add_argument("--max-packing", type=float, help="phi_M (default 0.82 2D, 0.64 3D)")

    e = sub.add_parser("evolution", help="Delta against d / w (figs 5.5a, 5.10a)")
    e.add_argument("run_dirs", nargs="+")
    e.add_argument("--radius-over-w", type=float, nargs="+", help="(a/w) of each run")
    e.add_argument("--thesis-radius-over-w", type=float, nargs="+",
                   help="(a/w) of the thesis to scale d to (default radius / 40)")
    common(e)
    v = sub.add_parser("velocity", help="steady colloid v_x(y) (figs 5.5b, 5.10b)")
    v.add_argument("run_dir")
    v.add_argument("--from-step", type=int)
    v.add_argument("--uniform", help="a run of the uniform suspension")
    common(v)
    h = sub.add_parser("viscosity", help="eta(y) of eq 5.33 against eq 5.29 (fig 5.5c)")
    h.add_argument("run_dir")
    h.add_argument("--from-step", type=int)
    h.add_argument("--with", dest="with_runs", nargs="+", metavar="RUN_DIR",
                   help="more realisations of the scene, merged with RUN_DIR")
    h.add_argument("--mirror", action="store_true",
                   help="merge v_x(y) and phi(y) with their mirror images about the centre")
    h.add_argument("--continuum", help="STEADY.h5 (steady_density) or auto")
    h.add_argument("--nu", type=float, help="nu of the pure fluid")
    h.add_argument("--fluid-run", help="a run without colloids for nu of the pure fluid")
    h.add_argument("--uniform-steps", type=int, nargs=2, metavar=("FROM", "TO"),
                   help="the fluid samples of the uniform suspension for the measured eta_0 "
                   "(default: those of the first window)")
    h.add_argument("--degree", type=int, help="even polynomial degree (>= 2; default: auto, "
                   f"the highest <= {8} whose v_x falls toward the walls)")
    h.add_argument("--force", choices=("local", "uniform"), default="local")
    h.add_argument("--diffusivity", type=float, nargs="+")
    h.add_argument("--k-d", type=float)
    h.add_argument("--k-eta", type=float)
    h.add_argument("--shear", choices=("poiseuille", "viscous"), default="poiseuille")
    h.add_argument("--cells", type=int, default=400)
    h.add_argument("--narrows", help="the narrows binary (default: $NARROWS, build/narrows, "
                   "the PATH)")
    common(h)
    f = sub.add_parser("fig54", help="eta(phi) / eta_f of uniform suspensions (fig 5.4)")
    f.add_argument("run_dirs", nargs="+")
    f.add_argument("--nu", type=float, help="nu of the pure fluid")
    f.add_argument("--from-step", type=int)
    f.add_argument("--to-step", type=int)
    common(f)
    return p


def main(argv):
    a = parser().parse_args(argv)
    try:
        if getattr(a, "degree", None) is not None and (a.degree < 2 or a.degree % 2):
            raise InputError(f"--degree {a.degree}: allowed: an even number >= 2")
        for key in ("nu", "max_packing"):
            val = getattr(a, key, None)
            if val is not None and not val > 0:
                raise InputError(f"--{key.replace('_', '-')} {val}: allowed: a number > 0")
        return {"evolution": cmd_evolution, "velocity": cmd_velocity,
                "viscosity": cmd_viscosity, "fig54": cmd_fig54}[a.command](a)
    except (InputError, NarrowsDataError) as e:
        return narrows_h5.report(TOOL, e)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
