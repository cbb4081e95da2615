#!/usr/bin/python3
"""Test of tools/pulses.py (Kanehl (thesis) §6.2: pulse speed, spacing, f_pt, state).

Usage: /usr/bin/python3 tools/test_pulses.py NARROWS_BINARY

a) Synthetic travelling waves written as a particle run's /observables/axial_fields (phi,
   velocity, fluid_velocity [T][bins], bins, step, time): a harmonic v = vbar + A cos(k (x - c t))
   upstream and downstream, and a sharp pulse shape (exp of a cosine: many harmonics). The tool's
   estimators are exact for them (the correlation ridge is at s = c tau, the correlation's first
   maximum at lambda, the spectrum's maximum at |c| / lambda; each refined on the exact Fourier
   series / DTFT, not on the grid): c, lambda and f_pt must be the exact values to 1e-6
   (optimiser tolerances 1e-9; no exact value lies on the grids of x, t or f, where an estimate
   without the refinement misses by more than 1e-3).
b) Classification (§6.2.2) of three synthetic runs with noise: pulses (<dv^2>/<v>^2 = 0.5),
   free flow (0.01, <v>/v0 = 0.1) and jammed (0.01, <v>/v0 = 0.001); v0 given by --v0, from the
   run's viscosity observable (g w^2 / (2 nu), computed here) and for the continuum run v_ss(0)
   of eq 6.4 (Table 6.2, mu = 1: e1 + 2 dv to 1e-12); the kinetic-theory nu pulses.py uses
   for v0 is the one `narrows info` prints for four scenes of run/ (srd 2D/3D, at+a 3D, and none
   for at+a 2D, where pulses.py asks for --nu with one line, exit 2); bins without colloids
   (velocity NaN) are interpolated and counted.
c) A continuum jamming run (run/continuum_jamming_pulses.toml started from phi = 0.75 + 0.01
   sin(2 pi 5 x / L): a train of 5 pulses; 256 points, t = 300, 1500 samples, ~3 s): c within 1 %
   of the speed of the PDE's own density maximum (one maximum of phi(x, t), smoothed over 2
   length units, followed sample by sample, refined by a parabola, unwrapped, least-squares
   slope over t >= 60), lambda within 2 % of the mean distance between the jams (L / the number
   of intervals where phi is above the middle of its range, averaged over the samples), f_pt
   within 2 % of |c| / lambda of these two.
Prints FAIL lines and "N passed, M failed"; exit 1 on any failure.
"""

import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import narrows_h5  # noqa: E402
from selftest import check, summary  # noqa: E402
import vss_fit  # noqa: E402  (eq 6.4 with Table 6.2, written independently of jamming_plot)


SCENE = """[run]
dimensions = 2
steps = 1000

[domain]
size = [{L}, 50.0]

[fluid]
collision = "at+a"
density = 25
dt = 0.02

[body_force]
value = [{g}, 0.0]
"""



def write_run(path, t, x, v, phi, length, g=0.05, extra=None):
    os.makedirs(path, exist_ok=True)
    step = np.arange(len(t), dtype=np.int64) * 10
    series = {"axial_fields": {"step": step, "time": t, "phi": phi, "velocity": v,
                               "fluid_velocity": 2 * v, "bins": x}}
    series.update(extra or {})
    narrows_h5.write_observables(os.path.join(path, "observables.h5"), series=series,
                                 scene=SCENE.format(L=length, g=g))


def run_tool(path, *args):
    done = subprocess.run([sys.executable, os.path.join(HERE, "pulses.py"), path, *args],
                          capture_output=True, text=True)
    if done.returncode != 0:
        return None, done.stderr.strip()
    with open(os.path.join(path, "pulses.json")) as f:
        return json.load(f), done.stdout


def rel(a, b):
    return abs(a - b) / abs(b) if a is not None else math.inf


