#!/usr/bin/python3
"""Bitwise comparison of two narrows output folders (the harness tools/compare_builds.sh runs it).

    /usr/bin/python3 tools/compare_outputs.py DIR_A DIR_B [--all]

Every file in either folder must be in both. HDF5 files (*.h5): the same objects (groups,
datasets, named types), every dataset of the same shape, dtype and bytes, every attribute of
the same type, shape and bytes. Logs (log.txt, log-<step>.txt): the same lines after the
timing lines are dropped or have their numbers masked (TIMING_RULES below). Any other file
(trajectory.xdmf, ...): the same bytes.

Prints `same` (exit 0) or `DIFFERENT: <file> <dataset or attribute> <first differing index>`
(exit 1), followed by up to 10 further differences as indented lines (all of them with --all).
Exit 2 on a usage error or an unreadable file.

Excluded, because they differ between builds or runs by design (keep this list small):
  EXCLUDED_ATTRIBUTES   (object path, attribute name) pairs not compared
  TIMING_RULES          log lines that hold wall-clock timings
"""

import os
import re
import sys

import numpy as np

import narrows_h5

# /h5md/creator carries the program version (NARROWS_VERSION = CMake's PROJECT_VERSION) in
# every observables, checkpoint and trajectory file: a refactor may bump it. Nothing else in
# the files differs between two runs of one binary (checked: all 34 scenes of run/ on 1 and 3
# ranks, run twice into different folders: no dataset or other attribute differed; HDF5's own
# object timestamps are in the file bytes, not in datasets or attributes, so they never count).
EXCLUDED_ATTRIBUTES = {
    ("/h5md/creator", "version"),
}

# Log lines: (regex, replacement). A replacement of None drops the line; otherwise the match
# is replaced and the rest of the line is still compared. Found by diffing the logs of two runs
# of one binary over every scene (and from the format strings of the log lines).
TIMING_RULES = [
    # wall-clock time of the main loop: "Loop time of 0.05056 s on 1 ranks for 40 steps with
    # 25000 particles (1.978e+07 particle-steps/s)"; the counts stay compared
    (re.compile(r"^Loop time of \S+ s (on .*) \(\S+ (\S+/s)\)$"), r"Loop time of <t> s \1 (<rate> \2)"),
    # checkpoint writes: "checkpoint DIR/checkpoint-0000000040.h5: 1.0 MB of particles in
    # 0.0242 s (41.3 MB/s)", lgca "... 0.1 MB of lattice in 0.0163 s"
    (re.compile(r"^(checkpoint .* of (particles|lattice)) in \S+ s( \(\S+ MB/s\))?$"), r"\1 in <t> s"),
    # the colloid packing's time: "packing: 44 colloids at fraction 0.7518, ..., 7810
    # relaxation steps, 0.03 s"
    (re.compile(r"^(packing: .*relaxation steps), \S+ s$"), r"\1, <t> s"),
    # the no-slip coupling's share of the loop time (and of its messages): only timings
    (re.compile(r"^no-slip coupling( messages)?: \S+ s of the loop"), None),
    (re.compile(r"^no-slip coupling stages \(s"), None),
    # every rank's seconds in messages, and the busy time's max/mean per balance check
    (re.compile(r"^messages and waiting: \S+ s of the loop"), None),
    (re.compile(r"^busy time (every|max/mean per check)"), None),
    # (bytes sent depend on the ghost regions, which may be wider than a step needs: not a result)
    (re.compile(r"^colloid messages: \S+ bytes per step"), r"colloid messages: <n> bytes per step"),
    # the axial fields' cost per sample: "axial_fields: 2.56 ms per sample on the busiest rank"
    (re.compile(r"^(axial_fields): \S+ ms per sample"), r"\1: <t> ms per sample"),
    # the density_kde windows' cost: "kde windows: 0.0656 ms per sample on rank 0 (...), 0 ms
    # per window closed (...); 0 windows of 100000 steps"; the window count stays compared
    (re.compile(r"^kde windows: \S+ ms per sample (.*), \S+ ms per window closed"),
     r"kde windows: <t> ms per sample \1, <t> ms per window closed"),
    # progress lines: "step 100 / 1000 (10.0 %), 2.1e+07 particle-steps/s, ETA 5s" (when they
    # appear depends on the wall clock)
    (re.compile(r", ETA \S+$"), None),
    # the run directory (both builds write into their own folders): "... output in DIR",
    # "checkpoint DIR/checkpoint-0000000040.h5: ...", "trajectory: ... to DIR/trajectory.h5"
    (re.compile(r", output in .*$"), ", output in <dir>"),
    (re.compile(r"(?<!\S)\S*/([^/\s]+\.(h5|xdmf|txt))(?=[\s:,)]|$)"), r"<dir>/\1"),
    # the program version: "narrows 0.1.0 run SCENE on R rank(s), ..."
    (re.compile(r"^narrows \S+ run "), "narrows <version> run "),
]

MAX_SHOWN = 10


def filtered_log(path):
    kept = []
    with open(path, encoding="utf-8", errors="surrogateescape") as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            for pattern, replacement in TIMING_RULES:
                if replacement is None:
                    if pattern.search(line):
                        line = None
                        break
                else:
                    line = pattern.sub(replacement, line)
            if line is not None:
                kept.append((number, line))
    return kept


def compare_logs(rel, path_a, path_b, out):
    a, b = filtered_log(path_a), filtered_log(path_b)
    for (na, la), (nb, lb) in zip(a, b):
        if la != lb:
            out.append(f"{rel} line {na} (B: line {nb}): {la!r} != {lb!r}")
            return
    if len(a) != len(b):
        which, extra = ("A", a[len(b)]) if len(a) > len(b) else ("B", b[len(a)])
        out.append(f"{rel} line {extra[0]}: only in {which} (A {len(a)}, B {len(b)} "
                   f"compared lines): {extra[1]!r}")


