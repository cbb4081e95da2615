#!/usr/bin/env python3
"""Fits K_d of the segregation theory (Kanehl (thesis) ch.5, eq 5.23) to the per-kind kernel density
profiles (observable density_kde, eq 5.2) of a particle run with [[colloids.kind]].

  /usr/bin/python3 tools/segregation_fit.py RUN_DIR --diffusivity D_1 [D_2] [options]

The run's scene (stored in observables.h5) gives the channel (half width w = domain.size[1] / 2,
walls at y = 0 and 2w), the kinds (radius, count: mean fraction N pi a^2 / area in 2D, N 4/3 pi
a^3 / volume in 3D) and the dimension; the centre speed v0 is the largest mean x velocity of
the run's velocity_profile (the mean over its second half) unless --centre-speed is given.
The single-colloid diffusivities D_0 are not in the run: give them (--diffusivity, one per
kind, in the order of [[colloids.kind]]); only K_d D_0 enters the profiles, so a fitted K_d is
relative to them. For each trial K_d the continuum engine computes the steady profiles
(narrows run of a [continuum] model = "segregation" scene with K_c = 1, K_eta = --k-eta;
observable steady_density, by shooting). Data and model are compared as shapes over
|y - w| <= w - exclude (default: twice the largest radius, the wall layers the theory does not
have), each normalised to its mean there, at bins every 2 kernel widths (nearly independent),
weighted by the run's block errors. K_d minimises chi^2 (golden section in log K_d); its
interval is where the parabola through chi^2 at the minimum and +-0.02 in log K_d rises by
max(1, chi^2/dof) (printed as K_d +- half its width, and the interval). Prints one line
"K_d = ... +- ...", the chi^2 of uniform profiles (the evidence for any segregation) and the
fit's details; --plot writes RUN_DIR/segregation_fit.png.
"""

import argparse
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

import narrows_h5
from continuum_run import find_narrows
from narrows_h5 import NarrowsDataError


class InputError(Exception):
    """A bad command line (bad data raise narrows_h5.NarrowsDataError)."""


