#!/usr/bin/python3
"""Speedup and efficiency table (and plot) from narrows logs.

Reads the final "Loop time of T s on P ranks for S steps with N particles" line of each log
file given (e.g. the logs a jobscripts/*_scaling.slurm run leaves), groups them by kind:
  strong: same N for every P  -> speedup T1/TP, efficiency T1/(P TP)
  weak:   N grows with P      -> efficiency T1/TP (work per rank constant)
Usage: scaling_table.py [--weak] [--png FILE] LOG [LOG ...]
"""
import argparse
import re
import sys

LINE = re.compile(r"Loop time of ([0-9.eE+-]+) s on (\d+) ranks for (\d+) steps with (\d+) particles")


def read(path):
    found = None
    with open(path, errors="replace") as f:
        for line in f:
            m = LINE.search(line)
            if m:
                found = (int(m.group(2)), float(m.group(1)), int(m.group(3)), int(m.group(4)))
    if found is None:
        sys.exit(f"scaling_table: {path}: no 'Loop time' line (did the run finish?)")
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("logs", nargs="+")
    ap.add_argument("--weak", action="store_true", help="weak scaling (work per rank fixed)")
    ap.add_argument("--png", help="also plot speedup/efficiency to this PNG")
    a = ap.parse_args()
    runs = sorted(read(p) for p in a.logs)
    p1, t1, s1, n1 = runs[0]
    rate1 = s1 * n1 / t1
    print(f"{'ranks':>6} {'particles':>12} {'time/s':>10} {'particle-steps/s':>17} {'speedup':>8} {'efficiency':>10}")
    rows = []
    for p, t, s, n in runs:
        rate = s * n / t
        if a.weak:
            speedup = rate / rate1 * p1
            eff = (rate / p) / (rate1 / p1)
        else:
            speedup = (t1 / s1) / (t / s) * p1
            eff = speedup / p
        rows.append((p, speedup, eff))
        print(f"{p:>6} {n:>12} {t:>10.4g} {rate:>17.4g} {speedup:>8.3f} {eff:>10.3f}")
    if a.png:
        import narrows_h5  # the plot setup every tool shares (no HDF5 here)
        plt = narrows_h5.pyplot()
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.5))
        ps = [r[0] for r in rows]
        ax1.plot(ps, [r[1] for r in rows], "o-", label="measured")
        if not a.weak:
            ax1.plot(ps, ps, "k--", lw=0.8, label="ideal")
        ax1.set_xlabel("ranks"); ax1.set_ylabel("speedup" if not a.weak else "throughput ratio")
        ax1.legend()
        ax2.plot(ps, [r[2] for r in rows], "o-")
        ax2.axhline(1.0, color="k", lw=0.8, ls="--")
        ax2.set_xlabel("ranks"); ax2.set_ylabel("efficiency"); ax2.set_ylim(0, 1.1)
        fig.suptitle(("weak" if a.weak else "strong") + " scaling, narrows MPCD")
        fig.tight_layout()
        fig.savefig(a.png, dpi=120)
        print(f"plot in {a.png}")


if __name__ == "__main__":
    main()
