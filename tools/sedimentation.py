#!/usr/bin/python3
"""Sedimentation observables of Tabatabaei (2008) ch.4 from one or more run directories.

Usage: sedimentation.py RUN_DIR [RUN_DIR ...] [--skip 0.25] [--blocks 10] [--chain PNG]
                        [--wake PNG]

For every run: the colloids' mean settling velocity along the gravity (x) axis in the frame
co-moving with the centre of mass (eq 4.8-4.10, the run's "settling_velocity" series, averaged
over the samples after the first --skip fraction, error from --blocks block means), and the
Reynolds number Re = v_s L_y / nu (eq 4.11) with nu from SRD kinetic theory. With several runs
at different colloids.gravity, a linear fit v_s = mu g with its R^2 (Tabatabaei (2008) fig 4.10).
With --chain, the chain distances D_i(t) of §4.5 from "colloid_positions": colloids labelled by
their initial x, groups of 5 consecutive ones, D_i = mean distance to the next colloid within
group i; plotted against time for the first run.
With --wake, the fluid number density along the channel in the frame of each colloid, from the
first run's trajectory.h5 (output.trajectory_every, trajectory_subsample = 1): in the colloid's
lane (|y - y_c| < r) and beside it, averaged over the frames after --skip and over the colloids,
with block errors. A random solvent, which keeps mass but not momentum, piles fluid up ahead of
a settling colloid and leaves it thinned behind; SRD's flow carries it round.
"""

import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import narrows_h5  # noqa: E402
from narrows_h5 import NarrowsDataError  # noqa: E402
from plot_profile import theory_viscosity  # noqa: E402


def read(run_dir):
    run = narrows_h5.open_run(run_dir)
    scene = run.scene()
    settling = run.series("settling_velocity")
    v = settling["value"][:, 0]
    t = settling["time"]
    pos = pos_t = None
    if run.has("colloid_positions"):
        positions = run.series("colloid_positions")
        pos, pos_t = positions["value"], positions["time"]
    return scene, t, v, pos_t, pos


def block_mean(v, blocks):
    n = len(v) // blocks
    if n == 0:
        return float(np.mean(v)), float("nan")
    m = v[: n * blocks].reshape(blocks, n).mean(axis=1)
    return float(m.mean()), float(m.std(ddof=1) / np.sqrt(blocks))


def unwrap(x, L):
    d = np.diff(x, axis=0)
    d -= L * np.round(d / L)
    return np.concatenate([x[:1], x[:1] + np.cumsum(d, axis=0)])


def chain_distances(pos, L, g, group=5):
    """D_i(t) of Tabatabaei (2008) §4.5: colloids ordered by initial x from the head (the front in
    the direction of gravity; for g = 0 the largest x) to the tail, gaps d between successive ones,
    D_i = mean of group i's 5 gaps, so D_1 is at the head as in Tabatabaei's fig 4.12."""
    x = unwrap(pos[:, :, 0], L)
    order = np.argsort(x[0])
    if g >= 0.0:
        order = order[::-1]
    x = x[:, order]
    gaps = np.abs(np.diff(x, axis=1))  # d between consecutive colloids
    groups = gaps.shape[1] // group
    return np.stack([gaps[:, i * group:(i + 1) * group].mean(axis=1) for i in range(groups)], 1)


def growth_rates(t, D, blocks):
    """Least-squares slope dD_i/dt over the whole run, with an error from the scatter of the
    slopes fitted in `blocks` consecutive time blocks (each block's slope is an independent
    estimate of the same rate if the growth is steady; a curved D_i(t) shows as a large error)."""
    rates, errors = [], []
    n = len(t) // blocks
    for i in range(D.shape[1]):
        rates.append(float(np.polyfit(t, D[:, i], 1)[0]))
        b = [np.polyfit(t[k * n:(k + 1) * n], D[k * n:(k + 1) * n, i], 1)[0] for k in range(blocks)]
        errors.append(float(np.std(b, ddof=1) / np.sqrt(blocks)))
    return np.array(rates), np.array(errors)


