#!/usr/bin/python3
"""The steady-state velocity v_ss(phi) of short channels and the fit of Kanehl (thesis) eq 6.4
(fig 6.8, Table 6.2).

  vss_fit.py run RUN_DIR [--transient T] [--blocks 4]
      v_ss of one run -> RUN_DIR/vss.json (v_ss, v_ss_error, phi, mu_cc, mu_cw, seed, ...)
  vss_fit.py fit SOURCE... [--transient T] [--out PREFIX] [--column-mu KEY] [--column-phi KEY]
      SOURCE: a table (CSV) written by tools/sweep.py --collect "tools/vss_fit.py run", run
      folders (each measured as `run` does), or vss.json files. Writes PREFIX.json (default
      vss_fit.json, every mu), PREFIX-mu<mu>.json (one mu each: the flat object that the
      continuum jamming model reads with continuum.vss_fit = FILE) and PREFIX.png (fig 6.8 style).

v_ss of one run (§6.2.2: the uniform flow of a channel of l = 200 b): the mean colloid x
velocity after the transient, from /observables/colloid_positions (value [T][N_c][d]; x is
periodic: each displacement between samples is taken as the shortest image, so a colloid must
move less than half the channel between samples), as the mean over colloids of (x(t_end) -
x(t_start)) / (t_end - t_start); its error: the samples after the transient are cut into
--blocks time blocks, v_ss is measured in each, error = std / sqrt(blocks). Without
colloid_positions, the mean of /observables/axial_fields/velocity over bins and samples, each
bin weighted by its colloid fraction phi (bins without colloids left out; the same blocks). phi is the
scene's colloids.packing_fraction, mu the scene's colloids.spring.mu_cc and mu_cw (a run without
them: --phi / --mu on the command line).

The fit: runs with the same (mu, phi) are repeats: their mean and standard error (std /
sqrt(n), ddof = 1; a single run keeps its block error). For each mu, eq 6.4
    v(phi) = delta_v [1 + tanh((phi_c - phi) / delta_phi)] + { e1 + e2 phi         (phi < phi_c)
                                                             { e3 (phi - phi_q)^2  (phi >= phi_c)
with e3 = (e1 + e2 phi_c) / (phi_c - phi_q)^2 (continuity at phi_c) is fitted by weighted least
squares (scipy.optimize.curve_fit, sigma = the standard errors, absolute_sigma=True; started
from Table 6.2's column nearest in mu), giving delta_v, delta_phi, phi_c, e1, e2, phi_q with
errors (the square roots of the covariance's diagonal), e3 and its error (propagated with the covariance),
chi^2 and its degrees of freedom. The parameters are kept in their physical ranges (delta_v
in [0, 10], delta_phi in [1e-4, 0.05], phi_c inside the measured phi, e1 > 0, e2 <= 0, phi_q
between the smallest phi and 1); one that ends on its bound is not fixed by the data and is
listed in at_bound (and marked in the printout). The JSON holds narrows' own table and Table 6.2's column
beside it; the PNG shows the points with error bars, the fit, and Table 6.2's curve dashed.
Velocities are in the runs' units (b / t0 for the MPCD runs of Table 6.1, Table 6.2's units).
"""

import argparse
import csv
import json
import math
import os
import sys
import warnings

import numpy as np

import narrows_h5

NAMES = ("delta_v", "delta_phi", "phi_c", "e1", "e2", "phi_q")  # continuum.vss's keys
TABLE_6_2 = {  # Kanehl (thesis) Table 6.2: dv, dphi, phi_c, e1, e2, phi_q
    "infinity": (0.0489, 0.00247, 0.744, 2.82, -3.68, 0.819),
    "1": (0.0413, 0.0025, 0.762, 2.56, -3.24, 0.845),
    "1/2": (0.0247, 0.00312, 0.778, 2.78, -3.45, 0.854),
    "0": (0.0005, 0.00233, 0.808, 2.90, -3.53, 0.846),
}
TABLE_MU = {"infinity": math.inf, "1": 1.0, "1/2": 0.5, "0": 0.0}


