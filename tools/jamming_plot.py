#!/usr/bin/python3
"""Figures of the jamming model (Kanehl (thesis) ch.6) like the thesis': growth rate against k,
the fixed-point classes in the (c, phi0) plane and a phase portrait; with --waves also the limit
cycles and homoclinic orbits of the travelling waves (a second PNG, tools/jamming_waves.py).

Usage: jamming_plot.py [OUTDIR] [--mu 1] [--phi 0.75] [--c -2.8] [--q 2.228] [--png FILE]
                       [--waves [--waves-z 300]]

The model: with OUTDIR the parameters the run used (/parameters/continuum of its observables:
a Table 6.2 column, continuum.vss or continuum.vss_fit), else Table 6.2's column --mu. Prints
the unstable band of eq 6.11 at phi0 (its edge searched from k -> 0, where Re lambda =
k^2 (phi0^2 v_ss'^2 v_ss / (sigma D) - 1), upwards and bisected).

Panels:
  a) growth rate Re lambda(k) of eq 6.11 at phi0 = --phi (or the run's mean) with the band
     edge; with OUTDIR (a `narrows run` of model "jamming") the rates measured in the run,
     printed as "growth k = ... measured eq-6.11 rel.error samples": least-squares slopes of
     ln |phi_n(t)| while the mode stays within e^8 of its first size and above 1e3 amax^2
     (amax the largest mode: the quadratic terms feed it less than 1e-3 of itself). Start the run from
     continuum.initial kind "eigenmode" (amplitude <= 1e-6: each mode on its slow eigenvector,
     so the rates hold from t = 0 and no mode's harmonics swamp the decaying ones; they agree
     with eq 6.11 within 1 % on both sides of the band edge, tests/cli/jamming_growth.sh);
     from random noise the fit starts at t = 4 and rates beyond k ~ 0.75 are unreliable.
     The run's fronts are checked (front_residual): once pulses have formed, the residual of
     the velocity equation of the travelling waves (eq 6.14, (v - c) v_z = sigma - xi(phi) v,
     c fitted) above 5 % of its terms over the last samples prints one warning line on stderr
     naming continuum.cells to raise (run/continuum_jamming_pulses.toml: 17 % at 1024 points,
     9 % at 2048, 2.4 % at 4096 on length 100); the line "front:" gives the grid points
     across the steepest front as well;
  b) Re lambda at k = 1 against phi for the four columns of Table 6.2 (fig 6.11);
  c) the fixed-point classes of eq 6.13-6.14 in the (c, phi0) plane (eq 6.20) with the Hopf
     line of eq 6.21 (fig 6.14 left);
  d) the phase portrait at (--c, --q): nullclines (eq 6.16-6.17), fixed points with their
     type, trajectories and the limit cycle around the middle fixed point if there is one
     (fig 6.12, 6.18 b).
--waves (OUT/jamming_waves.png, a minute or two): the area of limit cycles between the Hopf
and the homoclinic line (fig 6.14 right, 6.18 a), three closed orbits I-III in the phase
plane and their profiles phi(z), v(z) (fig 6.18 c); prints the homoclinic line.
The formulas are those of src/continuum/jamming_*.cpp and travelling_wave.cpp written again in
numpy (the C++ functions are validated by the tests; this only draws). Writes a PNG (default
OUTDIR/jamming.png or ./jamming.png) and prints the fixed points.
"""

import argparse
import math
import os
import sys

import numpy as np

import narrows_h5

TABLE_6_2 = {  # dv, dphi, phi_c, e1, e2, phi_q
    "infinity": (0.0489, 0.00247, 0.744, 2.82, -3.68, 0.819),
    "1": (0.0413, 0.0025, 0.762, 2.56, -3.24, 0.845),
    "1/2": (0.0247, 0.00312, 0.778, 2.78, -3.45, 0.854),
    "0": (0.0005, 0.00233, 0.808, 2.90, -3.53, 0.846),
}


VSS_NAMES = ("delta_v", "delta_phi", "phi_c", "e1", "e2", "phi_q")