def read_run(run_dir):
    run = narrows_h5.open_run(os.path.join(run_dir, narrows_h5.OBSERVABLES))
    g = run.series("density_kde")
    out = {"y": g["bins"], "value": g["value"], "error": g["error"],
           "width": float(g["width"][0]), "path": run.path}
    out["scene"] = run.scene()
    if run.has("velocity_profile"):
        v = run.series("velocity_profile")["value"]
        out["velocity"] = v[v.shape[0] // 2:, :, 0].mean(axis=0)
    return out


def channel(run, diffusivity, centre_speed):
    s = run["scene"]
    dims = int(s.get("run", {}).get("dimensions", 2))
    size = s["domain"]["size"]
    kinds = s.get("colloids", {}).get("kind")
    if not kinds:
        raise NarrowsDataError(run["path"], "the scene has no [[colloids.kind]]",
                               "a run with one or two colloid kinds")
    if len(kinds) > 2:
        raise NarrowsDataError(run["path"], f"{len(kinds)} colloid kinds", "one or two")
    if len(diffusivity) != len(kinds):
        raise InputError(f"--diffusivity: {len(diffusivity)} values for {len(kinds)} kinds; "
                         "allowed: one D_0 > 0 per kind")
    volume = float(np.prod(size))
    out = []
    for k, d in zip(kinds, diffusivity):
        a = float(k["radius"])
        body = math.pi * a * a if dims == 2 else 4.0 / 3.0 * math.pi * a ** 3
        out.append({"radius": a, "fraction": k["count"] * body / volume, "diffusivity": d})
    if centre_speed is None:
        if "velocity" not in run:
            raise NarrowsDataError(run["path"], "no velocity_profile for v0", "--centre-speed V0")
        centre_speed = float(np.max(run["velocity"]))
    return dims, size[1] / 2.0, out, centre_speed


def steady(narrows, dims, w, kinds, v0, k_d, k_eta, cells, work):
    text = ("[run]\nengine = \"continuum\"\n[continuum]\nmodel = \"segregation\"\n"
            f"dimensions = {dims}\nhalf_width = {w!r}\ncells = {cells}\n"
            f"centre_speed = {v0!r}\nk_c = 1.0\nk_eta = {k_eta!r}\nk_d = {k_d!r}\n"
            "time = 1e-9\nsamples = 1\n")
    for k in kinds:
        text += (f"[[continuum.kind]]\nradius = {k['radius']!r}\nfraction = {k['fraction']!r}\n"
                 f"diffusivity = {k['diffusivity']!r}\n")
    text += "[output]\nobservables = [\"steady_density\"]\nprogress = false\n"
    scene = os.path.join(work, "fit.toml")
    with open(scene, "w") as f:
        f.write(text)
    out = os.path.join(work, "out")
    r = subprocess.run([narrows, "run", scene, "--out", out, "--overwrite"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise InputError(f"narrows run of the segregation model at K_d = {k_d:g} failed: "
                         + (r.stderr.strip().splitlines() or ["?"])[-1])
    run = narrows_h5.open_run(out)
    if not run.has("steady_density"):
        return None  # none at this K_d (e.g. close packing reached): chi^2 = infinity
    g = run.series("steady_density")
    return g["bins"], g["value"]


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("run_dir")
    p.add_argument("--diffusivity", type=float, nargs="+", required=True)
    p.add_argument("--centre-speed", type=float)
    p.add_argument("--k-eta", type=float, default=1.51)
    p.add_argument("--range", type=float, nargs=2, default=[0.01, 1000.0],
                   metavar=("LO", "HI"), help="search interval of K_d")
    p.add_argument("--exclude", type=float, help="wall strip left out (default 2 max radius)")
    p.add_argument("--cells", type=int, default=400)
    p.add_argument("--narrows", help="the narrows binary (default: $NARROWS, build/narrows, "
                                      "the PATH)")
    p.add_argument("--plot", action="store_true")
    a = p.parse_args(argv)
    try:
        if any(d <= 0 for d in a.diffusivity):
            raise InputError("--diffusivity: allowed: numbers > 0")
        a.narrows = find_narrows(a.narrows)
        run = read_run(a.run_dir)
        dims, w, kinds, v0 = channel(run, a.diffusivity, a.centre_speed)
        exclude = a.exclude if a.exclude is not None else 2.0 * max(k["radius"] for k in kinds)
        y = run["y"] - w
        stride = max(1, int(round(2.0 * run["width"] /
                                  (run["y"][1] - run["y"][0]))))
        keep = np.nonzero(np.abs(y) <= w - exclude)[0][::stride]
        if len(keep) < 3:
            raise InputError(f"--exclude {exclude:g}: fewer than 3 bins left in the channel")
        data = run["value"][:, keep]
        err = run["error"][:, keep]
        norm = data.mean(axis=1, keepdims=True)
        data, err = data / norm, err / norm
        if np.any(err <= 0):
            raise NarrowsDataError(run["path"], "density_kde errors of 0 in the fit region",
                                   "a run with samples in every block")
        with tempfile.TemporaryDirectory() as work:
            cache = {}

            def model(k_d):
                if k_d not in cache:
                    got = steady(a.narrows, dims, w, kinds, v0, k_d, a.k_eta, a.cells, work)
                    if got is None:
                        cache[k_d] = None
                        return None
                    ym, phi = got
                    m = np.stack([np.interp(y[keep], ym, phi[:, i]) for i in range(len(kinds))])
                    cache[k_d] = m / m.mean(axis=1, keepdims=True)
                return cache[k_d]

            def chi2(log_k):
                m = model(math.exp(log_k))
                if m is None:
                    return math.inf
                return float(np.sum(((data - model(math.exp(log_k))) / err) ** 2))

            lo, hi = math.log(a.range[0]), math.log(a.range[1])
            grid = np.linspace(lo, hi, 13)
            values = [chi2(x) for x in grid]
            i = int(np.argmin(values))
            if not math.isfinite(values[i]):
                raise InputError("no steady state of the segregation model for any K_d in "
                                 f"--range {a.range[0]:g} {a.range[1]:g}")
            lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
            g = (math.sqrt(5) - 1) / 2
            c, d = hi - g * (hi - lo), lo + g * (hi - lo)
            fc, fd = chi2(c), chi2(d)
            for _ in range(20):
                if fc < fd:
                    hi, d, fd = d, c, fc
                    c = hi - g * (hi - lo)
                    fc = chi2(c)
                else:
                    lo, c, fc = c, d, fd
                    d = lo + g * (hi - lo)
                    fd = chi2(d)
            best = 0.5 * (lo + hi)
            cmin = chi2(best)
            dof = data.size - 1
            rise = max(1.0, cmin / dof)
            # chi^2 is a parabola in log K_d near its minimum: its curvature from +- 0.02.
            h = 0.02
            curv = (chi2(best + h) - 2.0 * cmin + chi2(best - h)) / (h * h)
            sigma = math.sqrt(2.0 * rise / curv) if curv > 0 else math.inf
            k_best = math.exp(best)
            k_lo, k_hi = math.exp(best - sigma), math.exp(best + sigma)
            fitted = model(k_best)
        print(f"K_d = {k_best:.5g} +- {0.5 * (k_hi - k_lo):.2g} (chi^2 + {rise:.3g} at "
              f"[{k_lo:.5g}, {k_hi:.5g}]; K_c = 1, K_eta = {a.k_eta:g})")
        flat = float(np.sum(((data - 1.0) / err) ** 2))
        if best <= math.log(a.range[0]) + 0.3 or best >= math.log(a.range[1]) - 0.3:
            print(f"warning: K_d at the edge of --range {a.range[0]:g} {a.range[1]:g}: no "
                  "minimum inside it")
        print(f"uniform profiles (K_d -> infinity): chi^2 = {flat:.4g} (minus the fit's: "
              f"{flat - cmin:.3g}, the evidence for segregation)")
        print(f"chi^2 / dof = {cmin:.4g} / {dof} over {len(keep)} bins per kind, |y - w| <= "
              f"{w - exclude:g} (every {stride} bins)")
        for i, k in enumerate(kinds):
            print(f"kind {i}: radius {k['radius']:g}, fraction {k['fraction']:.4g}, D_0 = "
                  f"{k['diffusivity']:g}, Peclet a^3 v0 / (w^2 D_0) = "
                  f"{k['radius'] ** 3 * v0 / (w * w * k['diffusivity']):.4g}")
        print(f"channel: {dims}D, w = {w:g}, v0 = {v0:.5g}")
        if a.plot:
            plt = narrows_h5.pyplot()
            fig, ax = plt.subplots(figsize=(6, 4))
            for i in range(len(kinds)):
                ax.errorbar(y[keep] / w, data[i], err[i], fmt="o", ms=3, label=f"kind {i} run")
                ax.plot(y[keep] / w, fitted[i], "-", label=f"kind {i} theory")
            ax.set_xlabel("y / w")
            ax.set_ylabel("c / mean")
            ax.set_title(f"K_d = {k_best:.4g}")
            ax.legend()
            fig.savefig(os.path.join(a.run_dir, "segregation_fit.png"), dpi=120)
    except (InputError, NarrowsDataError) as e:
        return narrows_h5.report("segregation_fit", e)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
