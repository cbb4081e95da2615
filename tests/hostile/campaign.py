#!/usr/bin/python3
"""The hostile-input campaigns of issues 18 and 35 as a test.

Mutates every scene in run/ (keys deleted, values retyped, zero, negative, 1e19, 1e300, NaN,
inf, integers beyond int64, garbage text), feeds whole-file garbage (empty, binary, truncated,
deeply nested, huge arrays, a FIFO), runs `narrows check` on each case and a short `narrows run`
on a sample of the accepted ones, and damages checkpoints of one scene per engine (single bit
flips in dataset data and anywhere in the file, truncation, swapped engines) before
`narrows run --restart`.

The classes of issue 35 (tests/hostile/campaign_models.py): colloid checkpoints (no-slip
colloids without contacts, with hard and with spring contacts) and continuum checkpoints
(Burgers, TASEP, jamming, segregation) written on 1, 2 or 3 ranks and edited into impossible
states (overlaps, radii, masses, positions outside the box or in a wall, speeds, NaN and inf in
every field, non-unit quaternions, fields and rows deleted or added, contacts between bodies that
do not touch, steps and times that disagree, an edited scene; densities outside the model's
range), restarted on 1, 2 or 3 ranks, each to be refused with exit 2, one line, nothing in
--out; extreme model values (colloids.spring.*, the keys of hard-contact and no-slip scenes,
continuum.*: 0, -1, 1e300, 5e-324, nan, inf) through `check` and a short run; and SIGTERM early
(0-0.5 s after main() installed its handlers: in MPI_Init) or late (inside the loop) into runs of
every engine, no-slip, hard, spring and continuum scenes on 1-3 ranks, each to end with exit 0
within 20 s.

Fails on: any exit other than 0, 2 or 3; death by a signal; a run over its budget (a SIGTERM is
sent at the budget, and a run that has not ended a grace period later is a hang); a restart from
a checkpoint whose data were damaged that is not refused (exit 2); an impossible state restarted
from (exit 0) or not refused before the first step (exit 3); a refusal of more than one line or
with files in --out.

Usage: campaign.py NARROWS SOURCE_DIR [--full] [--seed N] [--jobs J] [--classes all|old|new]
  quick (default): 60 of the ~6000 scene mutations, 6 short runs, 3 data bit flips per
  checkpoint and 4 in /colloid/* of the lgca colloid checkpoint; of issue 35's classes a
  hard-contact, a spring-contact, a Burgers and a segregation checkpoint with 2-3 edits each and
  its untouched control, 4 extreme values, 2 signals (67 s on 2 busy cores; the ctest);
  --full: 1000 scene mutations, 120 short runs, 25 data bit flips per checkpoint (125 over the
  five: mpcd, mpcd with colloids, lgca, lgca with a colloid, kmc) and 100 in /colloid/*; every
  edit of issue 35's classes on checkpoints of 8 scenes each written on 1, 2 and 3 ranks (each
  edit restarted on 1, 2 and 3 ranks over the three; two thirds of the edits on each), 770
  extreme values through check (and a short run of each accepted one), 120 signals. --seed
  picks another sample; --classes new runs issue 35's classes alone.
Prints the counts: of issue 18's classes cases, refused, accepted, invariant stops, stopped at
the budget, crashes, hangs, damaged restarts not refused; of each of issue 35's classes (and per
rank count) cases, refused, accepted, invariant stops, crashes, hangs, impossible accepted.
"""
import argparse
import concurrent.futures as cf
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import tomllib

import h5py

import campaign_models

VALUES = ["0", "-1", "1e19", "1e300", "-1e300", "1e-300", "nan", "inf", '"garbage"', "true",
          "[]", "[1e300, 1e300, 1e300]", "99999999999999999999", "{ a = 1 }"]


def leaves(table, prefix=""):
    """(dotted key, value) of every scalar or array below the sections of a scene."""
    for k, v in table.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            yield from leaves(v, key + ".")
        elif prefix:
            yield key, v


def set_line(text, section, key, value):
    """The scene text with `key = value` in [section] replaced (value None: the line deleted);
    None if the key is not on a line of its own (inline tables, multi-line arrays)."""
    lines = text.split("\n")
    current = None
    for i, line in enumerate(lines):
        head = re.match(r"\s*\[([^\[\]]+)\]\s*(#.*)?$", line)
        if head:
            current = head.group(1).strip()
            continue
        m = re.match(r"(\s*)([A-Za-z0-9_\-\"]+)\s*=\s*(.*)$", line)
        if current == section and m and m.group(2).strip('"') == key:
            rest = m.group(3)
            if rest.startswith("[") and rest.count("[") != rest.count("]"):
                return None  # multi-line array
            lines[i] = None if value is None else f"{m.group(1)}{key} = {value}"
            return "\n".join(l for l in lines if l is not None)
    return None


