#!/usr/bin/python3
"""The time-averaged distribution of contact overlaps of a spring-contact run, as Kanehl
(thesis) fig 6.2a, with the numbers the thesis states beside it (the bulk of the overlaps 1-2 %
of the radius deep, fewer than 10 % of the contacts deeper than 0.04 a).

Usage: overlaps.py RUN_DIR [--transient T] [--png FILE] [--json FILE]

Reads /observables/contact_statistics (written with colloids.contacts = "spring" and
"contact_statistics" in output.observables; docs/scenes.md: value [T][2][bins] counts of
colloid-colloid and colloid-wall overlaps delta/a, `beyond` the deeper ones) of the samples at
t >= T, adds their counts and writes DIR/overlaps.png (the probability density of delta/a per
kind of contact) and DIR/overlaps.json: per kind the number of contacts counted, the median,
mode and 90th percentile of delta/a, the fraction between 0.01 and 0.02 and the fraction deeper
than 0.04 (the counts are exact on the bin edges 0.01, 0.02 and 0.04; the median and percentile
are interpolated inside their bin), the mean sliding fraction, and the thesis' two statements.
Exit 2 on bad input.
"""

import argparse
import json
import os
import sys

import numpy as np

import narrows_h5
from narrows_h5 import NarrowsDataError

KINDS = ("colloid-colloid", "colloid-wall")


def quantile(edges, counts, total, q):
    """delta/a below which a fraction q of all `total` contacts lie, interpolated linearly inside
    its bin (counts beyond the last edge count towards total only)."""
    cum = np.cumsum(counts)
    target = q * total
    i = int(np.searchsorted(cum, target))
    if i >= len(counts):
        return None  # beyond the last bin
    below = cum[i - 1] if i else 0.0
    return float(edges[i] + (target - below) / counts[i] * (edges[i + 1] - edges[i]))


def fmt(x):
    return "beyond the bins" if x is None else f"{x:.4f}"


def summarise(run_dir, transient):
    run = narrows_h5.open_run(run_dir)
    s = run.series("contact_statistics")
    keep = s.time >= transient
    if not keep.any():
        raise NarrowsDataError(run.path, f"no contact_statistics sample at t >= {transient}",
                               f"--transient below the last sample's time {s.time[-1]:g}")
    counts = s.value[keep].sum(axis=0)  # [2][bins]
    beyond = s["beyond"][keep].sum(axis=0)
    sliding = s["sliding_fraction"][keep]
    width = float(np.asarray(s["bin_width"]).reshape(-1)[0]) if "bin_width" in s.keys() else \
        float(s.bins[1] - s.bins[0])
    edges = np.concatenate([s.bins - width / 2, [s.bins[-1] + width / 2]])
    out = {"samples": int(keep.sum()), "from_time": float(s.time[keep][0]),
           "to_time": float(s.time[keep][-1]), "thesis": {"bulk": "1-2 % of the radius deep",
                                                           "deeper_than_0.04": "< 0.10"}}
    for k, name in enumerate(KINDS):
        c = counts[k].astype(float)
        total = c.sum() + float(beyond[k])
        r = {"contacts": total, "sliding_fraction": float(np.nanmean(sliding[:, k]))}
        if total > 0:
            between = c[(edges[:-1] >= 0.01 - 1e-12) & (edges[1:] <= 0.02 + 1e-12)].sum()
            deeper = c[edges[:-1] >= 0.04 - 1e-12].sum() + float(beyond[k])
            r.update(median=quantile(edges, c, total, 0.5), p90=quantile(edges, c, total, 0.9),
                     mode=float(s.bins[int(np.argmax(c))]), fraction_1_to_2_percent=between / total,
                     fraction_deeper_than_0_04=deeper / total)
        out[name] = r
    return out, edges, counts


def draw(png, edges, counts, summary):
    plt = narrows_h5.pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, name in enumerate(KINDS):
        total = summary[name]["contacts"]
        if total <= 0:
            continue
        density = counts[k] / total / np.diff(edges)
        ax.step(edges[:-1], density, where="post",
                label=f"{name}: {int(total)} contacts, median {fmt(summary[name]['median'])}, "
                f"{100 * summary[name]['fraction_deeper_than_0_04']:.0f} % > 0.04")
    ax.axvspan(0.01, 0.02, color="0.85", label="thesis: bulk 1-2 % deep")
    ax.axvline(0.04, color="k", ls="--", lw=1, label="thesis: < 10 % deeper than 0.04")
    ax.set(xlabel="overlap delta_n / a", ylabel="probability density",
           title=f"overlaps, t = {summary['from_time']:g}-{summary['to_time']:g} "
           f"(Kanehl (thesis) fig 6.2a)")
    ax.set_xlim(0, edges[-1])
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run_dir")
    ap.add_argument("--transient", type=float, default=0.0)
    ap.add_argument("--png")
    ap.add_argument("--json")
    args = ap.parse_args(argv)
    summary, edges, counts = summarise(args.run_dir, args.transient)
    base = args.run_dir if os.path.isdir(args.run_dir) else os.path.dirname(args.run_dir)
    png = args.png or os.path.join(base, "overlaps.png")
    path = args.json or os.path.join(base, "overlaps.json")
    draw(png, edges, counts, summary)
    with open(path, "w") as f:
        json.dump(summary, f, indent=1)
    for name in KINDS:
        r = summary[name]
        if r["contacts"] > 0:
            print(f"{name}: {int(r['contacts'])} contacts in {summary['samples']} samples, median "
                  f"{fmt(r['median'])}, mode {r['mode']:.4f}, 90 % below {fmt(r['p90'])}, "
                  f"{100 * r['fraction_1_to_2_percent']:.1f} % at 0.01-0.02, "
                  f"{100 * r['fraction_deeper_than_0_04']:.1f} % deeper than 0.04, "
                  f"{100 * r['sliding_fraction']:.1f} % sliding")
    print(f"wrote {png} and {path}")
    return 0


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("overlaps", main, sys.argv[1:]))