class InputError(Exception):
    """A bad command line or table."""


def eq_6_4(phi, dv, dphi, phi_c, e1, e2, phi_q):
    """Kanehl (thesis) eq 6.4 with e3 from continuity at phi_c."""
    phi = np.asarray(phi, float)
    e3 = (e1 + e2 * phi_c) / (phi_c - phi_q) ** 2
    step = dv * (1 + np.tanh((phi_c - phi) / dphi))
    return step + np.where(phi < phi_c, e1 + e2 * phi, e3 * (phi - phi_q) ** 2)


def table_column(mu):
    """The name of Table 6.2's column nearest to mu (in log(1 + mu))."""
    mu = float(mu)
    return min(TABLE_MU, key=lambda k: abs(math.atan(TABLE_MU[k]) - math.atan(mu)))


# ---- one run -------------------------------------------------------------------------------


def block_error(values):
    values = np.asarray(values, float)
    return float(np.std(values, ddof=1) / math.sqrt(len(values))) if len(values) >= 2 else float("nan")


def run_vss(run_dir, transient=0.0, blocks=4, phi=None, mu=None):
    """{v_ss, v_ss_error, phi, mu_cc, mu_cw, seed, source, samples} of one run folder."""
    run = narrows_h5.open_run(run_dir)
    scene = run.scene()
    colloids = scene.get("colloids", {})
    spring = colloids.get("spring", {})
    out = {"run": os.path.abspath(run_dir), "seed": scene.get("run", {}).get("seed")}
    out["phi"] = phi if phi is not None else colloids.get("packing_fraction")
    out["mu_cc"] = mu if mu is not None else spring.get("mu_cc")
    out["mu_cw"] = mu if mu is not None else spring.get("mu_cw")
    if out["phi"] is None or out["mu_cc"] is None:
        raise InputError(f"{run.newest}: the scene has no colloids.packing_fraction or "
                         "colloids.spring.mu_cc; allowed: --phi and --mu")
    if run.has("colloid_positions"):
        s = run.series("colloid_positions")
        keep = s.time >= transient
        t, x = s.time[keep], s.value[keep][:, :, 0]
        if len(t) < 2 * blocks:
            raise InputError(f"{run.label}: {len(t)} colloid_positions samples after "
                             f"--transient {transient:g}; allowed: at least {2 * blocks}")
        length = float(scene["domain"]["size"][0])
        dx = np.diff(x, axis=0)
        dx -= length * np.round(dx / length)  # the shortest image: x is periodic
        disp = np.concatenate([np.zeros((1, x.shape[1])), np.cumsum(dx, axis=0)])
        edges = np.linspace(0, len(t) - 1, blocks + 1).astype(int)
        vel = lambda a, b: float(np.mean(disp[b] - disp[a]) / (t[b] - t[a]))  # noqa: E731
        out["v_ss"] = vel(0, len(t) - 1)
        out["v_ss_error"] = block_error([vel(a, b) for a, b in zip(edges[:-1], edges[1:])])
        out["source"], out["samples"] = "colloid_positions", int(len(t))
    elif run.has("axial_fields"):
        s = run.series("axial_fields")
        keep = s.time >= transient
        v = np.asarray(s["velocity"][keep], float)
        if len(v) < 2 * blocks:
            raise InputError(f"{run.label}: {len(v)} axial_fields samples after --transient "
                             f"{transient:g}; allowed: at least {2 * blocks}")
        # the colloids' mean: bins weighted by their colloid fraction phi (v is NaN where a
        # bin has no colloid material, and its phi 0)
        w = np.asarray(s["phi"][keep], float) if "phi" in s else np.ones_like(v)
        w = np.where(np.isfinite(v) & np.isfinite(w), w, 0.0)
        v = np.where(w > 0, v, 0.0)
        mean = lambda a, b: float(np.sum(a * b) / np.sum(b))  # noqa: E731
        out["v_ss"] = mean(v, w)
        out["v_ss_error"] = block_error([mean(a, b) for a, b in
                                         zip(np.array_split(v, blocks), np.array_split(w, blocks))])
        out["source"], out["samples"] = "axial_fields", int(len(v))
    else:
        raise narrows_h5.missing_observable(run.label, "colloid_positions",
                                            'a run listing "colloid_positions" (or '
                                            '"axial_fields") in output.observables')
    return out


