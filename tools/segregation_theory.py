#!/usr/bin/env python3
"""The segregation theory of Kanehl (thesis) ch.5 from the continuum engine (model
"segregation"): fig 5.3 and eq 5.29, and which single-colloid diffusivity D_0 the thesis' model
curves need (docs/segregation.md).

  /usr/bin/python3 tools/segregation_theory.py fig5_3 [--out DIR]
  /usr/bin/python3 tools/segregation_theory.py d0 [--out DIR]
  /usr/bin/python3 tools/segregation_theory.py scan [--out DIR]

fig5_3: runs the model's observable collective_diffusivity (a run of no length) for the 2D
mixture of fig 5.3 (c_L = c_S, a_L / a_S = 2: phi_L / phi_S = 4) and a 3D one, reads them
through narrows_h5 and draws DIR/fig5_3.png: (a) D_C / (K_d D_0) = 1 / S(phi) against phi (eq
5.23 with S of eq 5.19-5.20; dashed: eq 5.19's "(1 - phi2)" read as 1 - phi^2 instead of the
(1 - phi)^2 the model uses; dotted: the off-diagonal D_C^SL / (K_d D_0^S) of eq 5.28), (b) eta /
eta_0 of eq 5.29 in 2D (phi_M = 0.82) and 3D (0.64). Prints the curves at phi = 0.1 .. 0.8.

d0: the steady profiles of the thesis' 2D channel (w = 40, a_S = 2, a_L = 4, phi = 0.5, K_eta /
K_c = 1.51, K_d / K_c = 7.46, phi_L / phi_S = 1, 0.67, 0.5, 0.4, 0.2, 0.08) and of its 3D channel
(phi = 0.35, K_d / K_c = 0.61, phi_M = 0.64) for each D_0 convention: (i) Table 5.1's D as given,
(ii) Table 5.1's D / d (the tabulated D are d times eq 4.51), (iii) Stokes-Einstein kT / (6 pi
rho nu a) with nu measured here (2D 3.98) or the thesis' (2D 3.22, 3D 3.15); and for each of
three centre speeds: "table" v0 = w^2 D_S / a_S^3 with Table 5.1's D_S (Pe_S = 1 as the thesis
computes it: its Pe_L ~ 10 in 2D is Table 5.1's ratio), "own" the same with the convention's
D_S, "drive" v0 = g w^2 / (2 nu) with g = 1e-4 (run/segregation_table5_1_channel_2d.toml; the
thesis gives no g). The steady state (centre values, c(0)/c_mean, the wall ratio K_c a^2 gdot phi
/ (K_d D_0)) is what `narrows check` prints. Prints one table per dimension and writes it to
DIR/d0_conventions.md; K_d is the value that gives each convention the thesis' K_d D_0^S (K_d /
K_c = 7.46 with its Stokes-Einstein D_0 at nu = 3.22; 0.61 at 3.15 in 3D).

scan: 2D, the small disks' wall ratio and the large disks' central peak at phi_L / phi_S = 0.67,
0.5, 0.4 (fig 5.8) against f = K_c v0 / (K_d D_0^S) in units of its value at Pe_S = 1 (f = 1 to
8), for D_L / D_S of Table 5.1 (0.71) and of Stokes-Einstein (1/2): whether any single speed
gives both the thesis' wall ratio ~ 3 and a rising peak. Writes DIR/d0_scan.md.
"""

import argparse
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

import narrows_h5
from continuum_run import find_narrows

W, A_S, A_L = 40.0, 2.0, 4.0
RATIOS = (1.0, 0.67, 0.5, 0.4, 0.2, 0.08)
# dims: (rho, total phi, K_d / K_c, phi_M, Table 5.1 D_S, D_L, the thesis' nu, nu measured here)
CHANNEL = {2: (50.0, 0.5, 7.46, 0.82, 0.00137, 0.000973, 3.22, 3.98),
           3: (10.0, 0.35, 0.61, 0.64, 0.00214, 0.000852, 3.15, None)}
DRIVE_G = 1e-4


class InputError(Exception):
    """A failed narrows call or an output the tool cannot read."""


def stokes_einstein(rho, nu, a, kt=1.0):
    """D_0 = kT / (6 pi eta a), eta = rho nu (Kanehl (thesis) sec 5.2.4)."""
    return kt / (6.0 * math.pi * rho * nu * a)


