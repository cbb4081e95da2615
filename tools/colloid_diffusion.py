#!/usr/bin/python3
"""Diffusion coefficient of one no-slip colloid (Kanehl (thesis) §4.4.2, fig 4.9, Table 5.1)
against Stokes-Einstein with the measured viscosity and against the thesis' Table 5.1 / d.

Usage: colloid_diffusion.py --dim 2 --radius 2 [--box-over-a 20] [--density 50] [--dt 0.01]
                            [--time 1000] [--every 10] [--tmax 20] [--ranks 1] [--seed 1]
                            [--nu NU | --measure-nu] [--out out/diff_2d_a2] [--json FILE]
                            [--narrows build/narrows] [--analyse-only]

Runs narrows on a periodic box of side l = box_over_a * a with one density-matched colloid of
radius a, MPC-AT+a, coupling = "no-slip"; the engine's colloid statistics (sampled every
--every steps, lags up to --tmax) give
  D(t) = (1/d) int_0^t C (eq 4.50-4.51), D = its mean over the last quarter of [0, tmax]
      (Kanehl's thesis reads D(t' = 15 t0)), error: the engine's spread of the 10 block
      integrals over sqrt(10) (docs/scenes.md), at the last lags;
  and independently the MSD slope <|r(t) - r(0)|^2> / (2 d t) at t = tmax.
nu: --measure-nu runs a Poiseuille slit of the same fluid (walls at y = 0 and l, side l) and
fits nu to the profile (the `viscosity` observable) over 256 samples of half the momentum
relaxation time l^2 / (pi^2 nu) after ten of them, error from 64 blocks of four (a few s); else --nu, else
narrows' measured 3.98 (2D, n 50, dt 0.01) or Table 5.1's 3.15 (3D).
Stokes-Einstein for the periodic box (eta = n nu, kT = 1; Hasimoto (1959)):
  2D: D_SE = kT (ln(l/a) - 1.3105) / (4 pi eta), 3D: D_SE = kT (1 - 2.837297 a/l) / (6 pi eta a).
Table 5.1 (l = 20a, n 50 (2D) or 10 (3D), dt 0.01): 2D D = 0.00137 (a = 2), 0.000973 (a = 4);
3D 0.00214 (a = 2), 0.000852 (a = 4): d times the thesis' own eq 4.51. Compared in
Stokes-Einstein's dimensionless form, the mobility D eta / kT (depends on l/a alone), with the
thesis' fluid at narrows' measured nu (2D 3.98, 3D 3.15: its eta = 199 and 31.5) and this run's
taken to l = 20a by Stokes-Einstein's l-dependence: "D/(table/d)" should be 1, "D/table" 1/d.
--json FILE writes the numbers (tools/test_colloid_diffusion.py, ctest tools.colloid_diffusion).
"""

import argparse
import math
import os
import subprocess
import sys

import numpy as np

import json

import narrows_h5

TABLE = {(2, 2.0): 0.00137, (2, 4.0): 0.000973, (3, 2.0): 0.00214, (3, 4.0): 0.000852}
NU = {2: 3.98, 3: 3.15}


def scene_text(a):
    L = a.box_over_a * a.radius
    steps = int(round(a.time / a.dt))
    size = ", ".join([f"{L:g}"] * a.dim)
    pos = ", ".join([f"{L / 2:g}"] * a.dim)
    lag = a.every * int(round(a.tmax / (a.dt * a.every)))
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
max_lag = {lag}
correlation_every = {a.every}

[output]
dir = "{a.out}"
every = {steps}
observables = ["temperature", "colloid_vacf", "colloid_diffusion", "colloid_msd",
               "colloid_angular_vacf"]
"""


def poiseuille_text(a, out):
    """The same fluid in a slit of width l (walls at y = 0, l; 10 long in x, periodic), driven
    to u0 ~ 0.2-0.4; 266 samples of half the momentum relaxation time l^2 / (pi^2 nu) each."""
    L = a.box_over_a * a.radius
    n, dt = a.density, a.dt
    f = n - 1 + math.exp(-n)
    nu0 = dt * (n / f - 0.5) + f / (12 * n * dt)  # MPC-AT, Noguchi & Gompper (2008): sets g only
    g = 1.6 * nu0 / L**2
    relax = L**2 / (math.pi**2 * nu0)
    every = max(1, int(round(0.5 * relax / dt)))
    size = ", ".join(["10"] + [f"{L:g}"] * (a.dim - 1))
    force = ", ".join([repr(g)] + ["0.0"] * (a.dim - 1))
    return f"""[run]