# ---- the fit -------------------------------------------------------------------------------


def read_sources(sources, transient, blocks, column_mu, column_phi):
    """[(mu, phi, v_ss, v_ss_error)] of every run in the sources."""
    rows = []
    for src in sources:
        if src.endswith(".csv"):
            with open(src, newline="") as f:
                table = list(csv.DictReader(f))
            if not table:
                raise InputError(f"{src}: an empty table")
            for key in ("v_ss", column_mu, column_phi):
                if key not in table[0]:
                    raise InputError(f"{src}: no column {key!r}; found {', '.join(table[0])}; "
                                     "allowed: a table of tools/sweep.py --collect "
                                     "\"tools/vss_fit.py run\" (or --column-mu/--column-phi)")
            for r in table:
                if r["v_ss"] in ("", "nan", "None"):
                    continue
                rows.append((float(r[column_mu]), float(r[column_phi]), float(r["v_ss"]),
                             float(r.get("v_ss_error") or "nan")))
        elif src.endswith(".json"):
            with open(src) as f:
                r = json.load(f)
            rows.append((float(r["mu_cc"]), float(r["phi"]), float(r["v_ss"]),
                         float(r.get("v_ss_error") or "nan")))
        else:
            r = run_vss(src, transient, blocks)
            rows.append((float(r["mu_cc"]), float(r["phi"]), r["v_ss"], r["v_ss_error"]))
    if not rows:
        raise InputError("no runs found in " + " ".join(sources))
    return rows


def aggregate(rows):
    """{mu: (phi[], mean[], error[], n[])}: repeats at the same (mu, phi) averaged."""
    groups = {}
    for mu, phi, v, e in rows:
        groups.setdefault(mu, {}).setdefault(round(phi, 10), []).append((v, e))
    out = {}
    for mu, by_phi in sorted(groups.items()):
        phis = sorted(by_phi)
        means, errors, counts = [], [], []
        for p in phis:
            vs = np.array([v for v, _ in by_phi[p]])
            means.append(float(vs.mean()))
            counts.append(len(vs))
            if len(vs) >= 2:
                errors.append(float(vs.std(ddof=1) / math.sqrt(len(vs))))
            else:
                errors.append(float(by_phi[p][0][1]))
        out[mu] = (np.array(phis), np.array(means), np.array(errors), np.array(counts))
    return out


