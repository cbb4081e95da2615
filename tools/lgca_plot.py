#!/usr/bin/python3
"""Plots of an lgca run (observables.h5 of `narrows run` with engine "lgca").

- shear wave: ln of the amplitude A(t) of u_x = A sin(2 pi y / L_y) against t (several files,
  e.g. runs with different seeds, are averaged), the straight-line fit over the window
  [--first, --last] and the Boltzmann decay exp(-nu k^2 t) of PHYSICS.md, k = 2 pi / L_y,
  L_y = size[1] sqrt(3)/2; prints nu from the fit (error: jackknife over the files when there
  are several) against the Boltzmann nu;
- fields (density, velocity): the last sample of u_x and of the density over the lattice;
- tagged VACF (/observables/vacf): FHP models on log-log axes, Z(t) + (1 - d)/N (eq 22) with its
  error, the power-law fit Z ~ t^-a over [--tail-first, --tail-last] (weighted by the error;
  prints a and its error) and eq 19 at t = 1; the 1D model on linear axes with the plateau
  -(1 - d)/N of eq 22 (van der Hoef & Frenkel fig 1);
- colloid, held or moving (/observables/colloid_vacf, colloid_diffusion; van der Hoef & Frenkel
  fig 3): the canonical VACF Z(t) (of U - V, V the conserved centre-of-mass velocity, + M/M_tot:
  the eq 22 analogue) on log-log axes with the unsteady-Stokes theory of a disc in a 2D fluid
  (held_disc_vacf) and its asymptote M/(8 pi rho nu t); prints local exponents over
  --colloid-windows (Z averaged over +-10 % in t, jackknife errors over the blocks of all files);
  D(t) against ln t with the straight-line fit over [--colloid-first, --colloid-last], R^2, the
  curvature d2D/d(ln t)^2 (jackknife errors) and the theory's slope. The theory is that of a free
  disc without the 2D renormalisation (D(t) in D + nu, van der Hoef & Frenkel §4.3): the held
  disc's, and for a moving disc a reference it departs from at late times. A chained run continues
  its averages (they are in the checkpoint): give the last segment's observables-<step>.h5 only.
  Several files (e.g. runs with other seeds, or segments written before the averages were
  checkpointed) are averaged with equal weights.

Usage: tools/lgca_plot.py OUT/observables.h5 [MORE.h5 ...] [--png FILE] [--first T0] [--last T1]
                          [--tail-first T0] [--tail-last T1] [--colloid-first T0] [--colloid-last T1]
                          [--colloid-windows 100:300,...] [--colloid-nu NU] [--colloid-a A]
"""
import argparse
import math
import os
import sys

import numpy as np

import narrows_h5


def boltzmann_nu(model, d):
    e = 1.0 - d
    if model == "fhp-i":
        return 1 / (12 * d * e**3) - 1 / 8
    if model == "fhp-ii":
        return 1 / (28 * d * e**3 * (1 - 4 * d / 7)) - 1 / 8
    if model == "fhp-iii":
        return 1 / (28 * d * e * (1 - 8 * d * e / 7)) - 1 / 8
    if model == "fhp-saturated":
        return 1 / (12 * d * e * (1 + 2 * d * e)) - 1 / 8
    raise ValueError(model)


def fit_rate(t, a, first, last):
    sel = (t >= first) & (t <= last) & (a > 0)
    slope, icpt = np.polyfit(t[sel], np.log(a[sel]), 1)
    return -slope, icpt


def fit_tail(t, z, e, first, last):
    """Weighted least squares of ln z = c - a ln t; returns a, its error, c."""
    sel = (t >= first) & (t <= last) & (z > 0)
    x, y, w = np.log(t[sel]), np.log(z[sel]), (z[sel] / np.maximum(e[sel], 1e-300)) ** 2
    (slope, icpt), cov = np.polyfit(x, y, 1, w=np.sqrt(w), cov="unscaled")
    return -slope, math.sqrt(cov[0, 0]), icpt