def scene_cases(src):
    """(name, text) of every mutated scene."""
    cases = []
    for path in sorted(os.listdir(os.path.join(src, "run"))):
        if not path.endswith(".toml"):
            continue
        text = open(os.path.join(src, "run", path), encoding="utf-8").read()
        data = tomllib.loads(text)
        for dotted, _ in leaves(data):
            parts = dotted.split(".")
            section, key = ".".join(parts[:-1]), parts[-1]
            for value in [None] + VALUES:
                t = set_line(text, section, key, value)
                if t is not None:
                    label = "deleted" if value is None else value
                    cases.append((f"{path}: {dotted} = {label}", t, path))
        # whole-file damage of this scene
        cases.append((f"{path}: first half", text[: len(text) // 2], path))
        cases.append((f"{path}: a NUL byte", text[:40] + "\0" + text[40:], path))
    return cases


def garbage_cases():
    rng = random.Random(1)
    return [
        ("empty file", "", None),
        ("only comments", "# nothing\n", None),
        ("random bytes", bytes(rng.randrange(256) for _ in range(4000)).decode("latin-1"), None),
        ("5000 nested inline tables", "a = " + "{b = " * 5000 + "1" + "}" * 5000 + "\n", None),
        ("5000 nested arrays", "a = " + "[" * 5000 + "]" * 5000 + "\n", None),
        ("1e5 nested tables", "[" + ".".join(["a"] * 100000) + "]\n", None),
        ("1e5 dotted keys", ".".join(["a"] * 100000) + " = 1\n", None),
        ("array of 1e5 numbers", "[run]\nengine = \"mpcd\"\n[domain]\nsize = [" +
         ", ".join(["1.0"] * 100000) + "]\n", None),
        ("20 MB of spaces", " " * (20 << 20) + "\n", None),
    ]


class Tally:
    def __init__(self):
        self.counts = {k: 0 for k in ["cases", "refused", "accepted", "invariant", "stopped",
                                      "crash", "hang", "damaged accepted"]}
        self.failures = []
        self.verbose = False

    def add(self, name, outcome, detail=""):
        if self.verbose:
            print(f"{outcome:10} {name} {detail}".rstrip(), flush=True)
        self.counts["cases"] += 1
        self.counts[outcome] += 1
        if outcome in ("crash", "hang", "damaged accepted", "stopped"):
            self.failures.append(f"{outcome}: {name} {detail}".strip())


def run(cmd, budget, grace=15.0, cwd=None):
    """(outcome, exit code, seconds, stderr tail): outcome refused/accepted/invariant/stopped/
    crash/hang (campaign_models.execute, with the last stderr line only)."""
    outcome, code, seconds, lines = campaign_models.execute(cmd, budget, grace, cwd)
    return outcome, code, seconds, lines[-1] if lines else ""


def shorten(scene_name, mutated_key):
    """--set overrides that keep a run short, leaving the mutated key alone."""
    out = []
    if scene_name.startswith(("kmc", "tasep")):
        for key, value in [("kmc.replicas", "2"), ("kmc.time", "2.0"), ("kmc.warmup", "0.0")]:
            if key != mutated_key:
                out += ["--set", f"{key}={value}"]
    elif mutated_key != "run.steps":
        out += ["--set", "run.steps=3"]
    return out


def flip_bit(path, byte, bit):
    with open(path, "r+b") as f:
        f.seek(byte)
        b = f.read(1)[0]
        f.seek(byte)
        f.write(bytes([b ^ (1 << bit)]))


def data_ranges(path):
    """(name, offset, size) of the stored bytes of every dataset of an HDF5 file."""
    out = []

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            off = obj.id.get_offset()
            size = obj.id.get_storage_size()
            if off is not None and size > 0:
                out.append((name, off, size))

    with h5py.File(path, "r") as f:
        f.visititems(visit)
    return out


def old_classes(a, narrows, rng, tally, tmp):
    """Issue 18's classes: scene mutations and garbage through check and short runs, the
    FIFO, damaged checkpoints."""
    cases = scene_cases(a.src)
    cases = rng.sample(cases, 1000 if a.full else 60)
    cases += garbage_cases()

    # ---- check on every case, a short run on a sample of the accepted ones ----
    def one(i, name, text, scene):
        path = os.path.join(tmp, f"case{i}.toml")
        with open(path, "w", encoding="utf-8", errors="surrogateescape") as f:
            f.write(text)
        results = [("check " + name, *run([narrows, "check", path], 20.0))]
        return path, results

    accepted = []
    with cf.ThreadPoolExecutor(a.jobs) as pool:
        futures = [pool.submit(one, i, *c) for i, c in enumerate(cases)]
        for fut, case in zip(futures, cases):
            path, results = fut.result()
            for name, outcome, code, seconds, tail in results:
                tally.add(name, outcome, f"(exit {code}, {seconds:.1f} s) {tail}")
                if outcome == "accepted" and case[2] is not None:
                    accepted.append((case, path))
    runs = rng.sample(accepted, min(120 if a.full else 6, len(accepted)))
    budget = 30.0 if a.full else 15.0

    def short_run(case, path):
        name, _, scene = case
        key = name.split(": ", 1)[1].split(" = ")[0]
        out = tempfile.mkdtemp(prefix="run-", dir=tmp)
        cmd = [narrows, "run", path, "--out", out] + shorten(scene, key)
        return ("run " + name, *run(cmd, budget))

    with cf.ThreadPoolExecutor(a.jobs) as pool:
        for name, outcome, code, seconds, tail in pool.map(lambda c: short_run(*c), runs):
            tally.add(name, outcome, f"(exit {code}, {seconds:.1f} s) {tail}")

    # FIFO as the scene: refused, not a hang
    fifo = os.path.join(tmp, "scene.fifo")
    os.mkfifo(fifo)
    tally.add("check FIFO", run([narrows, "check", fifo], 10.0)[0])

    # ---- damaged checkpoints ----
    flips = a.flips if a.flips is not None else (25 if a.full else 3)
    engines = ["quickstart.toml", "colloids_conservation.toml", "lgca_shear_wave.toml",
               "lgca_colloid_moving.toml", "kmc_family1_product.toml"]
    # flips in the disc's state and averages of the lgca colloid checkpoint only (/colloid/*)
    colloid_flips = a.colloid_flips if a.colloid_flips is not None else \
        (100 if a.full else 4)
    good = {}
    short_scene = {}  # the scene of each checkpoint, shortened in its text
    for scene in engines:
        out = os.path.join(tmp, "ckpt-" + scene)
        text = open(os.path.join(a.src, "run", scene), encoding="utf-8").read()
        edits = shorten(scene, "")
        for k in range(1, len(edits), 2):
            key, value = edits[k].split("=")
            section, name = key.rsplit(".", 1)
            text = set_line(text, section, name, value) or text
        short_scene[scene] = os.path.join(tmp, "short-" + scene)
        with open(short_scene[scene], "w", encoding="utf-8") as f:
            f.write(text)
        outcome, code, _, tail = run([narrows, "run", short_scene[scene], "--out", out],
                                     60.0)
        ckpts = sorted(f for f in os.listdir(out) if f.startswith("checkpoint-")) \
            if os.path.isdir(out) else []
        if outcome != "accepted" or not ckpts:
            tally.add("checkpoint of " + scene, "crash", f"(exit {code}) {tail}")
            continue
        good[scene] = os.path.join(out, ckpts[-1])

    def restart(scene, ckpt, label, must_refuse):
        out = tempfile.mkdtemp(prefix="restart-", dir=tmp)
        src_scene = short_scene[scene]
        # one step (kmc: two replicas) beyond the checkpoint, else "nothing to run" answers
        # before the data are read
        extra = ["--set", "run.steps=6"] if not scene.startswith("kmc") else \
            ["--set", "kmc.replicas=4"]
        outcome, code, seconds, tail = run([narrows, "run", src_scene, "--restart", ckpt,
                                            "--out", out] + extra, budget)
        shutil.rmtree(out, ignore_errors=True)
        if must_refuse and outcome != "refused" and outcome not in ("crash", "hang"):
            outcome = "damaged accepted"
        if must_refuse is None and outcome != "accepted":  # the control: must continue
            outcome = "crash"
        return (f"restart {scene} from {label}", outcome, f"(exit {code}) {tail}")

    jobs = []

    def data_flip(scene, ckpt, ranges, label):
        """A copy of ckpt with a bit of a dataset's stored data flipped: must be refused."""
        name, off, length = rng.choice(ranges)
        byte, bit = off + rng.randrange(length), rng.randrange(8)
        bad = os.path.join(tmp, label + ".h5")
        shutil.copy(ckpt, bad)
        flip_bit(bad, byte, bit)
        jobs.append((scene, bad, f"bit {bit} of byte {byte} ({name})", True))

    for scene, ckpt in good.items():
        jobs.append((scene, ckpt, "its undamaged checkpoint", None))
    for n, (scene, ckpt) in enumerate(good.items()):
        ranges = data_ranges(ckpt)
        size = os.path.getsize(ckpt)
        for k in range(flips):
            data_flip(scene, ckpt, ranges, f"flip{n}-{k}")
            # a bit anywhere (may be unused space): no crash, no hang
            bad = os.path.join(tmp, f"any{n}-{k}.h5")
            shutil.copy(ckpt, bad)
            byte = rng.randrange(min(size, 1 << 16) if k % 2 else size)
            flip_bit(bad, byte, rng.randrange(8))
            jobs.append((scene, bad, f"a bit of byte {byte} anywhere", False))
        colloid = [r for r in ranges if r[0].startswith("colloid/")]
        for k in range(colloid_flips if colloid else 0):
            data_flip(scene, ckpt, colloid, f"colloid{n}-{k}")
        cut = os.path.join(tmp, f"cut{n}.h5")
        with open(ckpt, "rb") as f, open(cut, "wb") as g:
            g.write(f.read(size // 2))
        jobs.append((scene, cut, "the first half", True))
    # swapped engines: every checkpoint under every other engine's scene
    for scene in good:
        for other, ckpt in good.items():
            if other != scene:
                jobs.append((scene, ckpt, "a checkpoint of " + other, True))
    with cf.ThreadPoolExecutor(a.jobs) as pool:
        for name, outcome, detail in pool.map(lambda j: restart(*j), jobs):
            tally.add(name, outcome, detail)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("narrows")
    ap.add_argument("src")
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--seed", type=int, default=18)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--flips", type=int, default=None, help="data bit flips per checkpoint")
    ap.add_argument("--colloid-flips", type=int, default=None,
                    help="data bit flips in /colloid/* of the lgca colloid checkpoint")
    ap.add_argument("--verbose", action="store_true", help="print every case")
    ap.add_argument("--classes", choices=["all", "old", "new"], default="all",
                    help="old: issue 18's classes only; new: issue 35's only")
    a = ap.parse_args()
    narrows = os.path.abspath(a.narrows)
    rng = random.Random(a.seed)
    tally = Tally()
    tally.verbose = a.verbose
    tmp = tempfile.mkdtemp(prefix="narrows-campaign-")
    os.environ.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
    # hwloc's PCI scan makes each MPI start 1.7 s here instead of 0.8 s. (Isolated singletons,
    # OMPI_MCA_ess_singleton_isolated, would start faster but share one job id, and parallel
    # cases then collide in MPI-IO.)
    os.environ.setdefault("HWLOC_COMPONENTS", "-linuxio,-pci,-opencl,-cuda,-nvml,-gl")
    # As the ctest sets them (tests/CMakeLists.txt, QUICK_MPI_START): without the SIGKILL grace
    # mpirun returns 0.3 s after a refusal on N ranks instead of 2.4 s. (The signals class sends
    # SIGTERM to the ranks, not to mpirun.)
    os.environ.setdefault("OMPI_MCA_pml", "ob1")
    os.environ.setdefault("OMPI_MCA_odls_base_sigkill_timeout", "0")
    new = None
    try:
        if a.classes != "new":
            old_classes(a, narrows, rng, tally, tmp)
        if a.classes != "old":
            with cf.ThreadPoolExecutor(a.jobs) as pool:
                new = campaign_models.campaign(
                    narrows, a.src, tmp, rng, a.full, a.jobs, a.verbose,
                    lambda fn, items: pool.map(fn, items))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    c = tally.counts
    if a.classes != "new":
        print(f"campaign ({'full' if a.full else 'quick'}), issue 18's classes: {c['cases']} cases, "
              f"{c['refused']} refused, {c['accepted']} accepted, {c['invariant']} invariant "
              f"stops, {c['stopped']} stopped at the budget, {c['crash']} crashes, {c['hang']} "
              f"hangs, {c['damaged accepted']} damaged checkpoints not refused")
    failures = list(tally.failures)
    if new is not None:
        print(f"campaign ({'full' if a.full else 'quick'}), issue 35's classes: {new.total()} "
              f"cases")
        for line in new.report():
            print(line)
        failures += new.failures
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0

if __name__ == "__main__":
    sys.exit(main())
