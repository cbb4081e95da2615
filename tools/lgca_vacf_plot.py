#!/usr/bin/python3
"""VACF of a tagged particle in the 1D d'Humieres lattice gas (van der Hoef & Frenkel fig 1).

Reads the files DIR/vacf_L<L>.h5 that tests/validation/test_lgca_vacf_1d.cpp writes when it
runs with NARROWS_VACF_OUT=DIR (datasets vacf, vacf_error, particles, density, L, plateau,
plateau_error, window_start, window_end, ensemble) and plots the normalised VACF
Z(t) = <v(0)v(t)>/<v^2> against t for every L found (van der Hoef & Frenkel: 500, 2000, 100000),
zoomed on the plateaus, with the line -(1 - d)/N of eq 22 for each L and the measured window mean.
A second panel shows N Z(t), where every plateau of the P = 0 ensemble sits at -(1 - d), with the
window mean as a thick bar (systems whose N Z is dominated by noise are left out).

Usage:
  NARROWS_VACF_OUT=/tmp/vacf build/tests/validation_tests --gtest_filter='LgcaVacf1d*'
  tools/lgca_vacf_plot.py /tmp/vacf [--png vacf_1d.png]
"""
import argparse
import glob
import os
import sys

import numpy as np

import narrows_h5
from narrows_h5 import NarrowsDataError

NAMES = ("vacf", "vacf_error", "particles", "density", "L", "plateau", "plateau_error",
         "window_start", "window_end", "ensemble")


def load(path):
    out = narrows_h5.read_datasets(path)  # strings (ensemble) as str
    for name in NAMES:
        if name not in out:
            raise NarrowsDataError(path, f"no /{name}")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir", help="directory with vacf_L*.h5")
    ap.add_argument("--png", default=None, help="output image (default DIR/vacf_1d.png)")
    args = ap.parse_args()
    files = sorted(glob.glob(os.path.join(args.dir, "vacf_L*.h5")),
                   key=lambda p: int(os.path.basename(p)[6:-3]))
    if not files:
        raise NarrowsDataError(args.dir, "no vacf_L*.h5", "a folder that NARROWS_VACF_OUT gave "
                               "the validation test (usage above)")
    runs = [load(p) for p in files]

    plt = narrows_h5.pyplot()
    fig, (ax, axn) = plt.subplots(2, 1, figsize=(7, 8), sharex=True)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, r in enumerate(runs):
        c = colors[k % len(colors)]
        z, e = r["vacf"], r["vacf_error"]
        t = np.arange(len(z))
        n, d, L = float(r["particles"]), float(r["density"]), int(r["L"])
        label = f"L = {L}, N = {n:.0f} ({r['ensemble']})"
        ax.plot(t[1:], z[1:], color=c, lw=0.8, label=label)
        ax.fill_between(t[1:], (z - e)[1:], (z + e)[1:], color=c, alpha=0.25, lw=0)
        ax.axhline(-(1 - d) / n, color=c, ls="--", lw=0.8)
        t1, t2 = int(r["window_start"]), int(r["window_end"])
        if n * r["plateau_error"] < 0.5:  # N Z of the largest system is only noise
            axn.plot(t[1:], n * z[1:], color=c, lw=0.8, label=label)
            axn.plot([t1, t2], [n * r["plateau"]] * 2, color=c, lw=2.5, alpha=0.7)
        print(f"L = {L:6d} N = {n:8.0f} {r['ensemble']:>14s}: plateau over [{t1}, {t2}] = "
              f"{r['plateau']:.4g} +- {r['plateau_error']:.2g}, N x plateau = "
              f"{n * r['plateau']:.4f} +- {n * r['plateau_error']:.4f}, -(1-d)/N = "
              f"{-(1 - d) / n:.4g}")
    d = float(runs[0]["density"])
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_ylim(-6e-4, 6e-4)
    ax.set_ylabel(r"$Z(t) = \langle v(0)v(t)\rangle / \langle v^2\rangle$")
    ax.set_title(f"1D d'Humieres gas, d = {d}: dashed -(1-d)/N (eq 22)")
    ax.legend(fontsize=8)
    axn.axhline(-(1 - d), color="k", ls="--", lw=0.8, label="-(1 - d)")
    axn.axhline(0.0, color="k", lw=0.5)
    axn.set_ylim(-1.5, 2.0)
    axn.set_xlabel("t (steps)")
    axn.set_ylabel(r"$N\,Z(t)$")
    axn.legend(fontsize=8)
    fig.tight_layout()
    png = args.png or os.path.join(args.dir, "vacf_1d.png")
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("lgca_vacf_plot", main))
