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
    no load imbalance (the jammed plugs of the thesis' runs make one, not modelled);
  * a message costs alpha + bytes / bandwidth (alpha = 2 us, 10 GB/s: an InfiniBand cluster);
  * MPI_Alltoall of one int per rank: Bruck's algorithm, ceil(log2 P) rounds of alpha + P/2 x 4
    bytes; MPI_Allreduce/Allgather of a few numbers: 2 ceil(log2 P) alpha;
  * a halo exchange (parallel/exchange.cpp) is an MPI_Alltoall of the row counts, then
    point-to-point messages between the ranks that have rows for each other only (the
    neighbouring slabs): the measured messages per step, each a latency, plus the measured
    bytes over the bandwidth. (Until 2026-12-02 the rows went by MPI_Alltoallv, which may pay a
    latency for each of the P - 1 ranks even when the message is empty: 0.02 at 512 ranks.)
  * bytes per rank and step stay those measured on 3 ranks: they come from the two faces of a
    slab, whose cross-section does not change with P. Beyond 12000 / P < the ghost range
    (2 r_max + skin + a step's path, ~6.3 b: from P ~ 1900) a rank gets ghosts from more than
    one neighbour each side; the bytes stay about the same, the messages double.
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
    a = p.parse_args()
    c = per_step(a.short, a.long, a.steps)
    if c["alltoall"][0] <= 0:
        sys.exit("scaling_model: no halo exchange was counted (run on more than one rank)")
    halo_calls = c["alltoall"][0]  # one MPI_Alltoall of the counts per exchange
    messages = c["isend"][0]
    halo_bytes = c["isend"][1]
    small = c["allreduce"][0] + c["allgather"][0] + c["reduce"][0] + c["bcast"][0]
    print(f"measured per step (busiest rank of 3): {halo_calls:.1f} halo exchanges "
          f"(MPI_Alltoall of the counts each), {messages:.1f} messages of rows sent "
          f"({halo_bytes:.4g} bytes), {small:.1f} small collectives (allreduce, allgather, "
          f"reduce, bcast); one-rank cost {1.0 / a.rate:.3g} s per fluid particle-step")
    print(f"model: alpha = {a.alpha * 1e6:.3g} us, bandwidth = {a.bandwidth / 1e9:.3g} GB/s, "
          f"{a.particles:.3g} fluid particles\n")
    print("| ranks | slab (b) | compute/step | comm/step | of it counts (Alltoall) | efficiency |")
    print("|---|---|---|---|---|---|")
    for P in a.ranks:
        lg = math.ceil(math.log2(P))
        compute = a.particles / P / a.rate
        alltoall = halo_calls * lg * (a.alpha + P / 2 * 4 / a.bandwidth)
        ghost_sides = 2 if 12000.0 / P < 6.3 else 1  # neighbours each side that send ghosts
        rows = ghost_sides * messages * a.alpha + halo_bytes / a.bandwidth
        collectives = small * 2 * lg * a.alpha
        comm = alltoall + rows + collectives
        print(f"| {P} | {12000.0 / P:.3g} | {compute * 1e3:.3g} ms | {comm * 1e3:.3g} ms | "
              f"{alltoall * 1e3:.3g} ms | {compute / (compute + comm):.2f} |")


if __name__ == "__main__":
    main()