def travelling(tmp):
    L, X, T, dt = 120.0, 97, 400, 0.5
    x = (np.arange(X) + 0.5) * L / X
    t = np.arange(T) * dt
    cases = {  # name: (c, lambda, profile of the phase)
        "harmonic upstream": (-1.37, L / 5, np.cos),
        "harmonic downstream": (0.83, L / 3, np.cos),
        "sharp pulses": (-2.11, L / 4, lambda p: np.exp(2 * np.cos(p)) / 3),
    }
    for name, (c, lam, shape) in cases.items():
        k = 2 * np.pi / lam
        phase = k * (x[None, :] - c * t[:, None])
        v = 0.3 + 0.2 * shape(phase)
        path = os.path.join(tmp, name.replace(" ", "_"))
        write_run(path, t, x, v, 0.75 - 0.1 * shape(phase), L)
        res, out = run_tool(path, "--v0", "3.0")
        if res is None:
            check(f"a) {name}: pulses.py runs", False, out)
            continue
        f = abs(c) / lam
        check(f"a) {name}: c = {c}", rel(res["pulse_speed"], c) < 1e-6, res["pulse_speed"])
        check(f"a) {name}: lambda = {lam}", rel(res["spacing"], lam) < 1e-6, res["spacing"])
        check(f"a) {name}: f_pt = |c| / lambda = {f:.6g}", rel(res["f_pt"], f) < 1e-6, res["f_pt"])
        check(f"a) {name}: every number has a finite _error",
              all(res.get(key + "_error") is not None and res[key + "_error"] >= 0
                  for key in ("mean_velocity", "v0", "relative_variance", "f_pt", "pulse_speed",
                              "spacing")), res)
        check(f"a) {name}: PNG written", os.path.getsize(os.path.join(path, "pulses.png")) > 0)
        periods = f * (t[-1] - t[0])
        check(f"a) {name}: a warning exactly when the record holds fewer than 2 periods "
              f"({periods:.3g})", ("f_pt is not resolved" in out) == (periods < 2), out)
    # a pulse period longer than the record: f_pt is not resolved, and the tool says so
    c, lam = -0.1, L / 2
    v = 0.3 + 0.2 * np.cos(2 * np.pi / lam * (x[None, :] - c * t[:, None]))
    path = os.path.join(tmp, "slow")
    write_run(path, t, x, v, 0.75 + 0 * v, L)
    res, out = run_tool(path, "--v0", "3.0")
    check("a) a period longer than the record: the unresolved-f_pt warning",
          res is not None and "f_pt is not resolved" in out, out)


