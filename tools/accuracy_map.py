#!/usr/bin/python3
"""Accuracy against cost for every engine: error of the main measured quantity against the CPU
time it took, one Pareto plot per engine and one combined table.

Usage: accuracy_map.py [--tiny | --medium] [--narrows BUILD/narrows] [--out DIR]
                       [--readme README.md] [--only ENGINE,...]

Engines and their knobs (each a function in ENGINES below):
  mpcd    collision rule (srd, at, at+a) x dt x n: nu fitted to a Poiseuille profile in a 3D
          slit (walls at y = 0, L_y) against the kinetic theory that `narrows info` prints
          (3D: at+a has a formula there, not in 2D). Cost per cell and unit of simulated time.
  md      colloids.md_substeps: energy drift (E_end - E_0)/E_0 of run/colloids_conservation.toml
          and the settling velocity of run/sedimentation_fig4_10.toml against that of the finest
          sub-step. Cost per unit of simulated time.
  fhp     lattice size x run length: nu from the decay of a shear wave (FHP-III, d = 0.3),
          against the Boltzmann value, with its statistical error over seeds. Cost per nu.
  kmc     replicas x time: the open TASEP current (alpha = 0.3, beta = 0.7, low-density
          phase) against its exact value alpha (1 - alpha) = 0.21, with its statistical error.
          Cost per current estimate.
Hook: the continuum engine and the colloid models of Kanehl (thesis) add a function returning
rows of the same form (see Row) and append it to ENGINES; the plot and the table pick it up.

Cost is the CPU time (user + system) of the narrows child process, from getrusage(
RUSAGE_CHILDREN) before and after each single-rank run, not wall time: this machine is
shared, so wall times are polluted by other jobs. Writes DIR/accuracy_<engine>.png (error
against cost, the Pareto front joined; md gives two: md_energy and md_settling) and prints a Markdown table; with --readme, replaces the
table between <!-- accuracy-map --> and <!-- /accuracy-map --> there.
--tiny runs one or two points per engine in seconds (tests/cli/accuracy_map_tiny.sh keeps the
tool from rotting); the default full map takes about 10-15 minutes on one core.
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


class Row(dict):
    """engine, knob (text), error (relative, signed), stat (its statistical error, or nan),
    cpu (s), cost (cpu per unit of work), unit (of the cost), note."""


def cpu_of_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def narrows_run(narrows, scene, out, sets):
    """Runs one single-rank job; returns its CPU seconds (child user + system)."""
    cmd = [narrows, "run", scene, "--out", out, "--set", "output.progress=false"]
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


def mpcd_rows(args, scale):
    size = (16, 12, 6)
    grid = {"tiny": (["srd"], [0.5], [3], 10),
            "medium": (["srd", "at", "at+a"], [0.1, 1.0], [5], 40),
            "full": (["srd", "at", "at+a"], [0.1, 0.5, 1.0], [5, 10], 80)}[scale]
    rules, dts, ns, relax_times = grid
    rows = []
    for rule in rules:
        for dt in dts:
            for n in ns:
                base = [f"fluid.collision={rule}", f"fluid.dt={dt}", f"fluid.density={n}",
                        f"domain.size=[{size[0]}.0, {size[1]}.0, {size[2]}.0]",
                        "run.dimensions=3", "walls.virtual_flow=mirror"]
                nu0 = info_nu(args.narrows, "run/ata_fluid_table5_1_3d.toml", base)
                L = size[1]
                g = 8.0 * nu0 * 0.05 / L**2  # centre velocity 0.05 (Ma ~ 0.04)
                relax = L**2 / (math.pi**2 * nu0)  # momentum relaxation time
                steps = max(1000, int(relax_times * relax / dt / 100 + 1) * 100)
                every = max(1, steps // 40)
                d = os.path.join(args.out, f"mpcd_{rule}_dt{dt:g}_n{n:g}")
                sets = base + [f"body_force.value=[{g!r}, 0.0, 0.0]", f"run.steps={steps}",
                               f"output.every={every}",
                               "output.observables=[\"velocity_profile\",\"temperature\"]"]
                cpu = narrows_run(args.narrows, "run/ata_fluid_table5_1_3d.toml", d, sets)
                run = narrows_h5.open_run(d)
                profile = run.series("velocity_profile")
                y = profile["bins"]
                prof = profile["value"][:, :, 0]
                temp = run.series("temperature")["value"]
                half = prof[len(prof) // 2:]
                q = y * (L - y) - 1.0 / 12.0  # the parabola averaged over a bin of width 1
                fits = np.linalg.lstsq(np.vstack([q, np.ones_like(q)]).T, half.T, rcond=None)[0]
                a = fits[0].mean()
                nu = g / (2.0 * a)
                stat = fits[0].std(ddof=1) / math.sqrt(fits.shape[1]) / abs(a)
                # theory at the measured temperature (nu is not linear in kT: ask narrows again)
                kT = float(np.mean(temp[len(temp) // 2:]))
                nu_t = info_nu(args.narrows, "run/ata_fluid_table5_1_3d.toml", base + [f"fluid.kT={kT!r}"])
                work = size[0] * size[1] * size[2] * steps * dt
                rows.append(Row(engine="mpcd", knob=f"{rule} dt={dt:g} n={n:g}",
                                error=nu / nu_t - 1.0, stat=stat, cpu=cpu,
                                cost=cpu / work * 1e6, unit="CPU µs per cell and time unit",
                                note=f"nu {nu:.4f} vs theory {nu_t:.4f}, {steps} steps"))
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


# Hook: the continuum engine and the colloid models of Kanehl (thesis) append their functions
# here.
ENGINES = {"mpcd": mpcd_rows, "md": md_rows, "fhp": fhp_rows, "kmc": kmc_rows}


def pareto(rows):
    """Rows not beaten in both |error| and cost by another row."""
    front = []
    for r in sorted(rows, key=lambda r: r["cost"]):
        if not math.isfinite(r["error"]):
            continue
        if not front or abs(r["error"]) < abs(front[-1]["error"]):
            front.append(r)
    return front


def plot(engine, rows, png):
    plt = narrows_h5.pyplot()
    fig, ax = plt.subplots(figsize=(6, 4.2))
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
    ax.set_ylabel("|relative error|")
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
            lines.append(f"| {engine} | {r['knob']} | {100 * r['error']:+.3g} % | {stat} | "
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
