#!/usr/bin/python3
"""Test of tools/segregation_plot.py (Kanehl (thesis) figs 5.4, 5.5, 5.10) on synthetic runs
written in the particle-side segregation layout of issue 32 (windowed density_kde, evolution,
colloid_velocity_profile) and the fluid's velocity_profile / viscosity.

Usage: /usr/bin/python3 tools/test_segregation_plot.py [NARROWS_BINARY]   (the binary only for
f); a) to e) give the continuum curve of `viscosity` as a steady_density file written here)

a) evolution: Delta(d) = D_inf (1 - exp(-d / d_tau)) + Gaussian noise (sd 0.005, fixed seed) in
   80 windows over d = 0..160 w, d_tau = 20 w (kind 0) and 40 w (kind 1; the total: 20 w), v_c =
   0.05 in colloid_velocity_profile (a plug, so the centre value is exact). The fit must give
   d_tau within 3 of its standard errors of the truth (a pull; measured 19.92 +- 0.22) and the
   error below 10 % (the fit is informative); d_sat = 3 d_tau; steady yes. A run of d_tau = 500
   w seen to 160 w: steady no, with the note that d_sat lies beyond the run; d_tau = 0.5 w with
   windows 2 w apart: the note that it saturated before the second window (d_sat unresolved).
   The noise floor of Delta (consecutive late windows of density_kde): 0 for noiseless windows;
   with independent noise of sd 0.005 on each kind's F = 0.05 per bin (two kinds of 20), c = 20
   (F_0 + F_1), the floor 2 * 2 * 20^2 sd^2 / 2^2 = 0.01 within 15 % (20 pairs of 80 bins: a
   relative sd of the estimate of ~4 %). The scaling to the thesis: a/w = 0.1 run, default
   thesis a/w = radius / 40 = 0.025: factor 16. Without colloid_velocity_profile v_c comes from
   the fluid velocity_profile maximum, and the output says so.
b) viscosity, uniform suspension: v_x = f (w^2 - y^2) / (2 eta) with f = rho g (1 - phi)
   (acts_on = "fluid", phi = 0.314), eta = eta_0 = rho nu (1 - phi/phi_M)^-2 (nu given):
   eta(y) / eta_0 = 1 to 1e-6 over the compared region (the parabola is in the polynomial
   family, so the fit is exact to rounding; measured 1e-14); with 0.2 % noise on v_x per bin and
   window (fixed seed) within 2 % (measured 0.23 %). Without --nu, eta_0 is the measured
   rho nu_eff of the fluid's Poiseuille profile before the first window: eta_0 to 1e-9. A
   parabola with a wiggle of 10 % of its centre speed (period 6 a, layering): at degree 8 the fit
   rises toward a wall somewhere (eta < 0); the default degree (the highest whose fit falls
   toward the walls) is lower and keeps eta >= 0.
c) viscosity, plug: phi(y) = phi (1 + 0.4 cos(pi y / w)), eta = eta_f (1 - phi(y)/phi_M)^-2,
   acts_on = "fluid+colloids" (f = rho g), v_x from gdot = -f y / eta(y) integrated from the
   wall; density_kde and the continuum steady_density both carry phi(y). The largest relative
   difference of eq 5.33 and eq 5.29 over w/4 < |y| < w - 2a must be < 0.3 % for both curves
   (a smooth profile fitted with an even polynomial of degree 10 per half: measured 3.2e-4;
   degree 8 gives 2.0e-3, degree 6 4.8e-3, so the bound also pins the fit's accuracy).
d) fig54: five runs (phi = 0 ... 0.4, 2D) whose fluid velocity_profile is the Poiseuille
   parabola of nu_eff = nu_f (1 - phi/0.82)^-2 with the force per volume rho g (1 - phi), one
   of them with the viscosity observable only (g / (2 a), as narrows writes it): eta/eta_f over
   eq 5.29 must be 1 to 1e-9; a 3D run set uses phi_M = 0.64; a run without colloids gives
   nu_f; without it and without --nu: exit 2 with one line.
e) velocity: six windows, the first a parabola v0 (1 - y^2/w^2) with v0 = 0.1, then plugs of
   0.2 (weight 1) and 0.26 (weight 3): the steady centre over the last K = 4 windows is their
   weight-merged mean 0.245 (to 1e-12), from --from-step 5000 on 0.26; the uniform parabola has
   v0 = 0.1 and wall speed 0 (to 1e-9).
f) with NARROWS_BINARY: viscosity --continuum auto on the plug run of c) (2D, one kind,
   --diffusivity 0.00137): the continuum engine runs on the scene built from the run's kinds;
   phi(y) recovered from its eq 5.29 curve (inverting eq 5.29) has the run's mean fraction
   (within 1e-4: the run's bins cover [-w, w] and the curve is interpolated from the 400
   continuum cells; measured 2.5e-7)
   and is enriched at the centre (phi(0) > mean: shear-induced migration); without --diffusivity
   D_0 is Stokes-Einstein's with --nu (the convention of the model's default K_d); without
   either: exit 2, one line naming --diffusivity.
Prints FAIL lines and "N passed, M failed"; exit 1 on any failure.
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

TOOL = os.path.join(HERE, "segregation_plot.py")


def scene(w, lx, kinds, g=0.001, rho=10.0, acts_on="fluid", dims=2):
    size = f"[{lx}, {2 * w}]" if dims == 2 else f"[{lx}, {2 * w}, {lx}]"
    text = (f"[run]\ndimensions = {dims}\nsteps = 1000\n[domain]\nsize = {size}\n"
            f"[fluid]\ncollision = \"at+a\"\ndensity = {rho}\ndt = 0.01\n"
            f"[body_force]\nvalue = [{g}, 0.0{', 0.0' if dims == 3 else ''}]\n"
            f"acts_on = \"{acts_on}\"\n[walls]\n")
    if kinds:
        text += "[colloids]\ncoupling = \"no-slip\"\ncontacts = \"hard\"\nplacement = \"random\"\n"
        for a, n in kinds:
            text += f"[[colloids.kind]]\nradius = {a}\ncount = {n}\n"
    elif acts_on != "fluid":
        text = text.replace(f"acts_on = \"{acts_on}\"\n", "")
    return text


def write(path, text, series):
    os.makedirs(path, exist_ok=True)
    narrows_h5.write_observables(os.path.join(path, "observables.h5"), series=series, scene=text)


def tool(*args):
    done = subprocess.run([sys.executable, TOOL, *args, "--json"], capture_output=True,
                          text=True)
    if done.returncode != 0:
        return None, done.stderr.strip()
    return json.loads(done.stdout), done.stderr


def rel(a, b):
    return abs(a - b) / abs(b)


# ---- a) evolution ----------------------------------------------------------------------------


def evolution_run(path, d_tau, d_tau_kind1, with_velocity=True, seed=1, kde_noise=0.0):
    w, vc, n_win, bins = 10.0, 0.05, 80, 80
    rng = np.random.default_rng(seed)
    d_over_w = np.linspace(0, 160, n_win)
    time = 10.0 + d_over_w * w / vc  # window ends; the first at t = 10
    step = np.round(time / 0.01).astype(np.int64)
    curve = lambda tau: 0.3 * (1 - np.exp(-d_over_w / tau))  # noqa: E731
    value = curve(d_tau) + rng.normal(0, 0.005, n_win)
    value[0] = 0.0
    by = np.stack([curve(d_tau) + rng.normal(0, 0.005, n_win),
                   curve(d_tau_kind1) + rng.normal(0, 0.005, n_win)], axis=1)
    by[0] = 0.0
    y = (np.arange(bins) + 0.5) * 2 * w / bins
    series = {"evolution": {"step": step, "time": time, "value": value, "by_kind": by}}
    kde = np.full((n_win, 2, bins), 1 / (2 * w)) + kde_noise * rng.normal(size=(n_win, 2, bins))
    series["density_kde"] = {"step": step, "time": time, "value": kde, "bins": y,
                             "samples": np.full(n_win, 10), "width": np.array([0.25]),
                             "counts": np.array([20, 20])}
    if with_velocity:
        series["colloid_velocity_profile"] = {
            "step": step, "time": time, "value": np.full((n_win, 2, bins), vc),
            "weight": np.ones((n_win, 2, bins)), "bins": y}
    else:
        series["velocity_profile"] = {"step": step, "time": time, "bins": y,
                                      "value": np.stack([np.stack([vc * (1 - ((y - w) / w) ** 2),
                                                                   0 * y], axis=1)] * n_win)}
    write(path, scene(w, 40, [(1.0, 20), (1.0, 20)]), series)  # two kinds of one radius


def test_evolution(tmp):
    p = os.path.join(tmp, "evo")
    evolution_run(p, 20.0, 40.0)
    res, err = tool("evolution", p)
    if res is None:
        check("a) evolution runs", False, err)
        return
    r = res["runs"][0]
    pull = (r["d_tau"] - 20.0) / r["d_tau_error"]
    check("a) d_tau = 20 w within 3 standard errors", abs(pull) < 3, (r["d_tau"],
                                                                       r["d_tau_error"]))
    check("a) d_tau error below 10 %", r["d_tau_error"] / r["d_tau"] < 0.1, r["d_tau_error"])
    check("a) d_sat = 3 d_tau", rel(r["d_sat"], 3 * r["d_tau"]) < 1e-12, r["d_sat"])
    check("a) Delta_inf = 0.3 within 3 standard errors",
          abs(r["delta_inf"] - 0.3) < 3 * r["delta_inf_error"], r["delta_inf"])
    check("a) v_c = 0.05 from colloid_velocity_profile",
          rel(r["v_c"], 0.05) < 1e-12 and "colloid" in r["v_c_from"], (r["v_c"], r["v_c_from"]))
    check("a) steady", r["steady"] is True, r["late_slope"])
    k1 = r["by_kind"][1]
    check("a) kind 1: d_sat = 120 w within 3 standard errors",
          abs(k1["d_sat"] - 120) < 3 * k1["d_sat_error"], (k1["d_sat"], k1["d_sat_error"]))
    check("a) scaling to the thesis: (0.1 / 0.025)^2 = 16",
          rel(r["d_sat_thesis"], 16 * r["d_sat"]) < 1e-12 and rel(r["a_over_w"], 0.1) < 1e-12,
          (r.get("d_sat_thesis"), r.get("a_over_w")))
    res, _ = tool("evolution", p, "--thesis-radius-over-w", "0.05")
    check("a) --thesis-radius-over-w 0.05: factor 4",
          res is not None and rel(res["runs"][0]["scale"], 4.0) < 1e-12)
    q = os.path.join(tmp, "evo_slow")
    evolution_run(q, 500.0, 500.0, seed=2)
    res, err = tool("evolution", q)
    check("a) d_tau = 500 w seen to 160 w: not steady, d_sat beyond the run",
          res is not None and res["runs"][0]["steady"] is False
          and res["runs"][0]["resolved"] is False and "beyond" in res["runs"][0].get("note", ""),
          err if res is None else res["runs"][0])
    check("a) no noise in density_kde: noise floor 0", r["noise_floor"] == 0.0, r["noise_floor"])
    q = os.path.join(tmp, "evo_noisy")
    evolution_run(q, 20.0, 40.0, seed=5, kde_noise=0.005)
    res, err = tool("evolution", q)
    floor = None if res is None else res["runs"][0]["noise_floor"]
    # c = 20 (F_0 + F_1): mean 2, consecutive differences of variance 2 * 2 * 20^2 * sd^2 per bin
    want = 2 * 2 * 20 ** 2 * 0.005 ** 2 / 2.0 ** 2
    check(f"a) density_kde noise sd 0.005 per kind and bin: noise floor {want:g} within 15 %",
          floor is not None and rel(floor, want) < 0.15, err if res is None else floor)
    q = os.path.join(tmp, "evo_fast")
    evolution_run(q, 0.5, 0.5, seed=4)
    res, err = tool("evolution", q)
    check("a) d_tau = 0.5 w (windows 2 w apart): saturated before the second window",
          res is not None and res["runs"][0]["resolved"] is False
          and "before the second window" in res["runs"][0].get("note", "")
          and res["runs"][0]["d_sat"] < 160 / 79, err if res is None else res["runs"][0])
    f = os.path.join(tmp, "evo_fluid")
    evolution_run(f, 20.0, 40.0, with_velocity=False)
    res, err = tool("evolution", f)
    check("a) v_c from the fluid velocity_profile maximum when there is no colloid profile",
          res is not None and rel(res["runs"][0]["v_c"], 0.05) < 1e-3
          and "fluid" in res["runs"][0]["v_c_from"], err)
    check("a) a PNG", os.path.getsize(os.path.join(p, "segregation_evolution.png")) > 0)


# ---- b, c) viscosity -------------------------------------------------------------------------


def viscosity_run(path, w, radius, count, v_of_s, phi_of_s, acts_on, g, rho, noise=0.0,
                  seed=3, fluid_nu=None):
    bins, n_win, lx = 320, 6, 100.0
    y = (np.arange(bins) + 0.5) * 2 * w / bins
    s = y - w
    inside = np.abs(s) < w - radius
    rng = np.random.default_rng(seed)
    v = np.where(inside, v_of_s(s), np.nan)
    value = np.stack([np.stack([v * (1 + noise * rng.normal(size=bins))]) for _ in range(n_win)])
    weight = np.stack([np.stack([inside.astype(float)])] * n_win)
    phi = phi_of_s(s) * inside
    area = math.pi * radius ** 2
    F = phi * lx / (count * area)  # phi = N F v / L_x
    kde = np.stack([np.stack([F])] * n_win)
    step = (np.arange(n_win) + 1) * 1000
    time = step * 0.01
    series = {"colloid_velocity_profile": {"step": step, "time": time, "value": value,
                                           "weight": weight, "bins": y},
              "density_kde": {"step": step, "time": time, "value": kde, "bins": y,
                              "samples": np.full(n_win, 10), "width": np.array([0.25]),
                              "counts": np.array([count])}}
    if fluid_nu is not None:  # the fluid's Poiseuille profile of the uniform suspension
        fstep = np.arange(1, 11) * 100
        prof = np.zeros((10, bins, 2))
        prof[:, :, 0] = g * (1 - phi_of_s(s).mean()) / (2 * fluid_nu) * y * (2 * w - y)
        series["velocity_profile"] = {"step": fstep, "time": fstep * 0.01, "value": prof,
                                      "bins": y}
    write(path, scene(w, lx, [(radius, count)], g=g, rho=rho, acts_on=acts_on), series)
    return s, inside


def test_viscosity(tmp):
    w, a, g, rho, nu = 20.0, 1.0, 0.002, 10.0, 0.5
    lx = 100.0
    n = 400
    phi = n * math.pi * a * a / (lx * 2 * w)  # 0.314
    eta0 = rho * nu * (1 - phi / 0.82) ** -2
    # b) a parabola: f = rho g (1 - phi) (acts_on = "fluid"), eta = eta0 everywhere
    f = rho * g * (1 - phi)
    for noise, tol, label in ((0.0, 1e-6, "exact"), (0.002, 0.02, "0.2 % noise")):
        p = os.path.join(tmp, f"parabola_{label.split()[0]}")
        viscosity_run(p, w, a, n, lambda s: f * (w * w - s * s) / (2 * eta0),
                      lambda s: np.full_like(s, phi), "fluid", g, rho, noise,
                      fluid_nu=eta0 / rho)
        res, err = tool("viscosity", p, "--nu", str(nu))
        if res is None:
            check(f"b) viscosity runs ({label})", False, err)
            continue
        pr = res["profile"]
        y = np.array(pr["y"])
        e = np.array([np.nan if x is None else x for x in pr["eta_over_eta0"]])
        region = (np.abs(y) > w / 4) & (np.abs(y) < w - 2 * a)
        worst = float(np.max(np.abs(e[region] - 1)))
        check(f"b) parabola ({label}): eta(y) / eta_0 = 1 within {tol:g} over w/4 < |y| < w - 2a",
              worst < tol, worst)
        if label != "exact":
            # two noisy realisations (--with) merged with their mirror images (--mirror): four
            # times the samples, so the noise of eta falls; the same curve within the tolerance
            q = os.path.join(tmp, "parabola_noise_b")
            viscosity_run(q, w, a, n, lambda s: f * (w * w - s * s) / (2 * eta0),
                          lambda s: np.full_like(s, phi), "fluid", g, rho, noise,
                          fluid_nu=eta0 / rho, seed=7)
            res2, err2 = tool("viscosity", p, "--with", q, "--mirror", "--nu", str(nu))
            if res2 is None:
                check("b) --with --mirror runs", False, err2)
            else:
                e2 = np.array([np.nan if x is None else x
                               for x in res2["profile"]["eta_over_eta0"]])
                worst2 = float(np.max(np.abs(e2[region] - 1)))
                symmetric = np.allclose(e2, e2[::-1], equal_nan=True)
                check("b) --with and --mirror: eta(y) / eta_0 = 1 within the tolerance, and "
                      "mirror-symmetric", worst2 < tol and symmetric, worst2)
        if label == "exact":
            d = res["compare"]["particles"]["max_relative_difference"]
            check("b) eq 5.29 with the particles' uniform phi agrees to 1e-6", d < 1e-6, d)
            check("b) eta_0 from eq 5.29 with --nu", rel(res["eta0"], eta0) < 1e-12, res["eta0"])
            res, err = tool("viscosity", p)
            check("b) without --nu: eta_0 = rho nu_eff of the uniform suspension's Poiseuille "
                  "profile (eq 4.49, force rho g (1 - phi))",
                  res is not None and rel(res["eta0"], eta0) < 1e-9
                  and "measured" in res["eta0_from"], err if res is None else res["eta0"])
    # b) layering: a wiggle of 10 % of the centre speed (period 6 a) on the parabola
    p = os.path.join(tmp, "wiggle")
    viscosity_run(p, w, a, n, lambda s: f * (w * w - s * s) / (2 * eta0) * 1.0
                  + 0.1 * f * w * w / (2 * eta0) * np.cos(2 * math.pi * s / 6),
                  lambda s: np.full_like(s, phi), "fluid", g, rho)
    res, err = tool("viscosity", p, "--nu", str(nu))
    check("b) a wiggled parabola: the auto degree (< 8) keeps eta >= 0",
          res is not None and res["eta_positive"] and max(res["degree"]) < 8,
          err if res is None else res["degree"])
    res, err = tool("viscosity", p, "--nu", str(nu), "--degree", "8")
    check("b) the same at --degree 8: eta < 0 somewhere (why the degree is chosen)",
          res is not None and not res["eta_positive"], err)
    # c) a plug: phi(y) = phi (1 + 0.4 cos(pi y / w)), eta of eq 5.29, f = rho g
    eta_f = rho * nu
    phis = lambda s: phi * (1 + 0.4 * np.cos(math.pi * s / w))  # noqa: E731
    fine = np.linspace(0, w, 20001)
    gdot = -rho * g * fine / (eta_f * (1 - phis(fine) / 0.82) ** -2)
    vfine = -np.concatenate([[0], np.cumsum(0.5 * (gdot[1:] + gdot[:-1]) * np.diff(fine))])
    vfine = vfine[-1] - vfine  # v(w) = 0
    p = os.path.join(tmp, "plug")
    viscosity_run(p, w, a, n, lambda s: np.interp(np.abs(s), fine, vfine), phis,
                  "fluid+colloids", g, rho)
    yc = (np.arange(400) + 0.5) * 2 * w / 400 - w
    steady = os.path.join(tmp, "steady.h5")
    narrows_h5.write_observables(steady, series={"steady_density": {
        "step": np.array([0]), "time": np.array([0.0]), "value": phis(yc)[:, None],
        "bins": yc}})
    res, err = tool("viscosity", p, "--nu", str(nu), "--continuum", steady, "--degree", "10")
    if res is None:
        check("c) viscosity runs (plug)", False, err)
        return
    for name in ("continuum", "particles"):
        d = res["compare"][name]["max_relative_difference"]
        check(f"c) plug: eq 5.33 = eq 5.29 ({name}' phi) within 0.3 %", d is not None and d < 0.003,
              d)
    check("c) a PNG", os.path.getsize(os.path.join(p, "segregation_viscosity.png")) > 0)
    done = subprocess.run([sys.executable, TOOL, "viscosity", p, "--nu", str(nu)],
                          capture_output=True, text=True)
    check("c) the text output names the acceptance number",
          done.returncode == 0 and "largest |relative difference|" in done.stdout, done.stderr)


# ---- e) velocity ----------------------------------------------------------------------------


def test_velocity(tmp):
    w, bins, n_win = 10.0, 80, 6
    y = (np.arange(bins) + 0.5) * 2 * w / bins
    s = y - w
    value = np.empty((n_win, 2, bins))
    weight = np.ones((n_win, 2, bins))
    value[0] = 0.1 * (1 - (s / w) ** 2)  # the uniform suspension: v0 = 0.1, no slip
    value[1:4] = 0.2
    value[4:] = 0.26
    weight[4:] = 3.0
    weight[1:, 1] *= 2.0  # kind 1 weighs twice kind 0 (it does not change the merged plug)
    step = (np.arange(n_win) + 1) * 1000
    p = os.path.join(tmp, "vel")
    write(p, scene(w, 40, [(1.0, 10), (0.5, 20)]), {"colloid_velocity_profile": {
        "step": step, "time": step * 0.01, "value": value, "weight": weight, "bins": y}})
    res, err = tool("velocity", p)
    if res is None:
        check("e) velocity runs", False, err)
        return
    # the last K = 4 windows (2..5): (0.2 * 1 * 2 + 0.26 * 3 * 2) / (2 + 6) = 0.245
    check("e) steady centre: the last 4 windows weight-merged = 0.245",
          rel(res["steady_centre"], 0.245) < 1e-12, res["steady_centre"])
    check("e) the uniform parabola of the first window: v0 = 0.1, wall 0",
          rel(res["uniform_v0"], 0.1) < 1e-9 and abs(res["uniform_wall"]) < 1e-9,
          (res["uniform_v0"], res["uniform_wall"]))
    res, err = tool("velocity", p, "--from-step", "5000")
    check("e) --from-step 5000: the last two windows = 0.26",
          res is not None and rel(res["steady_centre"], 0.26) < 1e-12, err)


# ---- d) fig 5.4 ------------------------------------------------------------------------------


def poiseuille_run(path, phi, nu_f, dims, phim, observable="velocity_profile"):
    w, lx, a, g, rho = 20.0, 100.0, 2.0, 0.001, 10.0
    volume = lx * 2 * w * (lx if dims == 3 else 1)
    body = math.pi * a * a if dims == 2 else 4 / 3 * math.pi * a ** 3
    n = int(round(phi * volume / body))
    phi_true = n * body / volume
    nu = nu_f * (1 - phi_true / phim) ** -2
    g_eff = g * (1 - phi_true)
    y = (np.arange(80) + 0.5) * 2 * w / 80
    v = g_eff / (2 * nu) * y * (2 * w - y)
    step = np.arange(1, 11) * 100
    series = {}
    if observable == "velocity_profile":
        prof = np.zeros((10, 80, dims))
        prof[:, :, 0] = v
        series["velocity_profile"] = {"step": step, "time": step * 0.01, "value": prof, "bins": y}
    else:
        series["viscosity"] = {"step": step, "time": step * 0.01,
                               "value": np.full(10, g / (2 * (g_eff / (2 * nu))))}
    write(path, scene(w, lx, [(a, n)] if n else [], g=g, rho=rho, dims=dims), series)
    return phi_true


def test_fig54(tmp):
    paths = []
    for i, phi in enumerate((0.0, 0.1, 0.2, 0.3, 0.4)):
        p = os.path.join(tmp, f"u2_{i}")
        poiseuille_run(p, phi, 0.8, 2, 0.82, "viscosity" if i == 3 else "velocity_profile")
        paths.append(p)
    res, err = tool("fig54", *paths)
    if res is None:
        check("d) fig54 runs", False, err)
        return
    worst = max(abs(r["ratio"] - 1) for r in res["runs"])
    check("d) 2D: eta/eta_f = eq 5.29 (phi_M 0.82) to 1e-9", worst < 1e-9, worst)
    check("d) 2D: four suspensions, nu_f from the run without colloids",
          len(res["runs"]) == 4 and rel(res["nu_f"], 0.8) < 1e-9, res["nu_f"])
    check("d) the viscosity observable is used when there is no velocity_profile",
          any(r["from"] == "viscosity observable" for r in res["runs"]))
    # eq 4.49 with g as applied (fluid-only drive): the force per volume over rho is g (1 - phi)
    worst = max(abs(r["eta_over_eta_f_applied_g"] * (1 - r["phi"]) / r["eta_over_eta_f"] - 1)
                for r in res["runs"])
    check("d) 'g applied' = eta/eta_f / (1 - phi) with the fluid-only drive", worst < 1e-9, worst)
    paths3 = []
    for i, phi in enumerate((0.1, 0.3)):
        p = os.path.join(tmp, f"u3_{i}")
        poiseuille_run(p, phi, 0.6, 3, 0.64)
        paths3.append(p)
    res, err = tool("fig54", *paths3, "--nu", "0.6")
    check("d) 3D with --nu: eq 5.29 with phi_M = 0.64 to 1e-9",
          res is not None and res["max_packing"] == 0.64
          and max(abs(r["ratio"] - 1) for r in res["runs"]) < 1e-9, err)
    done = subprocess.run([sys.executable, TOOL, "fig54", *paths3], capture_output=True,
                          text=True)
    check("d) no pure fluid and no --nu: exit 2, one line naming --nu",
          done.returncode == 2 and "--nu" in done.stderr and len(done.stderr.splitlines()) == 1,
          done.stderr)
    done = subprocess.run([sys.executable, TOOL, "viscosity", paths[0]], capture_output=True,
                          text=True)
    check("d) viscosity of a run without colloid observables: exit 2, one line",
          done.returncode == 2 and len(done.stderr.splitlines()) == 1, done.stderr)


def test_auto(tmp, narrows):
    os.environ["NARROWS"] = narrows  # the binary under test, for every call below
    p = os.path.join(tmp, "plug")
    done = subprocess.run([sys.executable, TOOL, "viscosity", p, "--nu", "0.5", "--continuum",
                           "auto", "--diffusivity", "0.00137", "--json"], capture_output=True,
                          text=True, env=dict(os.environ, NARROWS=narrows))
    if done.returncode != 0:
        check("f) viscosity --continuum auto runs", False, done.stderr)
        return
    res = json.loads(done.stdout)
    phim, phibar = res["max_packing"], res["phi"]
    y = np.array(res["profile"]["y"])
    rel_eta = np.array(res["profile"]["eq_5_29_continuum"], float)
    phi = phim * (1 - (1 - phibar / phim) / np.sqrt(rel_eta))
    check("f) the continuum phi(y) has the run's mean fraction (1e-4)",
          rel(phi.mean(), phibar) < 1e-4, (phi.mean(), phibar))
    check("f) the continuum phi(y) is enriched at the centre",
          np.interp(0.0, y, phi) > phibar, np.interp(0.0, y, phi))
    res, err = tool("viscosity", p, "--nu", "0.5", "--continuum", "auto")
    check("f) without --diffusivity: D_0 of Stokes-Einstein with --nu",
          res is not None and "Stokes-Einstein" in res["compare"]["continuum"]["from"], err)
    done = subprocess.run([sys.executable, TOOL, "viscosity", os.path.join(tmp, "parabola_exact"),
                           "--continuum", "auto"], capture_output=True, text=True,
                          env=dict(os.environ, NARROWS=narrows))
    check("f) auto without --diffusivity and without nu: exit 2, one line naming --diffusivity",
          done.returncode == 2 and "--diffusivity" in done.stderr
          and len(done.stderr.splitlines()) == 1, done.stderr)


def main():
    with tempfile.TemporaryDirectory() as tmp:
        test_evolution(tmp)
        test_viscosity(tmp)
        test_fig54(tmp)
        test_velocity(tmp)
        if len(sys.argv) > 1:
            test_auto(tmp, sys.argv[1])
    return summary()


if __name__ == "__main__":
    sys.exit(main())
