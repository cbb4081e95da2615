#!/usr/bin/python3
"""Moves one fluid particle of an mpcd checkpoint next to (or onto) a colloid's centre and
rewrites the checksum of /particles/fluid/position/value, so that the file still verifies and
only the restart's state checks can refuse it.

Usage: move_fluid_particle.py IN OUT FLUID_ROW COLLOID_ROW FRACTION
  puts fluid row FLUID_ROW at FRACTION x radius from colloid row COLLOID_ROW's centre, along
  +x (-x near the box's edge; FRACTION 0: the centre); prints "FLUID_ID COLLOID_ID".

The checksum is that of src/io/row_hash.hpp: the sum modulo 2^64 over the rows of
row_hash(row index, the row's 64-bit words).
"""
import shutil
import sys

import h5py
import numpy as np

M1, M2 = np.uint64(0x9E3779B97F4A7C15), np.uint64(0xD6E8FEB86659FD93)


def rows_checksum(a):
    """io::rows_hash of a [rows][width] array of 8-byte values, as the writer computes it."""
    w = np.ascontiguousarray(a).view(np.uint64).reshape(a.shape[0], -1)
    with np.errstate(over="ignore"):
        h = (np.arange(w.shape[0], dtype=np.uint64) + np.uint64(1)) * M1
        for k in range(w.shape[1]):
            h = (h ^ w[:, k]) * M2
        h ^= h >> np.uint64(32)
        h *= M2
        h ^= h >> np.uint64(32)
        return np.uint64(h.sum(dtype=np.uint64))


def main():
    src, dst, row, crow, frac = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), \
        float(sys.argv[5])
    shutil.copy(src, dst)
    with h5py.File(dst, "r+") as f:
        pos = f["/particles/fluid/position/value"]
        p = pos[...]
        if rows_checksum(p) != np.uint64(pos.attrs["checksum"][0]):
            sys.exit("the checksum of the input does not match: not a checkpoint narrows wrote")
        centre = f["/particles/colloids/position/value"][crow]
        radius = f["/particles/colloids/radius/value"][crow]
        edge = f["/particles/fluid/box/edges"][0]
        p[row] = centre
        p[row, 0] += frac * radius if centre[0] + frac * radius < edge else -frac * radius
        pos[...] = p
        pos.attrs["checksum"] = np.array([rows_checksum(p)], dtype=np.uint64)
        print(int(f["/particles/fluid/id/value"][row]), int(f["/particles/colloids/id/value"][crow]))


if __name__ == "__main__":
    main()