class Model:
    def __init__(self, mu="1", drive=1.0, diffusion=1.0, vss=None):
        """v_ss of Table 6.2's column mu, or of vss = (delta_v, delta_phi, phi_c, e1, e2,
        phi_q) (eq 6.4)."""
        self.dv, self.dphi, self.phic, self.e1, self.e2, self.phiq = (
            TABLE_6_2[mu] if vss is None else tuple(float(x) for x in vss))
        self.e3 = (self.e1 + self.e2 * self.phic) / (self.phic - self.phiq) ** 2
        self.sigma, self.D = drive, diffusion
        self.label = f"mu = {mu}" if vss is None else "vss " + ", ".join(
            f"{n} = {x:g}" for n, x in zip(VSS_NAMES, vss))

    def vss(self, p):
        p = np.asarray(p, dtype=float)
        step = self.dv * (1 + np.tanh((self.phic - p) / self.dphi))
        return step + np.where(p < self.phic, self.e1 + self.e2 * p, self.e3 * (p - self.phiq) ** 2)

    def dvss(self, p):
        p = np.asarray(p, dtype=float)
        t = np.tanh((self.phic - p) / self.dphi)
        step = -self.dv * (1 - t * t) / self.dphi
        return step + np.where(p < self.phic, self.e2, 2 * self.e3 * (p - self.phiq))

    def xi(self, p):
        return self.sigma / self.vss(p)

    def dxi(self, p):
        return -self.sigma * self.dvss(p) / self.vss(p) ** 2

    def growth(self, p0, k):
        """Eq 6.11 (with sigma, D): the eigenvalue of larger real part."""
        xi, D = self.xi(p0), self.D
        a = -(D * k * k + xi) / 2
        disc = a * a - xi * D * k * k + 1j * k * p0 * self.sigma * self.dxi(p0) / xi
        return a + np.sqrt(disc + 0j) - 1j * k * self.vss(p0)

    def long_wave(self, p0):
        """phi0^2 v_ss'^2 v_ss / (sigma D) - 1: Re lambda = k^2 times this as k -> 0."""
        return p0 * p0 * self.dvss(p0) ** 2 * self.vss(p0) / (self.sigma * self.D) - 1

    def band_edge(self, p0, k_max=20.0, samples=4000):
        """The upper edge of the unstable band of eq 6.11 (0 if none up to k_max): the scan
        starts at k -> 0 (the sign of long_wave), so a band narrower than the first sample is
        bisected between 0 and it, not missed."""
        ks = np.concatenate([[0.0], np.linspace(0, k_max, samples + 1)[1:]])
        unstable = np.concatenate([[self.long_wave(p0) > 0], self.growth(p0, ks[1:]).real > 0])
        edge = 0.0
        for i in np.nonzero(unstable[:-1] & ~unstable[1:])[0]:
            a, b = ks[i], ks[i + 1]
            for _ in range(100):
                mid = 0.5 * (a + b)
                a, b = (mid, b) if self.growth(p0, mid).real > 0 else (a, mid)
            edge = 0.5 * (a + b)
        return k_max if unstable[-1] else edge

    def jacobian_eigs(self, c, p0):
        """Eigenvalues of eq 6.19 (with sigma, D) at the fixed point phi0."""
        v0 = self.vss(p0)
        a, b = (v0 - c) / self.D, p0 / self.D
        cc, d = -self.dxi(p0) * v0 / (v0 - c), -self.xi(p0) / (v0 - c)
        tr, det = a + d, a * d - b * cc
        root = np.sqrt(tr * tr / 4 - det + 0j)
        return tr / 2 + root, tr / 2 - root

    def kind(self, c, p0):
        l1, l2 = self.jacobian_eigs(c, p0)
        if abs(l1.imag) > 0:
            return "focus sink" if l1.real < 0 else "focus source"
        if l1.real * l2.real < 0:
            return "saddle"
        return "node sink" if l1.real < 0 else "node source"

    def rhs(self, c, q, p, v):
        return ((v - c) * p - q) / self.D, (self.sigma - self.xi(p) * v) / (v - c)

    def fixed_points(self, c, q):
        p = np.linspace(1e-3, 0.999, 40001)
        g = p * (self.vss(p) - c) - q
        out = []
        for i in np.nonzero(np.sign(g[:-1]) != np.sign(g[1:]))[0]:
            a, b = p[i], p[i + 1]
            for _ in range(80):
                m = 0.5 * (a + b)
                ga = a * (self.vss(a) - c) - q
                gm = m * (self.vss(m) - c) - q
                a, b = (a, m) if ga * gm <= 0 else (m, b)
            out.append(0.5 * (a + b))
        return out

    def trajectory(self, c, q, p, v, h, steps):
        ps, vs = [p], [v]
        for _ in range(steps):
            k1 = self.rhs(c, q, p, v)
            k2 = self.rhs(c, q, p + h / 2 * k1[0], v + h / 2 * k1[1])
            k3 = self.rhs(c, q, p + h / 2 * k2[0], v + h / 2 * k2[1])
            k4 = self.rhs(c, q, p + h * k3[0], v + h * k3[1])
            p = p + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            v = v + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            if not (0 < p < 1) or not np.isfinite(v) or abs(v) > 5:
                break
            ps.append(p)
            vs.append(v)
        return np.array(ps), np.array(vs)