def fit(phi, v, err, start):
    """Weighted least squares of eq 6.4: (params, errors, covariance, chi2, dof)."""
    from scipy.optimize import curve_fit
    err = np.asarray(err, float)
    if not np.all(np.isfinite(err) & (err > 0)):
        raise InputError("every point needs a positive finite error (repeats, or a run's "
                         "block error)")
    if len(phi) <= len(NAMES):
        raise InputError(f"{len(phi)} values of phi for 6 parameters; allowed: at least 7")
    # The jump at phi_c is narrow (dphi ~ 0.003): a start on the wrong side of a data point
    # ends in a local minimum. So the fit starts at the given start and with phi_c at each of
    # the midpoints of the 6 largest drops of v between neighbouring phi, and keeps the least
    # chi^2.
    order = np.argsort(phi)
    ps, vs = np.asarray(phi, float)[order], np.asarray(v, float)[order]
    drops = np.argsort(vs[1:] - vs[:-1])[:6]
    starts = [tuple(start)] + [tuple(start[:2]) + (0.5 * (ps[i] + ps[i + 1]),) + tuple(start[3:])
                               for i in drops if ps[i + 1] > ps[i]]
    # The parameters stay physical (eq 6.4's meaning; continuum.vss refuses others): a step
    # down (delta_v >= 0) of positive width, phi_c inside the measured range, a free-flow branch
    # that falls (e2 <= 0) from a positive e1, phi_q at most 1. Without these, data without a
    # visible jump end in a negative width or a phi_c outside the data, with meaningless errors.
    lower = [0.0, 1e-4, ps[0], 1e-9, -50.0, ps[0]]
    upper = [10.0, 0.05, ps[-1], 50.0, 0.0, 1.0]
    best = None
    for p0 in starts:
        p0 = np.clip(p0, np.add(lower, 1e-9), np.subtract(upper, 1e-9))
        try:
            with np.errstate(all="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore")
                p, cov = curve_fit(eq_6_4, phi, v, p0=p0, sigma=err, absolute_sigma=True,
                                   bounds=(lower, upper), maxfev=20000)
        except RuntimeError:
            continue
        chi2 = float(np.sum(((v - eq_6_4(phi, *p)) / err) ** 2))
        if np.all(np.isfinite(cov)) and (best is None or chi2 < best[2]):
            best = (p, cov, chi2)
    if best is None:
        raise InputError("the least-squares fit of eq 6.4 did not converge from any start")
    p, cov, chi2 = best
    at_bound = [n for n, x, lo, hi in zip(NAMES, p, lower, upper)
                if abs(x - lo) < 1e-6 * max(1.0, abs(lo)) or abs(x - hi) < 1e-6 * max(1.0, abs(hi))]
    return p, np.sqrt(np.diag(cov)), cov, chi2, len(phi) - len(NAMES), at_bound


def e3_with_error(p, cov):
    """e3 = (e1 + e2 phi_c) / (phi_c - phi_q)^2 and its error (gradient . cov . gradient)."""
    def e3(q):
        return (q[3] + q[4] * q[2]) / (q[2] - q[5]) ** 2
    grad = np.zeros(len(p))
    for i in range(len(p)):
        h = 1e-7 * max(abs(p[i]), 1e-6)
        a, b = np.array(p, float), np.array(p, float)
        a[i] += h
        b[i] -= h
        grad[i] = (e3(a) - e3(b)) / (2 * h)
    return float(e3(p)), float(math.sqrt(max(grad @ cov @ grad, 0.0)))


def fit_all(groups):
    """{mu: result dict} of the fit for each friction coefficient."""
    results = {}
    for mu, (phi, v, err, n) in groups.items():
        column = table_column(mu)
        start = TABLE_6_2[column]
        p, perr, cov, chi2, dof, at_bound = fit(phi, v, err, start)
        e3, e3err = e3_with_error(p, cov)
        r = {"mu": mu, "points": int(len(phi)), "runs": int(n.sum()), "chi2": chi2, "dof": dof,
             "at_bound": at_bound}
        for name, value, e in zip(NAMES, p, perr):
            r[name], r[name + "_error"] = float(value), float(e)
        r["e3"], r["e3_error"] = e3, e3err
        r["table_6_2_column"] = column
        r["table_6_2"] = dict(zip(NAMES, start))
        r["data"] = {"phi": phi.tolist(), "v_ss": v.tolist(), "v_ss_error": err.tolist(),
                     "repeats": n.tolist()}
        results[mu] = r
    return results


