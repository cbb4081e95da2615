#!/usr/bin/python3
"""Plots of an lgca run (observables.h5 of `narrows run` with engine "lgca").

- shear wave: ln of the amplitude A(t) of u_x = A sin(2 pi y / L_y) against t (several files,
  e.g. runs with different seeds, are averaged), the straight-line fit over the window
  [--first, --last] and the Boltzmann decay exp(-nu k^2 t) of PHYSICS.md, k = 2 pi / L_y,
  L_y = size[1] sqrt(3)/2; prints nu from the fit (error: jackknife over the files when there
  are several) against the Boltzmann nu;
- fields (density, velocity): the last sample of u_x and of the density over the lattice;
- tagged VACF (/observables/vacf): FHP models on log-log axes, Z(t) + (1 - d)/N (eq 22) with its
  error, the power-law fit Z ~ t^-a over [--tail-first, --tail-last] (weighted by the error;
  prints a and its error) and eq 19 at t = 1; the 1D model on linear axes with the plateau
  -(1 - d)/N of eq 22 (seed 002 fig 1);
- held colloid (/observables/colloid_vacf, colloid_diffusion; seed 002 fig 3): the VACF on
  log-log axes with the power-law fit over [--colloid-first, --colloid-last], and D(t) against
  ln t with the straight-line fit over the same window and its R^2. Several files (e.g. the
  segments of a restarted run, observables-<step>.h5) are averaged with equal weights.

Usage: tools/lgca_plot.py OUT/observables.h5 [MORE.h5 ...] [--png FILE] [--first T0] [--last T1]
                          [--tail-first T0] [--tail-last T1] [--colloid-first T0] [--colloid-last T1]
"""
import argparse
import math
import tomllib

import h5py
import numpy as np


def boltzmann_nu(model, d):
    e = 1.0 - d
    if model == "fhp-i":
        return 1 / (12 * d * e**3) - 1 / 8
    if model == "fhp-ii":
        return 1 / (28 * d * e**3 * (1 - 4 * d / 7)) - 1 / 8
    if model == "fhp-iii":
        return 1 / (28 * d * e * (1 - 8 * d * e / 7)) - 1 / 8
    if model == "fhp-saturated":
        return 1 / (12 * d * e * (1 + 2 * d * e)) - 1 / 8
    raise ValueError(model)


def scene_of(f):
    text = f["parameters/scene"][()]
    if isinstance(text, bytes):
        text = text.decode()
    return tomllib.loads(text)


def fit_rate(t, a, first, last):
    sel = (t >= first) & (t <= last) & (a > 0)
    slope, icpt = np.polyfit(t[sel], np.log(a[sel]), 1)
    return -slope, icpt


def fit_tail(t, z, e, first, last):
    """Weighted least squares of ln z = c - a ln t; returns a, its error, c."""
    sel = (t >= first) & (t <= last) & (z > 0)
    x, y, w = np.log(t[sel]), np.log(z[sel]), (z[sel] / np.maximum(e[sel], 1e-300)) ** 2
    (slope, icpt), cov = np.polyfit(x, y, 1, w=np.sqrt(w), cov="unscaled")
    return -slope, math.sqrt(cov[0, 0]), icpt


