#!/usr/bin/env python3
"""Efficiency of the full Kanehl (thesis) Table 6.1 channel (l = 12000 b) on many ranks, predicted
from what a short run here measures (issue 21, acceptance 7). tools/scaling_model.sh makes the
inputs.

Measured (inputs):
  * the MPI calls per step of each kind and the bytes a rank sends per step, from two runs of the
    l = 600 b scene on 3 ranks that differ only in their number of steps (tools/mpi_calls.c
    counts every call; the difference of the two counts over the difference of the steps is
    per step, without the start-up and the final checkpoint);
  * the one-rank loop time per fluid particle-step of the coupled system (fluid, no-slip
    colloids, spring contacts), from the same scene on 1 rank.
Model (stated, not measured here):
  * compute time per step and rank = fluid particles per rank x the one-rank cost: the work is
    proportional to the slab (the colloids and their contacts go with the fluid they displace);
    no load imbalance (the jammed plugs of the thesis' runs make one, not modelled), plus the
    redundant spring work of the ghost shell: every rank moves its ghost colloids through the
    spring sub-steps itself (coupling/no_slip.cpp), (substeps + 2) contact distances of
    2 r_max + 2 m beyond the base region on each side, at the measured contact cost per
    colloid-step (the "contacts" stage of the one-rank log);
  * a message costs alpha + bytes / bandwidth (alpha = 2 us, 10 GB/s: an InfiniBand cluster);
  * a halo exchange (parallel/exchange.cpp) is one round of point-to-point messages, one to
    each neighbouring rank that can hold rows (counts in the messages themselves; no
    collective): the copies of ghost colloids and of their contacts (--wide 2) reach every rank
    within the ghost shell (ceil(shell / slab) on each side); the impulse sums, refreshes and
    migrations one on each side (the shell is dropped after the spring sub-steps); the measured
    bytes over the bandwidth;
  * MPI_Allreduce of a few numbers: recursive doubling, ceil(log2 P) rounds of alpha
    (Thakur et al. (2005), short messages);
  * bytes per rank and step stay those measured on 3 ranks: they come from the ghost shell on
    both faces of a slab, whose size does not change with P.
"""
import argparse
import math
import sys


