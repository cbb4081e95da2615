#!/usr/bin/python3
"""Plot the time-averaged x-velocity profile of a narrows run against Poiseuille or Kolmogorov theory.

Usage: plot_profile.py OUTDIR [--png FILE]

Reads OUTDIR/observables.h5: /observables/velocity_profile (value [T][bins][d], bin centres
in .../bins), averaged over the second half of the samples, and the scene text in
/parameters/scene.
- Channel ([walls] and a constant force g along x): the steady profile is the Poiseuille
  parabola u(y) = g y (L - y) / (2 nu); the script fits u = a q(y) + b (q the bin average of
  y (L - y)), so nu_measured = g / (2 a), with an error from the spread of the per-sample fits,
  and b is the velocity left at the walls (slip).
- Periodic box with a sine force (amplitude F0): u(y) = F0 L^2 / (4 pi^2 nu) sin(2 pi y / L);
  the amplitude of the measured profile gives nu_measured.
Either is compared with the MPCD theory viscosity of the scene's collision rule at the
measured temperature. Writes a PNG (default OUTDIR/profile.png) and prints one line.
"""

import argparse
import math
import os
import sys

import numpy as np

import narrows_h5
from narrows_h5 import NarrowsDataError


def second_half(values):
    """Samples T//2 ... T-1 (all of them if there is only one)."""
    return values[len(values) // 2:] if len(values) > 1 else values


def theory_viscosity(collision, dims, n, dt, angle_deg, kT):
    """(nu, None) or (None, reason). MPCD units: cell size a = 1, particle mass m = 1."""
    f = n - 1.0 + math.exp(-n)
    alpha = math.radians(angle_deg)
    if collision == "srd":
        if dims == 2:
            kinetic = 0.5 * kT * dt * (n / (f * math.sin(alpha) ** 2) - 1.0)
            collisional = (1.0 / (12.0 * dt)) * (f / n) * (1.0 - math.cos(alpha))
        else:
            kinetic = 0.5 * kT * dt * (
                5.0 * n / (f * (2.0 - math.cos(alpha) - math.cos(2.0 * alpha))) - 1.0)
            collisional = (1.0 / (18.0 * dt)) * (f / n) * (1.0 - math.cos(alpha))
        return kinetic + collisional, None
    if collision == "at":
        return kT * dt * (n / f - 0.5) + f / (12.0 * n * dt), None
    if collision == "at+a":
        if dims == 2:
            return None, "no theory for at+a in 2D"
        return kT * dt * (n / (n - 1.25) - 0.5) + (n - 1.4) / (24.0 * n * dt), None
    return None, f"no theory for collision '{collision}'"


def read_run(outdir):
    run = narrows_h5.open_run(outdir)
    path = run.path
    group = run.series("velocity_profile")
    value = np.asarray(group["value"], dtype=float)
    if value.shape[0] == 0:
        raise NarrowsDataError(path, "/observables/velocity_profile has no samples")
    if group.bins is not None:
        bins = np.asarray(group.bins, dtype=float)
    else:  # fall back to unit-width bins from y = 0
        bins = np.arange(value.shape[1]) + 0.5
    steps = np.asarray(group.step) if group.step is not None else None
    temperature = None
    if run.has("temperature"):
        t = np.asarray(run.series("temperature").value, dtype=float)
        if t.shape and t.shape[0] > 0:
            temperature = float(np.mean(second_half(t)))
    scene_text = run.scene_text(required=False)
    ux = value if value.ndim == 2 else value[..., 0]  # [T][bins]: x-velocity
    samples = second_half(ux)
    if steps is not None and len(steps) == len(ux):
        used = second_half(steps)
        averaged = f"steps {int(used[0])}-{int(used[-1])}, {len(used)} samples"
    else:
        averaged = f"{len(samples)} samples"
    return path, bins, samples, temperature, scene_text, averaged


def scene_parameters(scene_text, path):
    """Dict of what the theory needs, or None if the scene has neither flow."""
    if not scene_text:
        return None
    scene = narrows_h5.parse_scene(scene_text, path)
    force = scene.get("body_force", {})
    if "walls" in scene and "value" in force:
        flow = "poiseuille"
    elif "walls" not in scene and force.get("kind") == "sine":
        flow = "kolmogorov"
    else:
        return None
    try:
        size = scene["domain"]["size"]
        fluid = scene["fluid"]
        return {
            "flow": flow,
            "F0": float(force["amplitude"]) if flow == "kolmogorov" else float(force["value"][0]),
            "L": float(size[1]),
            "dims": int(scene.get("run", {}).get("dimensions", len(size))),
            "collision": str(fluid["collision"]),
            "n": float(fluid["density"]),
            "dt": float(fluid["dt"]),
            "angle": float(fluid.get("angle", 90.0)),
            "kT": float(fluid.get("kT", 1.0)),
        }
    except (KeyError, IndexError, TypeError, ValueError) as e:
        raise NarrowsDataError(path, f"scene lacks what the theory needs ({e!r})") from e


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("outdir", help="run output directory holding observables.h5")
    parser.add_argument("--png", help="output image (default OUTDIR/profile.png)")
    args = parser.parse_args(argv[1:])
    png = args.png or os.path.join(args.outdir, "profile.png")

    path, y, samples, temperature, scene_text, averaged = read_run(args.outdir)
    params = scene_parameters(scene_text, path)

    plt = narrows_h5.pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    u = samples.mean(axis=0)
    ax.plot(y, u, "o", ms=4, label=f"measured ({averaged})")
    ax.set_xlabel("y")
    ax.set_ylabel(r"$\langle u_x \rangle$")

    if params is None:
        ax.set_title("velocity profile (neither a channel flow nor a sine force: no theory)")
        line = f"profile: no flow with a theory; plot in {png}"
    else:
        F0, L = params["F0"], params["L"]
        yy = np.linspace(0.0, L, 400)
        dy = L / len(y) if len(y) < 2 else float(np.mean(np.diff(y)))
        if params["flow"] == "poiseuille":
            q = y * (L - y) - dy * dy / 12.0
            design = np.vstack([q, np.ones_like(q)]).T
            fits = np.linalg.lstsq(design, samples.T, rcond=None)[0]  # [2][samples]
            a, b = fits[0].mean(), fits[1].mean()
            nu_measured = F0 / (2.0 * a) if a != 0.0 else math.inf
            err = (nu_measured * fits[0].std(ddof=1) / math.sqrt(fits.shape[1]) / abs(a)
                   if fits.shape[1] > 1 else math.nan)
            u0 = a * L * L / 4.0 + b
            shape = lambda nu: F0 * yy * (L - yy) / (2.0 * nu)  # noqa: E731
            fit_curve = a * yy * (L - yy) + b
            flow_name = "Poiseuille channel"
            extra = f", wall velocity {100 * b / u0:+.1f} % of u0"
        else:
            u_hat = 2.0 / L * float(np.sum(u * np.sin(2.0 * np.pi * y / L))) * dy
            nu_measured = F0 * L**2 / (4.0 * np.pi**2 * u_hat) if u_hat != 0.0 else math.inf
            amps = 2.0 / L * (samples * np.sin(2.0 * np.pi * y / L)).sum(axis=1) * dy
            err = (nu_measured * amps.std(ddof=1) / math.sqrt(len(amps)) / abs(u_hat)
                   if len(amps) > 1 else math.nan)
            shape = lambda nu: F0 * L**2 / (4.0 * np.pi**2 * nu) * np.sin(2.0 * np.pi * yy / L)  # noqa: E731,E501
            fit_curve = u_hat * np.sin(2.0 * np.pi * yy / L)
            flow_name = "Kolmogorov flow"
            extra = ""

        kT = params["kT"]
        kT_note = f"kT = {kT:g}"
        if temperature is not None and params["collision"] == "srd":
            kT = temperature
            kT_note = f"kinetic part at measured T = {temperature:.4g}"
        nu_theory, reason = theory_viscosity(params["collision"], params["dims"], params["n"],
                                             params["dt"], params["angle"], kT)
        measured = rf"$\nu_{{measured}}$ = {nu_measured:.4g} $\pm$ {err:.2g}"
        ax.plot(yy, fit_curve, "-", color="C0", lw=1, alpha=0.6, label="fit: " + measured)
        desc = f"{params['collision']} {params['dims']}D, n = {params['n']:g}, dt = {params['dt']:g}"
        if params["collision"] == "srd":
            desc += f", angle = {params['angle']:g}°"
        if nu_theory is not None:
            ax.plot(yy, shape(nu_theory), "--", color="C3",
                    label=rf"theory: $\nu$ = {nu_theory:.4g} ({kT_note})")
            off = 100.0 * (nu_measured - nu_theory) / nu_theory
            ax.set_title(f"{flow_name}, {desc}\n" + measured +
                         rf", $\nu_{{theory}}$ = {nu_theory:.4g} ({off:+.1f} %)", fontsize=10)
            line = (f"profile: nu_measured = {nu_measured:.6g} +- {err:.2g}, nu_theory = "
                    f"{nu_theory:.6g} ({off:+.2f} % off){extra}, plot in {png}")
        else:
            ax.plot([], [], " ", label=f"theory: none ({reason})")
            ax.set_title(f"{flow_name}, {desc}\n" + measured + r", $\nu_{theory}$: n/a",
                         fontsize=10)
            line = (f"profile: nu_measured = {nu_measured:.6g} +- {err:.2g}, nu_theory = n/a "
                    f"({reason}){extra}, plot in {png}")
        ax.set_xlim(0.0, L)

    ax.axhline(0.0, color="0.7", lw=0.5)
    ax.legend(fontsize=8)
    fig.tight_layout()
    try:
        fig.savefig(png, dpi=120)
    except OSError as e:
        print(f"plot_profile: cannot write {png}: {e.strerror}", file=sys.stderr)
        return 1
    print(line)
    return 0


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("plot_profile", main, sys.argv))
