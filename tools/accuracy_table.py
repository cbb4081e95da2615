#!/usr/bin/python3
"""Accuracy against cost on the 2D Poiseuille channel: nu error and wall time per 10^4 steps.

Usage: accuracy_table.py [--narrows BUILD/narrows] [--out DIR] [--readme README.md]

Runs the 2D SRD channel (alpha = 130 deg, L_x x L_y = 50 x 25, no-slip walls with virtual
particles) for every dt in {0.1, 0.5, 1.0} and n in {5, 10, 20}. The force is chosen for a
centre velocity u0 ~ 0.1 (Ma ~ 0.07) from the theory viscosity, the run length for ~200
momentum-relaxation times L_y^2/(pi^2 nu) (at least 4 10^4 steps); nu is fitted to the velocity
profile of each output interval of the second half (error from their spread), and compared
with SRD kinetic theory at the measured temperature. The wall time per 10^4 steps comes from
the run's own "Loop time" line (one rank); the last column scales the run's wall time by
(relative error / 1 %)^2, the time a 1 % error bar would take. Prints a Markdown table; with --readme, replaces
the table between the markers <!-- accuracy-table --> and <!-- /accuracy-table --> there.
"""

import argparse
import math
import os
import re
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_profile import read_run, theory_viscosity  # noqa: E402

LX, LY, ANGLE = 50, 25, 130.0


def run_case(narrows, out, dt, n):
    nu0, _ = theory_viscosity("srd", 2, n, dt, ANGLE, 1.0)
    g = 8.0 * nu0 * 0.1 / LY**2
    relax_steps = LY**2 / (math.pi**2 * nu0) / dt
    steps = max(40000, int(200 * relax_steps / 1000 + 1) * 1000)
    every = steps // 40
    d = os.path.join(out, f"dt{dt:g}_n{n:g}")
    cmd = [narrows, "run", "run/accuracy_channel.toml", "--out", d,
           "--set", f"fluid.dt={dt}", "--set", f"fluid.density={n}",
           "--set", f"body_force.value=[{g!r}, 0.0]", "--set", f"run.steps={steps}",
           "--set", f"output.every={every}"]
    res = subprocess.run(cmd, capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit(f"accuracy_table: {' '.join(cmd)} failed:\n{res.stderr}")
    m = re.search(r"Loop time of ([0-9.e+-]+) s .* for (\d+) steps with (\d+) particles",
                  res.stdout)
    seconds, nsteps, particles = float(m.group(1)), int(m.group(2)), int(m.group(3))
    _, y, samples, temperature, _, _ = read_run(d)
    q = y * (LY - y) - 1.0 / 12.0
    fits = np.linalg.lstsq(np.vstack([q, np.ones_like(q)]).T, samples.T, rcond=None)[0]
    a = fits[0].mean()
    nu = g / (2.0 * a)
    err = nu * fits[0].std(ddof=1) / math.sqrt(fits.shape[1]) / abs(a)
    nu_theory, _ = theory_viscosity("srd", 2, n, dt, ANGLE, temperature)
    return {"dt": dt, "n": n, "particles": particles, "nu": nu, "err": err,
            "theory": nu_theory, "seconds_per_1e4": seconds * 1e4 / nsteps,
            "relax": relax_steps, "T": temperature, "seconds": seconds}


def table(rows):
    lines = ["| dt | n | particles | nu measured | nu theory | error | wall s / 10^4 steps "
             "| steps per relaxation time | wall s for a 1 % error bar |",
             "|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        dev = 100.0 * (r["nu"] / r["theory"] - 1.0)
        lines.append(f"| {r['dt']:g} | {r['n']:g} | {r['particles']} | {r['nu']:.4f} ± "
                     f"{r['err']:.4f} | {r['theory']:.4f} | {dev:+.1f} ± "
                     f"{100 * r['err'] / r['theory']:.1f} % | {r['seconds_per_1e4']:.2f} | "
                     f"{r['relax']:.0f} | {r['seconds'] * (100 * r['err'] / r['nu'])**2:.0f} |")
    return "\n".join(lines)


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--narrows", default="build/narrows")
    p.add_argument("--out", default="out/accuracy")
    p.add_argument("--readme", help="README to update between the accuracy-table markers")
    args = p.parse_args(argv[1:])
    if not os.access(args.narrows, os.X_OK):
        print(f"accuracy_table: {args.narrows}: no such executable (build first)",
              file=sys.stderr)
        return 2
    rows = []
    for dt in (0.1, 0.5, 1.0):
        for n in (5, 10, 20):
            r = run_case(args.narrows, args.out, dt, n)
            print(f"dt {dt:g} n {n:g}: nu {r['nu']:.4f} +- {r['err']:.4f} vs {r['theory']:.4f}"
                  f" (T {r['T']:.3f}), {r['seconds_per_1e4']:.2f} s per 1e4 steps",
                  file=sys.stderr)
            rows.append(r)
    text = table(rows)
    print(text)
    if args.readme:
        with open(args.readme, encoding="utf-8") as f:
            readme = f.read()
        start, end = "<!-- accuracy-table -->", "<!-- /accuracy-table -->"
        if start not in readme or end not in readme:
            print(f"accuracy_table: {args.readme}: markers {start} ... {end} not found",
                  file=sys.stderr)
            return 2
        head, rest = readme.split(start, 1)
        _, tail = rest.split(end, 1)
        with open(args.readme, "w", encoding="utf-8") as f:
            f.write(head + start + "\n" + text + "\n" + end + tail)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