def per_step(short, long_, steps):
    """{kind: (calls, bytes)} per step on the busiest rank, from two MPI_CALLS_OUT files."""
    def read(path):
        ranks = {}
        for line in open(path):
            f = line.split()
            ranks[int(f[0])] = {f[i]: (int(f[i + 1]), int(f[i + 2])) for i in range(1, len(f), 3)}
        return ranks
    a, b = read(short), read(long_)
    out = {}
    for kind in b[0]:
        calls = max((b[r][kind][0] - a[r][kind][0]) / steps for r in b)
        nbytes = max((b[r][kind][1] - a[r][kind][1]) / steps for r in b)
        out[kind] = (calls, nbytes)
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("short", help="MPI_CALLS_OUT of the shorter run")
    p.add_argument("long", help="MPI_CALLS_OUT of the longer run")
    p.add_argument("--steps", type=float, required=True, help="steps the longer run has more")
    p.add_argument("--rate", type=float, required=True,
                   help="one-rank fluid particle-steps/s of the coupled scene")
    p.add_argument("--particles", type=float, default=3.75e6,
                   help="fluid particles of the full channel (default: l = 12000, 2w = 50, "
                        "n = 25, a quarter of the area free at phi = 0.75)")
    p.add_argument("--alpha", type=float, default=2e-6, help="latency per message, s")
    p.add_argument("--bandwidth", type=float, default=1e10, help="bytes/s per link")
    p.add_argument("--ranks", type=int, nargs="+", default=[64, 512, 3072])
    p.add_argument("--length", type=float, default=12000.0, help="channel length along x, b")
    p.add_argument("--colloids-per-length", type=float, default=1098 / 600.0,
                   help="colloids per b of channel (Table 6.1: 1098 in 600 b)")
    p.add_argument("--contact-cost", type=float, default=0.0,
                   help="one-rank seconds of the spring contacts per colloid-step")
    p.add_argument("--radius-max", type=float, default=2.94, help="largest colloid radius, b")
    p.add_argument("--path", type=float, default=0.26,
                   help="largest path of a colloid in a step, m (0.25 allowance + 3 v dt)")
    p.add_argument("--substeps", type=int, default=10, help="spring sub-steps (0: no shell)")
    p.add_argument("--shell", type=float, default=None,
                   help="ghost region beyond a slab, b (default: the spring shell from "
                        "--substeps, --radius-max, --path; hard contacts: base + 4 contact "
                        "distances)")
    p.add_argument("--wide", type=float, default=2,
                   help="exchanges per step that reach across the ghost shell")
    a = p.parse_args()
    c = per_step(a.short, a.long, a.steps)
    exchanges = c["waitall"][0] if "waitall" in c else c["alltoall"][0]
    if exchanges <= 0:
        sys.exit("scaling_model: no halo exchange was counted (run on more than one rank)")
    alltoall = c["alltoall"][0]
    messages = c["isend"][0]
    halo_bytes = c["isend"][1]
    small = c["allreduce"][0] + c["allgather"][0] + c["reduce"][0] + c["bcast"][0]
    contact = 2.0 * a.radius_max + 2.0 * a.path
    shell = ((a.substeps + 2) * contact if a.substeps > 0 else 0.0) + 1.0 + 2.0 * a.path + \
        2 ** (1 / 24) * 2.0 * a.radius_max + a.path
    if a.shell is not None:
        shell = a.shell
    print(f"halo exchanges per step: {exchanges:.3g}")
    print(f"measured per step (busiest rank of 3): {exchanges:.3g} halo exchanges "
          f"({alltoall:.3g} of them after an MPI_Alltoall of the counts), {messages:.1f} messages "
          f"of rows sent ({halo_bytes:.4g} bytes), {small:.1f} small collectives (allreduce, "
          f"allgather, reduce, bcast); one-rank cost {1.0 / a.rate:.3g} s per fluid "
          f"particle-step, contacts {a.contact_cost * 1e6:.3g} us per colloid-step")
    print(f"model: alpha = {a.alpha * 1e6:.3g} us, bandwidth = {a.bandwidth / 1e9:.3g} GB/s, "
          f"{a.particles:.3g} fluid particles, {a.colloids_per_length:.3g} colloids per b, "
          f"ghost shell {shell:.3g} b on each side ({a.wide} of the exchanges reach across it)\n")
    print("| ranks | slab (b) | neighbours each side | compute/step | of it the ghosts' contacts "
          "| comm/step | efficiency |")
    print("|---|---|---|---|---|---|---|")
    lines = []
    for P in a.ranks:
        lg = math.ceil(math.log2(P))
        slab = a.length / P
        sides = min(math.ceil(shell / slab), max((P - 1) // 2, 1))
        ideal = a.particles / P / a.rate
        ghosts = min(2.0 * shell, a.length - slab) * a.colloids_per_length
        redundant = ghosts * a.contact_cost
        compute = ideal + redundant
        narrow = max(exchanges - a.wide, 0.0)
        calls = narrow * 2 + min(a.wide, exchanges) * 2 * sides
        rows = calls * a.alpha + halo_bytes / a.bandwidth
        counts = alltoall * lg * (a.alpha + P / 2 * 4 / a.bandwidth)
        collectives = small * lg * a.alpha
        comm = rows + counts + collectives
        eff = ideal / (compute + comm)
        print(f"| {P} | {slab:.3g} | {sides} | {compute * 1e3:.3g} ms | {redundant * 1e3:.3g} ms "
              f"| {comm * 1e3:.3g} ms | {eff:.2f} |")
        lines.append(f"efficiency at {P} ranks: {eff:.2f}")
    print()
    print("\n".join(lines))


if __name__ == "__main__":
    main()
