#!/usr/bin/python3
"""Diffusion coefficient of one no-slip colloid (Kanehl (thesis) §4.4.2, fig 4.9, Table 5.1).

Usage: colloid_diffusion.py --dim 2 --radius 2 [--box-over-a 20] [--density 50] [--dt 0.01]
                            [--time 1000] [--every 10] [--tmax 20] [--blocks 10]
                            [--ranks 1] [--seed 1] [--collision at+a] [--out out/diff_2d_a2]
                            [--analyse-only]

Runs narrows (build/narrows, or --narrows PATH) on a periodic box of side l = box_over_a * a
with one density-matched colloid of radius a, MPC-AT+a (or --collision), coupling = "no-slip", writing the
colloid's velocity every --every steps to trajectory.h5 (the fluid subsampled away), then:
  C(t) = <U(0).U(t)> (eq 4.50) up to --tmax, D(t) = (1/d) int_0^t C (eq 4.51),
  D = the plateau, the mean of D(t) over the last quarter of [0, tmax] (Kanehl's thesis reads
      D(t' = 15 t0)),
  and independently the MSD slope, <|r(t) - r(0)|^2> / (2 d t) at t = tmax,
  and equipartition M<U^2>/(d kT) and I<Omega^2>/(d_rot kT) (measure() returns them all;
  tools/accuracy_map.py imports it).
Errors: the trajectory is cut into --blocks blocks; each gives its own D (VACF and MSD from
the block alone); the error is the standard error of the block values.
Table 5.1 (l = 20a, dt 0.01): 2D n = 50: D = 0.00137 (a = 2), 0.000973 (a = 4); 3D n = 10:
0.00214 (a = 2), 0.000852 (a = 4).
Finite size: in 3D a periodic box lowers D by xi kT / (6 pi eta l), xi = 2.837297 (Hasimoto;
Yeh & Hummer 2004), eta = n nu; the tool prints D corrected to l = 20a with the nu of
--nu (default: Table 5.1's 3.15 in 3D, narrows' measured 3.98 in 2D; see PHYSICS.md). In 2D
D grows like kT/(4 pi eta) ln(l/a) without limit, so l = 20a is part of the table's
definition; a smaller box is corrected by kT/(4 pi eta) ln(20a/l) (leading order).
"""

import argparse
import math
import os
import subprocess
import sys

import numpy as np

import narrows_h5

TABLE = {(2, 2.0): 0.00137, (2, 4.0): 0.000973, (3, 2.0): 0.00214, (3, 4.0): 0.000852}
NU = {2: 3.98, 3: 3.15}


def scene_text(a):
    L = a.box_over_a * a.radius
    steps = int(round(a.time / a.dt))
    size = ", ".join([f"{L:g}"] * a.dim)
    pos = ", ".join([f"{L / 2:g}"] * a.dim)
    return f"""[run]
engine = "mpcd"
dimensions = {a.dim}
seed = {a.seed}
steps = {steps}

[domain]
size = [{size}]

[fluid]
collision = "{getattr(a, 'collision', 'at+a')}"
density = {a.density:g}
dt = {a.dt:g}
kT = 1.0

[colloids]
coupling = "no-slip"
radius = {a.radius:g}
placement = "list"
positions = [[{pos}]]
""" + (f"""max_lag = {int(round(a.tmax / a.dt / a.every)) * a.every}
correlation_every = {a.every}
""" if getattr(a, "statistics", False) else "") + f"""
[output]
dir = "{a.out}"
every = {steps}
""" + (f"""observables = ["temperature", "colloid_vacf", "colloid_diffusion", "colloid_angular_vacf"]
""" if getattr(a, "statistics", False) else f"""observables = ["temperature"]
trajectory_every = {a.every}
trajectory_subsample = 1000000000
""")


def run(a):
    os.makedirs(a.out, exist_ok=True)
    path = os.path.join(a.out, "scene.toml")
    with open(path, "w") as f:
        f.write(scene_text(a))
    cmd = [a.narrows, "run", path, "--out", a.out, "--overwrite"]
    if a.ranks > 1:
        cmd = ["mpirun", "--oversubscribe", "-n", str(a.ranks)] + cmd
    print(" ".join(cmd), flush=True)
    subprocess.run(cmd, check=True)


