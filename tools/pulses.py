#!/usr/bin/python3
"""Velocity pulses of a dense suspension in a periodic channel (Kanehl (thesis) ch.6, §6.2):
the space-time plot of v and phi (fig 6.4 a), the power spectrum of v(x0, t) and the pulse-train
frequency f_pt (fig 6.4 b), <v>/v0, the pulse strength <dv^2>/<v>^2, the pulse speed c, the
spacing lambda and the state of the flow (§6.2.2).

Usage: pulses.py RUN_DIR [--transient T] [--v0 V0 | --nu NU] [--blocks 4] [--png F] [--json F]

Input (read through narrows_h5): a particle run's /observables/axial_fields/{phi, velocity,
fluid_velocity} ([T][bins], cross-section averages of eq 6.1, bins = x centres, with step and
time), or a continuum run of model "jamming" (observables density = phi and velocity = v, e.g.
run/continuum_jamming_pulses.toml). Samples with time < --transient are dropped. Bins without
colloid material (velocity NaN in axial_fields) get v interpolated linearly from the nearest
bins with some (periodic in x); the JSON's filled_fraction says how many.

v0, the colloid-free centre speed of the same channel and drive (§6.2.1):
  --v0 V0, else for a particle run g w^2 / (2 nu) with g = body_force.value[0], w =
  domain.size[1] / 2 and nu = --nu, else the mean of the run's `viscosity` observable (only in
  a run without [colloids]: with them it is the suspension's), else the kinetic theory narrows
  prints (srd, at in 2D/3D, at+a in 3D; 2D at+a has none: give --nu, e.g.
  Kanehl (thesis) Table 6.1: nu = 1.98); for a continuum run the model's own v_ss(phi = 0) of
  eq 6.4 (= e1 + dv [1 + tanh(phi_c / dphi)] with the parameters the run used, from
  /parameters/continuum, or Table 6.2's column `continuum.mu`), the speed
  of colloid-free flow in the model's units. v0 only enters <v>/v0 and the state.

Measures (<...> = mean over x and t after the transient; dv = v - <v>):
  mean_velocity <v> (and mean_velocity_over_v0), relative_variance <dv^2>/<v>^2;
  f_pt: the maximum of P(f) = mean over x of |sum_t w_t dv(x, t) e^{-2 pi i f t}|^2 (Hann
  window w), located on the periodogram grid and refined by maximising P(f) itself within one
  grid step (exact for a harmonic signal);
  pulse_speed c: the slope of the ridge of the space-time correlation C(s, tau) = <dv(x, t)
  dv(x + s, t + tau)> (s periodic): the ridge is followed from C's maximum at s = 0, tau = 0
  lag by lag (each maximum searched within half a spacing of the position extrapolated from the
  previous two, and refined on C's Fourier series, which is exact between the bins), over lags
  up to a third of the record; c is the least-squares slope of ridge position against lag
  (negative = upstream, against the flow); the JSON's ridge_step_over_spacing = |c| dt /
  lambda (dt: between samples) must stay below 1/2 (a warning above 0.4: c may be aliased);
  spacing lambda: the position of the maximum of the spatial correlation C(s, 0) in its first
  positive lobe after its first zero (refined on its Fourier series); the channel length if C
  has no such lobe within half the channel;
  state: "pulses" if <dv^2>/<v>^2 > 0.1, else "free" if <v>/v0 >= 0.005, else "jammed".
Errors (each number's `_error`): the record after the transient is cut into --blocks
consecutive time blocks of equal length, every quantity is measured in each block alone, and
the error is the standard error of the block values (std / sqrt(blocks), ddof = 1). For f_pt
the resolution of the whole record, 1 / (sqrt(12) T), is added in quadrature; for lambda the
resolution dx / sqrt(12) of the bins. The state is that of the whole record.

Writes RUN_DIR/pulses.png (a: v(x, t) coloured as fig 6.4 a, jammed brown where v/v0 < 0.005,
flowing green; b: phi(x, t); c: the spectrum with f_pt; d: the correlation ridge and its fit)
and RUN_DIR/pulses.json; prints one line per quantity.
"""

import argparse
import json
import math
import os
import sys

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # small products: threads only cost here
import numpy as np  # noqa: E402
from scipy.optimize import minimize_scalar  # noqa: E402

import narrows_h5  # noqa: E402
from narrows_h5 import NarrowsDataError  # noqa: E402