def classification(tmp):
    L, X, T, dt = 200.0, 100, 300, 1.0
    x = (np.arange(X) + 0.5) * L / X
    t = np.arange(T) * dt
    rng = np.random.default_rng(7)
    v0 = 4.0
    noise = lambda s: rng.normal(0.0, s, (T, X))  # noqa: E731
    lam, c = L / 4, -1.5
    wave = np.cos(2 * np.pi / lam * (x[None, :] - c * t[:, None]))
    runs = {  # name: (v, expected state, expected <v>/v0)
        "pulses": (0.4 + 0.4 * wave + noise(0.02), "pulses", 0.1),
        "free": (0.4 + noise(0.04), "free", 0.1),
        "jammed": (0.004 + noise(0.0004), "jammed", 0.001),
    }
    for name, (v, want, ratio) in runs.items():
        path = os.path.join(tmp, "state_" + name)
        write_run(path, t, x, v, 0.75 + 0 * v, L)
        res, out = run_tool(path, "--v0", str(v0), "--transient", "20")
        if res is None:
            check(f"b) {name}: pulses.py runs", False, out)
            continue
        check(f"b) {name}: state {want}", res["state"] == want, res["state"])
        check(f"b) {name}: <v>/v0 = {ratio} within 3 errors",
              abs(res["mean_velocity_over_v0"] - ratio) <= 3 * res["mean_velocity_over_v0_error"]
              + 1e-12, (res["mean_velocity_over_v0"], res["mean_velocity_over_v0_error"]))
    # bins without colloids (velocity NaN in axial_fields): interpolated, counted
    path = os.path.join(tmp, "state_gaps")
    v = runs["free"][0].copy()
    v[5, 10] = v[7, 0] = v[9, X - 1] = np.nan
    write_run(path, t, x, v, 0.75 + 0 * v, L)
    res, out = run_tool(path, "--v0", str(v0))
    check("b) bins without colloids: filled, counted, state free",
          res is not None and res["state"] == "free" and
          abs(res["filled_fraction"] - 3 / v.size) < 1e-15 and
          abs(res["mean_velocity_over_v0"] - 0.1) <= 3 * res["mean_velocity_over_v0_error"],
          res or out)
    # v0 from the run: g w^2 / (2 nu) with nu from the viscosity observable
    path = os.path.join(tmp, "state_v0")
    nu = 1.98
    visc = {"viscosity": {"step": np.arange(T, dtype=np.int64), "time": t, "value": np.full(T, nu)}}
    write_run(path, t, x, runs["free"][0], 0.75 + 0 * t[:, None] * x, L, g=0.05, extra=visc)
    res, out = run_tool(path, "--transient", "20")
    want = 0.05 * 25.0**2 / (2 * nu)
    check("b) v0 = g w^2 / (2 nu) from the viscosity observable",
          res is not None and rel(res["v0"], want) < 1e-12, (res and res["v0"], want, out))
    # 2D at+a without viscosity observable and no --nu: one line, exit 2
    path = os.path.join(tmp, "state_no_nu")
    write_run(path, t, x, runs["free"][0], 0.75 + 0 * runs["free"][0], L)
    done = subprocess.run([sys.executable, os.path.join(HERE, "pulses.py"), path],
                          capture_output=True, text=True)
    check("b) 2D at+a without nu: exit 2 with one line naming --nu",
          done.returncode == 2 and "--nu" in done.stderr and len(done.stderr.strip().splitlines()) == 1,
          (done.returncode, done.stderr))


def kinetic_theory(narrows):
    """pulses.py's kinetic-theory nu (for v0) is the nu `narrows info` prints (5 digits)."""
    import pulses
    run = os.path.join(os.path.dirname(HERE), "run")
    for name in ("quickstart.toml", "poiseuille_fig3_6.toml", "ata_fluid_table5_1_3d.toml",
                 "ata_fluid_table5_1_2d.toml"):
        done = subprocess.run([narrows, "info", os.path.join(run, name)], capture_output=True,
                              text=True)
        line = [l for l in done.stdout.splitlines() if l.startswith("viscosity")]
        with open(os.path.join(run, name)) as f:
            scene = narrows_h5.parse_scene(f.read())
        mine = pulses.kinetic_viscosity(scene.get("fluid", {}), scene["run"].get("dimensions", 2))
        if line and "nu = " in line[0]:
            theirs = float(line[0].split("nu = ")[1].split()[0])
            check(f"b) kinetic-theory nu of {name} = narrows info's {theirs}",
                  mine is not None and abs(mine - theirs) <= 1e-4 * theirs, mine)
        else:
            check(f"b) no kinetic-theory nu for {name}, as narrows info says", mine is None,
                  (mine, line))


def follow_maximum(phi, dx, width=2.0):
    """Position of one maximum of phi(x, t), followed sample by sample (searched within 5 bins
    of the previous position), refined by a parabola through the three points at the maximum,
    unwrapped. phi is first smoothed with a periodic Gaussian of the given width: a jam is a
    plateau of phi with ripples of 0.002 (the pseudo-spectral scheme), on which the raw argmax
    wanders; the smoothed maximum is the plateau's middle."""
    X = phi.shape[1]
    k = np.fft.fftfreq(X, dx)
    phi = np.real(np.fft.ifft(np.fft.fft(phi, axis=1) * np.exp(-2 * (np.pi * k * width) ** 2), axis=1))
    j = int(np.argmax(phi[0]))
    pos = []
    for row in phi:
        near = (j + np.arange(-5, 6)) % X
        j = int(near[np.argmax(row[near])])
        a, b, c = row[(j - 1) % X], row[j], row[(j + 1) % X]
        pos.append((j + 0.5 * (a - c) / (a - 2 * b + c)) * dx)
    pos = np.array(pos)
    L = dx * X
    steps = np.diff(pos)
    steps -= L * np.round(steps / L)
    return np.concatenate([[pos[0]], pos[0] + np.cumsum(steps)])