def vacf_panel(ax, g, lat, args):
    z, e, lags = g["value"], g["error"], g["lags"]
    if lat["model"] == "dhumieres-1d":
        n = g.number("particles")
        ax.plot(lags[1:], z[1:], lw=0.8, label=f"L = {lat['size'][0]}, N = {n:.0f}")
        ax.fill_between(lags[1:], (z - e)[1:], (z + e)[1:], alpha=0.3, lw=0)
        ax.axhline(g["plateau_theory"][0], ls="--", color="k", lw=0.8,
                   label="eq 22 plateau -(1 - d)/N" if g["plateau_theory"][0] else "0")
        lim = 10 * max(abs(g["plateau_theory"][0]), float(np.median(e[1:])))
        ax.set_ylim(-lim, lim)
        ax.set_xlabel("t")
        ax.set_ylabel("Z(t) = <v(0) v(t)> / <v^2>")
        ax.set_title(f"d'Humieres 1D, d = {lat['density']}")
        ax.legend(fontsize=8)
        return
    zc = g["corrected"]
    t = lags.astype(float)
    last = args.tail_last if args.tail_last is not None else t[-1]
    ok = zc > 0
    if ((t >= args.tail_first) & (t <= last) & ok).sum() < 3:
        print(f"{lat['model']} d = {lat['density']}: Z(1) = {z[1]:.6f} +- {e[1]:.2g}; fewer than "
              f"3 positive lags in {args.tail_first:g}..{last:g}: no tail fit")
        ax.loglog(t[1:][ok[1:]], zc[1:][ok[1:]], ".", label="Z(t) + (1 - d)/N (eq 22)")
        ax.legend(fontsize=8)
        return
    a, da, c = fit_tail(t, zc, e, args.tail_first, last)
    print(f"{lat['model']} d = {lat['density']}: Z(1) = {z[1]:.6f} +- {e[1]:.2g} (eq 19 "
          f"{g['one_step_theory'][0]:.6f}); tail Z + (1-d)/N ~ t^-a, a = {a:.4f} +- {da:.4f} "
          f"over lags {args.tail_first:g}..{last:g} ({int(g['curves'][0])} curves; the error "
          f"treats lags as independent and understates the spread of independent runs)")
    ax.errorbar(t[1:][ok[1:]], zc[1:][ok[1:]], yerr=e[1:][ok[1:]], fmt=".", ms=3, lw=0.5,
                label="Z(t) + (1 - d)/N (eq 22)")
    tt = np.array([args.tail_first, last])
    ax.loglog(tt, 1.3 * np.exp(c) * tt ** -a, "-", color="C3", lw=2, zorder=3, label=f"fit (x 1.3 for visibility): t^-{a:.3f}")
    t0 = g.number("mean_free_time")
    tb = np.linspace(1, min(t[-1], 15 * t0), 50)
    ax.loglog(tb, g["one_step_theory"][0] ** tb, "--", lw=0.8, label="Boltzmann Z(1)^t")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("t")
    ax.set_ylabel("Z(t)")
    ax.set_title(f"tagged VACF, {lat['model']}, d = {lat['density']}, "
                 f"{lat['size'][0]} x {lat['size'][1]}")
    ax.legend(fontsize=8)


def bessel_k0_k1_scaled(x):
    """e^x K0(x), e^x K1(x) for x > 0: K_n(x) = int_0^inf exp(-x cosh u) cosh(n u) du by the
    trapezoid rule (spectrally accurate for this integrand; h = 0.02 to machine precision)."""
    x = np.atleast_1d(np.asarray(x, float))[:, None]
    u = np.arange(0.0, 40.0, 0.02)[None, :]
    w = np.exp(-x * (np.cosh(u) - 1.0)) * 0.02
    w[:, 0] *= 0.5
    return w.sum(axis=1), (w * np.cosh(u)).sum(axis=1)