def conventions(dims):
    """[(label, D_S, D_L, nu of the drive)] of the D_0 conventions in `dims` dimensions."""
    rho, _, _, _, ds, dl, nu_thesis, nu_here = CHANNEL[dims]
    out = [("(i) Table 5.1", ds, dl, nu_here or nu_thesis),
           (f"(ii) Table 5.1 / {dims}", ds / dims, dl / dims, nu_here or nu_thesis)]
    for nu in (nu_here, nu_thesis):
        if nu is not None:
            out.append((f"(iii) Stokes-Einstein nu = {nu:g}", stokes_einstein(rho, nu, A_S),
                        stokes_einstein(rho, nu, A_L), nu))
    return out


def scene(dims, v0, kinds, k_d=None, phi_m=None, observables=None, time=1e-9):
    text = ('[run]\nengine = "continuum"\n[continuum]\nmodel = "segregation"\n'
            f"dimensions = {dims}\nhalf_width = {W!r}\ncells = 80\ncentre_speed = {v0!r}\n"
            f"k_c = 1.0\nk_eta = 1.51\ntime = {time!r}\nsamples = 1\n")
    if k_d is not None:
        text += f"k_d = {k_d!r}\n"
    if phi_m is not None:
        text += f"max_packing = {phi_m!r}\n"
    for a, f, d in kinds:
        text += f"[[continuum.kind]]\nradius = {a!r}\nfraction = {f!r}\ndiffusivity = {d!r}\n"
    text += "[output]\nprogress = false\n"
    if observables:
        text += "observables = [" + ", ".join(f'"{o}"' for o in observables) + "]\n"
    return text


STEADY = re.compile(r"^steady state kind (\d): phi\(0\) = (\S+), phi\(w\) = (\S+), "
                    r"c\(0\)/c_mean = (\S+), .* at the wall (\S+)$", re.M)


def parse_check(text):
    """{kind: (phi(0), phi(w), c(0)/c_mean, wall ratio)} from `narrows check` of a segregation
    scene; None if it found no steady state."""
    if "steady state: none found" in text:
        return None
    got = {int(m[0]): tuple(float(x) for x in m[1:]) for m in STEADY.findall(text)}
    if not got:
        raise InputError("narrows check printed no 'steady state kind' lines")
    return got


def steady(narrows, work, dims, v0, ds, dl, ratio, k_d):
    """The steady state of the mixture at phi_L / phi_S = ratio."""
    rho, phi, _, phi_m, *_ = CHANNEL[dims]
    large = phi * ratio / (1.0 + ratio)
    path = os.path.join(work, "d0.toml")
    with open(path, "w") as f:
        f.write(scene(dims, v0, [(A_S, phi - large, ds), (A_L, large, dl)], k_d, phi_m))
    r = subprocess.run([narrows, "check", path], capture_output=True, text=True)
    if r.returncode != 0:
        raise InputError("narrows check of the segregation model failed: " +
                         (r.stderr.strip().splitlines() or ["?"])[-1])
    return parse_check(r.stdout + r.stderr)


def speeds(dims, ds, nu):
    """The centre speeds {name: v0} of the three choices (drive only in 2D)."""
    table_ds = CHANNEL[dims][4]
    out = {"table": W * W * table_ds / A_S ** 3, "own": W * W * ds / A_S ** 3}
    if dims == 2:
        out["drive"] = DRIVE_G * W * W / (2.0 * nu)
    return out


def d0_rows(narrows, dims):
    rho, phi, kd_thesis, *_ = CHANNEL[dims]
    nu_thesis = CHANNEL[dims][6]
    target = kd_thesis * stokes_einstein(rho, nu_thesis, A_S)  # the thesis' K_d D_0^S
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for label, ds, dl, nu in conventions(dims):
            for speed, v0 in speeds(dims, ds, nu).items():
                per = [steady(narrows, work, dims, v0, ds, dl, r, kd_thesis) for r in RATIOS]
                rows.append({"convention": label, "speed": speed, "v0": v0, "D_S": ds,
                             "D_L": dl, "Pe_S": A_S ** 3 * v0 / (W * W * ds),
                             "Pe_L": A_L ** 3 * v0 / (W * W * dl), "K_d": target / ds,
                             "steady": per})
    return rows


def features(row):
    """The thesis' statements checked on a row: wall ratio of S ~ 3 (2D, sec 5.3.3) or ~ 12 (3D,
    sec 5.4.3) within a factor 1.5; c_L(0)/c_mean rising from phi_L/phi_S = 0.67 to 0.4 (fig 5.8);
    and on to 0.08 (fig 5.9)."""
    s = row["steady"]
    if any(x is None for x in s):
        return None, None, None
    peak = [x[1][2] for x in s]
    return s[0][0][3], peak[1] < peak[2] < peak[3], all(peak[k] < peak[k + 1]
                                                        for k in range(1, len(peak) - 1))