def first_index(a, b):
    """First index (row-major) where the arrays a and b (same shape and dtype) differ bitwise."""
    if a.dtype.hasobject:
        fa, fb = a.reshape(-1), b.reshape(-1)
        for i in range(fa.size):
            if type(fa[i]) is not type(fb[i]) or fa[i] != fb[i]:
                return tuple(int(k) for k in np.unravel_index(i, a.shape)) if a.shape else ()
        return None
    if a.dtype.itemsize == 0:
        return None
    ba = np.ascontiguousarray(a).view(np.uint8).reshape(a.shape + (a.dtype.itemsize,))
    bb = np.ascontiguousarray(b).view(np.uint8).reshape(b.shape + (b.dtype.itemsize,))
    diff = np.any(ba != bb, axis=-1)
    if not diff.any():
        return None
    if not a.shape:
        return ()
    return tuple(int(i) for i in np.unravel_index(int(np.argmax(diff.reshape(-1))), a.shape))


def fmt_index(index):
    if index == ():
        return "[scalar]"
    return "[" + ",".join(str(i) for i in index) + "]"


def read_attribute(obj, name):
    dtype, shape = narrows_h5.attribute_type(obj, name)
    value = obj.attrs[name]
    return dtype, shape, np.asarray(value) if not isinstance(value, (str, bytes)) \
        else np.array(value, dtype=object)


def compare_attributes(rel, path, obj_a, obj_b, out):
    names_a, names_b = set(obj_a.attrs.keys()), set(obj_b.attrs.keys())
    for name in sorted(names_a ^ names_b):
        out.append(f"{rel} {path}@{name} only in {'A' if name in names_a else 'B'}")
    for name in sorted(names_a & names_b):
        if (path, name) in EXCLUDED_ATTRIBUTES:
            continue
        ta, sa, va = read_attribute(obj_a, name)
        tb, sb, vb = read_attribute(obj_b, name)
        if ta != tb:
            out.append(f"{rel} {path}@{name} dtype {ta} != {tb}")
        elif sa != sb:
            out.append(f"{rel} {path}@{name} shape {sa} != {sb}")
        else:
            index = first_index(va, vb)
            if index is not None:
                out.append(f"{rel} {path}@{name} {fmt_index(index)}")


def kind(obj):
    return type(obj).__name__


def compare_h5(rel, path_a, path_b, out):
    with narrows_h5.open_h5(path_a) as fa, narrows_h5.open_h5(path_b) as fb:
        oa, ob = narrows_h5.objects(fa), narrows_h5.objects(fb)
        for path in sorted(set(oa) ^ set(ob)):
            out.append(f"{rel} {path} only in {'A' if path in oa else 'B'}")
        for path in sorted(set(oa) & set(ob)):
            a, b = oa[path], ob[path]
            if kind(a) != kind(b):
                out.append(f"{rel} {path} is a {kind(a)} in A, a {kind(b)} in B")
                continue
            if narrows_h5.is_dataset(a):  # the data first: a checksum attribute follows it
                compare_dataset(rel, path, a, b, out)
            compare_attributes(rel, path, a, b, out)


def compare_dataset(rel, path, a, b, out):
    if a.dtype != b.dtype:
        out.append(f"{rel} {path} dtype {a.dtype} != {b.dtype}")
    elif a.shape != b.shape:
        out.append(f"{rel} {path} shape {a.shape} != {b.shape}")
    elif a.shape is not None:  # (a null dataspace holds nothing)
        index = first_index(np.asarray(a[()], dtype=a.dtype), np.asarray(b[()], dtype=b.dtype))
        if index is not None:
            out.append(f"{rel} {path} {fmt_index(index)}")


def compare_bytes(rel, path_a, path_b, out):
    with open(path_a, "rb") as f:
        a = f.read()
    with open(path_b, "rb") as f:
        b = f.read()
    if a != b:
        n = min(len(a), len(b))
        i = next((k for k in range(n) if a[k] != b[k]), n)
        out.append(f"{rel} byte {i} (sizes {len(a)}, {len(b)})")


def files_under(root):
    found = set()
    for dirpath, _, names in os.walk(root):
        for name in names:
            found.add(os.path.relpath(os.path.join(dirpath, name), root))
    return found


def compare_dirs(dir_a, dir_b):
    out = []
    fa, fb = files_under(dir_a), files_under(dir_b)
    for rel in sorted(fa ^ fb):
        out.append(f"{rel} only in {'A' if rel in fa else 'B'} ({dir_a if rel in fa else dir_b})")
    for rel in sorted(fa & fb):
        pa, pb = os.path.join(dir_a, rel), os.path.join(dir_b, rel)
        base = os.path.basename(rel)
        if base.endswith(".h5"):
            compare_h5(rel, pa, pb, out)
        elif re.fullmatch(r"log(-\d+)?\.txt", base):
            compare_logs(rel, pa, pb, out)
        else:
            compare_bytes(rel, pa, pb, out)
    return out


def main(argv):
    args = [a for a in argv[1:] if a != "--all"]
    if len(args) != 2 or not all(os.path.isdir(a) for a in args):
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    try:
        differences = compare_dirs(*args)
    except Exception as error:  # unreadable or damaged file
        print(f"DIFFERENT: cannot compare: {error}")
        return 2
    if not differences:
        print("same")
        return 0
    print("DIFFERENT: " + differences[0])
    shown = differences[1:] if "--all" in argv else differences[1:1 + MAX_SHOWN]
    for line in shown:
        print("  " + line)
    if len(differences) - 1 > len(shown):
        print(f"  ... and {len(differences) - 1 - len(shown)} more (--all shows them)")
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