engine = "mpcd"
dimensions = {a.dim}
seed = {a.seed + 1000}
steps = {266 * every}

[domain]
size = [{size}]

[fluid]
collision = "{getattr(a, 'collision', 'at+a')}"
density = {n:g}
dt = {dt:g}
kT = 1.0

[body_force]
value = [{force}]

[walls]

[output]
dir = "{out}"
every = {every}
observables = ["viscosity"]
"""


def narrows_cmd(a, path, out):
    cmd = [a.narrows, "run", path, "--out", out, "--overwrite", "--set", "output.progress=false"]
    if a.ranks > 1:
        cmd = ["mpirun", "--oversubscribe", "-n", str(a.ranks)] + cmd
    return cmd


def run(a):
    os.makedirs(a.out, exist_ok=True)
    path = os.path.join(a.out, "scene.toml")
    with open(path, "w") as f:
        f.write(scene_text(a))
    cmd = narrows_cmd(a, path, a.out)
    print(" ".join(cmd), flush=True)
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def measure_nu(a):
    """nu and its error from the Poiseuille slit (poiseuille_text): the last 256 samples (after
    five relaxation times, when the start from rest is e^-5 gone), 64 blocks of four."""
    out = os.path.join(a.out, "poiseuille")
    if not a.analyse_only:
        os.makedirs(out, exist_ok=True)
        path = os.path.join(out, "scene.toml")
        with open(path, "w") as f:
            f.write(poiseuille_text(a, out))
        cmd = narrows_cmd(a, path, out)
        print(" ".join(cmd), flush=True)
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    nu = narrows_h5.open_run(out).series("viscosity")["value"][-256:]
    blocks = nu.reshape(64, 4).mean(axis=1)
    return float(nu.mean()), float(blocks.std(ddof=1) / math.sqrt(len(blocks)))


def stokes_einstein(d, radius, L, eta):
    """D of a stick disc (2D, per unit length) or sphere (3D) in a periodic box of side L
    (Hasimoto (1959), leading order), kT = 1."""
    if d == 2:
        return (math.log(L / radius) - 1.3105) / (4 * math.pi * eta)
    return (1 - 2.837297 * radius / L) / (6 * math.pi * eta * radius)


def colloid_mass(a):
    """Density-matched: n times the colloid's area (2D) or volume (3D)."""
    vol = math.pi * a.radius**2 if a.dim == 2 else 4 / 3 * math.pi * a.radius**3
    return a.density * vol


