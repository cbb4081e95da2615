"""Exit 0 when two checkpoints hold bitwise the same state, else name what differs.

Usage: same_state.py A.h5 B.h5 SPEC [SPEC ...]
A SPEC `SPECIES:FIELD,FIELD,...` compares particles: each species' rows are put in the order of
their key (`id`; `owner_id`, `partner_id` for the contact history) before its fields are
compared bit for bit (and by shape). A SPEC `/PATH` compares one dataset as written, bit for bit
(a lattice's words, kmc's running sums, continuum fields). The command-line tests' 1-vs-N-ranks
and restart checks share this one comparison.
"""
import sys

import h5py
import numpy as np


def rows(path, species, fields):
    key = ["owner_id", "partner_id"] if species == "contacts" else ["id"]
    with h5py.File(path, "r") as f:
        p = f["/particles/" + species]
        order = np.lexsort([p[k + "/value"][:] for k in reversed(key)])
        return [p[name + "/value"][:][order] for name in fields]


def bits(x):
    return np.ascontiguousarray(x).reshape(-1).view(np.uint8)


def main():
    a, b, *specs = sys.argv[1:]
    for spec in specs:
        if spec.startswith("/"):
            with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
                x, y = np.asarray(fa[spec][()]), np.asarray(fb[spec][()])
            if x.shape != y.shape or x.dtype != y.dtype or not np.array_equal(bits(x), bits(y)):
                sys.exit(f"{spec} differ")
            continue
        species, fields = spec.split(":")
        fields = fields.split(",")
        for name, x, y in zip(fields, rows(a, species, fields), rows(b, species, fields)):
            if x.shape != y.shape or not np.array_equal(x.view(np.uint64), y.view(np.uint64)):
                sys.exit(f"{species} {name} differ")


if __name__ == "__main__":
    main()
