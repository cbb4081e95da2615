#!/usr/bin/python3
"""Test of tools/sweep.py: an interrupted sweep resumes without redoing finished points, and
the SLURM array file is valid bash that names every point.

Usage: /usr/bin/python3 tools/test_sweep.py NARROWS_BINARY

The sweep: run/continuum_jamming_pulses.toml at 128 points with continuum.time = 2, 6000 (the
second ~3 s) times 2 repeats (continuum.initial.seed = 1, 2): 4 points, one at a time. The sweep
gets SIGTERM while the first long point (p0002) runs, after its log exists. Checked:
- the first sweep exits 1; p0000 and p0001 are finished (DONE), p0002 has a checkpoint and no
  DONE, p0003 was never started;
- the same command again (with --collect "tools/pulses.py --no-plot") prints "skipped" for
  p0000 and p0001 and leaves their files untouched (modification times), continues p0002 with
  --restart (its observables-<step>.h5 exists, its log says restart), starts p0003 afresh, exits 0;
- the table (CSV and HDF5) has the 4 points with their continuum.time and seed, and the
  pulses.py columns; the repeats' seeds differ and so do their results;
- a third call skips all four and runs nothing;
- --slurm writes a file that passes `bash -n`, has an array of 4 indices and names every point
  with its --set values (also both keys of a linked KEY1+KEY2=V); run locally as index 1 (no srun: narrows directly) it finishes that
  point (DONE) and a second call says "finished before"; index 2 stopped by SIGUSR1 (as SLURM
  does before the time limit) leaves a checkpoint and no DONE and resubmits index 2 with
  CHAIN_INDEX=2 (no sbatch here: "would submit"), and that next job continues with --restart
  and finishes the point;
- bad --set: exit 2 with one line; another grid into the same folder: exit 2.
Prints FAIL lines and "N passed, M failed"; exit 1 on any failure.
"""

import csv
import glob
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(os.path.dirname(HERE), "run", "continuum_jamming_pulses.toml")
sys.path.insert(0, HERE)
import narrows_h5  # noqa: E402
from selftest import check, summary  # noqa: E402




def sweep_cmd(narrows, out, *extra):
    return [sys.executable, os.path.join(HERE, "sweep.py"), SCENE, "--out", out,
            "--set", "continuum.cells=128", "--set", "continuum.samples=40",
            "--set", "continuum.time=2.0,6000.0", "--set", "output.progress=false",
            "--repeats", "2", "--seed-key", "continuum.initial.seed", "--narrows", narrows,
            *extra]


def wait_for(condition, timeout):
    t0 = time.time()
    while time.time() - t0 < timeout:
        if condition():
            return True
        time.sleep(0.05)
    return False


def mtimes(d):
    return {p: os.path.getmtime(p) for p in sorted(glob.glob(os.path.join(d, "*")))}


def resume(tmp, narrows):
    out = os.path.join(tmp, "sw")
    first = subprocess.Popen(sweep_cmd(narrows, out), stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, text=True)
    names = None
    ok = wait_for(lambda: len(glob.glob(os.path.join(out, "p0002-*", "log.txt"))) == 1, 120)
    check("the long point p0002 started", ok)
    time.sleep(0.5)
    first.send_signal(signal.SIGTERM)
    text, _ = first.communicate(timeout=120)
    print(text, end="")
    check("interrupted sweep exits 1", first.returncode == 1, first.returncode)
    points = sorted(os.path.basename(p) for p in glob.glob(os.path.join(out, "p*")))
    names = {p[:5]: os.path.join(out, p) for p in points}
    check("points p0000-p0002 exist, p0003 not started", sorted(names) ==
          ["p0000", "p0001", "p0002"], points)
    if sorted(names) != ["p0000", "p0001", "p0002"]:
        return
    done = lambda k: os.path.isfile(os.path.join(names[k], "DONE"))  # noqa: E731
    check("p0000, p0001 finished", done("p0000") and done("p0001"))
    check("p0002 interrupted: a checkpoint, no DONE",
          not done("p0002") and glob.glob(os.path.join(names["p0002"], "checkpoint-*.h5")))
    check("one progress line per finished point", text.count(": done in ") == 2, text)
    before = {k: mtimes(names[k]) for k in ("p0000", "p0001")}

    second = subprocess.run(sweep_cmd(narrows, out, "--collect", os.path.join(HERE, "pulses.py")
                                      + " --no-plot"), capture_output=True, text=True, timeout=240)
    print(second.stdout, end="")
    check("resumed sweep exits 0", second.returncode == 0, second.stderr[-400:])
    for k in ("p0000", "p0001"):
        check(f"{k} skipped", re.search(rf"{k}\S*: finished before: skipped", second.stdout),
              second.stdout)
        after = {p: t for p, t in mtimes(names[k]).items() if p in before[k]}
        check(f"{k}: its files untouched", after == before[k])
    check("p0002 restarted from its checkpoint",
          re.search(r"p0002\S*: done in .*restarted from checkpoint-\d+\.h5", second.stdout)
          and glob.glob(os.path.join(names["p0002"], "observables-*.h5")), second.stdout)
    p3 = glob.glob(os.path.join(out, "p0003-*"))
    check("p0003 run afresh", len(p3) == 1 and re.search(r"p0003\S*: done in .*\(fresh\)",
                                                         second.stdout), second.stdout)
    with open(os.path.join(out, "table.csv")) as f:
        rows = list(csv.DictReader(f))
    check("table: 4 rows", len(rows) == 4, len(rows))
    if len(rows) == 4:
        check("table: the sweep's values and seeds",
              [r["continuum.time"] for r in rows] == ["2.0", "2.0", "6000.0", "6000.0"] and
              [r["continuum.initial.seed"] for r in rows] == ["1", "2", "1", "2"], rows[0].keys())
        check("table: pulses.py's columns", all(r.get("pulse_speed") not in (None, "") and
                                                r.get("state") for r in rows), rows[0])
        check("table: the repeats differ", rows[2]["relative_variance"] != rows[3]["relative_variance"])
    t = narrows_h5.read_datasets(os.path.join(out, "table.h5"), "table")
    check("table.h5: the same columns", len(t.get("point", [])) == 4 and "f_pt" in t and
          "continuum.time" in t, sorted(t))
    third = subprocess.run(sweep_cmd(narrows, out), capture_output=True, text=True, timeout=60)
    check("a third call skips all four", third.returncode == 0 and
          third.stdout.count("finished before: skipped") == 4, third.stdout)