def vacf(v, nlag):
    """<v(0).v(t)> for t = 0..nlag-1 over all time origins (FFT, unbiased)."""
    n = len(v)
    c = np.zeros(nlag)
    for k in range(v.shape[1]):
        f = np.fft.rfft(v[:, k], 2 * n)
        c += np.fft.irfft(f * np.conj(f))[:nlag]
    return c / (n - np.arange(nlag))


def colloid_mass(a):
    """Density-matched: n times the colloid's area (2D) or volume (3D)."""
    vol = math.pi * a.radius**2 if a.dim == 2 else 4 / 3 * math.pi * a.radius**3
    return a.density * vol


def stokes_einstein(d, radius, box, eta, kT=1.0):
    """D of a no-slip sphere in a periodic cubic box of side `box` (3D): Stokes-Einstein
    kT / (6 pi eta a) lowered by Hasimoto's xi kT / (6 pi eta l), xi = 2.837297 (Hasimoto
    (1959); Yeh & Hummer (2004) eq 7). In 2D there is no Stokes-Einstein limit (D grows like
    ln l): None."""
    if d != 3:
        return None
    return kT / (6 * math.pi * eta * radius) - 2.837297 * kT / (6 * math.pi * eta * box)


def measure(a):
    """The numbers of one run: D from the VACF plateau and from the MSD with their block
    errors, <U^2>, M<U^2>/(d kT) and the spin equipartition I<Omega^2>/(d_rot kT) (I = M a^2/2
    in 2D, 2 M a^2/5 in 3D; d_rot = 1 in 2D, 3 in 3D) with their block errors."""
    with narrows_h5.open_trajectory(a.out) as f:
        v = f.dataset("particles/colloids/velocity/value")[:, 0, :]
        x = f.dataset("particles/colloids/position/value")[:, 0, :]
        w = f.dataset("particles/colloids/angular_velocity/value")[:, 0, :]
    d = a.dim
    L = a.box_over_a * a.radius
    h = a.every * a.dt  # time between frames
    dx = np.diff(x, axis=0)
    dx -= L * np.round(dx / L)
    r = np.concatenate([np.zeros((1, d)), np.cumsum(dx, axis=0)])
    nlag = int(round(a.tmax / h)) + 1
    t = np.arange(nlag) * h
    tail = t >= 0.75 * a.tmax
    M = colloid_mass(a)
    inertia = M * a.radius**2 * (0.5 if d == 2 else 0.4)
    spin = inertia * (w[:, 2] ** 2 if d == 2 else np.sum(w**2, axis=1) / 3)
    trans = M * np.sum(v**2, axis=1) / d

    def estimate(vb, rb):
        c = vacf(vb, nlag)
        D_t = np.concatenate([[0.0], np.cumsum(0.5 * (c[1:] + c[:-1]) * h)]) / d
        lag = nlag - 1
        msd = np.mean(np.sum((rb[lag:] - rb[:-lag]) ** 2, axis=1))
        return c, D_t, D_t[tail].mean(), msd / (2 * d * t[-1])

    c, D_t, D_vacf, D_msd = estimate(v, r)
    nb = len(v) // a.blocks
    blocks = [estimate(v[i * nb:(i + 1) * nb], r[i * nb:(i + 1) * nb]) for i in range(a.blocks)]
    se = lambda z: np.std(z, ddof=1) / math.sqrt(len(z))
    block_mean = lambda z: np.array([z[i * nb:(i + 1) * nb].mean() for i in range(a.blocks)])
    return dict(d=d, L=L, h=h, t=t, c=c, D_t=D_t, frames=len(v), T=(len(v) - 1) * h,
                D_vacf=D_vacf, D_vacf_err=se(np.array([b[2] for b in blocks])),
                D_msd=D_msd, D_msd_err=se(np.array([b[3] for b in blocks])),
                trans=trans.mean(), trans_err=se(block_mean(trans)),
                spin=spin.mean(), spin_err=se(block_mean(spin)))


