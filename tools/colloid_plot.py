#!/usr/bin/python3
"""Plot the colloid VACF C(tau), its running integral D(t) with the fitted plateau (Kanehl (thesis) fig 4.9) and the per-kind kernel density profiles of a narrows MPCD run.

Usage: colloid_plot.py OUTDIR|observables.h5 [--png FILE] [--window T1 T2]

Reads /observables/colloid_vacf, colloid_diffusion and density_kde (whichever the run wrote;
at least one of them) from OUTDIR/observables.h5. C(tau) and D(t) are drawn per kind of
colloid with their error bands (spread of block averages). The plateau of D(t) is fitted as
the mean of D over the window T1 <= t <= T2 (default: the last third of the lags), with the
mean of the errors there as its error (the values in the window are strongly correlated, so
this does not shrink with the number of lags). Prints one line per kind,
"kind K: D = ... +- ... (plateau over t in [T1, T2])", and, with density_kde, the integral of
each profile. Writes a PNG (default OUTDIR/colloids.png). Exit 2 on bad input.
"""

import argparse
import os
import sys

import numpy as np

import narrows_h5
from narrows_h5 import NarrowsDataError


def read(path):
    run = narrows_h5.open_run(path)
    out = {}
    names = run.names()
    for name in ("colloid_vacf", "colloid_diffusion"):
        if name in names:
            g = run.series(name)
            lags = g["lags"]
            out[name] = {"lags": lags,
                         "value": g["value_by_kind"].reshape(-1, len(lags)),  # [kinds][lags]
                         "error": g["error_by_kind"].reshape(-1, len(lags)),
                         "samples": int(g["samples"][0])}
    if "density_kde" in names:
        g = run.series("density_kde")
        out["density_kde"] = {"y": g["bins"], "value": g["value"], "error": g["error"],
                              "width": float(g["width"][0]), "counts": g["counts"],
                              "samples": int(g["samples"][0])}
    if not out:
        raise NarrowsDataError(path, "none of colloid_vacf, colloid_diffusion, density_kde",
                               "a run that lists them in output.observables")
    return out


def plateau(t, d, e, window):
    """Mean of D over the window and the mean error there."""
    t1, t2 = window if window else (t[-1] * 2.0 / 3.0, t[-1])
    sel = (t >= t1) & (t <= t2) & np.isfinite(d)
    if not np.any(sel):
        raise NarrowsDataError(None, f"no lag in the plateau window [{t1:g}, {t2:g}] (lags 0 "
                                     f"to {t[-1]:g})")
    err = e[sel]
    err = err[np.isfinite(err)]
    return float(np.mean(d[sel])), float(np.mean(err)) if len(err) else float("nan"), t1, t2


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", help="output directory of a run, or its observables.h5")
    parser.add_argument("--png", help="output image (default RUN/colloids.png)")
    parser.add_argument("--window", nargs=2, type=float, metavar=("T1", "T2"),
                        help="plateau window of D(t) (default: the last third of the lags)")
    args = parser.parse_args(argv[1:])
    path = narrows_h5.observables_path(args.run)
    data = read(path)
    plt = narrows_h5.pyplot()
    panels = [n for n in ("colloid_vacf", "colloid_diffusion", "density_kde") if n in data]
    fig, axes = plt.subplots(1, len(panels), figsize=(5 * len(panels), 4), squeeze=False)
    lines = []
    for ax, name in zip(axes[0], panels):
        d = data[name]
        if name == "colloid_vacf":
            for k, (c, e) in enumerate(zip(d["value"], d["error"])):
                ax.plot(d["lags"], c, label=f"kind {k}")
                ax.fill_between(d["lags"], c - e, c + e, alpha=0.3)
            ax.axhline(0.0, color="grey", lw=0.5)
            ax.set_xlabel("tau")
            ax.set_ylabel("C(tau) = <v(t).v(t+tau)>")
            ax.set_title(f"colloid VACF ({d['samples']} samples)")
        elif name == "colloid_diffusion":
            for k, (v, e) in enumerate(zip(d["value"], d["error"])):
                p, pe, t1, t2 = plateau(d["lags"], v, e, args.window)
                ax.plot(d["lags"], v, label=f"kind {k}: D = {p:.4g} +- {pe:.2g}")
                ax.fill_between(d["lags"], v - e, v + e, alpha=0.3)
                ax.hlines(p, t1, t2, colors="k", linestyles="--")
                lines.append(f"kind {k}: D = {p:.6g} +- {pe:.2g} (plateau over t in "
                             f"[{t1:g}, {t2:g}])")
            ax.set_xlabel("t")
            ax.set_ylabel("D(t) = (1/d) int_0^t C")
            ax.set_title("running integral, fitted plateau (dashed)")
        else:
            dy = d["y"][1] - d["y"][0] if len(d["y"]) > 1 else 1.0
            for k, (f, e) in enumerate(zip(d["value"], d["error"])):
                ax.plot(d["y"], f, label=f"kind {k} ({int(d['counts'][k])} colloids)")
                ax.fill_between(d["y"], f - e, f + e, alpha=0.3)
                lines.append(f"kind {k}: density_kde integrates to "
                             f"{float(np.nansum(f) * dy):.4f} over y")
            ax.set_xlabel("y")
            ax.set_ylabel("F_k(y) (eq 5.2)")
            ax.set_title(f"kernel density, eps = {d['width']:g} ({d['samples']} samples)")
        ax.legend(fontsize=8)
    fig.tight_layout()
    png = args.png or os.path.join(os.path.dirname(path) or ".", "colloids.png")
    try:
        fig.savefig(png, dpi=100)
    except OSError as e:
        print(f"colloid_plot: cannot write {png}: {e.strerror}", file=sys.stderr)
        return 2
    for line in lines:
        print(line)
    print(f"wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("colloid_plot", main, sys.argv))
