#!/usr/bin/python3
"""A parameter sweep of one scene: a grid of --set values times --repeats seeds, run locally
(resumable) or as a SLURM array job, with each run's results collected into one table.

  sweep.py SCENE --out DIR [--set KEY=V1,V2,...]... [--repeats N] [--seed-key run.seed]
           [--seed0 S] [--jobs J] [--mpi K] [--narrows PATH]
           [--collect "TOOL [ARGS]"] [--collect-json NAME]
  sweep.py SCENE --out DIR ... --slurm [--slurm-file F] [--slurm-time 24:00:00] [--chain-max 50]

Points: every combination of the --set values (commas inside [] or {} or quotes do not split:
--set domain.size=[200.0,50.0],[400.0,50.0]; KEY1+KEY2=V1,V2 gives both keys each value, e.g.
colloids.spring.mu_cc+colloids.spring.mu_cw=0.5,1.0 for mu = mu_cc = mu_cw) times the repeats; repeat r (0-based) sets
SEED_KEY = S + r (S: --seed0, default the scene's value of SEED_KEY, else 1). Point i runs in
DIR/pNNNN-KEY=V-...-rR (KEY: the last part of the key path); DIR/sweep.json lists the points
(a later call with another grid into the same DIR is refused).

Locally: J points at a time (`narrows run SCENE --set ... --out POINT`, with --mpi K: `mpirun
--oversubscribe -n K narrows ...`), the output of each in POINT/sweep-<n>.out. A point is
finished when narrows exited 0 without being stopped by a signal (or said "nothing to run"):
the sweep writes POINT/DONE. A later call skips finished points and continues an unfinished
point that has a checkpoint with `--restart POINT` (a point without checkpoint starts afresh).
SIGTERM or SIGINT to the sweep passes SIGTERM on to the running points (narrows writes a
checkpoint and stops) and ends the sweep: the same command resumes it. DIR/sweep.lock keeps a
second sweep out of DIR while one runs; a point whose narrows (POINT/sweep.pid) still runs, e.g.
after the sweep was killed with SIGKILL, is left alone. One progress line per
point; exit 0 if every point finished, 1 otherwise.

--collect TOOL: for every finished point, `TOOL [ARGS] POINT` (a .py tool runs under this
Python) and its JSON (--collect-json NAME in POINT, default the tool's name with .json, or
vss.json for vss_fit.py; else the one JSON file the tool wrote) goes into one row of
DIR/table.csv and DIR/table.h5 (/table/<column>), with the point, repeat, seed and the --set
values (columns named by their keys) first; nested JSON objects are flattened with dots, lists
are left out.

--slurm writes a SLURM array job instead of running (default jobscripts/sweep-<DIR's name>.slurm):
one array index per point, named in a case statement; each job skips a finished point,
continues from the point's newest checkpoint (narrows run --restart, README "Checkpoints and
restart"), stops cleanly on SIGUSR1 five minutes before its time limit, and resubmits its own
index until the point is finished (at most --chain-max jobs), then writes POINT/DONE. Submit it
from the directory the sweep was written in; collect afterwards with the same sweep command
and --collect (every point is then skipped).
"""

import argparse
import csv
import glob
import itertools
import json
import os
import re
import shlex
import signal
import subprocess
import sys
import time

import narrows_h5
from continuum_run import find_narrows

DONE = "DONE"
STOPPED = re.compile(r"received SIG\w+: stopped")
NOTHING = "nothing to run"


class InputError(Exception):
    """A bad command line."""


def split_values(text):
    """V1,V2,... split at commas outside brackets, braces and quotes."""
    out, depth, quote, cur = [], 0, None, ""
    for ch in text:
        if quote:
            quote = None if ch == quote else quote
        elif ch in "\"'":
            quote = ch
        elif ch in "[{":
            depth += 1
        elif ch in "]}":
            depth -= 1
        elif ch == "," and depth == 0:
            out.append(cur)
            cur = ""
            continue
        cur += ch
    out.append(cur)
    return [v.strip() for v in out]


def parse_sets(sets):
    """[(key, [values])] of the --set arguments."""
    grid = []
    for s in sets:
        key, eq, values = s.partition("=")
        key = key.strip()
        if not eq or not key or not values.strip():
            raise InputError(f"--set {s!r}; allowed: KEY=V1,V2,... (e.g. "
                             "colloids.packing_fraction=0.74,0.75)")
        vals = split_values(values)
        if any(v == "" for v in vals):
            raise InputError(f"--set {s!r}: an empty value; allowed: KEY=V1,V2,...")
        if key in [k for k, _ in grid]:
            raise InputError(f"--set {key} given twice; allowed: one --set per key")
        grid.append((key, vals))
    return grid