JAM_THRESHOLD = 0.005  # <v>/v0 below it: jammed (Kanehl (thesis) §6.2.2, fig 6.4 a)
PULSE_THRESHOLD = 0.1  # <dv^2>/<v>^2 above it: travelling pulses (§6.2.2)


class InputError(Exception):
    """A bad command line (bad data raise narrows_h5.NarrowsDataError)."""


# ---- the fields ----------------------------------------------------------------------------


class Fields:
    """v[T][X] and phi[T][X] (phi may be None) at times t[T] and x centres x[X] of a periodic
    channel of length L; v0 and where it came from."""

    filled = 0.0  # the fraction of v values interpolated over bins without colloids

    def __init__(self, t, x, v, phi, length, v0=None, v0_source="", fluid=None):
        self.t, self.x, self.v, self.phi = (np.asarray(t, float), np.asarray(x, float),
                                            np.asarray(v, float), phi)
        self.length, self.v0, self.v0_source, self.fluid = float(length), v0, v0_source, fluid

    def after(self, transient):
        keep = self.t >= transient
        if keep.sum() < 8:
            raise InputError(f"--transient {transient:g} leaves {int(keep.sum())} samples "
                             f"(the run ends at t = {self.t[-1]:g}); allowed: at least 8 samples")
        cut = (lambda a: None if a is None else np.asarray(a)[keep])
        out = Fields(self.t[keep], self.x, self.v[keep], cut(self.phi), self.length, self.v0,
                     self.v0_source, cut(self.fluid))
        out.filled = self.filled
        return out


def kinetic_viscosity(fluid, dim):
    """The kinetic-theory nu of src/engines/mpcd/transport_theory.cpp (srd, at; at+a in 3D);
    None where narrows has no formula."""
    rule, dt = fluid.get("collision"), float(fluid.get("dt", 0))  # both required by narrows
    n, kT = float(fluid.get("density", 10)), float(fluid.get("kT", 1.0))  # schema defaults
    angle = math.radians(float(fluid.get("angle", 90.0)))
    if dt <= 0:
        return None
    f = n - 1.0 + math.exp(-n)
    ca, sa = math.cos(angle), math.sin(angle)
    if rule == "srd":
        if dim == 2:
            return (0.5 * kT * dt * (n / (f * sa * sa) - 1.0)
                    + (1.0 / (12.0 * dt)) * (f / n) * (1.0 - ca))
        return (0.5 * kT * dt * (5.0 * n / (f * (2.0 - ca - math.cos(2.0 * angle))) - 1.0)
                + (1.0 / (18.0 * dt)) * (f / n) * (1.0 - ca))
    if rule == "at":
        return kT * dt * (n / f - 0.5) + f / (12.0 * n * dt)
    if rule == "at+a" and dim == 3:
        return kT * dt * (n / (n - 1.25) - 0.5) + (n - 1.4) / (24.0 * n * dt)
    return None


def particle_v0(run, scene, nu, transient):
    """(v0, source) of a particle run: g w^2 / (2 nu)."""
    g = float(scene.get("body_force", {}).get("value", [0.0])[0])
    size = scene.get("domain", {}).get("size")
    if not size or len(size) < 2:
        raise NarrowsDataError(run.newest, "/parameters/scene has no domain.size [x, y]")
    if g == 0.0:
        raise NarrowsDataError(run.newest, "/parameters/scene has no body_force.value along x",
                               "a driven channel, or --v0")
    w = float(size[1]) / 2
    if nu is not None:
        source = f"--nu {nu:g}"
    elif run.has("viscosity") and "colloids" not in scene:  # with colloids: the suspension's
        s = run.series("viscosity")
        keep = s.time >= transient
        nu = float(np.mean(np.ravel(s.value[keep] if keep.any() else s.value)))
        source = "the run's viscosity observable"
    else:
        dim = int(scene.get("run", {}).get("dimensions", 2))
        nu = kinetic_viscosity(scene.get("fluid", {}), dim)
        if nu is None:
            raise InputError(f"{run.newest}: no kinetic-theory viscosity for fluid.collision = "
                             f"\"{scene.get('fluid', {}).get('collision')}\" in {dim}D and no "
                             "colloid-free viscosity observable; allowed: --nu NU (Kanehl (thesis) Table 6.1: "
                             "1.98 for at+a, rho = 25, dt = 0.02) or --v0 V0")
        source = "kinetic theory"
    return g * w * w / (2 * nu), f"g w^2/(2 nu), g = {g:g}, w = {w:g}, nu = {nu:.5g} ({source})"


