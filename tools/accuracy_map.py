#!/usr/bin/python3
"""Accuracy against cost for every engine: error of the main measured quantity against the CPU
time it took, one Pareto plot per engine and one combined table.

Usage: accuracy_map.py [--tiny | --medium] [--narrows BUILD/narrows] [--out DIR]
                       [--readme README.md] [--only ENGINE,...]

Engines and their knobs (each a function in ENGINES below):
  mpcd    collision rule (srd, at, at+a) x dt x n: nu fitted to a Poiseuille profile in a 3D
          slit (walls at y = 0, L_y) against the kinetic theory that `narrows info` prints
          (3D: at+a has a formula there, not in 2D), centre velocity 0.2, SRD with the layers
          thermostat; statistical error from 10 blocks after a warm-up of 6 relaxation times
          (poiseuille()). Cost per cell and unit of simulated time.
  md      colloids.md_substeps: energy drift (E_end - E_0)/E_0 of run/colloids_conservation.toml
          and the settling velocity of run/sedimentation_fig4_10.toml against that of the finest
          sub-step. Cost per unit of simulated time.
  fhp     lattice size x run length: nu from the decay of a shear wave (FHP-III, d = 0.3),
          against the Boltzmann value, with its statistical error over seeds. Cost per nu.
  kmc     replicas x time: the open TASEP current (alpha = 0.3, beta = 0.7, low-density
          phase) against its exact value alpha (1 - alpha) = 0.21, with its statistical error.
          Cost per current estimate.
  continuum  cells: L1 error of four Riemann problems (Burgers and TASEP flux, a shock and a
          fan each) against the exact solution written here in closed form (riemann_exact),
          and of a smooth Burgers sine before it breaks (by characteristics), relative to the
          L1 distance the wave moved; the order between grids and fitted over all of them in
          the notes (Riemann: 1, smooth: 2). Cost per solution.
  noslip  fluid.dt: one free no-slip sphere (3D, MPC-AT+a): D against Stokes-Einstein with the
          nu measured by poiseuille() and Hasimoto's periodic-box factor ("noslip D"), spin
          equipartition I<Omega^2>/(3 kT) ("noslip spin", with M<U^2>/(3 kT) in the note), both
          through tools/colloid_diffusion.py (imported); and per collision rule the slip length
          of a disc held in a 2D Poiseuille channel over its radius ("noslip slip"). Ghost
          particles on/off is no knob: no scene key switches the colloids' ghosts off
          (docs/scenes.md), so the map has no such rows.
  springs colloids.spring.substeps: kinetic temperature M<U^2>/(2 kT) of a dense bidisperse
          packing of spring-contact disks at rest in MPC-AT+a (a thermostatted fluid: a total
          energy drift means nothing there), and the deepest overlap (contact_statistics) in the
          note. Cost per unit of simulated time.
  hard    area fraction of event-driven hard disks: collision events per step (narrows counts
          them in the run log) and the CPU time per step; no error column (the events are
          exact), the plot is cost against events.

Cost is the CPU time (user + system) of the narrows child process, from getrusage(
RUSAGE_CHILDREN) before and after each single-rank run, not wall time: this machine is
shared, so wall times are polluted by other jobs. Writes DIR/accuracy_<engine>.png (error
against cost, the Pareto front joined; md gives two, md_energy and md_settling, noslip three,
noslip_D, noslip_spin and noslip_slip) and prints a Markdown table; with --readme, replaces the
table between <!-- accuracy-map --> and <!-- /accuracy-map --> there.
--tiny runs one or two points per engine in about a minute (tests/cli/accuracy_map_tiny.sh
checks every row group, so the tool cannot rot); the default full map takes about 4 CPU
minutes on one core.
"""

import argparse
import math
import os
import re
import resource
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import narrows_h5  # noqa: E402
from lgca_plot import boltzmann_nu, fit_rate  # noqa: E402
import colloid_diffusion  # noqa: E402


class Row(dict):
    """engine, knob (text), error (relative, signed), stat (its statistical error, or nan),
    cpu (s), cost (cpu per unit of work), unit (of the cost), note; a cost-only group (hard
    spheres) has error nan and events (per step)."""


def cpu_of_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def narrows_run(narrows, scene, out, sets):
    """Runs one single-rank job; returns its CPU seconds (child user + system)."""
    cmd = [narrows, "run", scene, "--out", out, "--overwrite", "--set", "output.progress=false"]
    for s in sets:
        cmd += ["--set", s]
    before = cpu_of_children()
    res = subprocess.run(cmd, capture_output=True, text=True)
    cpu = cpu_of_children() - before
    if res.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {res.returncode}: "
                           f"{res.stderr.strip().splitlines()[-1] if res.stderr.strip() else ''}")
    return cpu


def info_nu(narrows, scene, sets):
    cmd = [narrows, "info", scene]
    for s in sets:
        cmd += ["--set", s]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    m = re.search(r"viscosity \(kinetic theory\): nu = ([0-9.eE+-]+)", out)
    return float(m.group(1)) if m else None


# ---- MPCD fluid ---------------------------------------------------------------------------


POISEUILLE = {}  # (rule, dt, n, relax_times, seeds) -> measured nu, shared by mpcd and noslip