def measure_statistics(a):
    """The numbers of one run from narrows' own colloid statistics (tools/accuracy_map.py): the
    plateau of D(t) (eq 4.51, over the last quarter of [0, tmax]) and the equipartition ratios
    M<U^2>/(d kT) and I<Omega^2>/(d_rot kT) at lag 0 (I = M a^2/2 in 2D, 2 M a^2/5 in 3D;
    d_rot = 1 in 2D, 3 in 3D), each with narrows' error (10 blocks of time, docs/scenes.md)."""
    run_ = narrows_h5.open_run(a.out)
    diff = run_.series("colloid_diffusion")
    vacf = run_.series("colloid_vacf")
    spin = run_.series("colloid_angular_vacf")
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
    run_ = narrows_h5.open_run(a.out)
    diff = run_.series("colloid_diffusion")
    msd = run_.series("colloid_msd")
    c0 = float(run_.series("colloid_vacf")["value"][0])
    d = a.dim
    L = a.box_over_a * a.radius
    t, D_t, D_err = diff["lags"], diff["value"], diff["error"]
    tail = t >= 0.75 * t[-1]
    D, D_se = float(D_t[tail].mean()), float(D_err[tail].mean())
    D_msd = float(msd["value"][-1] / (2 * d * t[-1]))
    D_msd_se = float(msd["error"][-1] / (2 * d * t[-1]))
    mass = a.density * (math.pi * a.radius**2 if d == 2 else 4 / 3 * math.pi * a.radius**3)
    print(f"d = {d}, a = {a.radius:g}, l = {L:g} = {a.box_over_a:g} a, n = {a.density:g}, "
          f"dt = {a.dt:g}, T = {a.time:g} t0: M <U^2> / (d kT) = {c0 * mass / d:.4g}")
    print(f"D (VACF plateau, t = {t[tail][0]:g}-{t[-1]:g}) = {D:.5g} +- {D_se:.2g}")
    print(f"D (MSD at t = {t[-1]:g})              = {D_msd:.5g} +- {D_msd_se:.2g}")
    for tt in (1, 2, 5, 10, 15, 20, 40):
        if tt <= t[-1]:
            print(f"  D(t = {tt:>2}) = {D_t[np.argmin(np.abs(t - tt))]:.5g}")
    if a.measure_nu:
        nu, nu_se = measure_nu(a)
        src = "measured in a Poiseuille slit of the same fluid"
    else:
        nu, nu_se = (a.nu if a.nu else NU[d]), 0.0
        src = "given" if a.nu else "default"
    eta = a.density * nu
    se = stokes_einstein(d, a.radius, L, eta)
    ratio = D / se
    ratio_se = ratio * math.hypot(D_se / D, nu_se / nu)
    print(f"nu = {nu:.4g} +- {nu_se:.2g} ({src}), eta = n nu = {eta:.4g}")
    print(f"Stokes-Einstein (periodic box, Hasimoto): D_SE = {se:.5g}; D/D_SE = {ratio:.3f} +- "
          f"{ratio_se:.3f}")
    res = dict(dim=d, radius=a.radius, box=L, density=a.density, dt=a.dt, time=a.time, D=D,
               D_error=D_se, D_msd=D_msd, D_msd_error=D_msd_se, nu=nu, nu_error=nu_se, D_SE=se,
               ratio_SE=ratio, ratio_SE_error=ratio_se, kinetic=c0 * mass / d)
    ref = TABLE.get((d, a.radius))
    if ref:
        # the mobility D eta / kT at l = 20 a: this run's moved by Stokes-Einstein's l-dependence
        eta_thesis = (50.0 if d == 2 else 10.0) * NU[d]
        l20 = 20 * a.radius
        mob = (D + stokes_einstein(d, a.radius, l20, eta) - se) * eta
        mob_table = ref * eta_thesis
        r_d = mob / (mob_table / d)
        r_d_se = r_d * math.hypot(D_se / D, nu_se / nu)
        print(f"mobility D eta / kT at l = 20a: {mob:.4g}; Table 5.1 ({ref}, eta = {eta_thesis:g}): "
              f"{mob_table:.4g}, / d: {mob_table / d:.4g}; D/(table/d) = {r_d:.3f} +- {r_d_se:.3f}, "
              f"D/table = {r_d / d:.3f} +- {r_d_se / d:.3f}")
        res.update(table=ref, ratio_table_over_d=r_d, ratio_table_over_d_error=r_d_se,
                   ratio_table=r_d / d, ratio_table_error=r_d_se / d)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=1)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--dim", type=int, choices=(2, 3), required=True)
    p.add_argument("--radius", type=float, required=True)
    p.add_argument("--box-over-a", type=float, default=20.0)
    p.add_argument("--density", type=float)
    p.add_argument("--dt", type=float, default=0.01)
    p.add_argument("--time", type=float, default=1000.0, help="run length in t0")
    p.add_argument("--every", type=int, default=10, help="steps between samples of the colloid statistics")
    p.add_argument("--tmax", type=float, default=20.0, help="longest lag of C(t), in t0")
    p.add_argument("--ranks", type=int, default=1)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--collision", default="at+a", choices=("srd", "at", "at+a"))
    p.add_argument("--nu", type=float, help="kinematic viscosity (default: see above)")
    p.add_argument("--measure-nu", action="store_true",
                   help="measure nu in a Poiseuille slit of the same fluid (OUT/poiseuille)")
    p.add_argument("--json", help="write the numbers to this JSON file")
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