def continuum(tmp, narrows):
    scene = os.path.join(os.path.dirname(HERE), "run", "continuum_jamming_pulses.toml")
    out = os.path.join(tmp, "jam")
    done = subprocess.run([narrows, "run", scene,
                           "--set", 'continuum.initial={kind="sine",mean=0.75,amplitude=0.01,mode=5}',
                           "--set", "continuum.time=300.0", "--set", "continuum.samples=1500",
                           "--set", "continuum.cells=256", "--set", "output.progress=false",
                           "--out", out], capture_output=True, text=True)
    check("c) the continuum jamming run", done.returncode == 0, done.stderr[-500:])
    if done.returncode != 0:
        return
    res, text = run_tool(out, "--transient", "60")
    check("c) pulses.py on the continuum run", res is not None, text)
    if res is None:
        return
    run = narrows_h5.open_run(out)
    phi = run.series("density")
    keep = phi.time >= 60
    t, p = phi.time[keep], phi.value[keep]
    L = 100.0
    dx = L / p.shape[1]
    pos = follow_maximum(p, dx)
    c_max = float(np.polyfit(t, pos, 1)[0])
    # jams: the intervals where phi is above the middle of its range (upward crossings)
    mid = 0.5 * (p.max(axis=1) + p.min(axis=1))[:, None]
    up = (p > mid) & ~(np.roll(p, 1, axis=1) > mid)
    peaks = up.sum(axis=1)
    lam_max = float(np.mean(L / np.array(peaks)))
    f_max = abs(c_max) / lam_max
    print(f"continuum: pulses.py c = {res['pulse_speed']:.6g}, lambda = {res['spacing']:.6g}, "
          f"f_pt = {res['f_pt']:.6g}, state {res['state']}; density maximum: c = {c_max:.6g}, "
          f"lambda = {lam_max:.6g}, |c|/lambda = {f_max:.6g}")
    check("c) state pulses", res["state"] == "pulses", res["state"])
    check("c) c within 1 % of the speed of the density maximum",
          rel(res["pulse_speed"], c_max) < 0.01, (res["pulse_speed"], c_max))
    check("c) c upstream (negative)", res["pulse_speed"] < 0, res["pulse_speed"])
    check("c) lambda within 2 % of the distance between density maxima",
          rel(res["spacing"], lam_max) < 0.02, (res["spacing"], lam_max))
    check("c) f_pt within 2 % of |c| / lambda", rel(res["f_pt"], f_max) < 0.02, (res["f_pt"], f_max))
    check("c) v0 = v_ss(0) of eq 6.4 (Table 6.2, mu = 1)",
          rel(res["v0"], float(vss_fit.eq_6_4(0.0, *vss_fit.TABLE_6_2["1"]))) < 1e-12, res["v0"])


def main():
    if len(sys.argv) != 2:
        print("usage: test_pulses.py NARROWS_BINARY", file=sys.stderr)
        return 2
    with tempfile.TemporaryDirectory() as tmp:
        for part in (travelling, classification):
            try:
                part(tmp)
            except Exception as e:  # noqa: BLE001
                check(f"{part.__name__} ran to the end", False, f"{type(e).__name__}: {e}")
        try:
            kinetic_theory(sys.argv[1])
            continuum(tmp, sys.argv[1])
        except Exception as e:  # noqa: BLE001
            check("continuum ran to the end", False, f"{type(e).__name__}: {e}")
    return summary()


if __name__ == "__main__":
    sys.exit(main())