def poiseuille(args, rule, dt, n, relax_times, seeds=1, u0=0.2):
    """nu of MPCD in a 3D slit 16 x 12 x 6 (walls at y = 0, 12; virtual particles mirroring the
    flow): a body force g for a centre velocity u0 (Ma ~ 0.15), run 6 momentum relaxation times
    L^2/(pi^2 nu) to the steady state and then relax_times more, sampling the velocity profile
    every tenth of a relaxation time; each sample is fitted with the bin-averaged parabola
    y (L - y) - 1/12 and g / (2 curvature) is nu. The statistical error is that of the block
    averages of the curvature (20 blocks from 100 relaxation times on, each seed its own
    blocks): the parabola is the slowest mode, so samples within a relaxation time are
    correlated and only the blocks are independent. A sample's noise is about
    sqrt(2 kT / M_fluid) / (1.03 u0), 0.09 at n = 5 and u0 = 0.2 (0.37 at the earlier 0.05,
    which left 5-9 % errors); the full grid's 200 (n = 5) and 120 (n = 10) relaxation times
    gave errors of 0.57-1.29 % for 110 CPU s. SRD heats under shear, so its runs have the
    layers thermostat (Tabatabaei (2008) eq 3.53-3.54). Returns a dict with nu, stat
    (relative), nu_t (kinetic theory at the measured kT, from `narrows info`), cpu, steps."""
    key = (rule, dt, n, relax_times, seeds, u0)
    if key in POISEUILLE:
        return dict(POISEUILLE[key], cpu=0.0, cached=True)
    size = (16, 12, 6)
    scene = "run/ata_fluid_table5_1_3d.toml"
    base = [f"fluid.collision={rule}", f"fluid.dt={dt}", f"fluid.density={n}",
            f"domain.size=[{size[0]}.0, {size[1]}.0, {size[2]}.0]",
            "run.dimensions=3", "walls.virtual_flow=mirror"]
    if rule == "srd":
        base.append("thermostat.kind=layers")
    nu0 = info_nu(args.narrows, scene, base)
    L = size[1]
    g = 8.0 * nu0 * u0 / L**2
    relax = L**2 / (math.pi**2 * nu0)  # momentum relaxation time of the slowest mode
    every = max(1, int(0.1 * relax / dt))
    warm = int(6 * relax / dt / every + 1) * every
    measure = max(10, int(relax_times * relax / dt / every / 10 + 1) * 10) * every
    steps = warm + measure
    blocks, temps, cpu = [], [], 0.0
    nblocks = 20 if relax_times >= 100 else 10  # blocks of at least 5 relaxation times
    for seed in range(1, seeds + 1):
        d = os.path.join(args.out, f"mpcd_{rule}_dt{dt:g}_n{n:g}_s{seed}")
        sets = base + [f"body_force.value=[{g!r}, 0.0, 0.0]", f"run.steps={steps}",
                       f"run.seed={seed}", f"output.every={every}",
                       "output.observables=[\"velocity_profile\",\"temperature\"]"]
        cpu += narrows_run(args.narrows, scene, d, sets)
        run = narrows_h5.open_run(d)
        profile = run.series("velocity_profile")
        y = profile["bins"]
        use = profile["step"] > warm
        prof = profile["value"][use, :, 0]
        temps.append(run.series("temperature")["value"][run.series("temperature")["step"] > warm])
        q = y * (L - y) - 1.0 / 12.0  # the parabola averaged over a bin of width 1
        fits = np.linalg.lstsq(np.vstack([q, np.ones_like(q)]).T, prof.T, rcond=None)[0][0]
        nb = len(fits) // nblocks
        blocks += [fits[i * nb:(i + 1) * nb].mean() for i in range(nblocks)]
    blocks = np.array(blocks)
    a = blocks.mean()
    nu = g / (2.0 * a)
    stat = blocks.std(ddof=1) / math.sqrt(len(blocks)) / abs(a)
    # theory at the measured temperature (nu is not linear in kT: ask narrows again)
    kT = float(np.mean(np.concatenate(temps)))
    nu_t = info_nu(args.narrows, scene, base + [f"fluid.kT={kT!r}"])
    result = dict(nu=nu, stat=stat, nu_t=nu_t, cpu=cpu, steps=steps, seeds=seeds, kT=kT,
                  work=size[0] * size[1] * size[2] * steps * dt * seeds, cached=False)
    POISEUILLE[key] = result
    return result


def mpcd_rows(args, scale):
    # relax_times: relaxation times measured after the warm-up, chosen per rule and dt from
    # the noise of a first full map so that every statistical error is below 2 %
    grid = {"tiny": (["srd"], [0.5], [3], lambda rule, dt, n: 10),
            "medium": (["srd", "at", "at+a"], [0.1, 1.0], [5], lambda rule, dt, n: 40),
            "full": (["srd", "at", "at+a"], [0.1, 0.5, 1.0], [5, 10],
                     lambda rule, dt, n: 200 if n < 10 else 120)}[scale]
    rules, dts, ns, relax_times = grid
    rows = []
    for rule in rules:
        for dt in dts:
            for n in ns:
                r = poiseuille(args, rule, dt, n, relax_times(rule, dt, n))
                rows.append(Row(engine="mpcd", knob=f"{rule} dt={dt:g} n={n:g}",
                                error=r["nu"] / r["nu_t"] - 1.0, stat=r["stat"], cpu=r["cpu"],
                                cost=r["cpu"] / r["work"] * 1e6,
                                unit="CPU µs per cell and time unit",
                                note=f"nu {r['nu']:.4f} vs theory {r['nu_t']:.4f}, "
                                     f"{r['steps']} steps"))
    return rows


# ---- MD colloids ---------------------------------------------------------------------------


