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
import os
import sys

import narrows_h5


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("dir")
    p.add_argument("--out")
    args = p.parse_args(argv[1:])
    out_path = args.out or os.path.join(args.dir, narrows_h5.JOINED)
    paths = narrows_h5.chain_files(args.dir)
    if not paths:  # not open_run: the joined file itself is no input here
        raise narrows_h5.NarrowsDataError(os.path.join(args.dir, narrows_h5.OBSERVABLES),
                                          "not found", "a run folder with observables.h5 or "
                                          "observables-<step>.h5")
    run = narrows_h5.open_run(args.dir, chain=True)
    series, results = run.write_joined(out_path)
    print(f"join_observables: {len(paths)} files, {series} series, {results} results "
          f"-> {out_path}")
    return 0


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("join_observables", main, sys.argv))