def continuum_v0(scene, params=None):
    """(v0, source) of a continuum jamming run: v_ss(0) of eq 6.4 with the parameters the run
    used (/parameters/continuum: a preset, continuum.vss or continuum.vss_fit), or for a file
    without them with Table 6.2's column continuum.mu."""
    from jamming_plot import Model, TABLE_6_2
    if params and all(k in params for k in ("delta_v", "delta_phi", "phi_c", "e1")):
        v0 = params["e1"] + params["delta_v"] * (1 + math.tanh(params["phi_c"] / params["delta_phi"]))
        return float(v0), f"v_ss(phi = 0) of eq 6.4 with the run's parameters " \
            f"({params.get('vss_source', 'parameters/continuum')})"
    mu = str(scene.get("continuum", {}).get("mu", "1"))
    if mu not in TABLE_6_2:
        raise NarrowsDataError(None, f"continuum.mu = {mu!r}", ", ".join(TABLE_6_2))
    return float(Model(mu).vss(0.0)), f"v_ss(phi = 0) of eq 6.4, Table 6.2 mu = {mu}"


def fill_gaps(v, x, length, label):
    """v with the NaN of bins without colloid material (axial_fields) replaced by the linear
    interpolation between the nearest bins that have some, periodic in x; and the fraction of
    values so filled. NarrowsDataError if a sample has no colloid material at all."""
    bad = ~np.isfinite(v)
    if not bad.any():
        return v, 0.0
    v = v.copy()
    for i in np.nonzero(bad.any(axis=1))[0]:
        good = ~bad[i]
        if not good.any():
            raise NarrowsDataError(label, f"axial_fields/velocity: sample {i} has no finite value",
                                   "samples with colloids")
        v[i, bad[i]] = np.interp(x[bad[i]], x[good], v[i, good], period=length)
    return v, float(bad.mean())


def load(run_dir, v0=None, nu=None, transient=0.0):
    """The fields of a run folder (axial_fields of a particle run, or a continuum run)."""
    run = narrows_h5.open_run(run_dir)
    scene = run.scene()
    engine = scene.get("run", {}).get("engine", "mpcd")
    if run.has("axial_fields"):
        s = run.series("axial_fields")
        x = np.asarray(s["bins"], float)
        size = scene.get("domain", {}).get("size")
        length = float(size[0]) if size else float(np.median(np.diff(x))) * len(x)
        if v0 is None:
            v0, source = particle_v0(run, scene, nu, transient)
        else:
            source = "--v0"
        v, filled = fill_gaps(np.asarray(s["velocity"], float), x, length, run.label)
        fields = Fields(s["time"], x, v, s.get("phi"), length, v0, source,
                        s.get("fluid_velocity"))
        fields.filled = filled
        return fields
    if engine == "continuum":
        model = scene.get("continuum", {}).get("model")
        if model != "jamming":
            raise NarrowsDataError(run.newest, f'a continuum run of model = "{model}"',
                                   'model = "jamming", or a particle run with axial_fields')
        phi = run.series("density")
        vel = run.series("velocity")
        x = np.asarray(phi["bins"], float)
        length = float(scene["continuum"].get("length", np.median(np.diff(x)) * len(x)))
        if v0 is None:
            v0, source = continuum_v0(scene, run.parameter_attributes("continuum"))
        else:
            source = "--v0"
        return Fields(vel.time, x, vel.value, phi.value, length, v0, source)
    raise narrows_h5.missing_observable(run.label, "axial_fields",
                                        'a particle run listing "axial_fields" in '
                                        'output.observables, or a continuum run of model "jamming"')


# ---- the measures --------------------------------------------------------------------------


def spectrum(v, dt):
    """(f, P): the Hann-windowed periodogram of dv(x, t) along t, averaged over x."""
    d = v - v.mean()
    w = np.hanning(len(d))[:, None]
    p = np.abs(np.fft.rfft(d * w, axis=0)) ** 2
    return np.fft.rfftfreq(len(d), dt), p.mean(axis=1)


def pulse_frequency(v, t):
    """f_pt: the maximum of the x-averaged power spectrum of dv(x0, t) over f > 0, refined by
    maximising P(f) between the neighbouring grid frequencies."""
    dt = (t[-1] - t[0]) / (len(t) - 1)
    f, p = spectrum(v, dt)
    if len(f) < 3:
        return float("nan")
    i = 1 + int(np.argmax(p[1:]))
    d = (v - v.mean()) * np.hanning(len(v))[:, None]
    tt = np.arange(len(v)) * dt

    def minus_power(freq):
        e = np.exp(-2j * np.pi * freq * tt)
        return -np.mean(np.abs(e @ d) ** 2)

    lo, hi = f[max(i - 1, 0)], f[min(i + 1, len(f) - 1)]
    if hi <= lo:
        return float(f[i])
    r = minimize_scalar(minus_power, bounds=(lo, hi), method="bounded",
                        options={"xatol": 1e-10 * max(hi, 1e-300)})
    return float(r.x) if -r.fun >= p[i] else float(f[i])


