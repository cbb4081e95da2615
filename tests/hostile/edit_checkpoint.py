#!/usr/bin/python3
"""Edits a narrows checkpoint as a hostile user would, then rewrites the checksum of every
dataset it touched, so that the file still verifies and only the restart's state checks can
refuse it (issue 35 item 1).

Usage: edit_checkpoint.py IN OUT EDIT [EDIT ...]   (IN may equal OUT)
  set DATASET INDEX VALUE   one entry (INDEX "3", "3,1", or "" for a scalar; VALUE a number, inf, nan, 1e300)
  scale DATASET FACTOR      every entry times FACTOR
  fill DATASET VALUE        every entry VALUE
  delete PATH               removes a dataset or group (e.g. /particles/colloids/orientation_w)
  append DATASET            one more row (a copy of the last)
  drop DATASET              one row less (the last)
  replace DATASET OLD NEW   a string dataset with OLD replaced by NEW (e.g. /parameters/scene)
  nochecksum DATASET        the dataset's new checksum is not written (its old one stays)
  strip                     no checksums at all (as narrows wrote checkpoints before issue 18)

Checksums are those of src/io/row_hash.hpp: rows_hash for the particle rows
(/particles/<species>/<field>/value), bytes_hash for every other dataset.
"""
import shutil
import sys

import h5py
import numpy as np

MASK = (1 << 64) - 1
M1, M2 = 0x9E3779B97F4A7C15, 0xD6E8FEB86659FD93


def rows_checksum(a):
    """io::rows_hash of a [rows][width] array of 8-byte values."""
    w = np.ascontiguousarray(a).view(np.uint64).reshape(a.shape[0], -1)
    with np.errstate(over="ignore"):
        h = (np.arange(w.shape[0], dtype=np.uint64) + np.uint64(1)) * np.uint64(M1)
        for k in range(w.shape[1]):
            h = (h ^ w[:, k]) * np.uint64(M2)
        h ^= h >> np.uint64(32)
        h *= np.uint64(M2)
        h ^= h >> np.uint64(32)
        return int(h.sum(dtype=np.uint64))


def mix64(z):
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
    return z ^ (z >> 31)


def bytes_hash(b):
    """io::bytes_hash of a small object."""
    h = mix64(len(b) ^ 0x6A09E667F3BCC909)
    for at in range(0, len(b), 8):
        h = mix64(h ^ int.from_bytes(b[at:at + 8].ljust(8, b"\0"), "little"))
    return h


def raw_bytes(ds):
    if ds.dtype.kind == "S":
        return bytes(ds[()]).ljust(ds.dtype.itemsize, b"\0")
    return np.ascontiguousarray(ds[()]).tobytes()


def is_rows(name):
    parts = name.strip("/").split("/")
    return len(parts) == 4 and parts[0] == "particles" and parts[3] == "value"


def rewrite(f, name, data):
    """Replaces dataset `name` by `data` (any shape), keeping its attributes."""
    old = f[name]
    attrs = dict(old.attrs)
    del f[name]
    ds = f.create_dataset(name, data=data)
    for k, v in attrs.items():
        ds.attrs[k] = v


def edit(src, dst, args):
    """Copies src to dst (unless they are the same) and applies the edits `args` (the command
    line's EDIT words) to dst; SystemExit on a bad edit."""
    if src != dst:
        shutil.copy(src, dst)
    touched, keep_old, strip = set(), set(), False
    with h5py.File(dst, "r+") as f:
        i = 0
        while i < len(args):
            op = args[i]
            if op == "set":
                name, index, value = args[i + 1:i + 4]
                a = np.array(f[name][()])
                idx = tuple(int(x) for x in index.split(",") if x != "")
                a[idx] = float(value) if a.dtype.kind == "f" else int(value)
                f[name][...] = a
                touched.add(name)
                i += 4
            elif op == "scale":
                name, factor = args[i + 1:i + 3]
                f[name][...] = f[name][()] * float(factor)
                touched.add(name)
                i += 3
            elif op == "fill":
                name, value = args[i + 1:i + 3]
                f[name][...] = float(value)
                touched.add(name)
                i += 3
            elif op == "delete":
                del f[args[i + 1]]
                i += 2
            elif op in ("append", "drop"):
                name = args[i + 1]
                a = f[name][()]
                rewrite(f, name, np.concatenate([a, a[-1:]]) if op == "append" else a[:-1])
                touched.add(name)
                i += 2
            elif op == "replace":
                name, old, new = args[i + 1:i + 4]
                text = bytes(f[name][()]).decode()
                if old not in text:
                    sys.exit(f"{name} does not hold {old!r}")
                text = text.replace(old, new).encode()
                rewrite(f, name, np.array(text, dtype=f"S{len(text)}"))
                touched.add(name)
                i += 4
            elif op == "nochecksum":
                keep_old.add(args[i + 1])
                i += 2
            elif op == "strip":
                strip = True
                i += 1
            else:
                sys.exit(f"unknown edit {op}")
        if strip:
            f.visititems(lambda n, o: o.attrs.__delitem__("checksum")
                         if "checksum" in o.attrs else None)
            return
        for name in touched - keep_old:
            ds = f[name]
            if "checksum" not in ds.attrs:
                continue
            a = ds[()]
            s = rows_checksum(a.reshape(a.shape[0], -1)) if is_rows(name) else \
                bytes_hash(raw_bytes(ds))
            ds.attrs["checksum"] = np.array([s], dtype=np.uint64)


def main():
    edit(sys.argv[1], sys.argv[2], sys.argv[3:])


if __name__ == "__main__":
    main()
