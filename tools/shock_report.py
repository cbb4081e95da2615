#!/usr/bin/python3
"""One shock two ways (issue 22, item 4, the kmc half): the three-state lattice gas (a kmc run
with a shock, e.g. run/kmc_family2_shock.toml) against the conservation law of its preset's flux
(Tabatabaei (2008) eq 2.60 / 2.126), solved by the continuum engine from the same Riemann data:
the two densities are the kmc run's mean densities away from the shock, held as reservoirs.

One PNG with three panels: density profiles at four times (kmc dots; continuum, sharp; the
continuum shock smeared by the kmc shock's random walk, a Gaussian of variance 2 D_s t, dashed),
the mean shock position against time (kmc, continuum, Rankine-Hugoniot, Tabatabaei's v_s), and
its variance (kmc against 2 D_s t). A table of shock speed and diffusion constant from each
source is printed and written next to the PNG (same name, .txt).

Three ways (issue 22 item 4, --chain RUN_DIR): a second row for a sedimenting colloid chain, an
mpcd run with colloids (run/sedimentation_chain_31.toml, Tabatabaei (2008) §4.5 and ch.5; see
chain_shock.py): the chain's line density at four times against the continuum engine's colloid-chain flux (eq
5.3, c and c' of --c, --c-prime; co-moving frame, v_cm = 0), the head shock's position against
time (mpcd, continuum, Rankine-Hugoniot c rho0 + c'), and the mean square of its displacement
about the mean drift against the lag (2 D_s tau). The table gains the chain's rows.
tools/shock_three_ways.sh runs all three and writes the report with one command.

Usage: tools/shock_report.py KMC_OUT/observables.h5 [--png FILE] [--block B] [--narrows PATH]
                             [--chain MPCD_RUN_DIR [--c C] [--c-prime C1]]
"""
import argparse
import math
import os
import sys

import numpy as np

import narrows_h5
from chain_shock import (continuum_chain, density, fit_line, read_chain,
                         speed_and_diffusion)
from continuum_run import find_narrows, kmc_flux_lines, run_continuum


def block(x, b):
    n = len(x) // b
    return x[: n * b].reshape(n, b).mean(axis=1)


def fit_slope(t, y, err):
    """Weighted least-squares slope of y(t) and its standard error."""
    w = 1.0 / np.maximum(err, 1e-12) ** 2
    A = np.vstack([np.ones_like(t), t]).T
    cov = np.linalg.inv(A.T @ (A * w[:, None]))
    coef = cov @ (A.T @ (w * y))
    return coef[1], math.sqrt(cov[1, 1])


def smeared(profile, sigma):
    """profile convolved with a Gaussian of standard deviation sigma (cells), ends held."""
    if sigma <= 0:
        return profile
    half = int(math.ceil(4 * sigma))
    g = np.exp(-0.5 * (np.arange(-half, half + 1) / sigma) ** 2)
    g /= g.sum()
    ext = np.concatenate([np.full(half, profile[0]), profile, np.full(half, profile[-1])])
    return np.convolve(ext, g, mode="valid")