def correlation_modes(v, nlag):
    """G[lag][k] = mean over t of conj(F_k(t)) F_k(t + lag) for lag = 0..nlag, F = the FFT of
    dv along x; all lags at once through the FFT along t (zero-padded: no wrap-around), in
    chunks of modes to bound the memory."""
    d = v - v.mean()
    F = np.fft.fft(d, axis=1)
    T, X = F.shape
    if nlag == 0:
        return np.mean(np.abs(F) ** 2, axis=0)[None, :].astype(complex)
    n = 1 << int(math.ceil(math.log2(2 * T)))
    out = np.empty((nlag + 1, X), complex)
    pairs = (T - np.arange(nlag + 1))[:, None]
    for a in range(0, X, 256):
        H = np.fft.fft(F[:, a:a + 256], n=n, axis=0)
        out[:, a:a + 256] = np.fft.ifft(np.conj(H) * H, axis=0)[:nlag + 1] / pairs
    return out


def series_at(g, s, length):
    """C(s) = Re sum_k G_k e^{2 pi i k s / L} / X^2, the correlation between the bins (k in
    numpy's FFT order; exact for data band-limited to the bins)."""
    X = len(g)
    k = np.fft.fftfreq(X, 1.0 / X)
    return float(np.real(np.sum(g * np.exp(2j * np.pi * k * s / length)))) / X**2


def refine_max(g, guess, lo, hi, length):
    """The maximum of C(s) in [lo, hi] near guess (a grid maximum)."""
    r = minimize_scalar(lambda s: -series_at(g, s, length), bounds=(lo, hi), method="bounded",
                        options={"xatol": 1e-9 * length})
    return float(r.x) if -r.fun >= series_at(g, guess, length) else float(guess)


def spacing(v, length):
    """lambda: the first maximum of C(s, 0) after its first zero; the channel length if none."""
    g = correlation_modes(v, 0)[0]
    c = np.real(np.fft.ifft(g)) / len(g)  # C at s = j dx
    dx = length / len(c)
    # the first positive lobe after the first zero (up to half the channel; a longer period
    # shows as the channel length itself)
    half = len(c) // 2 + 1
    neg = np.nonzero(c[:half] <= 0)[0]
    if len(neg) == 0:
        return length
    pos = neg[0] + np.nonzero(c[neg[0]:half] > 0)[0]
    if len(pos) == 0:
        return length
    end = pos[0] + np.nonzero(c[pos[0]:] <= 0)[0]
    end = end[0] if len(end) else len(c)
    j = pos[0] + int(np.argmax(c[pos[0]:end]))
    return refine_max(g, j * dx, (j - 1) * dx, (j + 1) * dx, length)


def ridge(v, t, length, lam, max_fraction=1 / 3):
    """(lags tau, ridge positions s(tau)) of the space-time correlation, unwrapped."""
    dt = (t[-1] - t[0]) / (len(t) - 1)
    nlag = max(2, int(len(t) * max_fraction))
    dx = length / v.shape[1]
    window = max(min(lam, length) / 2, 2 * dx)
    pos = [0.0]
    modes = correlation_modes(v, nlag)
    corr = np.real(np.fft.ifft(modes, axis=1)) / modes.shape[1]
    for lag in range(1, nlag + 1):
        g, c = modes[lag], corr[lag]
        guess = pos[-1] + (pos[-1] - pos[-2] if len(pos) > 1 else 0.0)
        # grid points within the window around the guess, unwrapped near the guess
        j = np.arange(len(c))
        s = j * dx
        s = s + length * np.round((guess - s) / length)
        inside = np.abs(s - guess) <= window
        if not inside.any():
            break
        best = np.argmax(np.where(inside, c, -np.inf))
        sb = s[best]
        pos.append(refine_max(g, sb, sb - dx, sb + dx, length))
    lags = np.arange(len(pos)) * dt
    return lags, np.array(pos)


