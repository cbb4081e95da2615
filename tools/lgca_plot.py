#!/usr/bin/python3
"""Plots of an lgca run (observables.h5 of `narrows run` with engine "lgca").

- shear wave: ln of the amplitude A(t) of u_x = A sin(2 pi y / L_y) against t (several files,
  e.g. runs with different seeds, are averaged), the straight-line fit over the window
  [--first, --last] and the Boltzmann decay exp(-nu k^2 t) of PHYSICS.md, k = 2 pi / L_y,
  L_y = size[1] sqrt(3)/2; prints nu from the fit (error: jackknife over the files when there
  are several) against the Boltzmann nu;
- fields (density, velocity): the last sample of u_x and of the density over the lattice.

Usage: tools/lgca_plot.py OUT/observables.h5 [MORE.h5 ...] [--png FILE] [--first T0] [--last T1]
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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("files", nargs="+")
    ap.add_argument("--png", default="lgca.png")
    ap.add_argument("--first", type=float, default=20.0, help="first step of the fit window")
    ap.add_argument("--last", type=float, default=None,
                    help="last step of the fit window (default: A fallen by e^-1.5, Boltzmann)")
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
