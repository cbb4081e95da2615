#!/usr/bin/python3
"""Plots of a kmc run (observables.h5 of `narrows run` with engine "kmc").

- density profile of each state, with the shock position when the run tracked one;
- current against density: the preset's theory curve (eq 2.48 with 2.59, or eq 2.126) and the
  measured point of each file given (bulk density, mean current, error bars);
- shock position: mean and variance against time, with the theory v_s and D_s;
- charge profiles at several times against the solution of the hydrodynamic equation
  d sigma/dt + d j(sigma)/dx = 0 (Tabatabaei (2008) eq 2.60; family 1 flux from eq 2.48 with
  rho*(sigma) of eq 2.59, family 2 eq 2.126): this tool does not solve it, the continuum engine
  does (`narrows run` of a conservation-law scene written from the kmc run's own scene: the
  preset's rates, the measured profile at the first sample coarse-grained into cells of B sites as
  the initial cell averages, the two end values held as reservoirs, samples at the kmc sample
  times).

Usage: tools/kmc_plot.py OUT/observables.h5 [MORE.h5 ...] [--png FILE] [--block B]
                         [--narrows PATH]
Prints the distance between the coarse-grained measured profile and the hydrodynamic solution
(mean |difference| per site over the jump |sigma_left - sigma_right|) at each plotted time.
"""
import argparse
import sys

import numpy as np

import narrows_h5
from continuum_run import find_narrows, kmc_flux_lines, run_continuum


def continuum_solution(narrows, kmc_scene_text, cells0, b, times):
    """Cell averages at `times` (the kmc sample times, equally spaced from 0) of the continuum
    engine started from cells0 (cells of b sites), with the kmc preset's flux."""
    n = len(cells0)
    values = ", ".join(repr(float(x)) for x in cells0)
    t, value = run_continuum(
        narrows,
        kmc_flux_lines(kmc_scene_text) + f"length = {float(n * b)!r}\ncells = {n}\n"
        f'boundary = "open"\ninitial = {{ kind = "cells", values = [{values}] }}\n'
        f"time = {float(times[-1])!r}\nsamples = {len(times) - 1}\n", ("density",))["density"]
    if not np.allclose(t, times, rtol=1e-9, atol=1e-9 * times[-1]):
        sys.exit("kmc_plot.py: continuum sample times differ from the kmc ones")
    return value