def wake_profile(run, skip, blocks, half=40.0, width=1.0):
    """Fluid density against dx = x - x_c (dx > 0 ahead along +x) in the colloid frames."""
    with narrows_h5.open_trajectory(run) as f:
        if int(f.parameter("subsample")) != 1:
            raise NarrowsDataError(f.path, "--wake needs every fluid particle",
                                   "output.trajectory_subsample = 1")
        L, W = f.array("particles/fluid/box/edges")[:2]
        xf = f.dataset("particles/fluid/position/value")  # read frame by frame
        xc = f.array("particles/colloids/position/value")
        r = f.array("particles/colloids/radius")
        edges = np.arange(-half, half + 0.5 * width, width)
        frames = range(int(skip * xf.shape[0]), xf.shape[0])
        lane = np.zeros((len(frames), len(edges) - 1))
        side = np.zeros_like(lane)
        for i, fr in enumerate(frames):
            p = xf[fr]
            for c in range(xc.shape[1]):
                dx = p[:, 0] - xc[fr, c, 0]
                dx -= L * np.round(dx / L)
                inlane = np.abs(p[:, 1] - xc[fr, c, 1]) < r[c]
                lane[i] += np.histogram(dx[inlane], edges)[0] / (width * 2.0 * r[c])
                side[i] += np.histogram(dx[~inlane], edges)[0] / (width * (W - 2.0 * r[c]))
            lane[i] /= xc.shape[1]
            side[i] /= xc.shape[1]
    n = len(frames) // blocks
    # block means: (blocks, bins)
    return (0.5 * (edges[1:] + edges[:-1]), lane[: n * blocks].reshape(blocks, n, -1).mean(axis=1),
            side[: n * blocks].reshape(blocks, n, -1).mean(axis=1))


def print_wake(run, skip, blocks, png):
    x, lane_b, side_b = wake_profile(run, skip, blocks)

    def mean_err(b):
        return b.mean(axis=0), b.std(axis=0, ddof=1) / np.sqrt(b.shape[0])

    (lane, dl), (side, ds) = mean_err(lane_b), mean_err(side_b)
    far = np.abs(x) > 30.0
    n0 = float(np.mean(np.concatenate([lane[far], side[far]])))
    print(f"\nfluid density in the colloid frame ({run}); far from the colloid n = {n0:.3f}")
    print("| dx | lane | error | beside | error |")
    print("|---|---|---|---|---|")
    for i in range(len(x)):
        if abs(x[i]) < 12.0 or i % 4 == 0:
            print(f"| {x[i]:+.1f} | {lane[i]:.3f} | {dl[i]:.3f} | {side[i]:.3f} | {ds[i]:.3f} |")
    ahead = (x > 2.0) & (x < 12.0)
    behind = (x < -2.0) & (x > -12.0)
    diff, err = mean_err(lane_b[:, ahead].mean(axis=1) - lane_b[:, behind].mean(axis=1))
    print(f"lane, ahead (2 < dx < 12) minus behind (-12 < dx < -2): {diff:+.3f} +- {err:.3f} "
          f"({diff / n0:+.1%} of n)")
    if png:
        plt = narrows_h5.pyplot()
        plt.errorbar(x, lane, dl, label="lane |y - y_c| < r")
        plt.errorbar(x, side, ds, label="beside the colloid")
        plt.axhline(n0, color="grey", lw=0.5)
        plt.xlabel("x - x_c (gravity along +x)")
        plt.ylabel("fluid number density")
        plt.legend()
        plt.savefig(png, dpi=120)
        print(f"wake profile: {png}")


