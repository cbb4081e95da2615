#!/usr/bin/python3
"""Figures of the jamming model (Kanehl (thesis) ch.6) like the thesis': growth rate against k,
the fixed-point classes in the (c, phi0) plane and a phase portrait.

Usage: jamming_plot.py [OUTDIR] [--mu 1] [--phi 0.75] [--c -2.8] [--q 2.228] [--png FILE]

Panels:
  a) growth rate Re lambda(k) of eq 6.11 at phi0 = --phi (sigma = D = 1 unless OUTDIR's scene
     says otherwise); with OUTDIR (a `narrows run` of model "jamming" started from small noise,
     e.g. run/continuum_jamming_pulses.toml with a small amplitude) the rates measured in the
     run: least-squares slopes of ln |phi_n(t)| over the samples while the mode stays within
     e^8 of its size after t = 4 (modes already 1e-4 of their start by then are left out) (as tests/validation/test_continuum_jamming.cpp does);
  b) Re lambda at k = 1 against phi for the four columns of Table 6.2 (fig 6.11);
  c) the fixed-point classes of eq 6.13-6.14 in the (c, phi0) plane (eq 6.20) with the Hopf
     line of eq 6.21 (fig 6.14);
  d) the phase portrait at (--c, --q): nullclines (eq 6.16-6.17), fixed points with their
     type, trajectories and the limit cycle around the middle fixed point if there is one
     (fig 6.12, 6.18 b).
The formulas are those of src/continuum/jamming_*.cpp and travelling_wave.cpp written again in
numpy (the C++ functions are validated by the tests; this only draws). Writes a PNG (default
OUTDIR/jamming.png or ./jamming.png) and prints the fixed points.
"""

import argparse
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


class Model:
    def __init__(self, mu="1", drive=1.0, diffusion=1.0):
        self.dv, self.dphi, self.phic, self.e1, self.e2, self.phiq = TABLE_6_2[mu]
        self.e3 = (self.e1 + self.e2 * self.phic) / (self.phic - self.phiq) ** 2
        self.sigma, self.D = drive, diffusion

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


def measured_rates(outdir):
    density = narrows_h5.open_run(outdir).series("density")
    phi = density["value"]
    t = density["time"]
    bins = density["bins"]
    length = bins[1] * len(bins)
    amp = np.abs(np.fft.rfft(phi, axis=1)) / phi.shape[1]
    ks, rates = [], []
    start = np.searchsorted(t, 4.0)
    for n in range(1, phi.shape[1] // 3):
        if amp[start, n] < 1e-4 * amp[0, n]:
            continue  # decayed to the rounding floor before t = 4
        y = np.log(amp[start:, n] + 1e-300)
        keep = np.abs(y - y[0]) <= 8
        stop = np.argmin(keep) if not keep.all() else len(y)
        if stop < 20:
            continue
        ks.append(2 * np.pi * n / length)
        rates.append(np.polyfit(t[start:start + stop], y[:stop], 1)[0])
    return np.array(ks), np.array(rates)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("outdir", nargs="?")
    ap.add_argument("--mu", default="1", choices=list(TABLE_6_2))
    ap.add_argument("--phi", type=float, default=0.75)
    ap.add_argument("--c", type=float, default=-2.8)
    ap.add_argument("--q", type=float, default=2.228)
    ap.add_argument("--png")
    args = ap.parse_args()
    drive, diffusion, mu, phi0 = 1.0, 1.0, args.mu, args.phi
    if args.outdir:
        run = narrows_h5.open_run(args.outdir)
        run.require_engine("continuum")
        cont = run.scene()["continuum"]
        drive, diffusion = cont.get("drive", 1.0), cont.get("diffusion", 1.0)
        mu = cont.get("mu", "1")
        phi0 = cont["initial"].get("mean", phi0)
    m = Model(mu, drive, diffusion)

    plt = narrows_h5.pyplot()
    import matplotlib.colors
    import matplotlib.patches
    fig, ax = plt.subplots(2, 2, figsize=(12, 9))
    k = np.linspace(1e-3, 3.0, 600)
    ax[0, 0].plot(k, m.growth(phi0, k).real, label="eq 6.11")
    if args.outdir:
        km, rm = measured_rates(args.outdir)
        ax[0, 0].plot(km, rm, "o", ms=4, label="PDE run: slope of ln|phi_n|")
    ax[0, 0].axhline(0, color="k", lw=0.5)
    ax[0, 0].set(xlabel="k", ylabel="Re lambda",
                 title=f"a) growth rate, phi0 = {phi0:g}, mu = {mu}, sigma = {drive:g}, D = {diffusion:g}")
    ax[0, 0].set_ylim(min(-1.0, m.growth(phi0, k).real.max() * -3), None)
    ax[0, 0].legend()

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


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("jamming_plot", main))