def d0_table(rows, dims):
    want = 3.0 if dims == 2 else 12.0
    head = ("| D_0 convention | v0 | D_S | D_L | Pe_S | Pe_L | K_d for the thesis' K_d D_0^S | "
            "wall ratio S, L (phi_L/phi_S = 1) | c_L(0)/c_mean at phi_L/phi_S = " +
            ", ".join(f"{r:g}" for r in RATIOS) + " | c_S(0)/c_mean at 1, 0.08 | "
            f"wall S ~ {want:g} | c_L peak rises 0.67 -> 0.4 | and on to 0.08 |")
    lines = [head, "|" + "---|" * head.count(" | ") + "---|"]
    for r in rows:
        s = r["steady"]
        wall, rises, on = features(r)
        if wall is None:
            cells = ["no steady state at some phi_L/phi_S"] + [""] * 5
        else:
            cells = [f"{s[0][0][3]:.3g}, {s[0][1][3]:.3g}",
                     ", ".join(f"{x[1][2]:.3g}" for x in s),
                     f"{s[0][0][2]:.3g}, {s[-1][0][2]:.3g}",
                     "yes" if abs(math.log(wall / want)) < math.log(1.5) else "no",
                     "yes" if rises else "no", "yes" if on else "no"]
        lines.append(f"| {r['convention']} | {r['speed']} {r['v0']:.4g} | {r['D_S']:.4g} | "
                     f"{r['D_L']:.4g} | {r['Pe_S']:.3g} | {r['Pe_L']:.3g} | {r['K_d']:.3g} | " +
                     " | ".join(cells) + " |")
    return "\n".join(lines)


def scan(narrows):
    """2D: the S wall ratio (phi_L/phi_S = 1) and c_L(0)/c_mean at 0.67, 0.5, 0.4 against the
    speed factor f = K_c v0 / (K_d D_0^S) over its value at Pe_S = 1, for D_L / D_S of Table 5.1
    and of Stokes-Einstein (1/2)."""
    ds = CHANNEL[2][4]
    lines = ["| D_L / D_S | f | wall ratio S | c_L(0)/c_mean at 0.67, 0.5, 0.4 | rises |",
             "|---|---|---|---|---|"]
    with tempfile.TemporaryDirectory() as work:
        for ratio in (CHANNEL[2][5] / ds, 0.5):
            for f in (1, 1.5, 2, 3, 4, 6, 8):
                v0 = f * W * W * ds / A_S ** 3
                got = [steady(narrows, work, 2, v0, ds, ds * ratio, r, CHANNEL[2][2])
                       for r in (1.0, 0.67, 0.5, 0.4)]
                if any(g is None for g in got):
                    lines.append(f"| {ratio:.3g} | {f:g} | no steady state at some phi_L/phi_S |"
                                 " | |")
                    continue
                peak = [g[1][2] for g in got[1:]]
                lines.append(f"| {ratio:.3g} | {f:g} | {got[0][0][3]:.3g} | " +
                             ", ".join(f"{p:.3g}" for p in peak) + " | " +
                             ("yes" if peak[0] < peak[1] < peak[2] else "no") + " |")
    return "\n".join(lines)


def curves(narrows, work, dims, kinds, name):
    out = os.path.join(work, name)
    path = out + ".toml"
    with open(path, "w") as f:
        f.write(scene(dims, 0.1, kinds, observables=["collective_diffusivity"]))
    r = subprocess.run([narrows, "run", path, "--out", out, "--overwrite"], capture_output=True,
                       text=True)
    if r.returncode != 0:
        raise InputError(f"narrows run of {name} failed: " +
                         (r.stderr.strip().splitlines() or ["?"])[-1])
    return narrows_h5.open_run(out).series("collective_diffusivity")