COUPLING = 1e3  # measured_rates: a mode counts while COUPLING amax^2 or larger


def measured_rates(run, cont):
    """(k, rate, samples) of each Fourier mode of the run's phi: the least-squares slope of
    ln |phi_n(t)| while the mode stays within e^8 of its size at the first sample used. Started
    from initial kind "eigenmode" (each mode on its slow eigenvector, amplitude <= 1e-6) the
    fit starts at t = 0 and takes the excited modes; from noise ("random"/"sine") at t = 4,
    after the fast partner's transient, leaving out modes already 1e-4 of their start."""
    density = run.series("density")
    phi, t, bins = density["value"], density["time"], density["bins"]
    cells = phi.shape[1]
    length = bins[1] * cells
    amp = np.abs(np.fft.rfft(phi, axis=1)) / cells
    init = cont.get("initial", {})
    eigen = init.get("kind") == "eigenmode"
    if eigen:
        modes = init.get("modes", list(range(1, (cells - 1) // 3 + 1)))
        start = 0
    else:
        modes = range(1, cells // 3)
        start = np.searchsorted(t, 4.0)
    # The quadratic terms (phi v)_x, (v^2/2)_x feed mode n from pairs of modes at a size of
    # order amax^2 (amax the largest mode): a mode is followed only while it is COUPLING times
    # larger, so that what it receives stays under 1 / COUPLING of it.
    amax = amp[:, 1:cells // 3].max(axis=1)
    ks, rates, counts = [], [], []
    for n in modes:
        if not eigen and amp[start, n] < 1e-4 * amp[0, n]:
            continue  # decayed to the rounding floor before t = 4
        y = np.log(amp[start:, n] + 1e-300)
        keep = (np.abs(y - y[0]) <= 8) & (amp[start:, n] >= COUPLING * amax[start:] ** 2)
        stop = np.argmin(keep) if not keep.all() else len(y)
        if stop < 10:
            continue
        ks.append(2 * np.pi * n / length)
        rates.append(np.polyfit(t[start:start + stop], y[:stop], 1)[0])
        counts.append(stop)
    return np.array(ks), np.array(rates), np.array(counts)


RESIDUAL_LIMIT = 0.05  # front_residual: the largest residual of eq 6.14 of a resolved front
RESIDUAL_SAMPLES = 5  # front_residual: the last samples with pulses it takes the median of


def front_residual(run, m, last=RESIDUAL_SAMPLES):
    """How well the run's pulses satisfy the velocity equation of the travelling waves, eq 6.14
    (with the drive sigma): (v - c) v_z = sigma - xi(phi) v. Per sample, v_z by spectral
    differentiation on the grid points (the engine is pseudo-spectral), c by least squares
    (the speed that fits eq 6.14 best, so a wrong speed does not count as a residual),
    R = (v - c) v_z - (sigma - xi(phi) v) and its size max |R| / max |(v - c) v_z| (at the
    front the two terms balance; elsewhere both vanish). A resolved front gives a few percent
    (what is left of the pulses' slow change); an under-resolved one more, where phi crosses
    phi_c and xi(phi) steps within delta_phi = 0.0025. Takes the median over the last `last`
    samples with pulses (max phi - min phi >= 0.01): while pulses form or merge they are no
    travelling waves and the residual is large at any resolution (25 % at t ~ 280 in
    run/continuum_jamming_pulses.toml at 4096 points), so the check assumes the run ends with
    settled pulses. Also the front's width in grid points, (max phi - min phi) / max |phi_{i+1}
    - phi_i|, i.e. 2 delta for phi ~ tanh(x / delta) (the fewest over those samples; 8 and 15
    points left 17 % and 9 %, 30 points 2.4 %). Returns (median ratio, first and last time used, median c,
    fewest points across a front) or None (no pulses, or no velocity observable)."""
    density = run.series("density")
    phi, t, bins = density["value"], density["time"], density["bins"]
    if not run.has("velocity"):
        return None
    v = run.series("velocity")["value"]
    cells = phi.shape[1]
    dx = bins[1] - bins[0]
    pulses = np.nonzero(phi.max(axis=1) - phi.min(axis=1) >= 0.01)[0][-last:]
    if len(pulses) == 0:
        return None
    ik = 1j * 2 * np.pi * np.fft.rfftfreq(cells, dx)
    ratios, speeds, points = [], [], []
    for i in pulses:
        jump = phi[i].max() - phi[i].min()
        points.append(jump / np.abs(np.diff(phi[i], append=phi[i][:1])).max())
        vz = np.fft.irfft(ik * np.fft.rfft(v[i]), cells)
        rhs = m.sigma - m.xi(phi[i]) * v[i]
        c = np.sum(vz * (v[i] * vz - rhs)) / np.sum(vz * vz)
        advection = (v[i] - c) * vz
        ratios.append(np.abs(advection - rhs).max() / np.abs(advection).max())
        speeds.append(c)
    return (float(np.median(ratios)), float(t[pulses[0]]), float(t[pulses[-1]]),
            float(np.median(speeds)), float(min(points)))


def model_of_run(run, cont):
    """The Model of a run: the parameters the engine wrote to /parameters/continuum, or (older
    files) the scene's mu."""
    drive, diffusion = cont.get("drive", 1.0), cont.get("diffusion", 1.0)
    attrs = run.parameter_attributes("continuum")
    if attrs is not None and all(n in attrs for n in VSS_NAMES):
        m = Model(drive=attrs.get("drive", drive), diffusion=attrs.get("diffusion", diffusion),
                  vss=[attrs[n] for n in VSS_NAMES])
        if "mu" in cont or ("vss" not in cont and "vss_fit" not in cont):
            m.label = f"mu = {cont.get('mu', '1')}"
        return m
    return Model(cont.get("mu", "1"), drive, diffusion)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir", nargs="?")
    ap.add_argument("--mu", default="1", choices=list(TABLE_6_2))
    ap.add_argument("--phi", type=float, default=0.75)
    ap.add_argument("--c", type=float, default=-2.8)
    ap.add_argument("--q", type=float, default=2.228)
    ap.add_argument("--png")
    ap.add_argument("--waves", action="store_true",
                    help="also the limit cycles of eq 6.13-6.14 (fig 6.14 right, 6.18 a, c): "
                         "OUT/jamming_waves.png; about a minute")
    ap.add_argument("--waves-z", type=float, default=300.0,
                    help="length in z each trajectory of --waves is followed (default 300)")
    args = ap.parse_args()
    phi0 = args.phi
    m = Model(args.mu)
    run = None
    if args.outdir:
        run = narrows_h5.open_run(args.outdir)
        run.require_engine("continuum")
        cont = run.scene()["continuum"]
        m = model_of_run(run, cont)
        phi0 = cont["initial"].get("mean", phi0)
    drive, diffusion = m.sigma, m.D
    edge = m.band_edge(phi0)
    print(f"eq 6.11 at phi0 = {phi0:g} ({m.label}, sigma = {drive:g}, D = {diffusion:g}): "
          f"long-wave coefficient {float(m.long_wave(phi0)):+.6g}, "
          + (f"unstable band 0 < k < {edge:.6g}" if edge > 0 else "no unstable band"))

    plt = narrows_h5.pyplot()
    import matplotlib.colors
    import matplotlib.patches
    fig, ax = plt.subplots(2, 2, figsize=(12, 9))
    k = np.linspace(1e-3, 3.0, 600)
    ax[0, 0].plot(k, m.growth(phi0, k).real, label="eq 6.11")
    if edge > 0:
        ax[0, 0].axvline(edge, color="0.5", ls=":", lw=1, label=f"band edge k = {edge:.4g}")
    if run is not None:
        km, rm, counts = measured_rates(run, cont)
        ax[0, 0].plot(km, rm, "o", ms=4, label="PDE run: slope of ln|phi_n|")
        print("     k        measured      eq 6.11     rel. error  samples")
        for kk, r, n in zip(km, rm, counts):
            th = float(m.growth(phi0, kk).real)
            print(f"growth k = {kk:.6f}  {r:+.6e}  {th:+.6e}  {(r - th) / abs(th):+.2e}  {n}")
        residual = front_residual(run, m)
        if not run.has("velocity"):
            print("front: not checked (the run has no velocity observable)")
        elif residual is None:
            print("front: no pulses (max phi - min phi < 0.01 in every sample)")
        else:
            ratio, t0, t1, c, points = residual
            print(f"front: {points:.3g} grid points across the steepest front; residual of eq "
                  f"6.14 {100 * ratio:.3g} % of its terms at c = {c:.4g} (median over the samples "
                  f"t = {t0:g}-{t1:g})")
            if ratio > RESIDUAL_LIMIT:
                cells = run.series("density")["value"].shape[1]
                print(f"warning: the pulse fronts are under-resolved: the residual of the velocity "
                      f"equation (eq 6.14) is {100 * ratio:.3g} % of its terms at t = {t0:g}-{t1:g}, "
                      f"above {100 * RESIDUAL_LIMIT:g} %; raise continuum.cells (now {cells}) for "
                      f"the same length, to {cells * 2 ** math.ceil(math.log2(ratio / RESIDUAL_LIMIT))}"
                      f" or more", file=sys.stderr)
                ax[0, 0].text(0.02, 0.02, f"front: eq 6.14 residual {100 * ratio:.3g} % (not "
                              f"resolved)", color="r", transform=ax[0, 0].transAxes)
    ax[0, 0].axhline(0, color="k", lw=0.5)
    ax[0, 0].set(xlabel="k", ylabel="Re lambda",
                 title=f"a) growth rate, phi0 = {phi0:g}, {m.label}, sigma = {drive:g}, "
                       f"D = {diffusion:g}")
    ax[0, 0].set_ylim(min(-1.0, m.growth(phi0, k).real.max() * -3), None)
    ax[0, 0].legend(fontsize=8)

    p = np.linspace(0.6, 0.85, 2000)
    for name in TABLE_6_2:
        ax[0, 1].plot(p, Model(name, drive, diffusion).growth(p, 1.0).real, label=f"mu = {name}")
    ax[0, 1].axhline(0, color="k", lw=0.5)
    ax[0, 1].set(xlabel="phi", ylabel="Re lambda(k = 1)", title="b) fig 6.11: Re lambda at k = 1")
    ax[0, 1].set_ylim(-0.5, 1.0)
    ax[0, 1].legend()

    kinds = ["saddle", "node sink", "node source", "focus sink", "focus source"]
    cs = np.linspace(-4.0, -1.0, 300)
    ps = np.linspace(0.70, 0.80, 300)
    C, P = np.meshgrid(cs, ps)
    l1, l2 = m.jacobian_eigs(C, P)
    grid = np.where(np.abs(l1.imag) > 0, np.where(l1.real < 0, 3, 4),
                    np.where(l1.real * l2.real < 0, 0, np.where(l1.real < 0, 1, 2)))
    cmap = matplotlib.colors.ListedColormap(["#bbbbbb", "#2c7bb6", "#d7191c", "#abd9e9", "#fdae61"])
    ax[1, 0].pcolormesh(cs, ps, grid, cmap=cmap, vmin=-0.5, vmax=4.5, shading="auto")
    hp = np.linspace(0.70, 0.80, 4000)
    hc = m.vss(hp) - np.sqrt(m.D * m.xi(hp))
    ax[1, 0].plot(hc, hp, "k--", lw=1, label="Hopf (eq 6.21)")
    ax[1, 0].plot([args.c], [m.fixed_points(args.c, args.q)[len(m.fixed_points(args.c, args.q)) // 2]],
                  "k*", ms=10, label=f"c = {args.c:g}, q = {args.q:g}")
    handles = [matplotlib.patches.Patch(color=cmap(i), label=kinds[i]) for i in range(5)]
    ax[1, 0].legend(handles=handles + ax[1, 0].get_legend_handles_labels()[0], fontsize=8)
    ax[1, 0].set(xlabel="c", ylabel="phi0", xlim=(cs[0], cs[-1]), ylim=(ps[0], ps[-1]),
                 title="c) fig 6.14: fixed points in the (c, phi0) plane")

    c, q = args.c, args.q
    fps = m.fixed_points(c, q)
    a = ax[1, 1]
    pp = np.linspace(0.6, 0.9, 3000)
    a.plot(pp, q / pp + c, "g", lw=1, label="v_N1 = q/phi + c")
    a.plot(pp, m.vss(pp), "m", lw=1, label="v_N2 = v_ss")
    marks = {"saddle": "s", "node sink": "v", "node source": "^", "focus sink": "o", "focus source": "o"}
    for f in fps:
        kind = m.kind(c, f)
        print(f"fixed point phi0 = {f:.6f}, v0 = {float(m.vss(f)):.6f}: {kind}, "
              f"lambda = {m.jacobian_eigs(c, f)[0]:.4f}, {m.jacobian_eigs(c, f)[1]:.4f}")
        a.plot(f, m.vss(f), marks[kind], ms=8, mfc="w" if "source" in kind else "k", mec="k",
               label=kind)
    for f in fps:
        for dp in (-0.01, -0.003, 0.003, 0.01):
            for h in (0.004, -0.004):
                tp, tv = m.trajectory(c, q, f + dp, float(m.vss(f)), h, 2500)
                a.plot(tp, tv, "0.6", lw=0.5)
    if len(fps) == 3:
        mid = fps[1]
        l1, _ = m.jacobian_eigs(c, mid)
        h = 0.004 if l1.real > 0 else -0.004
        tp, tv = m.trajectory(c, q, mid, float(m.vss(mid)) * 1.0001 + 1e-6, h, 100000)
        a.plot(tp[-1200:], tv[-1200:], "k", lw=2, label="limit cycle (last two turns of the spiral)")
    a.set(xlabel="phi", ylabel="v", xlim=(0.65, 0.85), ylim=(-0.05, 0.6),
          title=f"d) phase portrait, c = {c:g}, q = {q:g}")
    a.legend(fontsize=8)
    fig.tight_layout()
    png = args.png or os.path.join(args.outdir or ".", "jamming.png")
    fig.savefig(png, dpi=110)
    print(f"wrote {png}")
    if args.waves:
        import jamming_waves
        jamming_waves.figure(m, os.path.join(os.path.dirname(png) or ".", "jamming_waves.png"),
                             args.waves_z, args.c, args.q)


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("jamming_plot", main))
