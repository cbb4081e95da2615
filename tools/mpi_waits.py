#!/usr/bin/env python3
"""Names the call sites of tools/mpi_waits.c's files and prints, per rank, where the run spent
its seconds in blocking MPI calls (waiting included), the largest first.

    mpicc -shared -fPIC -O2 -o mpi_waits.so tools/mpi_waits.c
    MPI_WAITS_OUT=/tmp/waits mpirun -n 2 -x LD_PRELOAD=$PWD/mpi_waits.so -x MPI_WAITS_OUT \\
        build/narrows run run/pulses_table6_1.toml --set run.steps=200
    /usr/bin/python3 tools/mpi_waits.py /tmp/waits.* [--steps 200] [--top 8]

Each row: seconds (per step with --steps), calls, the MPI call, and the nearest callers in the
program (addr2line's function names, without arguments), innermost first."""
import argparse
import re
import subprocess
import sys


def function_names(frames):
    """{"module+0xoffset": function name} for the frames, one addr2line call per module."""
    offsets = {}
    for frame in frames:
        module, _, off = frame.rpartition("+")
        if module:
            offsets.setdefault(module, set()).add(off)
    found = {}
    for module, offs in offsets.items():
        offs = sorted(offs)
        try:
            out = subprocess.run(["addr2line", "-f", "-C", "-e", module, *offs],
                                 capture_output=True, text=True, check=True).stdout.splitlines()
        except (OSError, subprocess.CalledProcessError) as e:
            sys.exit(f"mpi_waits.py: addr2line on {module} failed: {e}")
        for off, name in zip(offs, out[0::2]):
            found[f"{module}+{off}"] = name
    return found


def short(name):
    """A C++ name without argument lists, templates, lambdas' signatures or namespaces."""
    name = re.sub(r"\{lambda\([^)]*\)#(\d+)\}", r"lambda#\1", name)
    depth, kept = 0, []
    for ch in name:  # drop <...> and (...)
        if ch in "<(":
            depth += 1
        elif ch in ">)":
            depth -= 1
        elif depth == 0:
            kept.append(ch)
    name = "".join(kept)
    return "::".join(p for p in name.split("::") if p not in ("narrows", "std", "")
                     and not p.startswith("_"))[-60:]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+", help="MPI_WAITS_OUT.<rank> files")
    ap.add_argument("--steps", type=float, default=0, help="divide by this many steps")
    ap.add_argument("--top", type=int, default=8, help="rows per rank")
    a = ap.parse_args()
    for path in sorted(a.files):
        rows = []
        try:
            lines = open(path).read().splitlines()
        except OSError as e:
            sys.exit(f"mpi_waits.py: {path}: {e.strerror}")
        for line in lines:
            f = line.split()
            try:
                rows.append((float(f[0]), int(f[1]), f[2], f[3:]))
            except (IndexError, ValueError):
                sys.exit(f"mpi_waits.py: {path}: line '{line}': expected 'seconds calls call "
                         "callers...'")
        name = function_names(c for row in rows for c in row[3])
        rows.sort(key=lambda r: -r[0])
        total = sum(r[0] for r in rows)
        per = a.steps if a.steps > 0 else 1.0
        unit = "ms per step" if a.steps > 0 else "s"
        scale = 1e3 if a.steps > 0 else 1.0
        print(f"{path}: {total * scale / per:.4g} {unit} in blocking MPI calls over {len(rows)} call sites")
        for sec, calls, call, callers in rows[:a.top]:
            chain = []
            for c in callers:
                module = c.rpartition("+")[0]
                if not module or module.endswith("mpi_waits.so") or "libmpi" in module:
                    continue
                n = short(name[c])
                if n and n != "??" and (not chain or chain[-1] != n):
                    chain.append(n)
            print(f"  {sec * scale / per:9.4f} {calls / per:8.3g} {call:10s} {' < '.join(chain[:4])}")


if __name__ == "__main__":
    main()