def vacf_panel(ax, g, lat, args):
    z, e, lags = g["value"][()], g["error"][()], g["lags"][()]
    if lat["model"] == "dhumieres-1d":
        n = float(g["particles"][()][0])
        ax.plot(lags[1:], z[1:], lw=0.8, label=f"L = {lat['size'][0]}, N = {n:.0f}")
        ax.fill_between(lags[1:], (z - e)[1:], (z + e)[1:], alpha=0.3, lw=0)
        ax.axhline(g["plateau_theory"][()][0], ls="--", color="k", lw=0.8,
                   label="eq 22 plateau -(1 - d)/N" if g["plateau_theory"][()][0] else "0")
        lim = 10 * max(abs(g["plateau_theory"][()][0]), float(np.median(e[1:])))
        ax.set_ylim(-lim, lim)
        ax.set_xlabel("t")
        ax.set_ylabel("Z(t) = <v(0) v(t)> / <v^2>")
        ax.set_title(f"d'Humieres 1D, d = {lat['density']}")
        ax.legend(fontsize=8)
        return
    zc = g["corrected"][()]
    t = lags.astype(float)
    last = args.tail_last if args.tail_last is not None else t[-1]
    ok = zc > 0
    if ((t >= args.tail_first) & (t <= last) & ok).sum() < 3:
        print(f"{lat['model']} d = {lat['density']}: Z(1) = {z[1]:.6f} +- {e[1]:.2g}; fewer than "
              f"3 positive lags in {args.tail_first:g}..{last:g}: no tail fit")
        ax.loglog(t[1:][ok[1:]], zc[1:][ok[1:]], ".", label="Z(t) + (1 - d)/N (eq 22)")
        ax.legend(fontsize=8)
        return
    a, da, c = fit_tail(t, zc, e, args.tail_first, last)
    print(f"{lat['model']} d = {lat['density']}: Z(1) = {z[1]:.6f} +- {e[1]:.2g} (eq 19 "
          f"{g['one_step_theory'][()][0]:.6f}); tail Z + (1-d)/N ~ t^-a, a = {a:.4f} +- {da:.4f} "
          f"over lags {args.tail_first:g}..{last:g} ({int(g['curves'][()][0])} curves; the error "
          f"treats lags as independent and understates the spread of independent runs)")
    ax.errorbar(t[1:][ok[1:]], zc[1:][ok[1:]], yerr=e[1:][ok[1:]], fmt=".", ms=3, lw=0.5,
                label="Z(t) + (1 - d)/N (eq 22)")
    tt = np.array([args.tail_first, last])
    ax.loglog(tt, 1.3 * np.exp(c) * tt ** -a, "-", color="C3", lw=2, zorder=3, label=f"fit (x 1.3 for visibility): t^-{a:.3f}")
    t0 = float(g["mean_free_time"][()][0])
    tb = np.linspace(1, min(t[-1], 15 * t0), 50)
    ax.loglog(tb, g["one_step_theory"][()][0] ** tb, "--", lw=0.8, label="Boltzmann Z(1)^t")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("t")
    ax.set_ylabel("Z(t)")
    ax.set_title(f"tagged VACF, {lat['model']}, d = {lat['density']}, "
                 f"{lat['size'][0]} x {lat['size'][1]}")
    ax.legend(fontsize=8)