def lookup(scene, key):
    node = scene
    for part in key.split("."):
        if not isinstance(node, dict) or part not in node:
            return None
        node = node[part]
    return node


def safe(text):
    return re.sub(r"[^A-Za-z0-9_.+-]", "_", text)


def make_points(grid, repeats, seed_key, seed0):
    points = []
    for values in itertools.product(*[vals for _, vals in grid]):
        for r in range(repeats):
            i = len(points)
            sets = {k: v for (k, _), v in zip(grid, values)}
            name = "-".join([f"p{i:04d}"] + [f"{safe(k.split('+')[0].split('.')[-1])}={safe(v)}"
                                              for k, v in sets.items()] + [f"r{r}"])
            points.append({"index": i, "name": name, "sets": sets, "repeat": r,
                           "seed": seed0 + r})
    return points


def point_args(point, seed_key):
    args = []
    for keys, v in point["sets"].items():
        for k in keys.split("+"):  # KEY1+KEY2=...: both keys take each value
            args += ["--set", f"{k}={v}"]
    return args + ["--set", f"{seed_key}={point['seed']}"]


def checkpoints(run_dir):
    return sorted(glob.glob(os.path.join(glob.escape(run_dir), "checkpoint-[0-9]*.h5")))


def manifest(args, grid, points):
    return {"scene": os.path.abspath(args.scene), "sets": [[k, v] for k, v in grid],
            "repeats": args.repeats, "seed_key": args.seed_key,
            "points": [{k: p[k] for k in ("index", "name", "sets", "repeat", "seed")}
                       for p in points]}


def write_manifest(out, m):
    path = os.path.join(out, "sweep.json")
    if os.path.isfile(path):
        with open(path) as f:
            old = json.load(f)
        if old.get("points") != m["points"] or old.get("scene") != m["scene"]:
            raise InputError(f"{path}: another sweep (scene or grid) lives in {out}; "
                             "allowed: the same scene, --set, --repeats and seeds, or another --out")
    os.makedirs(out, exist_ok=True)
    with open(path, "w") as f:
        json.dump(m, f, indent=1)


# ---- running -------------------------------------------------------------------------------


