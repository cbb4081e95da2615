#!/usr/bin/python3
"""Join the observables of a run and its restarts into one file.

Usage: join_observables.py DIR [--out FILE]

A run writes DIR/observables.h5; each continuation with --restart writes
DIR/observables-<step>.h5 with the samples after the checkpoint it started from. This
script concatenates every /observables/<name>/{step, time, value} series in step order
into FILE (default DIR/observables-joined.h5). Where a later file repeats steps (a restart
from an older checkpoint), its samples replace the earlier ones from that step on. Bin
centres, /h5md and the newest /parameters/scene are copied. A result of a whole run (scalar
step, e.g. colloid_vacf, whose sums continue across restarts) is copied whole from the file
of the latest step that has it. Exit code 2 with one line on
stderr if DIR holds no observables file or a file is not HDF5.
"""

import argparse
import glob
import os
import re
import sys

import h5py
import numpy as np


def files_in_order(directory):
    first = os.path.join(directory, "observables.h5")
    later = glob.glob(os.path.join(directory, "observables-[0-9]*.h5"))
    later.sort(key=lambda p: int(re.search(r"observables-(\d+)\.h5$", p).group(1)))
    return ([first] if os.path.isfile(first) else []) + later


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("dir")
    p.add_argument("--out")
    args = p.parse_args(argv[1:])
    out_path = args.out or os.path.join(args.dir, "observables-joined.h5")
    paths = files_in_order(args.dir)
    if not paths:
        print(f"join_observables: {args.dir}: no observables.h5 or observables-<step>.h5",
              file=sys.stderr)
        return 2
    series = {}  # name -> dict(step, time, value, bins)
    results = {}  # name -> (step, path) of the newest result of a whole run
    for path in paths:
        if not h5py.is_hdf5(path):
            print(f"join_observables: {path}: not an HDF5 file", file=sys.stderr)
            return 2
        with h5py.File(path, "r") as f:
            for name, g in f.get("observables", {}).items():
                if g["step"].ndim == 0:
                    if name not in results or g["step"][()] >= results[name][0]:
                        results[name] = (g["step"][()], path)
                    continue
                step, time, value = g["step"][()], g["time"][()], g["value"][()]
                s = series.setdefault(name, {"step": step[:0], "time": time[:0],
                                             "value": value[:0], "bins": None})
                if len(step):  # later samples replace earlier ones from their first step on
                    keep = s["step"] < step[0]
                    s["step"] = np.concatenate([s["step"][keep], step])
                    s["time"] = np.concatenate([s["time"][keep], time])
                    s["value"] = np.concatenate([s["value"][keep], value])
                if "bins" in g:
                    s["bins"] = g["bins"][()]
    with h5py.File(paths[-1], "r") as newest, h5py.File(out_path, "w") as out:
        for group in ("h5md", "parameters"):
            if group in newest:
                newest.copy(group, out)
        obs = out.create_group("observables")
        for name, s in series.items():
            g = obs.create_group(name)
            for key in ("step", "time", "value"):
                g.create_dataset(key, data=s[key])
            if s["bins"] is not None:
                g.create_dataset("bins", data=s["bins"])
        for name, (_, path) in results.items():
            with h5py.File(path, "r") as f:
                f.copy("observables/" + name, obs)
    print(f"join_observables: {len(paths)} files, {len(series)} series, {len(results)} results "
          f"-> {out_path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