def pulse_speed(v, t, length, lam):
    """c: the least-squares slope of the correlation ridge s(tau)."""
    lags, pos = ridge(v, t, length, lam)
    if len(lags) < 2:
        return float("nan"), lags, pos
    return float(np.polyfit(lags, pos, 1)[0]), lags, pos


def classify(mean_over_v0, relative_variance):
    """Kanehl (thesis) §6.2.2: pulses, free flow or jammed."""
    if relative_variance > PULSE_THRESHOLD:
        return "pulses"
    return "free" if mean_over_v0 >= JAM_THRESHOLD else "jammed"


def measure_once(v, t, length, v0):
    """The measures of one record (no errors)."""
    mean = float(v.mean())
    rel = float(((v - mean) ** 2).mean() / mean**2) if mean != 0 else float("inf")
    lam = spacing(v, length)
    c, _, _ = pulse_speed(v, t, length, lam)
    return {"mean_velocity": mean, "mean_velocity_over_v0": mean / v0 if v0 else float("nan"),
            "relative_variance": rel, "f_pt": pulse_frequency(v, t), "pulse_speed": c,
            "spacing": lam}


def analyse(fields, blocks=4):
    """The measures of the whole record with block errors; the state; the spectrum and ridge
    for the figure."""
    v, t, length, v0 = fields.v, fields.t, fields.length, fields.v0
    whole = measure_once(v, t, length, v0)
    per_block = []
    edges = np.linspace(0, len(t), blocks + 1).astype(int)
    if blocks >= 2 and len(t) // blocks >= 8:
        for a, b in zip(edges[:-1], edges[1:]):
            per_block.append(measure_once(v[a:b], t[a:b], length, v0))
    out = {}
    duration = t[-1] - t[0] + (t[-1] - t[0]) / (len(t) - 1)
    dx = length / v.shape[1]
    for key, value in whole.items():
        vals = np.array([m[key] for m in per_block], float)
        vals = vals[np.isfinite(vals)]
        err = float(np.std(vals, ddof=1) / math.sqrt(len(vals))) if len(vals) >= 2 else math.nan
        resolution = {"f_pt": 1 / (math.sqrt(12) * duration), "spacing": dx / math.sqrt(12)}
        if key in resolution:
            err = math.hypot(err, resolution[key]) if math.isfinite(err) else resolution[key]
        out[key], out[key + "_error"] = value, err
    out["v0"], out["v0_error"], out["v0_source"] = v0, 0.0, fields.v0_source
    out["state"] = classify(whole["mean_velocity_over_v0"], whole["relative_variance"])
    out["blocks"] = len(per_block)
    out["duration"], out["length"] = float(duration), length
    out["samples"], out["bins"] = len(t), v.shape[1]
    if fields.phi is not None:
        out["mean_phi"] = float(np.nanmean(fields.phi))
    if fields.fluid is not None:
        out["mean_fluid_velocity"] = float(np.nanmean(fields.fluid))
    out["filled_fraction"] = fields.filled
    # the ridge moves |c| dt per sample; beyond half a spacing it cannot be told from the next
    # pulse's (sampling aliases c)
    dt = (t[-1] - t[0]) / (len(t) - 1)
    out["ridge_step_over_spacing"] = abs(whole["pulse_speed"]) * dt / whole["spacing"]
    return out


# ---- output --------------------------------------------------------------------------------


