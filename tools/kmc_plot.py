#!/usr/bin/python3
"""Plots of a kmc run (observables.h5 of `narrows run` with engine "kmc").

- density profile of each state, with the shock position when the run tracked one;
- current against density: the preset's theory curve (eq 2.48 with 2.59, or eq 2.126) and the
  measured point of each file given (bulk density, mean current, error bars);
- shock position: mean and variance against time, with the theory v_s and D_s;
- charge profiles at several times against the solution of the hydrodynamic equation
  d sigma/dt + d j(sigma)/dx = 0 (seed 000 eq 2.60; family 1 flux from eq 2.48 with rho*(sigma)
  of eq 2.59, as written by narrows into /observables/current_theory), solved by finite volumes
  with the Godunov flux, started from the measured profile at the first sample and held at the
  two end densities.

Usage: tools/kmc_plot.py OUT/observables.h5 [MORE.h5 ...] [--png FILE] [--block B]
Prints the distance between the coarse-grained measured profile and the hydrodynamic solution
(mean |difference| per site over the jump |sigma_left - sigma_right|) at each plotted time.
"""
import argparse
import sys

import h5py
import numpy as np


def godunov_flux(a, b, dens, flux):
    """Godunov flux between left states a and right states b for a tabulated flux j(u)."""
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    ja, jb = np.interp(a, dens, flux), np.interp(b, dens, flux)
    inside = (dens[None, :] >= lo[:, None]) & (dens[None, :] <= hi[:, None])
    big = np.where(inside, flux[None, :], np.inf)
    small = np.where(inside, flux[None, :], -np.inf)
    fmin = np.minimum(np.minimum(ja, jb), big.min(axis=1))
    fmax = np.maximum(np.maximum(ja, jb), small.max(axis=1))
    return np.where(a <= b, fmin, fmax)


def solve_hydro(sigma0, dx, times, dens, flux):
    """Profiles at `times` (from 0) of d sigma/dt + d j/dx = 0, cells of width dx."""
    slope = np.max(np.abs(np.gradient(flux, dens)))
    dt_max = 0.4 * dx / max(slope, 1e-12)
    left, right = sigma0[0], sigma0[-1]
    u = sigma0.astype(float).copy()
    out, t = [], 0.0
    for target in times:
        while t < target - 1e-12:
            dt = min(dt_max, target - t)
            ext = np.concatenate(([left], u, [right]))
            f = godunov_flux(ext[:-1], ext[1:], dens, flux)
            u = u - dt / dx * (f[1:] - f[:-1])
            t += dt
        out.append(u.copy())
    return out


def block(x, b):
    n = len(x) // b
    return x[: n * b].reshape(n, b).mean(axis=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("files", nargs="+")
    ap.add_argument("--png", default=None, help="output PNG (default: next to the first file)")
    ap.add_argument("--block", type=int, default=10, help="sites per coarse-graining block")
    args = ap.parse_args()

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    first = h5py.File(args.files[0], "r")["observables"]
    panels = ["profile", "current"]
    if "shock_position" in first:
        panels.append("shock")
    if "charge_profile" in first and "current_theory" in first:
        panels.append("hydro")
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.2))

    # density profile
    ax = axes[panels.index("profile")]
    d = first["density_profile/value"][-1]
    sites = first["density_profile/bins"][:]
    for n in range(3):
        ax.plot(sites, d[:, n], label=f"P(n = {n})")
    if "shock_position" in first:
        ax.axvline(first["shock_position/value"][-1], color="k", ls=":", label="shock (last)")
    ax.set_xlabel("site")
    ax.set_ylabel("occupation probability")
    ax.set_title("density profile (time average)")
    ax.legend(fontsize=8)

    # current against density
    ax = axes[panels.index("current")]
    if "current_theory" in first:
        dens = first["current_theory/bins"][:]
        ax.plot(dens, first["current_theory/value"][0], "k-", label="theory (preset)")
    family1 = "current_theory" in first and first["current_theory/bins"][0] < 0
    for name in args.files:
        f = h5py.File(name, "r")["observables"]
        if "shock_position" in f:  # a moving shock: the time average is no stationary state
            continue
        p = f["density_profile/value"][-1]
        pe = f["density_profile_error/value"][-1]
        L = p.shape[0]
        bulk = slice(L // 4, L - L // 4)
        if family1:  # charge sigma = P(A) - P(B), A = state 0, B = state 2
            x = (p[bulk, 0] - p[bulk, 2]).mean()
            xe = np.sqrt((pe[bulk, 0] ** 2 + pe[bulk, 2] ** 2).mean() / max(1, bulk.stop - bulk.start))
        else:  # particles rho = P(1) + P(2)
            x = (p[bulk, 1] + p[bulk, 2]).mean()
            xe = np.sqrt((pe[bulk, 1] ** 2 + pe[bulk, 2] ** 2).mean() / max(1, bulk.stop - bulk.start))
        j = f["current_mean/value"][-1]
        je = f["current_mean_error/value"][-1]
        ax.errorbar([x], [j], xerr=[xe], yerr=[je], fmt="o", ms=4)
        print(f"{name}: bulk density {x:.5f}, current {j:.5f} +- {je:.2g}")
    ax.set_xlabel("charge sigma" if family1 else "particle density rho")
    ax.set_ylabel("current j")
    ax.set_title("current against density")
    ax.legend(fontsize=8)

    if "shock" in panels:
        ax = axes[panels.index("shock")]
        t = first["shock_position/time"][:]
        m = first["shock_position/value"][:]
        var = first["shock_position_variance/value"][:]
        ax.errorbar(t, m - m[0], yerr=first["shock_position_error/value"][:], fmt=".",
                    label="mean displacement")
        ax.errorbar(t, var - var[0], yerr=first["shock_position_variance_error/value"][:], fmt=".",
                    label="variance growth")
        if "shock_theory" in first:
            v, D = first["shock_theory/value"][0]
            ax.plot(t, v * t, "C0-", label=f"v t (v = {v:.4g})")
            ax.plot(t, 2 * D * t, "C1-", label=f"2 D t (D = {D:.4g})")
        ax.set_xlabel("time")
        ax.set_ylabel("sites, sites$^2$")
        ax.set_title("shock position")
        ax.legend(fontsize=8)

    if "hydro" in panels:
        ax = axes[panels.index("hydro")]
        dens = first["current_theory/bins"][:]
        flux = first["current_theory/value"][0]
        q = first["charge_profile/value"][:]
        t = first["charge_profile/time"][:]
        b = max(1, args.block)
        x = block(first["charge_profile/bins"][:], b)
        picks = sorted(set([0, len(t) // 3, 2 * len(t) // 3, len(t) - 1]))
        hydro = solve_hydro(block(q[0], b), float(b), [t[i] for i in picks], dens, flux)
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
        ax.set_title("charge profile: kmc (dots), eq 2.60 (lines)")
        ax.legend(fontsize=8)

    fig.tight_layout()
    png = args.png or args.files[0].rsplit("/", 1)[0] + "/kmc.png"
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
