#!/usr/bin/python3
"""Draw one trajectory frame of a spring-contact run as Kanehl (thesis) fig 6.3: the disks
coloured by kind, each contact a red line between the two centres (a wall contact: from the
centre to the wall) whose width scales linearly with the normal force |F_n|, and the fluid's
velocity as black arrows, its lateral component amplified (x5 as in the thesis).

Usage: force_chains.py RUN_DIR|trajectory.h5 [--frame K] [--png FILE] [--bin B]
                       [--lateral F] [--x X0 X1] [--width W]

Reads DIR/trajectory.h5 through narrows_h5: /particles/colloids (position, id, radius),
/contacts (written with colloids.contacts = "spring": ids, normal_force, sliding, and the rows
of each frame) and /particles/fluid (position, velocity) of frame K (default: the last; negative
counts from the end). The arrows are the mean velocity of the trajectory's fluid particles in
square bins of B cells (default 10): with output.trajectory_subsample = s each bin holds about
n B^2 / s of them, so choose B large enough against the thermal noise (kT / m per particle).
The line of the strongest contact is W points wide (default 3). Prints the frame's step, time,
number of contacts and the fraction sliding, and the PNG path (default DIR/force_chains.png).
Exit 2 on bad input.
"""

import argparse
import os
import sys

import numpy as np

import narrows_h5
from narrows_h5 import NarrowsDataError


def read(path, frame):
    with narrows_h5.open_trajectory(path) as t:
        times = t.array("particles/colloids/position/time")
        n = len(times)
        if n == 0:
            raise NarrowsDataError(t.path, "no frames", "a run with output.trajectory_every > 0")
        k = frame if frame >= 0 else n + frame
        if not 0 <= k < n:
            raise NarrowsDataError(t.path, f"--frame {frame}: the file has {n} frames",
                                   f"0 to {n - 1}, or -1 to -{n}")
        out = {"frame": k, "time": float(times[k]),
               "step": int(t.dataset("particles/colloids/position/step")[k]),
               "x": t.dataset("particles/colloids/position/value")[k],
               "id": t.array("particles/colloids/id"),
               "radius": t.array("particles/colloids/radius"),
               "edges": t.array("particles/colloids/box/edges"),
               "fluid_x": t.dataset("particles/fluid/position/value")[k],
               "fluid_v": t.dataset("particles/fluid/velocity/value")[k]}
        if not t.has("contacts"):
            raise NarrowsDataError(t.path, "no /contacts",
                                   'a run with colloids.contacts = "spring" (its trajectory '
                                   "holds the contact network)")
        steps = t.array("contacts/step")
        hit = np.nonzero(steps == out["step"])[0]
        if len(hit) == 0:
            raise NarrowsDataError(t.path, f"no contact network of step {out['step']}")
        j = hit[-1]
        first, count = int(t.dataset("contacts/first")[j]), int(t.dataset("contacts/count")[j])
        rows = slice(first, first + count)
        out["pairs"] = t.dataset("contacts/ids")[rows]
        out["fn"] = t.dataset("contacts/normal_force")[rows]
        out["sliding"] = t.dataset("contacts/sliding")[rows]
        try:
            scene = narrows_h5.parse_scene(t.parameter("scene"), t.path)
        except NarrowsDataError:
            scene = {}
    kinds = scene.get("colloids", {}).get("kind", [])
    out["kind_radii"] = [float(q["radius"]) for q in kinds] if kinds else []
    return out