class Sweep:
    def __init__(self, args, points, narrows):
        self.args, self.points, self.narrows = args, points, narrows
        self.running = {}  # index -> (Popen, start time, how, log path)
        self.stopping = False
        self.finished = 0
        self.failed = []

    def dir(self, p):
        return os.path.join(self.args.out, p["name"])

    def is_done(self, p):
        return os.path.isfile(os.path.join(self.dir(p), DONE))

    def progress(self, p, text):
        n = len(self.points)
        print(f"[{p['index'] + 1}/{n}] {p['name']}: {text}", flush=True)

    def command(self, p):
        d = self.dir(p)
        cmd = [self.narrows, "run", os.path.abspath(self.args.scene)] + point_args(p, self.args.seed_key)
        how = "fresh"
        if checkpoints(d):
            cmd += ["--restart", d]
            how = f"restarted from {os.path.basename(checkpoints(d)[-1])}"
        cmd += ["--out", d]
        if self.args.mpi > 1:
            cmd = ["mpirun", "--oversubscribe", "-n", str(self.args.mpi)] + cmd
            if os.geteuid() == 0:
                cmd.insert(1, "--allow-run-as-root")
        return cmd, how

    def start(self, p):
        d = self.dir(p)
        os.makedirs(d, exist_ok=True)
        alive = running_pid(os.path.join(d, "sweep.pid"))
        if alive:
            self.progress(p, f"still run by process {alive} (an earlier sweep's): left alone")
            return
        cmd, how = self.command(p)
        n = len(glob.glob(os.path.join(glob.escape(d), "sweep-*.out")))
        log = os.path.join(d, f"sweep-{n}.out")
        with open(log, "w") as f:
            f.write("$ " + " ".join(shlex.quote(c) for c in cmd) + "\n")
            f.flush()
            proc = subprocess.Popen(cmd, stdout=f, stderr=subprocess.STDOUT,
                                    start_new_session=True)
        with open(os.path.join(d, "sweep.pid"), "w") as f:
            f.write(f"{proc.pid}\n")
        self.running[p["index"]] = (proc, time.time(), how, log)

    def reap(self, p, code):
        proc, t0, how, log = self.running.pop(p["index"])
        os.remove(os.path.join(self.dir(p), "sweep.pid"))
        with open(log) as f:
            text = f.read()
        seconds = time.time() - t0
        if code == 0 and (NOTHING in text or not STOPPED.search(text)):
            with open(os.path.join(self.dir(p), DONE), "w") as f:
                f.write(time.strftime("%Y-%m-%d %H:%M:%S\n"))
            self.finished += 1
            self.progress(p, f"done in {seconds:.1f} s ({how})")
            if self.args.collect:
                self.collect_one(p)
        elif code == 0:
            self.progress(p, f"stopped by a signal after {seconds:.1f} s ({how}); "
                             "a checkpoint is written: the same command continues it")
        else:
            self.failed.append(p["name"])
            last = text.strip().splitlines()[-1] if text.strip() else ""
            self.progress(p, f"FAILED with exit {code} after {seconds:.1f} s: {last} (see {log})")

    def stop(self, signum, _frame):
        if not self.stopping:
            print(f"sweep: received {signal.Signals(signum).name}: stopping the running points "
                  "(each writes a checkpoint)", flush=True)
        self.stopping = True
        for proc, *_ in self.running.values():
            if proc.poll() is None:
                try:
                    os.killpg(proc.pid, signal.SIGTERM)
                except ProcessLookupError:
                    pass

    def run(self):
        lock = os.path.join(self.args.out, "sweep.lock")
        other = running_pid(lock)
        if other and other != os.getpid():
            return narrows_h5.report("sweep", f"{lock}: another sweep (process {other}) runs "
                                     f"in {self.args.out}; allowed: wait for it, or stop it")
        with open(lock, "w") as f:
            f.write(f"{os.getpid()}\n")
        try:
            return self.run_points()
        finally:
            os.remove(lock)

    def run_points(self):
        signal.signal(signal.SIGTERM, self.stop)
        signal.signal(signal.SIGINT, self.stop)
        todo = []
        for p in self.points:
            if self.is_done(p):
                self.finished += 1
                self.progress(p, "finished before: skipped")
            else:
                todo.append(p)
        while (todo and not self.stopping) or self.running:
            while todo and not self.stopping and len(self.running) < self.args.jobs:
                self.start(todo.pop(0))
            time.sleep(0.1)
            for i in list(self.running):
                code = self.running[i][0].poll()
                if code is not None:
                    self.reap(self.points[i], code)
        if self.args.collect:
            for p in self.points:
                if self.is_done(p) and self.json_path(p) is None:
                    self.collect_one(p)
            self.write_table()
        left = len(self.points) - self.finished
        print(f"sweep: {self.finished} of {len(self.points)} points finished"
              + (f", {len(self.failed)} failed" if self.failed else "")
              + (f"; {left} left: run the same command to continue" if left else ""), flush=True)
        return 0 if left == 0 else 1

    # ---- collecting ----

    def tool_command(self, p):
        words = shlex.split(self.args.collect)
        if words[0].endswith(".py"):
            words = [sys.executable] + words
        return words + [self.dir(p)]

    def json_name(self):
        if self.args.collect_json:
            return self.args.collect_json
        words = shlex.split(self.args.collect)
        base = os.path.basename(words[0])
        return "vss.json" if base == "vss_fit.py" else os.path.splitext(base)[0] + ".json"

    def json_path(self, p):
        path = os.path.join(self.dir(p), self.json_name())
        return path if os.path.isfile(path) and os.path.getmtime(path) >= os.path.getmtime(
            os.path.join(self.dir(p), DONE)) else None

    def collect_one(self, p):
        before = time.time()
        done = subprocess.run(self.tool_command(p), capture_output=True, text=True)
        if done.returncode != 0:
            last = (done.stderr.strip() or done.stdout.strip()).splitlines()
            self.progress(p, f"--collect failed (exit {done.returncode}): "
                             f"{last[-1] if last else ''}")
            return
        path = os.path.join(self.dir(p), self.json_name())
        if not os.path.isfile(path) and not self.args.collect_json:
            new = [q for q in glob.glob(os.path.join(glob.escape(self.dir(p)), "*.json"))
                   if os.path.getmtime(q) >= before - 1]
            if len(new) == 1:
                os.replace(new[0], path)
        if not os.path.isfile(path):
            self.progress(p, f"--collect wrote no {self.json_name()}")

    def write_table(self):
        rows = []
        keys = [k for k, _ in parse_sets(self.args.set)]
        for p in self.points:
            path = os.path.join(self.dir(p), self.json_name())
            if not (self.is_done(p) and os.path.isfile(path)):
                continue
            with open(path) as f:
                data = flatten(json.load(f))
            row = {"point": p["index"], "name": p["name"], "repeat": p["repeat"],
                   self.args.seed_key: p["seed"]}
            row.update({k: number_or_text(p["sets"][k]) for k in keys})
            for k, v in data.items():
                row.setdefault(k, v)
            rows.append(row)
        if not rows:
            print("sweep: nothing collected yet")
            return
        columns = list(dict.fromkeys(k for r in rows for k in r))
        csv_path = os.path.join(self.args.out, "table.csv")
        with open(csv_path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=columns)
            w.writeheader()
            for r in rows:
                w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in columns})
        h5_path = os.path.join(self.args.out, "table.h5")
        narrows_h5.write_table(h5_path, {k: [r.get(k) for r in rows] for k in columns})
        print(f"sweep: {len(rows)} rows in {csv_path} and {h5_path}")