def three_ways(narrows, args):
    """The colloid chain's rows of the table and its row of panels (a function of three axes)."""
    ch = read_chain(args.chain)
    t, x = ch["t"], ch["x"]
    half = 0.5 / ch["rho0"]
    xs = x.max(axis=1) + half  # the front colloid (they pass each other in a zigzag) + d0/2
    v, v_err, D, D_err, tau, msd = speed_and_diffusion(t, xs)
    tc, xc, rho_c, xs_c = continuum_chain(narrows, ch, args.c, args.c_prime)
    ok = np.isfinite(xs_c)
    v_c = fit_line(tc[ok][len(tc[ok]) // 2:], xs_c[ok][len(tc[ok]) // 2:])[1]
    rh = args.c * ch["rho0"] + args.c_prime
    rh_fig5_1 = 5.71 * ch["rho0"] / float(ch["scene"]["domain"]["size"][1]) + 0.019
    mid = x[:, x.shape[1] // 3: 2 * x.shape[1] // 3].mean(axis=1)  # the chain's middle third
    v_mid = fit_line(t, mid)[1]
    # The same law with c from the chain's own bulk: c rho0 + c' = the middle third's speed.
    c_bulk = (v_mid - args.c_prime) / ch["rho0"]
    tb, _, _, xs_b = continuum_chain(narrows, ch, c_bulk, args.c_prime)
    okb = np.isfinite(xs_b)
    v_b = fit_line(tb[okb][len(tb[okb]) // 2:], xs_b[okb][len(tb[okb]) // 2:])[1]
    L = ch["L"]
    table = [f"colloid chain: {x.shape[1]} colloids at spacing {ch['d0']:.4g} (rho0 = "
             f"{ch['rho0']:.4g} per length) in a {L:g} channel, t = {t[0]:g} .. {t[-1]:g}, "
             f"frame of the centre of mass (mean v_cm {np.mean(ch['v_cm']):.3g})",
             "| source | speed (length/time, along gravity) | diffusion D_s |", "|---|---|---|",
             f"| colloid chain, mpcd (front colloid + d0/2: slope; residual MSD over lags "
             f"{tau[0]:.3g}-{tau[-1]:.3g}) | {v:.5g} +- {v_err:.2g} | {D:.5g} +- {D_err:.2g} |",
             f"| colloid chain, continuum engine (flux colloid-chain, c = {args.c:g}, c' = "
             f"{args.c_prime:g}, D = 0) | {v_c:.5g} | 0 |",
             f"| colloid chain, Rankine-Hugoniot c rho0 + c' | {rh:.5g} | |",
             f"| colloid chain, Rankine-Hugoniot with Tabatabaei (2008) fig 5.1's c = 5.71, "
             f"c' = 0.019 (rho read as colloids per unit area, rho0 / L_y) | {rh_fig5_1:.5g} | |",
             f"| colloid chain, mpcd middle third (bulk settling velocity, for c rho0 + c') | "
             f"{v_mid:.5g} | |",
             f"| colloid chain, continuum engine with c = {c_bulk:.4g} from that bulk velocity "
             f"| {v_b:.5g} | 0 |"]

    def plot(axes):
        ax = axes[0]
        picks = sorted(set([0, len(t) // 3, 2 * len(t) // 3, len(t) - 1]))
        width = 2.0 / ch["rho0"]
        lo = x.min() - width
        edges = lo + width * np.arange(int((x.max() - lo) / width) + 3)
        for k, i in enumerate(picks):
            near = slice(max(0, i - 2), min(len(t), i + 3))  # five samples around t_i
            rho = np.mean([density(row, edges) for row in x[near]], axis=0)
            ax.step(edges[:-1], rho, where="post", color=f"C{k}", lw=1)
            j = int(np.argmin(np.abs(tc - t[i])))
            ax.plot(xc, rho_c[j], "--", color=f"C{k}", lw=1, label=f"t = {t[i]:.4g}")
        ax.set_xlabel("x along gravity (co-moving frame)")
        ax.set_ylabel("colloids per unit length")
        ax.set_title(f"colloid chain: mpcd (steps, bins of {width:g}), continuum (dashed)",
                     fontsize=9)
        ax.legend(fontsize=8)
        ax = axes[1]
        ax.plot(t, xs, ".", ms=2, label=f"mpcd front colloid + d0/2 ({v:.4g})")
        ax.plot(tc[ok], xs_c[ok], "-", label=f"continuum engine ({v_c:.4g})")
        ax.plot(t, xs[0] + rh * (t - t[0]), ":", color="k", label=f"Rankine-Hugoniot ({rh:.4g})")
        ax.plot(tb[okb], xs_b[okb], "-.", label=f"continuum, c from the bulk ({v_b:.4g})")
        ax.set_xlabel("time")
        ax.set_ylabel("head shock position")
        ax.set_title("colloid chain: shock position")
        ax.legend(fontsize=8)
        ax = axes[2]
        ax.plot(tau, msd, "o", label="mpcd: increments about the mean drift")
        ax.plot(tau, 2 * D * tau, "-", label=f"2 D_s tau (D_s = {D:.3g})")
        ax.set_xlabel("lag tau")
        ax.set_ylabel("mean square displacement")
        ax.set_title("colloid chain: shock spread (continuum: sharp, 0)")
        ax.legend(fontsize=8)

    return {"table": table, "plot": plot}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("kmc", help="observables.h5 of a kmc run with a shock (kmc.samples > 0)")
    ap.add_argument("--png", default=None, help="output PNG (default: next to the kmc file)")
    ap.add_argument("--block", type=int, default=10, help="sites per coarse-graining block")
    ap.add_argument("--narrows", default=None, help="the narrows binary (default: build/narrows)")
    ap.add_argument("--chain", default=None,
                    help="three ways: the run directory of a sedimenting colloid chain (mpcd)")
    ap.add_argument("--c", type=float, default=0.1605,
                    help="c of eq 5.2 for the chain, velocity x length (default: the settling "
                    "velocities of run/sedimentation_1000.toml, 0.02057 and 0.03341 at "
                    "10 and 90 colloids per 1000)")
    ap.add_argument("--c-prime", type=float, default=0.0190,
                    help="c' of eq 5.2, the settling velocity of a lone colloid (same source)")
    args = ap.parse_args()
    narrows = find_narrows(args.narrows)

    run = narrows_h5.open_run(args.kmc)
    allowed = "a kmc run with a preset and a shock (kmc.samples > 0)"
    charge, shock, theory = (run.series(need, allowed)
                             for need in ("charge_profile", "shock_position", "current_theory"))
    scene_text = run.scene_text()
    q = charge["value"]  # [samples+1][L] mean charge per site
    t = charge["time"]
    L = q.shape[1]
    x_kmc = shock["value"]
    x_err = run.series("shock_position_error")["value"]
    var = run.series("shock_position_variance")["value"]
    var_err = run.series("shock_position_variance_error")["value"]
    dens, flux = theory["bins"], theory["value"][0]
    v_theory = d_theory = None
    if run.has("shock_theory"):
        v_theory, d_theory = run.series("shock_theory")["value"][0]

    # Riemann data: the measured densities either side of the shock, averaged over all samples
    # and over the sites the shock never came within 20 sites of (and 10 from the ends).
    s0 = int(round(x_kmc[0]))
    lo, hi = int(x_kmc.min()) - 20, int(math.ceil(x_kmc.max())) + 20
    if lo <= 10 or hi >= L - 10:
        raise narrows_h5.NarrowsDataError(args.kmc, "the shock came within 30 sites of an end",
                                          "a run whose shock stays inside")
    left, right = q[:, 10:lo].mean(), q[:, hi:L - 10].mean()
    rh = (np.interp(left, dens, flux) - np.interp(right, dens, flux)) / (left - right)
    cont = run_continuum(
        narrows,
        kmc_flux_lines(scene_text) + f'length = {float(L)!r}\ncells = {L}\nboundary = "open"\n'
        f'initial = {{ kind = "riemann", left = {float(left)!r}, right = {float(right)!r}, '
        f"position = {float(s0)!r} }}\ntime = {float(t[-1])!r}\nsamples = {len(t) - 1}\n")
    tc, rho_c = cont["density"]
    _, x_c = cont["shock_position"]
    if not np.allclose(tc, t, rtol=1e-9, atol=1e-9 * t[-1]):
        sys.exit("shock_report.py: continuum sample times differ from the kmc ones")

    v_kmc, v_kmc_err = fit_slope(t, x_kmc, np.maximum(x_err, 1e-3))
    half = len(t) // 2
    v_cont = (x_c[-1] - x_c[half]) / (t[-1] - t[half])
    d_kmc, d_kmc_err = fit_slope(t, var / 2.0, np.maximum(var_err / 2.0, 1e-3))
    rows = [("kmc (weighted fit of mean position and variance)", f"{v_kmc:.5g} +- {v_kmc_err:.2g}",
             f"{d_kmc:.5g} +- {d_kmc_err:.2g}"),
            ("continuum engine (D = 0; second half of the run)", f"{v_cont:.5g}", "0"),
            ("Rankine-Hugoniot (J(l) - J(r)) / (l - r)", f"{rh:.5g}", "")]
    if v_theory is not None:
        rows.append(("Tabatabaei (2008) eq 2.115-2.116 (shock random walk)", f"{v_theory:.5g}",
                     f"{d_theory:.5g}"))
    table = [f"lattice gas: shock {left:.4f} | {right:.4f} at site {s0}, L = {L}, "
             f"t = 0 .. {t[-1]:g}",
             "| source | speed (sites/time, to the right) | diffusion D_s |", "|---|---|---|"]
    table += [f"| {a} | {b} | {c} |" for a, b, c in rows]
    chain = three_ways(narrows, args) if args.chain else None
    if chain:
        table += [""] + chain["table"]
    print("\n".join(table))

    plt = narrows_h5.pyplot()
    fig, grid = plt.subplots(2 if chain else 1, 3, figsize=(16, 8.8 if chain else 4.4),
                             squeeze=False)
    axes = grid[0]
    b = max(1, args.block)
    xb = block(np.arange(1, L + 1, dtype=float), b)
    xc = np.arange(L) + 1.0  # continuum cell i covers [i, i + 1): site i + 1
    d_use = d_theory if d_theory is not None else max(d_kmc, 0.0)
    ax = axes[0]
    picks = sorted(set([0, len(t) // 3, 2 * len(t) // 3, len(t) - 1]))
    for c, i in enumerate(picks):
        ax.plot(xb, block(q[i], b), ".", color=f"C{c}", ms=3)
        ax.plot(xc, rho_c[i], "-", color=f"C{c}", lw=1, label=f"t = {t[i]:.4g}")
        ax.plot(xc, smeared(rho_c[i], math.sqrt(2.0 * d_use * t[i])), "--", color=f"C{c}", lw=1)
    ax.set_xlabel("site")
    ax.set_ylabel("density (charge per site)")
    ax.set_title("lattice gas: kmc (dots), continuum (lines), smeared by 2 D_s t (dashed)",
                 fontsize=9)
    ax.legend(fontsize=8)

    ax = axes[1]
    ax.errorbar(t, x_kmc, yerr=x_err, fmt=".", label="kmc mean")
    ax.plot(t, x_c, "-", label="continuum engine")
    ax.plot(t, s0 + rh * t, ":", color="k", label=f"Rankine-Hugoniot ({rh:.4g})")
    if v_theory is not None:
        ax.plot(t, s0 + v_theory * t, "--", color="C3", lw=1,
                label=f"Tabatabaei v_s ({v_theory:.4g})")
    ax.set_xlabel("time")
    ax.set_ylabel("shock position (site)")
    ax.set_title("shock position")
    ax.legend(fontsize=8)

    ax = axes[2]
    ax.errorbar(t, var, yerr=var_err, fmt=".", label="kmc variance")
    if d_theory is not None:
        ax.plot(t, var[0] + 2 * d_theory * t, "-",
                label=f"2 D_s t (Tabatabaei D_s = {d_theory:.4g})")
    ax.set_xlabel("time")
    ax.set_ylabel("variance (sites$^2$)")
    ax.set_title("shock position variance (continuum: sharp, 0)")
    ax.legend(fontsize=8)

    if chain:
        chain["plot"](grid[1])
    fig.tight_layout()
    png = args.png or os.path.join(os.path.dirname(os.path.abspath(args.kmc)), "shock_report.png")
    fig.savefig(png, dpi=110)
    txt = os.path.splitext(png)[0] + ".txt"
    with open(txt, "w") as fh:
        fh.write("\n".join(table) + "\n")
    print(f"wrote {png} and {txt}")
    return 0


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("shock_report", main))