def md_rows(args, scale):
    ks, steps, settle_steps = {"tiny": ([5, 15], 300, 300), "medium": ([2, 5, 15, 30], 3000, 3000),
                               "full": ([2, 5, 15, 30], 10000, 10000)}[scale]
    ref_k = max(ks) * 2
    v_ref = None
    rows = []
    for k in [ref_k] + ks:
        # settling velocity (run/sedimentation_fig4_10.toml at n = 5)
        d = os.path.join(args.out, f"md_settle_k{k}")
        cpu_s = narrows_run(args.narrows, "run/sedimentation_fig4_10.toml", d,
                            [f"colloids.md_substeps={k}", f"run.steps={settle_steps}",
                             "fluid.density=5", "output.every=10"])
        v = narrows_h5.open_run(d).series("settling_velocity")["value"][:, 0]
        v = v[len(v) // 2:]
        vs, vs_err = v.mean(), v.std(ddof=1) / math.sqrt(len(v) / 10)  # ~10 samples per block
        if k == ref_k:
            v_ref, v_ref_err = vs, vs_err
            continue
        d = os.path.join(args.out, f"md_energy_k{k}")
        try:
            cpu_e = narrows_run(args.narrows, "run/colloids_conservation.toml", d,
                                [f"colloids.md_substeps={k}", f"run.steps={steps}"])
            e = narrows_h5.open_run(d).series("energy")["value"]
            drift = e[-1] / e[0] - 1.0
        except RuntimeError:
            cpu_e, drift = float("nan"), float("nan")
        dt = 0.1  # colloids_conservation.toml
        rows.append(Row(engine="md energy", knob=f"md_substeps={k}", error=drift, stat=float("nan"),
                        cpu=cpu_e, cost=cpu_e / (steps * dt), unit="CPU s per time unit",
                        note=f"energy drift over {steps} steps"))
        rows.append(Row(engine="md settling", knob=f"md_substeps={k}", error=vs / v_ref - 1.0,
                        stat=math.hypot(vs_err, v_ref_err) / abs(v_ref), cpu=cpu_s,
                        cost=cpu_s / (settle_steps * 0.015), unit="CPU s per time unit",
                        note=f"v_s {vs:.4f} vs k={ref_k}: {v_ref:.4f}"))
    return rows


# ---- FHP lattice gas -----------------------------------------------------------------------


def fhp_rows(args, scale):
    sizes, lengths, seeds = {"tiny": ([(64, 32)], [0.5], 2),
                             "medium": ([(128, 32), (256, 64)], [0.5, 1.0], 3),
                             "full": ([(128, 32), (256, 64), (512, 128)], [0.5, 1.0, 2.0], 4)}[scale]
    d_link, model = 0.3, "fhp-iii"
    nu_b = boltzmann_nu(model, d_link)
    rows = []
    for sx, sy in sizes:
        k2 = (2 * math.pi / (sy * math.sqrt(3) / 2)) ** 2
        decay = 1.0 / (nu_b * k2)  # steps for the amplitude to fall by e
        for length in lengths:
            steps = max(10, int(length * decay))
            nus, cpu = [], 0.0
            for seed in range(1, seeds + 1):
                d = os.path.join(args.out, f"fhp_{sx}x{sy}_{length:g}_s{seed}")
                cpu += narrows_run(args.narrows, "run/lgca_shear_wave.toml", d,
                                   [f"lattice.size=[{sx}, {sy}]", f"run.steps={steps}",
                                    f"run.seed={seed}", f"lattice.model={model}",
                                    f"lattice.density={d_link}", "output.every=1"])
                wave = narrows_h5.open_run(d).series("shear_wave")
                t = wave["step"].astype(float)
                a = wave["value"]
                # skip the first steps: the initial shear wave is not yet the hydrodynamic mode
                rate, _ = fit_rate(t, a, min(20.0, steps / 4), float(steps))
                nus.append(rate / k2)
            nu, err = np.mean(nus), np.std(nus, ddof=1) / math.sqrt(len(nus))
            rows.append(Row(engine="fhp", knob=f"{sx}x{sy}, {length:g} decay times, {seeds} seeds",
                            error=nu / nu_b - 1.0, stat=err / nu_b, cpu=cpu, cost=cpu,
                            unit="CPU s per nu estimate",
                            note=f"nu {nu:.4f} ± {err:.4f} vs Boltzmann {nu_b:.4f}"))
    return rows


# ---- kmc -----------------------------------------------------------------------------------


def kmc_rows(args, scale):
    # at least 4 replicas: the statistical error is their spread
    grid = {"tiny": ([4], [200.0]), "medium": ([4, 16], [500.0, 2000.0]),
            "full": ([4, 16, 64], [500.0, 2000.0, 8000.0])}[scale]
    exact = 0.3 * (1 - 0.3)
    rows = []
    for replicas in grid[0]:
        for t in grid[1]:
            d = os.path.join(args.out, f"kmc_r{replicas}_t{t:g}")
            cpu = narrows_run(args.narrows, "run/tasep_open.toml", d,
                              [f"kmc.replicas={replicas}", f"kmc.time={t}",
                               "kmc.warmup=2000.0", "kmc.length=200"])
            run = narrows_h5.open_run(d)
            j = float(run.series("current_mean")["value"][-1])
            je = float(run.series("current_mean_error")["value"][-1])
            rows.append(Row(engine="kmc", knob=f"{replicas} replicas x t={t:g}",
                            error=j / exact - 1.0, stat=je / exact, cpu=cpu, cost=cpu,
                            unit="CPU s per current estimate",
                            note=f"J {j:.5f} ± {je:.5f} vs {exact:.4f}"))
    return rows


# ---- continuum ------------------------------------------------------------------------------


def riemann_exact(flux, left, right, xi):
    """The entropy solution rho(x/t) of rho_t + J(rho)_x = 0 with rho = left for x < 0, right
    for x > 0, in closed form (LeVeque (2002) ch. 11; written here, not taken from narrows):
      burgers: J = rho^2/2 (convex, J' = rho): left > right a shock at s = (left + right)/2,
               else the fan rho = x/t between left and right;
      tasep:   J = rho (1 - rho) (p = 1, q = 0; concave, J' = 1 - 2 rho): left < right a shock
               at s = 1 - left - right (Rankine-Hugoniot), else the fan rho = (1 - x/t)/2
               between right and left."""
    xi = np.asarray(xi, dtype=float)
    if flux == "burgers":
        if left > right:
            return np.where(xi < 0.5 * (left + right), left, right)
        return np.clip(xi, left, right)
    if flux == "tasep":
        if left < right:
            return np.where(xi < 1.0 - left - right, left, right)
        return np.clip(0.5 * (1.0 - xi), right, left)
    raise ValueError(flux)


# (flux, left, right, jump position); length 400, time 200: every wave stays inside
CONTINUUM_CASES = {"burgers shock": ("burgers", 1.0, 0.0, 100.0),
                   "burgers fan": ("burgers", 0.0, 1.0, 100.0),
                   "tasep shock": ("tasep", 0.1, 0.5, 100.0),
                   "tasep fan": ("tasep", 0.8, 0.2, 200.0)}


def burgers_sine_exact(x, t, length, mean, amp):
    """Burgers' rho = mean + amp sin(2 pi (x - rho t) / length) before the wave breaks
    (t < length / (2 pi amp)): the characteristics, solved by Newton's method."""
    k = 2.0 * math.pi / length
    rho = mean + amp * np.sin(k * x)
    for _ in range(50):
        f = rho - mean - amp * np.sin(k * (x - rho * t))
        rho = rho - f / (1.0 + amp * k * t * np.cos(k * (x - rho * t)))
    return rho


def step_order(errs, cells_list):
    """The note's order between the last two grids of errs (empty for the first)."""
    if len(errs) < 2:
        return ""
    k = len(errs) - 1
    return (f", order {math.log(errs[k - 1] / errs[k]) / math.log(cells_list[k] / cells_list[k - 1]):.2f}"
            f" from {cells_list[k - 1]}")


def fitted_order(rows, errs, cells_list, label):
    """The order fitted over all grids, appended to the last row's note and printed."""
    fit = -np.polyfit(np.log(cells_list), np.log(errs), 1)[0]
    rows[-1]["note"] += f"; fitted order {fit:.2f} ({cells_list[0]}-{cells_list[-1]} cells)"
    print(f"accuracy_map: continuum {label}: L1 order {fit:.3f} over {cells_list}", file=sys.stderr)


def smooth_rows(args, cells_list):
    """The same L1 error for smooth data, where the scheme is second order: Burgers, periodic,
    rho = 0.5 + 0.2 sin(2 pi x / 400) at t = 150 (it breaks at t = 318), against the cell
    averages of burgers_sine_exact (4-point Gauss-Legendre in each cell), relative to the L1
    distance the exact solution moved."""
    length, t_end, mean, amp = 400.0, 150.0, 0.5, 0.2
    gx, gw = np.polynomial.legendre.leggauss(4)
    rows, errs = [], []
    for cells in cells_list:
        d = os.path.join(args.out, f"continuum_burgers_sine_{cells}")
        os.makedirs(d, exist_ok=True)
        scene = os.path.join(d, "scene.toml")
        with open(scene, "w") as f:
            f.write(f"""[run]
engine = "continuum"

[continuum]
model = "conservation-law"
flux = "burgers"
length = {length}
cells = {cells}
boundary = "periodic"
initial = {{ kind = "sine", mean = {mean}, amplitude = {amp} }}
time = {t_end}
samples = 1
""")
        cpu = narrows_run(args.narrows, scene, d, [])
        rho = narrows_h5.open_run(d).series("density")
        dx = length / cells
        left = np.arange(cells) * dx
        pts = left[:, None] + 0.5 * dx * (gx[None, :] + 1.0)
        exact = (burgers_sine_exact(pts, t_end, length, mean, amp) * gw).sum(1) / 2.0
        start = (burgers_sine_exact(pts, 0.0, length, mean, amp) * gw).sum(1) / 2.0
        moved = np.sum(np.abs(exact - start)) * dx
        l1 = np.sum(np.abs(rho["value"][-1] - exact)) * dx
        errs.append(l1)
        order = step_order(errs, cells_list)
        rows.append(Row(engine="continuum", knob=f"burgers sine (smooth), {cells} cells",
                        error=l1 / moved, stat=float("nan"), cpu=cpu, cost=cpu,
                        unit="CPU s per solution", note=f"L1 {l1:.4g} of {moved:.4g}{order}"))
    fitted_order(rows, errs, cells_list, "burgers sine")
    return rows


def continuum_rows(args, scale):
    """cells -> L1 error of the finite-volume solution (MUSCL-Rusanov-SSPRK2, docs/scenes.md)
    against the cell averages of the exact Riemann solution at t = 200 (256 points per cell),
    divided by the L1 distance the exact solution moved, int |rho(x, t) - rho(x, 0)| dx, so it
    is the error relative to the wave. The order is -d ln L1 / d ln cells between successive
    grids, and fitted over all of them (in the note). Measured: 1.00 for all four, the fans as
    well as the shocks, while smooth_rows gives 1.98. A shock is smeared over a fixed number of
    cells (L1 ~ dx); a fan that starts from a jump comes out shifted by O(dx) as a whole (most of
    its L1 error lies inside the fan, not at its two kinks), so order 1 is the Riemann data's,
    not a loss of the scheme's second order."""
    cells_list = {"tiny": [100, 200], "medium": [100, 200, 400, 800],
                  "full": [100, 200, 400, 800, 1600]}[scale]
    length, t_end, sub = 400.0, 200.0, 256
    rows = smooth_rows(args, cells_list)
    for case, (flux, left, right, x0) in CONTINUUM_CASES.items():
        errs = []
        for cells in cells_list:
            d = os.path.join(args.out, f"continuum_{case.replace(' ', '_')}_{cells}")
            cpu = narrows_run(args.narrows, "run/continuum_burgers_riemann.toml", d,
                              [f"continuum.flux=\"{flux}\"", f"continuum.cells={cells}",
                               f"continuum.length={length}", f"continuum.time={t_end}",
                               "continuum.samples=1", f"continuum.initial.left={left!r}",
                               f"continuum.initial.right={right!r}",
                               f"continuum.initial.position={x0!r}"])
            rho = narrows_h5.open_run(d).series("density")
            t = float(rho["time"][-1])
            if abs(t - t_end) > 1e-9 * t_end:
                raise RuntimeError(f"{d}: last sample at t = {t}, not {t_end}")
            dx = length / cells
            xs = (np.arange(cells * sub) + 0.5) * (dx / sub)
            exact = riemann_exact(flux, left, right, (xs - x0) / t).reshape(cells, sub).mean(1)
            moved = np.sum(np.abs(riemann_exact(flux, left, right, (xs - x0) / t)
                                  - np.where(xs < x0, left, right))) * dx / sub
            l1 = np.sum(np.abs(rho["value"][-1] - exact)) * dx
            errs.append(l1)
            order = step_order(errs, cells_list)
            rows.append(Row(engine="continuum", knob=f"{case}, {cells} cells", error=l1 / moved,
                            stat=float("nan"), cpu=cpu, cost=cpu, unit="CPU s per solution",
                            note=f"L1 {l1:.4g} of {moved:.4g}{order}"))
        fitted_order(rows, errs, cells_list, case)
    return rows


# ---- no-slip colloids ------------------------------------------------------------------------


def hasimoto_factor(radius, box):
    """D in a periodic cubic box of side l over the unbounded one for a sphere of radius a:
    1 - 1.7601 phi^(1/3) + phi, phi = (4 pi / 3)(a / l)^3 (Hasimoto (1959), the simple cubic
    array; 1.7601 phi^(1/3) = 2.8373 a / l, Yeh & Hummer (2004) eq 7's xi)."""
    phi = 4.0 * math.pi / 3.0 * (radius / box) ** 3
    return 1.0 - 1.7601 * phi ** (1.0 / 3.0) + phi


def noslip_rows(args, scale):
    """One free density-matched no-slip sphere (3D, radius 2, periodic cube of side 6 radii,
    n = 5, MPC-AT+a; tools/colloid_diffusion.py writes the scene and measures) -> D from the
    VACF plateau (eq 4.50-4.51) against Stokes-Einstein kT / (6 pi eta a) with the nu measured
    by a Poiseuille run of the same fluid (poiseuille() above; eta = n nu), lowered to the box
    by hasimoto_factor(); and the equipartition of the spin I<Omega^2>/(3 kT) and of the
    translation M<U^2>/(3 kT) (both 1 in equilibrium). The numbers come from narrows' own
    colloid statistics (colloid_diffusion.measure_statistics; its measure() from a trajectory
    agrees to 0.1 % on the same run, but a trajectory of 10^4 frames costs several times the run). Knob: fluid.dt (dt <= 0.125 a, the
    coupling's limit, docs/scenes.md), each run the same number of steps. Ghost particles cannot be
    switched off: the no-slip coupling always fills the cut cells (docs/scenes.md has no key for
    it; walls.virtual_particles is the walls' own), so the map has no ghosts-off rows.
    And the slip length of a disc held in a 2D Poiseuille channel (slip_rows)."""
    # the same number of steps at every dt (the same CPU time): a larger dt buys a longer run
    dts, steps, seeds = {"tiny": ([0.05], 2000, 1), "medium": ([0.05, 0.1, 0.2], 10000, 1),
                         "full": ([0.025, 0.05, 0.1, 0.2], 30000, 1)}[scale]
    relax = {"tiny": 10, "medium": 30, "full": 60}[scale]  # of the Poiseuille run for nu
    blocks = 4 if scale == "tiny" else 10  # a block must be longer than tmax = 10
    radius, box_over_a, n, rule = 2.0, 6.0, 5.0, "at+a"
    # the fluid starts at zero total momentum (Tabatabaei (2008) §3.4.4), the colloid at rest:
    # M U = -P_fluid, so M<U^2>/(3 kT) is 1 - M/M_total, not 1
    m_c = n * 4.0 / 3.0 * math.pi * radius**3
    m_tot = n * (radius * box_over_a) ** 3
    rows = []
    for dt in dts:
        T = steps * dt
        every = max(1, int(round(0.1 / dt)))  # a sample every 0.1 t0
        cpu, meas = 0.0, []
        for seed in range(1, seeds + 1):
            a = argparse.Namespace(dim=3, radius=radius, box_over_a=box_over_a, density=n,
                                   dt=dt, time=T, every=every, tmax=10.0, blocks=blocks, seed=seed,
                                   collision=rule, statistics=True,
                                   out=os.path.join(args.out, f"noslip_dt{dt:g}_s{seed}"))
            os.makedirs(a.out, exist_ok=True)
            scene = os.path.join(a.out, "scene.toml")
            with open(scene, "w") as f:
                f.write(colloid_diffusion.scene_text(a))
            cpu += narrows_run(args.narrows, scene, a.out, [])
            meas.append(colloid_diffusion.measure_statistics(a))
        mean = lambda k: float(np.mean([m[k] for m in meas]))
        err = lambda k: math.sqrt(sum(m[k + "_err"] ** 2 for m in meas)) / len(meas)
        flow = poiseuille(args, rule, dt, n, relax)
        eta = n * flow["nu"]
        L = radius * box_over_a
        d_se = 1.0 / (6.0 * math.pi * eta * radius) * hasimoto_factor(radius, L)
        D, D_err = mean("D_vacf"), err("D_vacf")
        cost = (cpu + flow["cpu"]) / (T * seeds)
        rows.append(Row(engine="noslip D", knob=f"{rule} dt={dt:g}", error=D / d_se - 1.0,
                        stat=math.hypot(D_err / D, flow["stat"]) * D / d_se,
                        cpu=cpu + flow["cpu"], cost=cost, unit="CPU s per time unit",
                        note=f"D {D:.5f} ± {D_err:.5f} vs SE(Hasimoto, l = {L:g}) {d_se:.5f} "
                             f"at measured nu {flow['nu']:.4f} ± {100 * flow['stat']:.1f} % "
                             f"(theory {flow['nu_t']:.4f}); T = {T * seeds:g}"))
        rows.append(Row(engine="noslip spin", knob=f"{rule} dt={dt:g}",
                        error=mean("spin") - 1.0, stat=err("spin"), cpu=cpu, cost=cpu / (T * seeds),
                        unit="CPU s per time unit",
                        note=f"I<Ω²>/3kT {mean('spin'):.4f} ± {err('spin'):.4f}, "
                             f"M<U²>/3kT {mean('trans'):.4f} ± {err('trans'):.4f} (at zero "
                             f"total momentum 1 - M/M_total = {1 - m_c / m_tot:.3f})"))
    return rows + slip_rows(args, scale)


def slip_rows(args, scale):
    """A disc (radius 3) held at the centre of a 2D Poiseuille channel 32 x 16 (n = 10, dt = 0.1,
    g = 0.01; held by a mass of 1e12: every stage of the coupling runs as for a free one), the
    smaller form of tests/validation/test_no_slip_colloids.cpp (a): u_x of the fluid frames
    (trajectory every 20 steps, after 6 relaxation times of the channel) in wedges of half-angle
    20 deg across the channel on either side of the disc, binned (0.25) in the distance s from
    the surface, a quadratic fitted on 0 < s < 2 per block (10 blocks) and extrapolated to s = 0:
    the slip length b_s = u_t / (du_t/ds) there. error = b_s / R (a disc that let the fluid slip
    has b_s ~ R). Knob: the collision rule."""
    rules, steps = {"tiny": (["at+a"], 3000), "medium": (["at+a", "srd"], 8000),
                    "full": (["at+a", "srd"], 20000)}[scale]
    Lx, Ly, R, n, dt, g, every = 32.0, 16.0, 3.0, 10.0, 0.1, 0.01, 20
    rows = []
    for rule in rules:
        nu0 = info_nu(args.narrows, "run/ata_fluid_table5_1_2d.toml",
                      [f"fluid.collision={rule}", f"fluid.dt={dt}", f"fluid.density={n}"])
        nu0 = nu0 or 0.5  # `narrows info` has no 2D formula for at+a
        warm = int(0.6 * Ly**2 / nu0 / dt)  # 6 relaxation times Ly^2 / (pi^2 nu)
        d = os.path.join(args.out, f"slip_{rule}")
        os.makedirs(d, exist_ok=True)
        scene = os.path.join(d, "scene.toml")
        with open(scene, "w") as f:
            f.write(f"""[run]
engine = "mpcd"
dimensions = 2
seed = 11
steps = {warm + steps}

[domain]
size = [{Lx}, {Ly}]

[fluid]
collision = "{rule}"
density = {n}
dt = {dt}
{'[thermostat]' + chr(10) + 'kind = "layers"' + chr(10) if rule == "srd" else ""}
[body_force]
value = [{g}, 0.0]

[walls]

[colloids]
coupling = "no-slip"
contacts = "hard"
radius = {R}
mass = 1e12
placement = "list"
positions = [[{Lx / 2}, {Ly / 2}]]

[output]
every = {warm + steps}
observables = ["temperature"]
trajectory_every = {every}
trajectory_subsample = 1
""")
        cpu = narrows_run(args.narrows, scene, d, [])
        bin_w, reach, wedge = 0.25, 2.0, math.tan(math.radians(20.0))
        sc = (np.arange(int(reach / bin_w)) + 0.5) * bin_w
        with narrows_h5.open_trajectory(d) as f:
            pos = f.dataset("particles/fluid/position/value")
            vel = f.dataset("particles/fluid/velocity/value")
            frames = [k for k in range(pos.shape[0]) if k * every > warm]
            nb = len(frames) // 10
            intercepts, slopes = [], []
            for b in range(10):
                tot = np.zeros(len(sc))
                cnt = np.zeros(len(sc))
                for k in frames[b * nb:(b + 1) * nb]:
                    x, u = pos[k], vel[k][:, 0]
                    dx = x[:, 0] - Lx / 2
                    dx -= Lx * np.round(dx / Lx)
                    dy = x[:, 1] - Ly / 2
                    sd = np.hypot(dx, dy) - R
                    sel = (sd > 0) & (sd < reach) & (np.abs(dx) < wedge * np.abs(dy))
                    idx = (sd[sel] / bin_w).astype(int)
                    tot += np.bincount(idx, u[sel], len(sc))
                    cnt += np.bincount(idx, None, len(sc))
                c2, c1, c0 = np.polyfit(sc, tot / cnt, 2)
                intercepts.append(c0)
                slopes.append(c1)
        ut, sl = np.mean(intercepts), np.mean(slopes)
        se = lambda z: np.std(z, ddof=1) / math.sqrt(len(z))
        bs = ut / sl
        bs_err = abs(bs) * math.hypot(se(intercepts) / ut, se(slopes) / sl)
        rows.append(Row(engine="noslip slip", knob=f"{rule} dt={dt:g} n={n:g}", error=bs / R,
                        stat=bs_err / R, cpu=cpu, cost=cpu / ((warm + steps) * dt),
                        unit="CPU s per time unit",
                        note=f"b_s {bs:.3f} ± {bs_err:.3f} cells (R = {R:g}), u_t {ut:.4f}, "
                             f"shear {sl:.4f}; {len(frames)} frames"))
    return rows


# ---- spring and hard-sphere contacts ---------------------------------------------------------


def dense_scene(contacts, phi, steps, dt, extra):
    """A 2D channel 40 x 20 (walls at y = 0, 20) of no-slip disks packed to area fraction phi
    (Kanehl (thesis) §6.1: the bidisperse 2.1 / 2.94 mixture, number ratio 1 : 1), MPC-AT+a,
    n = 10, at rest (no drive): thermal contacts only."""
    return f"""[run]
engine = "mpcd"
dimensions = 2
seed = 5
steps = {steps}

[domain]
size = [40.0, 20.0]

[fluid]
collision = "at+a"
density = 10
dt = {dt}

[walls]

[colloids]
coupling = "no-slip"
contacts = "{contacts}"
placement = "packing"
packing_fraction = {phi}
{extra}
[[colloids.kind]]
radius = 2.1
count = 1

[[colloids.kind]]
radius = 2.94
count = 1
"""


def spring_rows(args, scale):
    """colloids.spring.substeps (velocity-Verlet sub-steps of the spring contacts per MPCD step)
    on dense_scene(phi = 0.7, dt = 0.02, k_n = k_t = 2500, mu = 1: Kanehl (thesis) Table 6.1)
    -> the kinetic temperature of the colloids, M<U^2>/(2 kT) per kind (from colloid_vacf at
    lag 0, density-matched masses; error = its mean over the kinds minus 1, stat. error from its
    10 blocks), and the deepest overlap of contact_statistics (bins of 0.002 of the smaller
    radius; the upper edge of the deepest bin reached). The fluid is thermostatted by MPC-AT+a, so
    a total-energy drift is no measure here: the temperature the colloids reach is."""
    subs, steps = {"tiny": ([2, 10], 1500), "medium": ([1, 2, 5, 10, 20], 5000),
                   "full": ([1, 2, 5, 10, 20, 80], 10000)}[scale]
    dt, phi, start = 0.02, 0.7, 500
    masses = [10.0 * math.pi * r**2 for r in (2.1, 2.94)]
    rows = []
    for k in subs:
        d = os.path.join(args.out, f"springs_sub{k}")
        os.makedirs(d, exist_ok=True)
        scene = os.path.join(d, "scene.toml")
        with open(scene, "w") as f:
            f.write(dense_scene("spring", phi, steps, dt,
                                f"statistics_from = {start}\nmax_lag = 10\n\n"
                                f"[colloids.spring]\nsubsteps = {k}\n"))
        cpu = narrows_run(args.narrows, scene, d,
                          ["output.every=10", "output.observables=[\"temperature\","
                           "\"colloid_vacf\",\"colloid_angular_vacf\",\"contact_statistics\"]"])
        run = narrows_h5.open_run(d)
        vacf = run.series("colloid_vacf")
        c0 = np.reshape(vacf["value_by_kind"], (2, -1))[:, 0]
        e0 = np.reshape(vacf["error_by_kind"], (2, -1))[:, 0]
        temps = np.array(masses) * c0 / 2.0
        t_err = np.array(masses) * e0 / 2.0
        w = run.series("colloid_angular_vacf")
        spin = np.array([0.5 * m * r**2 for m, r in zip(masses, (2.1, 2.94))]) * \
            np.reshape(w["value_by_kind"], (2, -1))[:, 0]
        cs = run.series("contact_statistics")
        use = cs["step"] >= start
        counts = cs["value"][use].sum(axis=(0, 1))
        beyond = cs["beyond"][use].sum()
        deepest = (np.nonzero(counts)[0].max() + 1) * cs.number("bin_width") if counts.any() else 0.0
        deep = f"> 0.2 ({beyond:g} beyond)" if beyond else f"{deepest:.3f}"
        rows.append(Row(engine="springs", knob=f"spring.substeps={k}",
                        error=float(temps.mean() - 1.0),
                        stat=float(math.hypot(*t_err) / 2.0), cpu=cpu, cost=cpu / (steps * dt),
                        unit="CPU s per time unit",
                        note=f"M<U²>/2kT {temps[0]:.3f} ± {t_err[0]:.3f} (a = 2.1), "
                             f"{temps[1]:.3f} ± {t_err[1]:.3f} (2.94); I<Ω²>/kT "
                             f"{spin[0]:.3f}, {spin[1]:.3f}; deepest overlap {deep} a"))
    return rows


def hard_rows(args, scale):
    """Event-driven rough hard disks (colloids.contacts = "hard") on dense_scene(phi, dt = 0.1):
    area fraction -> colloid collisions per step (the count the run log gives: "colloid
    contacts: N colloid-colloid and M colloid-wall collisions") and the CPU time per step. No
    error: the events are exact; the rows give the cost (error column empty, the plot is CPU
    per step against events per step)."""
    phis, steps = {"tiny": ([0.3], 300), "medium": ([0.1, 0.3, 0.5], 1000),
                   "full": ([0.05, 0.2, 0.35, 0.5, 0.6], 2000)}[scale]
    rows = []
    for phi in phis:
        d = os.path.join(args.out, f"hard_phi{phi:g}")
        os.makedirs(d, exist_ok=True)
        scene = os.path.join(d, "scene.toml")
        with open(scene, "w") as f:
            f.write(dense_scene("hard", phi, steps, 0.1, ""))
        cpu = narrows_run(args.narrows, scene, d, ["output.every=1000000",
                                                   "output.observables=[\"temperature\"]"])
        with open(os.path.join(d, "log.txt")) as f:
            m = re.search(r"colloid contacts: (\d+) colloid-colloid and (\d+) colloid-wall", f.read())
        if not m:
            raise RuntimeError(f"{d}/log.txt: no 'colloid contacts:' line")
        pairs, walls = int(m.group(1)), int(m.group(2))
        rows.append(Row(engine="hard spheres", knob=f"phi={phi:g}", error=float("nan"),
                        stat=float("nan"), cpu=cpu, cost=cpu / steps, unit="CPU s per step",
                        events=(pairs + walls) / steps,
                        note=f"{(pairs + walls) / steps:.3g} events per step ({pairs} pair, "
                             f"{walls} wall in {steps} steps)"))
    return rows


ENGINES = {"mpcd": mpcd_rows, "md": md_rows, "fhp": fhp_rows, "kmc": kmc_rows,
           "continuum": continuum_rows, "noslip": noslip_rows, "springs": spring_rows,
           "hard": hard_rows}


def pareto(rows):
    """Rows not beaten in both |error| and cost by another row."""
    front = []
    for r in sorted(rows, key=lambda r: r["cost"]):
        if not math.isfinite(r["error"]):
            continue
        if not front or abs(r["error"]) < abs(front[-1]["error"]):
            front.append(r)
    return front


YLABEL = {"continuum": "L1 error / L1 distance the exact solution moved",
          "noslip D": "|D / D_SE(Hasimoto) - 1|", "noslip spin": "|I<Ω²>/(3kT) - 1|",
          "noslip slip": "|slip length| / radius", "springs": "|M<U²>/(2kT) - 1| (colloids)"}


def plot(engine, rows, png):
    plt = narrows_h5.pyplot()
    fig, ax = plt.subplots(figsize=(6, 4.2))
    if all("events" in r for r in rows):  # a cost-only model: CPU against the work it does
        ax.plot([r["events"] for r in rows], [r["cost"] for r in rows], "o-", ms=4)
        for r in rows:
            ax.annotate(r["knob"], (r["events"], r["cost"]), fontsize=6, xytext=(3, 3),
                        textcoords="offset points")
        ax.set_xlabel("collision events per step")
        ax.set_ylabel(rows[0]["unit"])
        ax.set_title(f"{engine}: cost against events (CPU time of the child process)")
        fig.tight_layout()
        fig.savefig(png, dpi=110)
        plt.close(fig)
        return
    for r in rows:
        if not math.isfinite(r["error"]):
            continue
        y = max(abs(r["error"]), 1e-6)
        ax.errorbar(r["cost"], y, yerr=r["stat"] if math.isfinite(r["stat"]) else None,
                    fmt="o", ms=4, capsize=2)
        ax.annotate(r["knob"], (r["cost"], y), fontsize=6, xytext=(3, 3),
                    textcoords="offset points")
    front = pareto(rows)
    ax.plot([r["cost"] for r in front], [max(abs(r["error"]), 1e-6) for r in front], "k--",
            lw=0.8, label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(rows[0]["unit"])
    ax.set_ylabel(YLABEL.get(engine, "|relative error|"))
    ax.set_title(f"{engine}: accuracy against cost (CPU time of the child process)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def table(rows, scale, seconds):
    lines = [f"Cost = CPU time (user + system) of the single-rank narrows process "
             f"(getrusage of the child), not wall time: the machine is shared. Grid "
             f"`{scale}`; the whole map took {seconds:.0f} s of wall time.", "",
             "| engine | knob | error | stat. error | CPU s | cost | cost unit | Pareto | note |",
             "|---|---|---:|---:|---:|---:|---|---|---|"]
    for engine in dict.fromkeys(r["engine"] for r in rows):
        mine = [r for r in rows if r["engine"] == engine]
        front = [id(r) for r in pareto(mine)]
        for r in mine:
            stat = f"{100 * r['stat']:.2f} %" if math.isfinite(r["stat"]) else ""
            error = f"{100 * r['error']:+.3g} %" if math.isfinite(r["error"]) else ""
            lines.append(f"| {engine} | {r['knob']} | {error} | {stat} | "
                         f"{r['cpu']:.2f} | {r['cost']:.3g} | {r['unit']} | "
                         f"{'yes' if id(r) in front else ''} | {r['note']} |")
    return "\n".join(lines)


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--narrows", default="build/narrows")
    p.add_argument("--out", default="out/accuracy_map")
    p.add_argument("--readme", help="README to update between the accuracy-map markers")
    p.add_argument("--only", help="comma-separated engines (default: all)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--tiny", action="store_true", help="seconds: one point or two per engine")
    g.add_argument("--medium", action="store_true", help="a few minutes")
    args = p.parse_args(argv[1:])
    scale = "tiny" if args.tiny else "medium" if args.medium else "full"
    if not os.access(args.narrows, os.X_OK):
        sys.exit(f"accuracy_map: no narrows binary at {args.narrows} (build first or --narrows)")
    args.narrows = os.path.abspath(args.narrows)
    os.chdir(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    os.makedirs(args.out, exist_ok=True)
    start = time.time()
    rows = []
    for name, fn in ENGINES.items():
        if args.only and name not in args.only.split(","):
            continue
        mine = fn(args, scale)
        for group in dict.fromkeys(r["engine"] for r in mine):
            png = os.path.join(args.out, f"accuracy_{group.replace(' ', '_')}.png")
            plot(group, [r for r in mine if r["engine"] == group], png)
            print(f"accuracy_map: {group}: plot in {png}", file=sys.stderr)
        rows += mine
    text = table(rows, scale, time.time() - start)
    print(text)
    if args.readme:
        with open(args.readme) as f:
            readme = f.read()
        begin, end = "<!-- accuracy-map -->", "<!-- /accuracy-map -->"
        if begin not in readme or end not in readme:
            sys.exit(f"accuracy_map: {args.readme} has no {begin} ... {end} markers")
        head, rest = readme.split(begin, 1)
        _, tail = rest.split(end, 1)
        with open(args.readme, "w") as f:
            f.write(head + begin + "\n" + text + "\n" + end + tail)
    return 0


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("accuracy_map", main, sys.argv))