def fig5_3(narrows, out_dir):
    with tempfile.TemporaryDirectory() as work:
        # c_L = c_S: phi_L / phi_S = (a_L / a_S)^d.
        two = curves(narrows, work, 2, [(A_S, 0.1, 1.0), (A_L, 0.4, 0.5)], "fig5_3_2d")
        three = curves(narrows, work, 3, [(A_S, 0.3 / 9.0, 1.0), (A_L, 2.4 / 9.0, 0.5)],
                       "fig5_3_3d")
    phi, value = two["bins"], two["value"]
    diag = value[:, 0, 0]
    other = diag * (1.0 - phi) / (1.0 + phi)  # 1 / S with 1 - phi^2 for (1 - phi)^2
    print("Kanehl (thesis) fig 5.3 (2D, c_L = c_S, a_L / a_S = 2) and eq 5.29:")
    print("phi    D_C/(K_d D_0)  [1-phi^2 reading]  D_C^SL/(K_d D_0^S)  S(phi)   "
          "eta/eta_0 2D   eta/eta_0 3D")
    for p in (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8):
        k = int(np.argmin(np.abs(phi - p)))
        k3 = int(np.argmin(np.abs(three["bins"] - p)))
        eta3 = f"{three['viscosity'][k3]:.4g}" if abs(three["bins"][k3] - p) < 0.01 else "-"
        print(f"{phi[k]:.4f} {diag[k]:12.4g} {other[k]:16.4g} {value[k, 0, 1]:18.4g} "
              f"{two['structure_factor'][k]:10.4g} {two['viscosity'][k]:12.4g} {eta3:>12}")
    print(f"largest phi {phi[-1]:.4f}: D_C/(K_d D_0) = {diag[-1]:.4g} ({other[-1]:.4g} with "
          f"1 - phi^2); eta/eta_0 = {two['viscosity'][-1]:.4g} (3D at {three['bins'][-1]:.4f}: "
          f"{three['viscosity'][-1]:.4g})")
    plt = narrows_h5.pyplot()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10, 4))
    ax.plot(phi, diag, "-", label="eq 5.23, S of eq 5.19 with (1 - phi)^2 (model)")
    ax.plot(phi, other, "--", label="eq 5.19 read as 1 - phi^2")
    ax.plot(phi, value[:, 0, 1], ":", label="off-diagonal D_C^SL / (K_d D_0^S), eq 5.28")
    ax.set_yscale("log")
    ax.set_ylim(1e-2, None)
    ax.set_xlabel("phi")
    ax.set_ylabel("D_C / (K_d D_0)")
    ax.set_title("fig 5.3: 2D, c_L = c_S, a_L/a_S = 2")
    ax.legend(fontsize=7)
    bx.plot(phi, two["viscosity"], "-", label="2D, phi_M = 0.82")
    bx.plot(three["bins"], three["viscosity"], "--", label="3D, phi_M = 0.64")
    bx.set_yscale("log")
    bx.set_xlabel("phi")
    bx.set_ylabel("eta / eta_0")
    bx.set_title("eq 5.29")
    bx.legend(fontsize=7)
    fig.tight_layout()
    png = os.path.join(out_dir, "fig5_3.png")
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("what", choices=["fig5_3", "d0", "scan"])
    p.add_argument("--out", default=os.path.join("out", "segregation_theory"),
                   help="folder of the PNG / table (default out/segregation_theory)")
    p.add_argument("--narrows", help="the narrows binary (default: $NARROWS, build/narrows, "
                                      "the PATH)")
    p.add_argument("--dimensions", type=int, nargs="+", default=[2, 3], choices=[2, 3],
                   help="d0: the channels (default 2 3)")
    a = p.parse_args(argv)
    try:
        narrows = find_narrows(a.narrows)
        os.makedirs(a.out, exist_ok=True)
        if a.what == "fig5_3":
            fig5_3(narrows, a.out)
            return 0
        if a.what == "scan":
            out = scan(narrows)
            print(out)
            with open(os.path.join(a.out, "d0_scan.md"), "w") as f:
                f.write(out + "\n")
            return 0
        text = []
        for dims in a.dimensions:
            rows = d0_rows(narrows, dims)
            rho, phi, kd, phi_m, ds, dl, nu_t, nu_h = CHANNEL[dims]
            text.append(f"{dims}D: w = {W:g}, a_S = {A_S:g}, a_L = {A_L:g}, phi = {phi:g}, "
                        f"K_d/K_c = {kd:g}, K_eta/K_c = 1.51, phi_M = {phi_m:g}\n")
            text.append(d0_table(rows, dims) + "\n")
        out = "\n".join(text)
        print(out)
        path = os.path.join(a.out, "d0_conventions.md")
        with open(path, "w") as f:
            f.write(out)
        print(f"wrote {path}")
    except (InputError, narrows_h5.NarrowsDataError) as e:
        return narrows_h5.report("segregation_theory", e)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