def slurm(tmp, narrows):
    out = os.path.join(tmp, "sl")
    script = os.path.join(tmp, "sweep.slurm")
    linked = ["--set", "continuum.drive+continuum.diffusion=1.0"]  # both keys, one value
    done = subprocess.run(sweep_cmd(narrows, out, "--slurm", "--slurm-file", script, *linked),
                          capture_output=True, text=True, cwd=tmp)
    check("--slurm exits 0", done.returncode == 0, done.stderr)
    if done.returncode:
        return
    text = open(script).read()
    check("SLURM file passes bash -n",
          subprocess.run(["bash", "-n", script], capture_output=True).returncode == 0)
    check("an array of 4 indices", "#SBATCH --array=0-3" in text)
    import json
    with open(os.path.join(out, "sweep.json")) as f:
        points = json.load(f)["points"]
    for p in points:
        line = [l for l in text.splitlines() if l.strip().startswith(f"{p['index']}) ")]
        check(f"SLURM file names point {p['name']}",
              len(line) == 1 and p["name"] in line[0] and
              f"continuum.initial.seed={p['seed']}" in line[0] and
              f"continuum.time={p['sets']['continuum.time']}" in line[0] and
              "continuum.drive=1.0" in line[0] and "continuum.diffusion=1.0" in line[0], line)
    env = dict(os.environ, SLURM_ARRAY_TASK_ID="1", NARROWS=narrows, PATH="/usr/bin:/bin")
    run = subprocess.run(["bash", script], capture_output=True, text=True, cwd=tmp, env=env,
                         timeout=120)
    point = os.path.join(out, points[1]["name"])
    check("index 1 run locally finishes its point", run.returncode == 0 and
          os.path.isfile(os.path.join(point, "DONE")), run.stdout[-400:] + run.stderr[-400:])
    again = subprocess.run(["bash", script], capture_output=True, text=True, cwd=tmp, env=env)
    check("... and a second job says finished before",
          again.returncode == 0 and "finished before" in again.stdout, again.stdout)
    # the chain: index 2 (a long point) gets SIGUSR1 as SLURM sends it before the time limit
    env2 = dict(env, SLURM_ARRAY_TASK_ID="2")
    job = subprocess.Popen(["bash", script], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True, cwd=tmp, env=env2)
    point = os.path.join(out, points[2]["name"])
    wait_for(lambda: os.path.isfile(os.path.join(point, "log.txt")), 60)
    time.sleep(0.5)
    children = open(f"/proc/{job.pid}/task/{job.pid}/children").read().split()
    for pid in children:
        os.kill(int(pid), signal.SIGUSR1)
    text, _ = job.communicate(timeout=120)
    check("SIGUSR1: the job stops with a checkpoint, no DONE, and resubmits its own index",
          job.returncode == 0 and not os.path.isfile(os.path.join(point, "DONE")) and
          glob.glob(os.path.join(point, "checkpoint-*.h5")) and
          re.search(r"would submit: sbatch --array=2 --export=ALL,CHAIN_INDEX=2 ", text),
          (children, text[-600:]))
    env2["CHAIN_INDEX"] = "2"
    nxt = subprocess.run(["bash", script], capture_output=True, text=True, cwd=tmp, env=env2,
                         timeout=120)
    check("the next job of the chain continues the checkpoint and finishes the point",
          nxt.returncode == 0 and "--restart" in nxt.stdout and
          os.path.isfile(os.path.join(point, "DONE")) and
          glob.glob(os.path.join(point, "observables-*.h5")), nxt.stdout[-600:])


def refusals(tmp, narrows):
    bad = subprocess.run([sys.executable, os.path.join(HERE, "sweep.py"), SCENE, "--out",
                          os.path.join(tmp, "b"), "--set", "continuum.time"],
                         capture_output=True, text=True)
    check("bad --set: exit 2, one line", bad.returncode == 2 and "--set" in bad.stderr and
          len(bad.stderr.strip().splitlines()) == 1, (bad.returncode, bad.stderr))
    out = os.path.join(tmp, "sw")
    other = subprocess.run(sweep_cmd(narrows, out, "--repeats", "3"), capture_output=True, text=True)
    check("another grid into the same folder: exit 2, one line", other.returncode == 2 and
          "another sweep" in other.stderr and len(other.stderr.strip().splitlines()) == 1,
          (other.returncode, other.stderr))


def main():
    if len(sys.argv) != 2:
        print("usage: test_sweep.py NARROWS_BINARY", file=sys.stderr)
        return 2
    narrows = os.path.abspath(sys.argv[1])
    with tempfile.TemporaryDirectory() as tmp:
        for part in (resume, slurm, refusals):
            try:
                part(tmp, narrows)
            except Exception as e:  # noqa: BLE001
                check(f"{part.__name__} ran to the end", False, f"{type(e).__name__}: {e}")
    return summary()


if __name__ == "__main__":
    sys.exit(main())