def measure_statistics(a):
    """The numbers of measure() from narrows' own colloid statistics of a run made with
    a.statistics = True (scene_text then lists colloid_vacf, colloid_diffusion and
    colloid_angular_vacf, with max_lag = tmax and correlation_every = every, instead of a
    trajectory, whose writing costs more than the run when the frames are many): the same
    plateau of D(t) (eq 4.51, over the last quarter of [0, tmax]) and the equipartition ratios
    at lag 0, each with narrows' error (10 blocks of time, docs/scenes.md)."""
    run = narrows_h5.open_run(a.out)
    diff = run.series("colloid_diffusion")
    vacf = run.series("colloid_vacf")
    spin = run.series("colloid_angular_vacf")
    t = diff["lags"]
    tail = t >= 0.75 * t[-1]
    d = a.dim
    M = colloid_mass(a)
    inertia = M * a.radius**2 * (0.5 if d == 2 else 0.4)
    d_rot = 1 if d == 2 else 3
    return dict(d=d, L=a.box_over_a * a.radius, t=t, D_t=diff["value"],
                D_vacf=float(diff["value"][tail].mean()),
                D_vacf_err=float(diff["error"][tail].mean()),
                trans=float(M * vacf["value"][0] / d), trans_err=float(M * vacf["error"][0] / d),
                spin=float(inertia * spin["value"][0] / d_rot),
                spin_err=float(inertia * spin["error"][0] / d_rot))


def analyse(a):
    m = measure(a)
    d, L, c, D_t, D_vacf = m["d"], m["L"], m["c"], m["D_t"], m["D_vacf"]
    h = m["h"]
    print(f"d = {d}, a = {a.radius:g}, l = {L:g} = {a.box_over_a:g} a, n = {a.density:g}, "
          f"dt = {a.dt:g}: T = {m['T']:g} t0 in {m['frames']} frames, <U^2> = {c[0]:.5g} "
          f"(d kT/M = {d / colloid_mass(a):.5g})")
    print(f"D (VACF plateau, t = {0.75 * a.tmax:g}-{a.tmax:g}) = {D_vacf:.5g} +- "
          f"{m['D_vacf_err']:.2g}  (blocks: {a.blocks})")
    print(f"D (MSD at t = {a.tmax:g})              = {m['D_msd']:.5g} +- {m['D_msd_err']:.2g}")
    print(f"equipartition: M<U^2>/(d kT) = {m['trans']:.4f} +- {m['trans_err']:.4f}, "
          f"I<Omega^2>/(d_rot kT) = {m['spin']:.4f} +- {m['spin_err']:.4f}")
    for tt in (1, 2, 5, 10, 15, 20):
        if tt <= a.tmax:
            print(f"  D(t = {tt:>2}) = {D_t[int(round(tt / h))]:.5g}")
    nu = a.nu if a.nu else NU[d]
    eta = a.density * nu
    l20 = 20 * a.radius
    if d == 3:
        corr = 2.837297 / (6 * math.pi * eta) * (1 / L - 1 / l20)
        label = "Hasimoto xi kT/(6 pi eta) (1/l - 1/20a)"
    else:
        corr = 1 / (4 * math.pi * eta) * math.log(l20 / L)
        label = "kT/(4 pi eta) ln(20a/l)"
    ref = TABLE.get((d, a.radius))
    print(f"to l = 20a: + {corr:.3g} ({label}, eta = n nu = {eta:g}) -> D = {D_vacf + corr:.5g}"
          + (f"; Table 5.1: {ref} (ratio {(D_vacf + corr) / ref:.3f} +- "
             f"{m['D_vacf_err'] / ref:.3f})" if ref else ""))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--dim", type=int, choices=(2, 3), required=True)
    p.add_argument("--radius", type=float, required=True)
    p.add_argument("--box-over-a", type=float, default=20.0)
    p.add_argument("--density", type=float)
    p.add_argument("--dt", type=float, default=0.01)
    p.add_argument("--time", type=float, default=1000.0, help="run length in t0")
    p.add_argument("--every", type=int, default=10, help="steps between velocity samples")
    p.add_argument("--tmax", type=float, default=20.0, help="longest lag of C(t), in t0")
    p.add_argument("--blocks", type=int, default=10)
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--collision", default="at+a", choices=("srd", "at", "at+a"))
    p.add_argument("--nu", type=float, help="kinematic viscosity for the size correction")
    p.add_argument("--out", default=None)
    p.add_argument("--narrows", default=os.path.join(os.path.dirname(__file__), "..", "build",
                                                     "narrows"))
    p.add_argument("--analyse-only", action="store_true")
    a = p.parse_args()
    if a.density is None:
        a.density = 50.0 if a.dim == 2 else 10.0
    if a.out is None:
        a.out = f"out/diffusion_{a.dim}d_a{a.radius:g}_l{a.box_over_a:g}a"
    if not a.analyse_only:
        run(a)
    analyse(a)


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("colloid_diffusion", main))