def running_pid(path):
    """The process id in the file at path if that process still runs, else None."""
    try:
        with open(path) as f:
            pid = int(f.read().split()[0])
        os.kill(pid, 0)
        return pid
    except (OSError, ValueError, IndexError):
        return None


def number_or_text(value):
    try:
        return int(value)
    except ValueError:
        try:
            return float(value)
        except ValueError:
            return value.strip('"')


def flatten(obj, prefix=""):
    """Scalars of a JSON object, nested keys joined with dots (lists left out)."""
    out = {}
    for k, v in obj.items():
        if isinstance(v, dict):
            out.update(flatten(v, prefix + k + "."))
        elif not isinstance(v, list):
            out[prefix + k] = v
    return out


# ---- SLURM ---------------------------------------------------------------------------------


def slurm_script(args, points, path):
    rel = lambda p: os.path.relpath(p)  # noqa: E731  (relative to the submit directory)
    lines = [
        "#!/bin/bash",
        f"# Written by tools/sweep.py: {len(points)} points of {rel(args.scene)} into {rel(args.out)}",
        "# (one array index per point). Submit from the directory it was written in:",
        f"#   sbatch {rel(path)}",
        "# Each job skips a finished point (POINT/DONE), continues the point's newest checkpoint",
        "# (--restart), stops cleanly on SIGUSR1 before the time limit and resubmits its own index",
        "# until the point is finished; then it writes POINT/DONE. Collect the results with the",
        "# sweep command and --collect afterwards.",
        f"#SBATCH --job-name=sweep-{safe(os.path.basename(os.path.abspath(args.out)))}",
        f"#SBATCH --array=0-{len(points) - 1}",
        f"#SBATCH --ntasks={args.mpi}",
        f"#SBATCH --time={args.slurm_time}",
        "#SBATCH --signal=USR1@300",
        # in the submission folder: SLURM opens it before the script runs, and the sweep's own
        # folder need not exist yet on a fresh checkout
        f"#SBATCH --output=slurm-sweep-{safe(os.path.basename(os.path.abspath(args.out)))}"
        "-%A_%a.out",
        "set -euo pipefail",
        'cd "${SLURM_SUBMIT_DIR:-.}"',
        f"NARROWS=${{NARROWS:-{shlex.quote(rel(args.narrows_path))}}}",
        f"SCENE={shlex.quote(rel(args.scene))}",
        f"CHAIN_MAX=${{CHAIN_MAX:-{args.chain_max}}}",
        "CHAIN_INDEX=${CHAIN_INDEX:-1}",
        f"SCRIPT={shlex.quote(rel(path))}",
        'case "${SLURM_ARRAY_TASK_ID:?run it with sbatch: an array job}" in',
    ]
    for p in points:
        sets = " ".join(shlex.quote(a) for a in point_args(p, args.seed_key))
        lines.append(f"  {p['index']}) OUT={shlex.quote(rel(os.path.join(args.out, p['name'])))}; "
                     f"SETS=({sets}) ;;")
    lines += [
        '  *) echo "no point $SLURM_ARRAY_TASK_ID in this sweep"; exit 2 ;;',
        "esac",
        f'if [ -f "$OUT/{DONE}" ]; then echo "$OUT: finished before"; exit 0; fi',
        'mkdir -p "$OUT"',
        "restart=()",
        'if compgen -G "$OUT/checkpoint-[0-9]*.h5" > /dev/null; then restart=(--restart "$OUT"); fi',
        "if command -v srun > /dev/null 2>&1; then launcher=(srun)",
        f"elif [ {args.mpi} -gt 1 ]; then launcher=(mpirun --oversubscribe -n {args.mpi})",
        "else launcher=(); fi",
        'log="$OUT/sweep-slurm-${SLURM_JOB_ID:-local}-$CHAIN_INDEX.out"',
        'echo "job ${SLURM_JOB_ID:-local} (chain $CHAIN_INDEX of at most $CHAIN_MAX): $OUT ${restart[*]:-fresh start}"',
        "set +e",
        '"${launcher[@]}" "$NARROWS" run "$SCENE" "${SETS[@]}" "${restart[@]}" --out "$OUT" > "$log" 2>&1',
        "code=$?",
        "set -e",
        'cat "$log"',
        'if [ "$code" -ne 0 ]; then echo "narrows exited with $code: this point stops (see $log)"; exit "$code"; fi',
        f'if grep -q "{NOTHING}" "$log" || ! grep -Eq "received SIG[A-Z0-9]+: stopped" "$log"; then',
        f'  date > "$OUT/{DONE}"; echo "$OUT: finished"; exit 0',
        "fi",
        'if [ "$CHAIN_INDEX" -lt "$CHAIN_MAX" ]; then',
        '  next=(sbatch --array="$SLURM_ARRAY_TASK_ID" --export=ALL,CHAIN_INDEX=$((CHAIN_INDEX + 1)) "$SCRIPT")',
        '  if command -v sbatch > /dev/null 2>&1; then "${next[@]}"; else echo "would submit: ${next[*]}"; fi',
        "fi",
    ]
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("scene")
    ap.add_argument("--out", required=True, help="the sweep's folder")
    ap.add_argument("--set", action="append", default=[], help="KEY=V1,V2,...")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--seed-key", default="run.seed")
    ap.add_argument("--seed0", type=int)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--mpi", type=int, default=1, help="ranks per point")
    ap.add_argument("--narrows", help="the binary (default $NARROWS, build/narrows)")
    ap.add_argument("--collect", help='a tool run on each finished point, e.g. "tools/pulses.py"')
    ap.add_argument("--collect-json")
    ap.add_argument("--slurm", action="store_true", help="write a SLURM array job, run nothing")
    ap.add_argument("--slurm-file")
    ap.add_argument("--slurm-time", default="24:00:00")
    ap.add_argument("--chain-max", type=int, default=50)
    args = ap.parse_args(argv)
    try:
        for name in ("repeats", "jobs", "mpi", "chain_max"):
            if getattr(args, name) < 1:
                raise InputError(f"--{name.replace('_', '-')} {getattr(args, name)}; allowed: 1 or more")
        if not os.path.isfile(args.scene):
            raise InputError(f"{args.scene}: no such scene file")
        with open(args.scene) as f:
            scene = narrows_h5.parse_scene(f.read(), args.scene)
        grid = parse_sets(args.set)
        if args.seed_key in [k for k, _ in grid]:
            raise InputError(f"--set {args.seed_key}: the seed key is set by --repeats; allowed: "
                             "--seed0 S, or another --seed-key")
        if args.seed0 is None:
            found = lookup(scene, args.seed_key)
            args.seed0 = int(found) if isinstance(found, int) else 1
        points = make_points(grid, args.repeats, args.seed_key, args.seed0)
        if args.collect and not shlex.split(args.collect):
            raise InputError("--collect ''; allowed: a tool, e.g. \"tools/pulses.py --transient 50\"")
        write_manifest(args.out, manifest(args, grid, points))
        if args.slurm:
            args.narrows_path = args.narrows or os.environ.get("NARROWS") or "build/narrows"
            path = args.slurm_file or os.path.join(
                "jobscripts", f"sweep-{safe(os.path.basename(os.path.abspath(args.out)))}.slurm")
            os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
            with open(path, "w") as f:
                f.write(slurm_script(args, points, path))
            print(f"wrote {path}: {len(points)} points (sbatch {path})")
            return 0
    except InputError as e:
        return narrows_h5.report("sweep", e)
    narrows = find_narrows(args.narrows)
    return Sweep(args, points, narrows).run()


if __name__ == "__main__":
    sys.exit(narrows_h5.run_tool("sweep", main))