def main(argv):
    p = argparse.ArgumentParser(prog="force_chains.py", description=__doc__.split("\n\n")[0])
    p.add_argument("run")
    p.add_argument("--frame", type=int, default=-1)
    p.add_argument("--png")
    p.add_argument("--bin", type=float, default=10.0)
    p.add_argument("--lateral", type=float, default=5.0)
    p.add_argument("--x", type=float, nargs=2, metavar=("X0", "X1"))
    p.add_argument("--width", type=float, default=3.0)
    args = p.parse_args(argv[1:])
    if not args.bin > 0 or not args.width > 0:
        raise NarrowsDataError(None, f"--bin {args.bin:g} --width {args.width:g}",
                               "both > 0")
    d = read(args.run, args.frame)
    Lx, Ly = float(d["edges"][0]), float(d["edges"][1])
    x0, x1 = args.x if args.x else (0.0, Lx)
    if not x1 > x0:
        raise NarrowsDataError(None, f"--x {x0:g} {x1:g}", "X0 < X1")

    plt = narrows_h5.pyplot()
    from matplotlib.collections import LineCollection, PatchCollection
    from matplotlib.patches import Circle

    height = max(2.0, min(12.0, 16.0 * Ly / (x1 - x0)))
    fig, ax = plt.subplots(figsize=(16, height + 0.6))
    # Disks coloured by kind (the kind of [[colloids.kind]] whose radius matches, else by radius).
    radii = d["radius"]
    sizes = d["kind_radii"] or sorted(set(np.round(radii, 9)))
    palette = ["#9ecae1", "#fdae6b", "#a1d99b", "#bcbddc", "#fdd0a2"]
    colours = [palette[int(np.argmin([abs(r - s) for s in sizes])) % len(palette)] for r in radii]
    xs = d["x"]
    disks, faces = [], []
    for a in range(len(radii)):  # (periodic images across x = 0 and x = Lx)
        for shift in (-Lx, 0.0, Lx):
            cx = xs[a, 0] + shift
            if cx + radii[a] < x0 or cx - radii[a] > x1:
                continue
            disks.append(Circle((cx, xs[a, 1]), radii[a]))
            faces.append(colours[a])
    ax.add_collection(PatchCollection(disks, facecolors=faces, edgecolors="0.4", linewidths=0.3))
    # Contacts: centre to centre (minimum image), or centre to the wall; width linear in |F_n|.
    row = {int(i): a for a, i in enumerate(d["id"])}
    fn = np.asarray(d["fn"], dtype=float)
    top = fn.max() if len(fn) else 1.0
    segments, widths = [], []
    for (o, q), f in zip(d["pairs"], fn):
        a = row[int(o)]
        pa = xs[a, :2]
        if q < 0:
            pb = np.array([pa[0], 0.0 if q == -1 else Ly])
        else:
            pb = xs[row[int(q)], :2].copy()
            pb[0] = pa[0] + (pb[0] - pa[0] + 0.5 * Lx) % Lx - 0.5 * Lx
        for shift in (-Lx, 0.0, Lx):
            s = np.array([pa, pb]) + [shift, 0.0]
            if s[:, 0].max() < x0 or s[:, 0].min() > x1:
                continue
            segments.append(s)
            widths.append(args.width * f / top)
    ax.add_collection(LineCollection(segments, linewidths=widths, colors="red"))
    # The fluid's mean velocity in bins of B x B cells, lateral component amplified.
    fx, fv = d["fluid_x"], d["fluid_v"]
    nx, ny = max(1, int(round(Lx / args.bin))), max(1, int(round(Ly / args.bin)))
    ix = np.clip((fx[:, 0] / Lx * nx).astype(int), 0, nx - 1)
    iy = np.clip((fx[:, 1] / Ly * ny).astype(int), 0, ny - 1)
    n = np.zeros((nx, ny))
    u = np.zeros((nx, ny, 2))
    np.add.at(n, (ix, iy), 1.0)
    for k in range(2):
        np.add.at(u[:, :, k], (ix, iy), fv[:, k])
    full = n > 0
    u[full] /= n[full][:, None]
    cx, cy = np.meshgrid((np.arange(nx) + 0.5) * Lx / nx, (np.arange(ny) + 0.5) * Ly / ny,
                         indexing="ij")
    shown = full & (cx >= x0) & (cx <= x1)
    ax.quiver(cx[shown], cy[shown], u[:, :, 0][shown], args.lateral * u[:, :, 1][shown],
              color="black", angles="xy", scale_units="xy", pivot="mid", width=0.0015)
    ax.axhline(0.0, color="black", linewidth=1.0)
    ax.axhline(Ly, color="black", linewidth=1.0)
    ax.set_xlim(x0, x1)
    ax.set_ylim(-0.5, Ly + 0.5)
    ax.set_aspect("equal")
    slid = float(np.mean(d["sliding"])) if len(fn) else 0.0
    ax.set_title(f"step {d['step']}, t = {d['time']:g}: {len(fn)} contacts "
                 f"(line width ∝ |F_n|, widest {top:.3g}), {100 * slid:.1f} % sliding; "
                 f"fluid velocity in {args.bin:g}-cell bins, lateral x{args.lateral:g}",
                 fontsize=9)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    fig.tight_layout()
    base = args.run if os.path.isdir(args.run) else os.path.dirname(args.run) or "."
    png = args.png or os.path.join(base, "force_chains.png")
    try:
        fig.savefig(png, dpi=110)
    except OSError as e:
        print(f"force_chains: cannot write {png}: {e.strerror}", file=sys.stderr)
        return 2
    print(f"frame {d['frame']} (step {d['step']}, t = {d['time']:g}): {len(fn)} contacts, "
          f"{100 * slid:.1f} % sliding, largest |F_n| {top:.4g}")
    print(f"wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("force_chains", main, sys.argv))