def block(x, b):
    n = len(x) // b
    return x[: n * b].reshape(n, b).mean(axis=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--png", default=None, help="output PNG (default: next to the first file)")
    ap.add_argument("--block", type=int, default=10, help="sites per coarse-graining block")
    ap.add_argument("--narrows", default=None, help="the narrows binary (default: build/narrows)")
    args = ap.parse_args()

    plt = narrows_h5.pyplot()

    run = narrows_h5.open_run(args.files[0])
    run.require_engine("kmc")
    names = run.names()  # the observables of the first file
    panels = ["profile", "current"]
    if "shock_position" in names:
        panels.append("shock")
    if "charge_profile" in names and "current_theory" in names:
        panels.append("hydro")
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.2))

    # density profile
    ax = axes[panels.index("profile")]
    profile = run.series("density_profile")
    d = profile["value"][-1]
    sites = profile["bins"]
    for n in range(3):
        ax.plot(sites, d[:, n], label=f"P(n = {n})")
    if "shock_position" in names:
        ax.axvline(run.series("shock_position")["value"][-1], color="k", ls=":",
                   label="shock (last)")
    ax.set_xlabel("site")
    ax.set_ylabel("occupation probability")
    ax.set_title("density profile (time average)")
    ax.legend(fontsize=8)

    # current against density
    ax = axes[panels.index("current")]
    if "current_theory" in names:
        theory = run.series("current_theory")
        dens = theory["bins"]
        ax.plot(dens, theory["value"][0], "k-", label="theory (preset)")
    family1 = "current_theory" in names and run.series("current_theory")["bins"][0] < 0
    for name in args.files:
        f = narrows_h5.open_run(name)
        f.require_engine("kmc")
        if f.has("shock_position"):  # a moving shock: the time average is no stationary state
            continue
        p = f.series("density_profile")["value"][-1]
        pe = f.series("density_profile_error")["value"][-1]
        L = p.shape[0]
        bulk = slice(L // 4, L - L // 4)
        if family1:  # charge sigma = P(A) - P(B), A = state 0, B = state 2
            x = (p[bulk, 0] - p[bulk, 2]).mean()
            xe = np.sqrt((pe[bulk, 0] ** 2 + pe[bulk, 2] ** 2).mean() / max(1, bulk.stop - bulk.start))
        else:  # particles rho = P(1) + P(2)
            x = (p[bulk, 1] + p[bulk, 2]).mean()
            xe = np.sqrt((pe[bulk, 1] ** 2 + pe[bulk, 2] ** 2).mean() / max(1, bulk.stop - bulk.start))
        j = f.series("current_mean")["value"][-1]
        je = f.series("current_mean_error")["value"][-1]
        ax.errorbar([x], [j], xerr=[xe], yerr=[je], fmt="o", ms=4)
        print(f"{name}: bulk density {x:.5f}, current {j:.5f} +- {je:.2g}")
    ax.set_xlabel("charge sigma" if family1 else "particle density rho")
    ax.set_ylabel("current j")
    ax.set_title("current against density")
    ax.legend(fontsize=8)

    if "shock" in panels:
        ax = axes[panels.index("shock")]
        shock = run.series("shock_position")
        t = shock["time"]
        m = shock["value"]
        var = run.series("shock_position_variance")["value"]
        ax.errorbar(t, m - m[0], yerr=run.series("shock_position_error")["value"], fmt=".",
                    label="mean displacement")
        ax.errorbar(t, var - var[0], yerr=run.series("shock_position_variance_error")["value"],
                    fmt=".", label="variance growth")
        if "shock_theory" in names:
            v, D = run.series("shock_theory")["value"][0]
            ax.plot(t, v * t, "C0-", label=f"v t (v = {v:.4g})")
            ax.plot(t, 2 * D * t, "C1-", label=f"2 D t (D = {D:.4g})")
        ax.set_xlabel("time")
        ax.set_ylabel("sites, sites$^2$")
        ax.set_title("shock position")
        ax.legend(fontsize=8)

    if "hydro" in panels:
        ax = axes[panels.index("hydro")]
        charge = run.series("charge_profile")
        q = charge["value"]
        t = charge["time"]
        b = max(1, args.block)
        x = block(charge["bins"], b)
        picks = sorted(set([0, len(t) // 3, 2 * len(t) // 3, len(t) - 1]))
        scene_text = run.scene_text()
        solution = continuum_solution(find_narrows(args.narrows), scene_text, block(q[0], b), b, t)
        hydro = [solution[i] for i in picks]
        jump = abs(block(q[0], b)[0] - block(q[0], b)[-1])
        for c, (i, h) in enumerate(zip(picks, hydro)):
            meas = block(q[i], b)
            ax.plot(x, meas, ".", color=f"C{c}", ms=3)
            ax.plot(x, h, "-", color=f"C{c}", label=f"t = {t[i]:.4g}")
            dist = np.abs(meas - h).mean() / max(jump, 1e-12)
            still = np.abs(meas - block(q[0], b)).mean() / max(jump, 1e-12)
            print(f"t = {t[i]:.6g}: |measured - hydrodynamic| / jump = {dist:.4f} "
                  f"(|measured - initial| / jump = {still:.4f})")
        ax.set_xlabel("site")
        ax.set_ylabel("charge per site")
        ax.set_title("charge profile: kmc (dots), continuum engine, eq 2.60 (lines)")
        ax.legend(fontsize=8)

    fig.tight_layout()
    png = args.png or args.files[0].rsplit("/", 1)[0] + "/kmc.png"
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("kmc_plot", main))