def colloid_panel(ax, name, groups, args):
    lags = groups[0]["lags"][()].astype(float)
    vals = np.array([g["value"][()] for g in groups])
    errs = np.array([g["error"][()] for g in groups])
    v = vals.mean(axis=0)
    e = np.sqrt((errs**2).sum(axis=0)) / len(groups)
    last = args.colloid_last if args.colloid_last is not None else lags[-1]
    sel = (lags >= args.colloid_first) & (lags <= last)
    if name == "colloid_vacf":
        ok = sel & (v > 0)
        ax.errorbar(lags[1:], np.abs(v[1:]), yerr=e[1:], fmt=".", ms=2, lw=0.3,
                    label="|Z(t)| of the held colloid")
        if ok.sum() >= 3:
            a, c = np.polyfit(np.log(lags[ok]), np.log(v[ok]), 1)
            print(f"colloid VACF: Z ~ t^{a:.3f} over lags {args.colloid_first:g}..{last:g} "
                  f"({ok.sum()} positive of {sel.sum()} lags); Z({int(last)}) = "
                  f"{v[lags == last][0]:.4g} +- {e[lags == last][0]:.2g}")
            tt = np.array([args.colloid_first, last])
            ax.loglog(tt, np.exp(c) * tt**a, "-", color="C3", label=f"fit t^{a:.2f}")
            ax.loglog(tt, np.exp(c) * tt[0] ** (a + 1) / tt, "--", color="k", label="slope -1")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("t")
        ax.set_ylabel("Z(t) = <U(0).U(t)> / <U^2>")
        ax.set_title("held colloid: velocity autocorrelation")
    else:
        ok = sel & (lags > 0)
        ax.errorbar(np.log(lags[lags > 0]), v[lags > 0], yerr=e[lags > 0], fmt=".", ms=3,
                    label="D(t) = <|X(t) - X(0)|^2> / 4t")
        if ok.sum() >= 3:
            x, y = np.log(lags[ok]), v[ok]
            (k, c) = np.polyfit(x, y, 1)
            r2 = 1 - ((y - (k * x + c)) ** 2).sum() / ((y - y.mean()) ** 2).sum()
            print(f"colloid D(t) = {k:.4g} ln t + {c:.4g} over lags {args.colloid_first:g}.."
                  f"{last:g}: R^2 = {r2:.4f}")
            ax.plot(x, k * x + c, "-", color="C3", label=f"fit {k:.3g} ln t + {c:.3g}, R^2 = {r2:.3f}")
        ax.set_xlabel("ln t")
        ax.set_ylabel("D(t)")
        ax.set_title("held colloid: virtual diffusion coefficient")
    ax.legend(fontsize=8)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("files", nargs="+")
    ap.add_argument("--png", default="lgca.png")
    ap.add_argument("--first", type=float, default=20.0, help="first step of the fit window")
    ap.add_argument("--last", type=float, default=None,
                    help="last step of the fit window (default: A fallen by e^-1.5, Boltzmann)")
    ap.add_argument("--tail-first", type=float, default=20.0, help="first lag of the VACF tail fit")
    ap.add_argument("--tail-last", type=float, default=None,
                    help="last lag of the VACF tail fit (default: the last lag)")
    ap.add_argument("--colloid-first", type=float, default=100.0,
                    help="first lag of the colloid VACF and D(t) fits")
    ap.add_argument("--colloid-last", type=float, default=None,
                    help="last lag of the colloid fits (default: the last lag)")
    args = ap.parse_args()

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    files = [h5py.File(p, "r") for p in args.files]
    scene = scene_of(files[0])
    lat = scene["lattice"]
    obs = files[0]["observables"]
    panels = []
    if "shear_wave" in obs:
        panels.append("shear")
    if "velocity" in obs or "density" in obs:
        panels.append("fields")
    if "vacf" in obs:
        panels.append("vacf")
    if "colloid_vacf" in obs:
        panels += ["colloid_vacf", "colloid_diffusion"]
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4.5), squeeze=False)
    for ax, panel in zip(axes[0], panels):
        if panel == "shear":
            t = obs["shear_wave/step"][()].astype(float)
            runs = np.array([f["observables/shear_wave/value"][()] for f in files])
            a = runs.mean(axis=0)
            ly = lat["size"][1] * math.sqrt(3) / 2
            k = 2 * math.pi / ly
            nu0 = boltzmann_nu(lat["model"], lat["density"])
            last = args.last if args.last is not None else min(t[-1], 1.5 / (nu0 * k * k))
            rate, icpt = fit_rate(t, a, args.first, last)
            nu = rate / k**2
            err = 0.0
            if len(runs) > 1:
                jk = np.array([fit_rate(t, np.delete(runs, i, 0).mean(axis=0), args.first, last)[0]
                               for i in range(len(runs))]) / k**2
                err = math.sqrt((len(jk) - 1) / len(jk) * ((jk - jk.mean()) ** 2).sum())
            print(f"{lat['model']} d = {lat['density']}: nu = {nu:.5f} +- {err:.5f} "
                  f"(Boltzmann {nu0:.5f}, {100 * (nu / nu0 - 1):+.2f} %) from steps "
                  f"{args.first:g}..{last:g} of {len(runs)} run(s)")
            ax.semilogy(t, np.abs(a), ".", ms=3, label=f"measured ({len(runs)} run(s))")
            tt = np.linspace(0, t[-1], 200)
            ax.semilogy(tt, np.exp(icpt - rate * tt), "-",
                        label=f"fit {args.first:g}..{last:g}: nu = {nu:.4f} +- {err:.4f}")
            ax.semilogy(tt, a[0] * np.exp(-nu0 * k * k * tt), "--", label=f"Boltzmann nu = {nu0:.4f}")
            ax.set_xlabel("step")
            ax.set_ylabel("shear-wave amplitude")
            ax.set_title(f"{lat['model']}, d = {lat['density']}, {lat['size'][0]} x {lat['size'][1]}")
            ax.legend(fontsize=8)
        elif panel == "vacf":
            vacf_panel(ax, obs["vacf"], lat, args)
        elif panel.startswith("colloid"):
            colloid_panel(ax, panel, [f["observables/" + panel] for f in files], args)
        else:
            if "velocity" in obs:
                u = obs["velocity/value"][-1]
                im = ax.imshow(u[:, :, 0], origin="lower", aspect="auto", cmap="viridis")
                fig.colorbar(im, ax=ax, label="u_x (block average)")
                ax.set_title(f"u_x at step {obs['velocity/step'][-1]}")
            else:
                rho = obs["density/value"][-1]
                im = ax.imshow(rho, origin="lower", aspect="auto", cmap="viridis")
                fig.colorbar(im, ax=ax, label="particles per site (block average)")
                ax.set_title(f"density at step {obs['density/step'][-1]}")
            ax.set_xlabel("block along x")
            ax.set_ylabel("block along y (rows)")
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