def weighted_line(x, v, e):
    """Straight line v = a x + b weighted by the errors e: (a, da, b, db, chi^2 per dof)."""
    w = 1.0 / e**2
    A = np.stack([x, np.ones_like(x)], 1)
    cov = np.linalg.inv(A.T @ (A * w[:, None]))
    p = cov @ (A.T @ (w * v))
    chi2 = float(np.sum(w * (v - A @ p) ** 2)) / max(1, len(x) - 2)
    return p[0], np.sqrt(cov[0, 0]), p[1], np.sqrt(cov[1, 1]), chi2


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--skip", type=float, default=0.25)
    ap.add_argument("--blocks", type=int, default=10)
    ap.add_argument("--chain", help="PNG of the chain distances D_i(t) of the first run")
    ap.add_argument("--wake", help="PNG of the fluid density in the colloid frame (first run)")
    a = ap.parse_args()
    if a.wake:
        print_wake(a.runs[0], a.skip, a.blocks, a.wake)
    gs, vs, es, ns, phis = [], [], [], [], []
    print("| run | g | N_c | phi | v_s | error | Re |")
    print("|---|---|---|---|---|---|---|")
    for run in a.runs:
        scene, t, v, pos_t, pos = read(run)
        fl = scene["fluid"]
        nu, _ = theory_viscosity(fl.get("collision", "srd"), scene["run"].get("dimensions", 2),
                                 float(fl.get("density", 10)), float(fl["dt"]),
                                 float(fl.get("angle", 90.0)), float(fl.get("kT", 1.0)))
        g = float(scene["colloids"].get("gravity", [0.0])[0])
        keep = v[int(a.skip * len(v)):]
        m, e = block_mean(keep, a.blocks)
        Ly = float(scene["domain"]["size"][1])
        re = abs(m) * Ly / nu if nu else float("nan")
        nc = pos.shape[1] if pos is not None else int(scene["colloids"].get("count", 0))
        r = float(scene["colloids"].get("radius", 2.0))
        area = float(np.prod(scene["domain"]["size"]))
        phi = nc * np.pi * r * r / area if scene["run"].get("dimensions", 2) == 2 else \
            nc * 4.0 / 3.0 * np.pi * r**3 / area
        print(f"| {run} | {g:g} | {nc} | {phi:.4f} | {m:.5f} | {e:.5f} | {re:.4f} |")
        gs.append(g), vs.append(m), es.append(e), ns.append(nc), phis.append(phi)
        if a.chain and run == a.runs[0] and pos is not None:
            plt = narrows_h5.pyplot()
            D = chain_distances(pos, float(scene["domain"]["size"][0]), g)
            for i in range(D.shape[1]):
                plt.plot(pos_t, D[:, i], label=f"D_{i + 1}")
            plt.xlabel("t")
            plt.ylabel("D_i (D_1 at the head)")
            plt.title(f"chain of {pos.shape[1]} colloids, g = {g:g}")
            plt.legend()
            plt.savefig(a.chain, dpi=120)
            print(f"chain distances: {a.chain}; initial D_i = {np.round(D[0], 3)}, "
                  f"final D_i = {np.round(D[-1], 3)}")
            rate, err = growth_rates(pos_t, D, 4)
            for i in range(D.shape[1]):
                print(f"  dD_{i + 1}/dt = {rate[i]:.3e} +- {err[i]:.1e}")
            head_tail = rate[0] - rate[-1]
            print(f"  head - tail: {head_tail:.3e} +- {np.hypot(err[0], err[-1]):.1e}; "
                  f"slope of the rates against i: {np.polyfit(np.arange(1, len(rate) + 1), rate, 1)[0]:.3e}")
    if len(set(gs)) >= 2:
        g, v, e = np.array(gs), np.array(vs), np.array(es)
        mu = float(np.sum(g * v) / np.sum(g * g))  # v_s = mu g through the origin
        slope, icpt = np.polyfit(g, v, 1)
        r2 = 1.0 - np.sum((v - (slope * g + icpt)) ** 2) / np.sum((v - v.mean()) ** 2)
        print(f"\nlinear fit v_s = {slope:.4f} g + {icpt:.5f}, R^2 = {r2:.4f}; "
              f"through the origin mu = {mu:.4f}")
        if len(g) >= 3 and np.all(e > 0):
            # Weighted by the block errors; chi^2 per degree of freedom says whether the
            # straight line describes the points within their errors.
            sl, dsl, ic, dic, chi2 = weighted_line(g, v, e)
            print(f"weighted fit: slope {sl:.4f} +- {dsl:.4f}, intercept "
                  f"{ic:.5f} +- {dic:.5f}, chi^2/dof = {chi2:.2f}")
    elif len(set(phis)) >= 2 and np.all(np.array(es) > 0):
        # Tabatabaei (2008) §4.2-4.3: v_s against phi at fixed g, phi varied by the number of
        # colloids (fig 4.6, 4.7) or by the channel length (fig 4.3, 4.4, 4.8). If chi^2/dof > 1 the block
        # errors are too small (blocks shorter than the slowest correlation time); the error is
        # then scaled by sqrt(chi^2/dof).
        n, phi, v, e = np.array(ns, float), np.array(phis), np.array(vs), np.array(es)
        sp, dsp, ic, dic, chi2 = weighted_line(phi, v, e)
        scale = np.sqrt(max(1.0, chi2))
        varied = "N_c" if len(set(ns)) >= 2 else f"the length, N_c = {ns[0]}"
        print(f"\nweighted fit against phi ({varied} varied): dv_s/dphi = {sp:.4f} +- {dsp:.4f} "
              f"({sp / dsp:+.1f} sigma; {sp / (dsp * scale):+.1f} sigma with the error scaled by "
              f"sqrt(chi^2/dof)), v_s(0) = {ic:.5f} +- {dic:.5f}, relative {sp / ic:+.2f} +- "
              f"{dsp / abs(ic):.2f} per unit phi, chi^2/dof = {chi2:.2f} (Tabatabaei (2008) "
              f"fig 4.6: v_s = 0.15 phi + 0.019)")
        if len(set(ns)) >= 2:
            sl, dsl, _, _, _ = weighted_line(n, v, e)
            print(f"against N_c: dv_s/dN_c = {sl:.3e} +- {dsl:.1e}")

if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("sedimentation", main))