def draw(results, png):
    plt = narrows_h5.pyplot()
    fig, ax = plt.subplots(figsize=(8, 6))
    for i, (mu, r) in enumerate(sorted(results.items())):
        color = f"C{i}"
        d = r["data"]
        ax.errorbar(d["phi"], d["v_ss"], yerr=d["v_ss_error"], fmt="o", ms=4, color=color,
                    capsize=2, label=f"mu = {mu:g}: runs")
        lo, hi = min(d["phi"]), max(d["phi"])
        grid = np.linspace(lo - 0.01, hi + 0.01, 2000)
        ax.plot(grid, eq_6_4(grid, *[r[n] for n in NAMES]), "-", color=color,
                label=f"mu = {mu:g}: eq 6.4 fit, chi2/dof = {r['chi2']:.3g}/{r['dof']}")
        ax.plot(grid, eq_6_4(grid, *[r["table_6_2"][n] for n in NAMES]), "--", color=color,
                lw=1, label=f"Table 6.2, mu = {r['table_6_2_column']}")
    ax.set(xlabel="phi", ylabel="v_ss", title="steady-state velocity (Kanehl (thesis) fig 6.8)")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="v_ss of one run -> RUN_DIR/vss.json")
    r.add_argument("run_dir")
    r.add_argument("--transient", type=float, default=0.0)
    r.add_argument("--blocks", type=int, default=4)
    r.add_argument("--phi", type=float)
    r.add_argument("--mu", type=float)
    f = sub.add_parser("fit", help="eq 6.4 fitted to v_ss(phi) for each mu")
    f.add_argument("sources", nargs="+")
    f.add_argument("--transient", type=float, default=0.0)
    f.add_argument("--blocks", type=int, default=4)
    f.add_argument("--out", default="vss_fit")
    f.add_argument("--column-mu", default="mu_cc")
    f.add_argument("--column-phi", default="phi")
    args = ap.parse_args(argv)
    try:
        if args.blocks < 2:
            raise InputError(f"--blocks {args.blocks}; allowed: 2 or more")
        if args.command == "run":
            res = run_vss(args.run_dir, args.transient, args.blocks, args.phi, args.mu)
            path = os.path.join(args.run_dir, "vss.json")
            with open(path, "w") as fh:
                json.dump(res, fh, indent=1)
            print(f"v_ss = {res['v_ss']:.6g} +- {res['v_ss_error']:.3g} (phi = {res['phi']}, "
                  f"mu = {res['mu_cc']}, {res['source']}); wrote {path}")
            return 0
        rows = read_sources(args.sources, args.transient, args.blocks, args.column_mu,
                            args.column_phi)
        results = fit_all(aggregate(rows))
    except (InputError, RuntimeError, OSError, ValueError) as e:
        return narrows_h5.report("vss_fit", e)
    with open(args.out + ".json", "w") as fh:
        json.dump({f"{mu:g}": r for mu, r in results.items()}, fh, indent=1)
    for mu, r in results.items():  # one flat object per mu: continuum.vss_fit = "PREFIX-mu1.json"
        with open(f"{args.out}-mu{mu:g}.json", "w") as fh:
            json.dump(r, fh, indent=1)
    for mu, res in results.items():
        print(f"mu = {mu:g} ({res['runs']} runs at {res['points']} phi; chi2 = {res['chi2']:.4g} "
              f"for {res['dof']} dof)        Table 6.2 (mu = {res['table_6_2_column']})")
        for name in NAMES + ("e3",):
            table = res["table_6_2"].get(name)
            if name == "e3":
                t = res["table_6_2"]
                table = (t["e1"] + t["e2"] * t["phi_c"]) / (t["phi_c"] - t["phi_q"]) ** 2
            bound = "  (at its bound: the data do not fix it)" if name in res["at_bound"] else ""
            print(f"  {name:9s} = {res[name]:10.5g} +- {res[name + '_error']:.2g}    {table:.5g}"
                  + bound)
    draw(results, args.out + ".png")
    print(f"wrote {args.out}.json (every mu), {args.out}-mu<mu>.json (one mu each, for "
          f"continuum.vss_fit) and {args.out}.png")
    return 0


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("vss_fit", main))