def clean(value):
    """JSON has no NaN or infinity: null."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def draw(fields, res, png):
    plt = narrows_h5.pyplot()
    import matplotlib.colors as mcolors
    v, t, x, v0 = fields.v, fields.t, fields.x, fields.v0
    fig, ax = plt.subplots(2, 2, figsize=(12, 9))
    ext = [x[0] - (x[1] - x[0]) / 2, x[-1] + (x[1] - x[0]) / 2, t[0], t[-1]]
    # fig 6.4 a: jammed (v/v0 < 0.005) brown, flowing in greens growing with v
    top = max(float(np.max(v / v0)), 2 * JAM_THRESHOLD)
    greens = plt.get_cmap("Greens")(np.linspace(0.3, 1.0, 64))
    cmap = mcolors.ListedColormap(np.vstack([[[0.55, 0.35, 0.17, 1.0]], greens]))
    bounds = np.concatenate([[min(float(np.min(v / v0)), 0.0) - 1e-12],
                             np.linspace(JAM_THRESHOLD, top + 1e-12, 65)])
    norm = mcolors.BoundaryNorm(bounds, cmap.N)
    im = ax[0, 0].imshow(v / v0, origin="lower", aspect="auto", extent=ext, cmap=cmap, norm=norm,
                         interpolation="nearest")
    fig.colorbar(im, ax=ax[0, 0], label="v / v0 (brown: jammed, v/v0 < 0.005)")
    ax[0, 0].set(xlabel="x", ylabel="t", title=f"a) v(x, t): {res['state']}, "
                 f"<v>/v0 = {res['mean_velocity_over_v0']:.4g}")
    if fields.phi is not None:
        im = ax[0, 1].imshow(fields.phi, origin="lower", aspect="auto", extent=ext,
                             cmap="YlOrBr", interpolation="nearest")
        fig.colorbar(im, ax=ax[0, 1], label="phi")
        ax[0, 1].set(xlabel="x", ylabel="t", title="b) phi(x, t)")
    else:
        ax[0, 1].set_axis_off()
    dt = (t[-1] - t[0]) / (len(t) - 1)
    f, p = spectrum(v, dt)
    ax[1, 0].semilogy(f[1:], p[1:] / p[1:].max(), "k-", lw=1)
    if res["f_pt"] is not None and np.isfinite(res["f_pt"]):
        ax[1, 0].axvline(res["f_pt"], color="r", ls="--",
                         label=f"f_pt = {res['f_pt']:.4g} +- {res['f_pt_error']:.2g}")
        ax[1, 0].legend()
    ax[1, 0].set(xlabel="f", ylabel="P(f) / max", title="c) power spectrum of v(x0, t), mean over x0")
    lags, pos = ridge(v, t, fields.length, res["spacing"])
    ax[1, 1].plot(lags, pos, "o", ms=3, label="ridge of C(s, tau)")
    if np.isfinite(res["pulse_speed"]):
        ax[1, 1].plot(lags, res["pulse_speed"] * lags, "r-",
                      label=f"c = {res['pulse_speed']:.4g} +- {res['pulse_speed_error']:.2g}")
    ax[1, 1].set(xlabel="lag tau", ylabel="ridge position s",
                 title=f"d) pulse speed; spacing lambda = {res['spacing']:.4g}")
    ax[1, 1].legend()
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run_dir")
    ap.add_argument("--transient", type=float, default=0.0, help="drop samples with t < T")
    ap.add_argument("--v0", type=float, help="colloid-free centre speed (default: from the run)")
    ap.add_argument("--nu", type=float, help="fluid viscosity for v0 = g w^2 / (2 nu)")
    ap.add_argument("--blocks", type=int, default=4, help="time blocks of the errors (>= 2)")
    ap.add_argument("--png", help="default RUN_DIR/pulses.png")
    ap.add_argument("--json", help="default RUN_DIR/pulses.json")
    ap.add_argument("--no-plot", action="store_true")
    args = ap.parse_args(argv)
    try:
        if args.blocks < 2:
            raise InputError(f"--blocks {args.blocks}; allowed: 2 or more")
        for name in ("v0", "nu"):
            val = getattr(args, name)
            if val is not None and not (val > 0 and math.isfinite(val)):
                raise InputError(f"--{name} {val:g}; allowed: a positive number")
        fields = load(args.run_dir, args.v0, args.nu, args.transient).after(args.transient)
        res = analyse(fields, args.blocks)
    except InputError as e:
        return narrows_h5.report("pulses", e)
    res["transient"] = args.transient
    out_json = args.json or os.path.join(args.run_dir, "pulses.json")
    with open(out_json, "w") as f:
        json.dump({k: clean(v) for k, v in res.items()}, f, indent=1)
    for key in ("mean_velocity", "mean_velocity_over_v0", "relative_variance", "f_pt",
                "pulse_speed", "spacing"):
        print(f"{key} = {res[key]:.6g} +- {res[key + '_error']:.3g}")
    print(f"v0 = {res['v0']:.6g} ({res['v0_source']})")
    print(f"state = {res['state']}")
    periods = res["f_pt"] * (fields.t[-1] - fields.t[0])
    if not periods >= 2:
        print(f"warning: the record holds {periods:.2g} periods of f_pt (fewer than 2): f_pt is "
              "not resolved; run longer")
    if res["ridge_step_over_spacing"] > 0.4:
        print(f"warning: the pulses move {res['ridge_step_over_spacing']:.2f} spacings between "
              "samples: c may be aliased; sample more often (output.every)")
    if not args.no_plot:
        png = args.png or os.path.join(args.run_dir, "pulses.png")
        draw(fields, res, png)
        print(f"wrote {png} and {out_json}")
    else:
        print(f"wrote {out_json}")
    return 0


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("pulses", main))