def stehfest(n=14):
    v = []
    for k in range(1, n + 1):
        s = 0.0
        for j in range((k + 1) // 2, min(k, n // 2) + 1):
            s += (j ** (n // 2) * math.factorial(2 * j)
                  / (math.factorial(n // 2 - j) * math.factorial(j) * math.factorial(j - 1)
                     * math.factorial(k - j) * math.factorial(2 * j - k)))
        v.append((-1) ** (k + n // 2) * s)
    return np.array(v)

def held_disc_vacf(t, m, a, rho, nu, n=14):
    """Z(t) = C(t)/C(0) of a disc (mass m, radius a) in an incompressible 2D fluid: Laplace
    transform m / (s (m + m_f) + 4 pi eta lam a K1(lam a) / K0(lam a)), lam = (s/nu)^(1/2),
    m_f = pi a^2 rho (Stokes 1851, cylinder), inverted by Gaver-Stehfest."""
    t = np.atleast_1d(np.asarray(t, float))
    v = stehfest(n)
    eta = rho * nu
    mf = math.pi * a * a * rho
    out = np.zeros_like(t)
    for k in range(1, n + 1):
        s = k * math.log(2) / t
        z = np.sqrt(s / nu) * a
        k0, k1 = bessel_k0_k1_scaled(z)
        out += v[k - 1] * m / (s * (m + mf) + 4 * math.pi * eta * z * k1 / k0)
    return out * math.log(2) / t


def colloid_curves(groups):
    """Lags, mean curve and block curves of the held colloid's VACF or D(t) over all files (the
    segments of a chained run count with equal weights; their blocks are pooled). 'corrected'
    is the canonical curve (the eq 22 analogue + M/M_tot, see colloid_correlations.hpp); files
    written before it existed give the raw value and no blocks."""
    lags = groups[0]["lags"].astype(float)
    key = "corrected" if "corrected" in groups[0] else "value"
    v = np.array([g[key] for g in groups]).mean(axis=0)
    blocks = None
    if "corrected_blocks" in groups[0]:
        blocks = np.concatenate([g["corrected_blocks"].reshape(-1, len(lags)) for g in groups])
    return lags, v, blocks, key


def smoothed(lags, v, t, width=0.1):
    """Mean of v over lags in [t / (1 + w), t (1 + w)]: evens out sound echoes of the periodic
    box (and noise); for a power law the same factor at every t, so exponents are unbiased."""
    sel = (lags >= t / (1 + width)) & (lags <= t * (1 + width))
    return v[..., sel].mean(axis=-1)


def jackknife(blocks, f):
    """f of the mean over blocks, and its jackknife error over leave-one-block-out means."""
    full = f(blocks.mean(axis=0))
    if len(blocks) < 3:
        return full, float("nan")
    b = len(blocks)
    jk = np.array([f(np.delete(blocks, i, 0).mean(axis=0)) for i in range(b)])
    return full, math.sqrt((b - 1) / b * ((jk - jk.mean()) ** 2).sum())


def colloid_theory(scene, vacf0):
    """M (disc + gas inside), M_tot, rho, nu of the scene: the eq 22 plateau M / M_tot gives M."""
    lat, col = scene["lattice"], scene["colloid"]
    d = lat["density"]
    rho = 6 * d / (math.sqrt(3) / 2) # 6 links of mean occupation d per site of area sqrt(3)/2
    m_tot = col["mass"] + 6 * d * lat["size"][0] * lat["size"][1]
    plateau = vacf0["plateau"][0] if "plateau" in vacf0 else 0.0
    m = plateau * m_tot if plateau > 0 else col["mass"]
    return m, m_tot, rho, boltzmann_nu(lat["model"], d)


def colloid_panel(ax, name, groups, args, scene, vacfs):
    """groups: the observable `name` of each file; vacfs: the colloid_vacf of each file."""
    lags, v, blocks, key = colloid_curves(groups)
    np.seterr(all="ignore") # a short run (a test) leaves long lags empty: NaN, not an error
    m, m_tot, rho, nu0 = colloid_theory(scene, vacfs[0])
    nu = args.colloid_nu if args.colloid_nu is not None else nu0
    a = args.colloid_a if args.colloid_a is not None else scene["colloid"]["radius"]
    held = scene["colloid"].get("held", True)
    what = "held colloid" if held else "moving colloid"
    u2 = np.mean([g["mean_square_velocity"][0] for g in vacfs])
    last = args.colloid_last if args.colloid_last is not None else lags[-1]
    sel = (lags >= args.colloid_first) & (lags <= last)
    tag = "canonical (+ M/M_tot)" if key == "corrected" else "raw"
    amp = m / (8 * math.pi * rho * nu) # Z -> amp / t (per component, normalised)
    if name == "colloid_vacf":
        tt = lags[lags > 0]
        theory = held_disc_vacf(tt, m, a, rho, nu)
        err = blocks.std(axis=0, ddof=1) / math.sqrt(len(blocks)) if blocks is not None else None
        ax.errorbar(tt, v[lags > 0], yerr=None if err is None else err[lags > 0], fmt=".", ms=2,
                    lw=0.3, label=f"Z(t), {what}, {tag}")
        ax.loglog(tt, theory, "-", color="C2", lw=1,
                  label=f"unsteady Stokes disc, M = {m:.0f}, a = {a:g}, nu = {nu:.4f}")
        ta = tt[tt >= 100]
        ax.loglog(ta, amp / ta, "--", color="k", lw=0.8, label="asymptote M / (8 pi rho nu t)")
        print(f"colloid VACF ({tag}, {len(groups)} file(s), "
              f"{0 if blocks is None else len(blocks)} blocks): M = {m:.1f} (disc + gas inside), "
              f"M_tot = {m_tot:.0f}, rho = {rho:.4f}, nu = {nu:.5f}, a = {a:g}; "
              f"tail M/(8 pi rho nu t) = {amp:.2f}/t; the canonical box curve exceeds the "
              f"infinite system's by ~M/(2 M_tot) = {m / (2 * m_tot):.4f}")
        for w in args.colloid_windows.split(","):
            t1, t2 = (float(x) for x in w.split(":"))
            if t2 * 1.1 > lags[-1]:
                continue
            expo = lambda z: -np.log(smoothed(lags, z, t2) / smoothed(lags, z, t1)) / math.log(t2 / t1)
            if not (smoothed(lags, v, t1) > 0 and smoothed(lags, v, t2) > 0):
                print(f"  local exponent over lags {t1:g}..{t2:g}: Z not positive (too short a run)")
                continue
            if blocks is not None:
                n, e = jackknife(blocks, expo)
            else:
                n, e = expo(v), float("nan")
            th = held_disc_vacf(np.array([t1, t2]), m, a, rho, nu)
            print(f"  local exponent over lags {t1:g}..{t2:g} (Z averaged over +-10 % in t): "
                  f"{n:.3f} +- {e:.3f}; Z({t1:g}) = {smoothed(lags, v, t1):.4f}, "
                  f"Z({t2:g}) = {smoothed(lags, v, t2):.4f}; theory {math.log(th[0] / th[1]) / math.log(t2 / t1):.3f} "
                  f"(Z {th[0]:.4f}, {th[1]:.4f}), asymptote 1")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("t")
        ax.set_ylabel("Z(t) = <dU(0).dU(t)> / <dU^2> (+ M/M_tot)")
        ax.set_title(f"{what}: velocity autocorrelation")
    else:
        ok = sel & (lags > 0)
        x = np.log(lags[ok])
        ax.plot(np.log(lags[lags > 0]), v[lags > 0], ".", ms=3, label=f"D(t) = msd / 4t, {tag}")
        if ok.sum() >= 4:
            line = lambda y: np.polyfit(x, y[ok], 1)
            (k, c) = line(v)
            y = v[ok]
            r2 = 1 - ((y - (k * x + c)) ** 2).sum() / ((y - y.mean()) ** 2).sum()
            ek = ec2 = float("nan")
            c2 = np.polyfit(x, y, 2)[0]
            if blocks is not None:
                _, ek = jackknife(blocks, lambda z: line(z)[0])
                _, ec2 = jackknife(blocks, lambda z: np.polyfit(x, z[ok], 2)[0])
            # theory D(t) from the unsteady Stokes Z(t): D = u2/(4t) [t + 2 sum (t-s) Z(s)]
            s = np.arange(1, int(lags[-1]) + 1, dtype=float)
            zs = held_disc_vacf(np.unique(np.round(np.geomspace(1, s[-1], 300))), m, a, rho, nu)
            zi = np.interp(np.log(s), np.log(np.unique(np.round(np.geomspace(1, s[-1], 300)))), zs)
            cum0, cum1 = np.cumsum(zi), np.cumsum(s * zi)
            dth = lambda t: u2 / (4 * t) * (t + 2 * (t * cum0[int(t) - 2] - cum1[int(t) - 2]))
            dt = np.array([dth(t) for t in lags[ok]])
            kt, ct2 = np.polyfit(x, dt, 1)[0], np.polyfit(x, dt, 2)[0]
            print(f"colloid D(t) ({tag}) = ({k:.4g} +- {ek:.2g}) ln t + {c:.4g} over lags "
                  f"{args.colloid_first:g}..{last:g}: R^2 = {r2:.5f}, curvature d2D/d(ln t)^2 = "
                  f"{2 * c2:.4g} +- {2 * ec2:.2g}; theory there: slope {kt:.4g}, curvature "
                  f"{2 * ct2:.4g} (unsteady Stokes), "
                  f"asymptote <U^2>/2 M/(8 pi rho nu) = {u2 / 2 * amp:.4g}")
            ax.plot(x, k * x + c, "-", color="C3", label=f"fit {k:.3g} ln t + {c:.3g}, R^2 = {r2:.4f}")
            ax.plot(x, dt, "--", color="C2", label="unsteady Stokes disc")
        ax.set_xlabel("ln t")
        ax.set_ylabel("D(t)")
        ax.set_title("held colloid: virtual diffusion coefficient" if held
                     else "moving colloid: diffusion coefficient")
    ax.legend(fontsize=7)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("files", nargs="+")
    ap.add_argument("--png", default=None,
                    help="output PNG (default: lgca.png next to the first file)")
    ap.add_argument("--first", type=float, default=20.0, help="first step of the fit window")
    ap.add_argument("--last", type=float, default=None,
                    help="last step of the fit window (default: A fallen by e^-1.5, Boltzmann)")
    ap.add_argument("--tail-first", type=float, default=20.0, help="first lag of the VACF tail fit")
    ap.add_argument("--tail-last", type=float, default=None,
                    help="last lag of the VACF tail fit (default: the last lag)")
    ap.add_argument("--colloid-first", type=float, default=1000.0,
                    help="first lag of the colloid D(t) fit")
    ap.add_argument("--colloid-last", type=float, default=None,
                    help="last lag of the colloid D(t) fit (default: the last lag)")
    ap.add_argument("--colloid-windows", default="100:300,300:1000,500:2000,1000:2700",
                    help="lag windows t1:t2 of the colloid's local VACF exponents")
    ap.add_argument("--colloid-nu", type=float, default=None,
                    help="kinematic viscosity of the colloid theory (default: Boltzmann)")
    ap.add_argument("--colloid-a", type=float, default=None,
                    help="hydrodynamic radius of the colloid theory (default: colloid.radius)")
    args = ap.parse_args()

    plt = narrows_h5.pyplot()

    files = [narrows_h5.open_run(p) for p in args.files]
    files[0].require_engine("lgca")
    scene = files[0].scene()
    lat = scene["lattice"]
    obs = files[0].names()
    panels = []
    if "shear_wave" in obs:
        panels.append("shear")
    if "velocity" in obs or "density" in obs:
        panels.append("fields")
    if "vacf" in obs:
        panels.append("vacf")
    if "colloid_vacf" in obs:
        panels += ["colloid_vacf", "colloid_diffusion"]
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4.5), squeeze=False)
    for ax, panel in zip(axes[0], panels):
        if panel == "shear":
            t = files[0].series("shear_wave")["step"].astype(float)
            runs = np.array([f.series("shear_wave")["value"] for f in files])
            a = runs.mean(axis=0)
            ly = lat["size"][1] * math.sqrt(3) / 2
            k = 2 * math.pi / ly
            nu0 = boltzmann_nu(lat["model"], lat["density"])
            last = args.last if args.last is not None else min(t[-1], 1.5 / (nu0 * k * k))
            rate, icpt = fit_rate(t, a, args.first, last)
            nu = rate / k**2
            err = 0.0
            if len(runs) > 1:
                jk = np.array([fit_rate(t, np.delete(runs, i, 0).mean(axis=0), args.first, last)[0]
                               for i in range(len(runs))]) / k**2
                err = math.sqrt((len(jk) - 1) / len(jk) * ((jk - jk.mean()) ** 2).sum())
            print(f"{lat['model']} d = {lat['density']}: nu = {nu:.5f} +- {err:.5f} "
                  f"(Boltzmann {nu0:.5f}, {100 * (nu / nu0 - 1):+.2f} %) from steps "
                  f"{args.first:g}..{last:g} of {len(runs)} run(s)")
            ax.semilogy(t, np.abs(a), ".", ms=3, label=f"measured ({len(runs)} run(s))")
            tt = np.linspace(0, t[-1], 200)
            ax.semilogy(tt, np.exp(icpt - rate * tt), "-",
                        label=f"fit {args.first:g}..{last:g}: nu = {nu:.4f} +- {err:.4f}")
            ax.semilogy(tt, a[0] * np.exp(-nu0 * k * k * tt), "--", label=f"Boltzmann nu = {nu0:.4f}")
            ax.set_xlabel("step")
            ax.set_ylabel("shear-wave amplitude")
            ax.set_title(f"{lat['model']}, d = {lat['density']}, {lat['size'][0]} x {lat['size'][1]}")
            ax.legend(fontsize=8)
        elif panel == "vacf":
            vacf_panel(ax, files[0].series("vacf"), lat, args)
        elif panel.startswith("colloid"):
            colloid_panel(ax, panel, [f.series(panel) for f in files], args, scene,
                          [f.series("colloid_vacf") for f in files])
        else:
            if "velocity" in obs:
                velocity = files[0].series("velocity")
                u = velocity["value"][-1]
                im = ax.imshow(u[:, :, 0], origin="lower", aspect="auto", cmap="viridis")
                fig.colorbar(im, ax=ax, label="u_x (block average)")
                ax.set_title(f"u_x at step {velocity['step'][-1]}")
            else:
                density = files[0].series("density")
                rho = density["value"][-1]
                im = ax.imshow(rho, origin="lower", aspect="auto", cmap="viridis")
                fig.colorbar(im, ax=ax, label="particles per site (block average)")
                ax.set_title(f"density at step {density['step'][-1]}")
            ax.set_xlabel("block along x")
            ax.set_ylabel("block along y (rows)")
    fig.tight_layout()
    png = args.png or os.path.join(os.path.dirname(os.path.abspath(args.files[0])), "lgca.png")
    fig.savefig(png, dpi=120)
    print(f"wrote {png}")


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("lgca_plot", main))
