"""The shock of a sedimenting colloid chain (Tabatabaei (2008) §4.5 and ch.5) from an mpcd run
with colloids (e.g. run/sedimentation_chain_31.toml, observables "colloid_positions" and
"settling_velocity"), and its continuum prediction (flux "colloid-chain", Tabatabaei (2008)
eq 5.3). Imported by shock_report.py (--chain).

Frame: the one co-moving with the centre of mass of fluid and colloids (Tabatabaei (2008)
eq 4.8-4.10), where eq 5.2 holds with v_cm = 0: a colloid moves at the settling velocity
v_s = c rho + c'. The centre of mass moves by the colloids' mean lab displacement less the
integral of the run's settling velocity (mean colloid velocity minus v_cm, sampled as
output.every means).

Line density rho: colloids per unit channel length. The chain starts at spacing d0 (density
rho0 = 1 / d0); the colloids ahead of it in the direction of gravity are the head. With a flux
convex in rho (c > 0) the head is a shock (the denser chain behind it settles faster and catches
up), moving at the Rankine-Hugoniot speed (J(rho0) - J(0)) / rho0 = c rho0 + c', and the tail
a rarefaction fan from c' to 2 c rho0 + c'. Shock position: the head colloid plus half a
spacing, 1 / (2 rho0) (where the initial step of the coarse-grained density sits); the front
colloid at each time, not a labelled one: in the zigzag they pass each other.
"""
import math

import numpy as np

import narrows_h5
from continuum_run import run_continuum
from narrows_h5 import NarrowsDataError
from sedimentation import unwrap


def read_chain(run):
    """Positions along x in the co-moving frame [T][N] (ordered from the head), times, the
    channel length, rho0 and the gravity's sign."""
    path = run.rstrip("/") + "/observables.h5"
    data = narrows_h5.open_run(path)
    scene = data.scene()
    allowed = ("an mpcd run with colloids whose output.observables lists colloid_positions and "
               "settling_velocity")
    positions = data.series("colloid_positions", allowed)
    settling = data.series("settling_velocity", allowed)
    pos = positions["value"]
    t = positions["time"]
    vs = settling["value"][:, 0]
    ts = settling["time"]
    if pos.shape[1] < 4 or len(t) < 8:
        raise NarrowsDataError(path, f"{pos.shape[1]} colloids and {len(t)} samples",
                               "at least 4 colloids and 8 samples")
    L = float(scene["domain"]["size"][0])
    g = float(scene["colloids"].get("gravity", [0.0])[0])
    sign = 1.0 if g >= 0.0 else -1.0
    x = unwrap(pos[:, :, 0], L) * sign  # gravity along +x from here on
    x = x[:, np.argsort(-x[0])]  # head first
    # Centre of mass: X(t) - X(0) - integral of the settling velocity (means over the interval
    # that ends at each sample).
    if not np.allclose(ts, t):
        raise NarrowsDataError(path, "settling_velocity and colloid_positions differ in time")
    drift = np.concatenate([[0.0], np.cumsum(sign * vs[1:] * np.diff(t))])
    com = x.mean(axis=1) - x[0].mean() - drift
    x = x - com[:, None]
    gaps = -np.diff(x[0])
    rho0 = 1.0 / gaps.mean()
    return {"t": t, "x": x, "L": L, "rho0": rho0, "sign": sign, "v_cm": np.gradient(com, t),
            "scene": scene, "d0": gaps.mean()}


def fit_line(t, y):
    A = np.vstack([np.ones_like(t), t]).T
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    return coef


def speed_and_diffusion(t, xs, blocks=4):
    """Speed: least-squares slope of xs(t), error from `blocks` time blocks. Diffusion: the
    residual about that line, its increments' mean square M(tau) = 2 D tau fitted over lags of
    5-25 % of the run, error from the same blocks."""
    v = fit_line(t, xs)[1]
    dt = t[1] - t[0]
    r = xs - (xs[0] + v * (t - t[0]))

    def diffusion(seg):
        n = len(seg)
        lags = np.unique(np.clip(np.round(np.linspace(0.05, 0.25, 8) * n).astype(int), 1, n - 1))
        msd = np.array([np.mean((seg[k:] - seg[:-k]) ** 2) for k in lags])
        tau = lags * dt
        return float(np.sum(msd * tau) / np.sum(tau * tau) / 2.0), tau, msd

    D, tau, msd = diffusion(r)
    n = len(t) // blocks
    vb, Db = [], []
    for b in range(blocks):
        sl = slice(b * n, (b + 1) * n)
        vb.append(fit_line(t[sl], xs[sl])[1])
        seg = xs[sl] - fit_line(t[sl], xs[sl])[0] - vb[-1] * t[sl]
        Db.append(diffusion(seg)[0])
    v_err = float(np.std(vb, ddof=1) / math.sqrt(blocks))
    D_err = float(np.std(Db, ddof=1) / math.sqrt(blocks))
    return float(v), v_err, D, D_err, tau, msd


def density(x_row, edges):
    """Colloids per unit length in the bins `edges`."""
    h, _ = np.histogram(x_row, bins=edges)
    return h / np.diff(edges)


def front(xc, rho, level, start):
    """The first crossing of `level` going forward (+x) from index `start` (periodic profile on
    cell centres xc of spacing dx): the position of the head shock."""
    n = len(rho)
    dx = xc[1] - xc[0]
    for k in range(n):
        i, j = (start + k) % n, (start + k + 1) % n
        if rho[i] >= level > rho[j]:
            return xc[0] + (start + k + 0.5 + (rho[i] - level) / (rho[i] - rho[j])) * dx
    return float("nan")


def continuum_chain(narrows, chain, c, c_prime, samples=50):
    """The colloid-chain conservation law (D = 0) in the co-moving frame (v_cm = 0), periodic
    over the channel, from the chain's initial coarse-grained density: rho0 from half a spacing
    behind the tail to half a spacing ahead of the head. Returns times, cell centres (in the
    chain's unwrapped coordinate of t = 0), profiles and the head shock position."""
    L, x0, d0 = chain["L"], chain["x"][0], chain["d0"]
    cells = int(round(L))
    dx = L / cells
    tail, head = x0.min() - d0 / 2, x0.max() + d0 / 2
    origin = tail - 0.25 * (L - (head - tail))  # the chain inside [origin, origin + L)
    xc = origin + (np.arange(cells) + 0.5) * dx
    lo, hi = xc - dx / 2, xc + dx / 2
    values = chain["rho0"] * np.clip((np.minimum(hi, head) - np.maximum(lo, tail)) / dx, 0, 1)
    lines = (f'flux = "colloid-chain"\nc = {float(c)!r}\nc_prime = {float(c_prime)!r}\n'
             f'v_cm = 0.0\nlength = {L!r}\ncells = {cells}\nboundary = "periodic"\n'
             "initial = { kind = \"cells\", values = [" + ", ".join(repr(float(v)) for v in values)
             + f"] }}\ntime = {float(chain['t'][-1] - chain['t'][0])!r}\nsamples = {samples}\n")
    out = run_continuum(narrows, lines, observables=("density",))
    tc, rho = out["density"]
    start = int(np.argmax(values > 0) + np.sum(values > 0) // 2)  # inside the chain
    xs = np.array([front(xc, r, chain["rho0"] / 2, start) for r in rho])
    return tc + chain["t"][0], xc, rho, xs
