#!/usr/bin/python3
"""Energy drift of the MD-coupled colloids against the number of MD sub-steps, and its cost.

Usage: colloid_energy_drift.py [--narrows build/narrows] [--scene run/colloids_conservation.toml]
                               [--steps 10000] [--substeps 1,2,5,15,30] [--out DIR]

Runs the scene (periodic SRD fluid with colloids, no gravity, walls or thermostat: the total
energy is conserved up to the velocity-Verlet error) once per k = colloids.md_substeps, reads the
"energy" and "momentum" series from observables.h5 and the "Loop time" line of the log, and
prints a Markdown table: k, tau_MD, relative energy drift (E_end - E_0)/E_0, the slope of a
linear fit of E(t)/E_0 per unit time, the largest |P - P_0|, and the wall time.
"""

import argparse
import os
import re
import subprocess
import sys

import h5py
import numpy as np


def run_case(narrows, scene, out, k, steps):
    d = os.path.join(out, f"k{k}")
    cmd = [narrows, "run", scene, "--out", d, "--set", f"colloids.md_substeps={k}",
           "--set", f"run.steps={steps}", "--set", "output.progress=false"]
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:  # exit 3: the MD step is too long for the colloid-fluid potential
        return None, r.stderr.strip().splitlines()[-1] if r.stderr.strip() else f"exit {r.returncode}"
    with h5py.File(os.path.join(d, "observables.h5"), "r") as f:
        t = f["/observables/energy/time"][()]
        e = f["/observables/energy/value"][()]
        p = f["/observables/momentum/value"][()]
    with open(os.path.join(d, "log.txt")) as f:
        loop = re.search(r"Loop time of ([0-9.eE+-]+) s", f.read())
    seconds = float(loop.group(1)) if loop else float("nan")
    rel = e / e[0]
    slope = np.polyfit(t, rel, 1)[0]
    dp = np.max(np.abs(p - p[0]))
    return rel[-1] - 1.0, slope, dp, seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--narrows", default="build/narrows")
    ap.add_argument("--scene", default="run/colloids_conservation.toml")
    ap.add_argument("--steps", type=int, default=10000)
    ap.add_argument("--substeps", default="1,2,5,15,30")
    ap.add_argument("--out", default="out/colloid_energy_drift")
    a = ap.parse_args()
    dt = None
    with open(a.scene) as f:
        m = re.search(r"^dt\s*=\s*([0-9.eE+-]+)", f.read(), re.M)
        dt = float(m.group(1)) if m else float("nan")
    print(f"{a.scene}, {a.steps} steps, one rank")
    print()
    print("| k | tau_MD | (E_end - E_0)/E_0 | d(E/E_0)/dt | max abs(P - P_0) | wall time [s] |")
    print("|---|---|---|---|---|---|")
    for k in [int(s) for s in a.substeps.split(",")]:
        res = run_case(a.narrows, a.scene, a.out, k, a.steps)
        if res[0] is None:
            print(f"| {k} | {dt / k:.4g} | failed: {res[1][:90]} | | | |")
            continue
        drift, slope, dp, seconds = res
        print(f"| {k} | {dt / k:.4g} | {drift:.3e} | {slope:.3e} | {dp:.2e} | {seconds:.1f} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
