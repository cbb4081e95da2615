#!/usr/bin/python3
"""Self-test of tools/narrows_h5.py (no narrows binary needed).

Usage: /usr/bin/python3 tools/test_narrows_h5.py

Writes a tiny fake run folder with the module's own writer: observables.h5 (steps 0-50) and
two restarts, observables-0000000030.h5 (steps 40-70, from the checkpoint at 30: replaces the
samples from 40 on) and observables-0000000060.h5 (steps 70-90), each with a time series with
bins, a scalar series and a result of the whole run (scalar step). Checks the joined series,
the axes and results (from the newest file), the scene (text and dict), the file written by
write_joined and by tools/join_observables.py, and the errors: a missing observable, dataset,
file, a file that is not HDF5 and a scene that is not TOML each raise NarrowsDataError naming the
file and what is missing, and a tool reports it with one line on stderr and exit code 2.
Prints FAIL lines and "N passed, M failed"; exit code 1 on any failure.
"""

import contextlib
import io
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import narrows_h5  # noqa: E402
from selftest import check, summary  # noqa: E402
from narrows_h5 import NarrowsDataError  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = """[run]
engine = "mpcd"
dimensions = 2
steps = 90

[domain]
size = [8.0, 4.0]

[fluid]
collision = "srd"
dt = 0.1
"""




def close(a, b):
    """Same shape and values (to rounding)."""
    return np.shape(a) == np.shape(b) and np.allclose(a, b)


def raises(name, call, *fragments):
    """call() raises NarrowsDataError whose message holds every fragment; returns the message."""
    try:
        call()
    except NarrowsDataError as e:
        text = str(e)
        missing = [f for f in fragments if f not in text]
        check(name, not missing and "\n" not in text, f"message {text!r} lacks {missing}")
        return text
    except Exception as e:  # noqa: BLE001  (any other exception is a failure)
        check(name, False, f"raised {type(e).__name__}: {e}")
        return None
    check(name, False, "no error raised")
    return None


def segment(first, last, offset, bins_shift):
    """A file's samples at steps first..last (every 10): temperature = step + offset (the offset
    marks the file), velocity_profile [T][4][2] = that value everywhere, bins shifted to mark
    the file; a result with a scalar step at `last`."""
    step = np.arange(first, last + 1, 10, dtype=np.int64)
    value = step + float(offset)
    series = {
        "temperature": {"step": step, "time": 0.1 * step, "value": value},
        "velocity_profile": {"step": step, "time": 0.1 * step,
                             "value": np.repeat(value, 8).reshape(len(step), 4, 2),
                             "bins": np.arange(4) + 0.5 + bins_shift},
    }
    # a group of several sampled fields and no value (as axial_fields: phi, velocity [T][bins])
    series["axial_fields"] = {"step": step, "time": 0.1 * step,
                              "phi": np.repeat(value, 3).reshape(len(step), 3),
                              "velocity": -np.repeat(value, 3).reshape(len(step), 3),
                              "bins": np.arange(3) + 0.5}
    results = {"colloid_vacf": {"step": np.int64(last), "time": 0.1 * last,
                                "lags": np.arange(3.0), "value": np.full(3, float(offset)),
                                "samples": np.array([float(last)])}}
    return series, results


def main():
    try:
        checks()
    except Exception as e:  # noqa: BLE001  (a check that cannot even run is a failure)
        check("the checks ran to the end", False, f"{type(e).__name__}: {e}")
    return summary()


def checks():
    with tempfile.TemporaryDirectory() as tmp:
        run_dir = os.path.join(tmp, "run")
        os.makedirs(run_dir)
        for name, (first, last, offset) in {"observables.h5": (0, 50, 0),
                                            "observables-0000000030.h5": (40, 70, 1000),
                                            "observables-0000000060.h5": (70, 90, 2000)}.items():
            series, results = segment(first, last, offset, offset / 1000)
            narrows_h5.write_observables(os.path.join(run_dir, name), series=series,
                                         results=results, scene=SCENE + f"# {name}\n")
            # a dataset of one row per sample beside value (as contact_statistics writes)
            with h5py.File(os.path.join(run_dir, name), "a") as f:
                g = f["observables/velocity_profile"]
                d = g.create_dataset("contacts", data=np.stack([series["temperature"]["value"]] * 2,
                                                               axis=1))
                d.attrs["per_sample"] = np.array([1], dtype=np.int32)

        # the chain: files in step order, samples replaced from each restart's first step on
        chain = narrows_h5.chain_files(run_dir)
        check("chain_files: observables.h5, then by step",
              [os.path.basename(p) for p in chain] ==
              ["observables.h5", "observables-0000000030.h5", "observables-0000000060.h5"],
              chain)
        run = narrows_h5.open_run(run_dir, chain=True)
        t = run.series("temperature")
        want_step = np.arange(0, 91, 10)
        want_value = np.array([0, 10, 20, 30, 1040, 1050, 1060, 2070, 2080, 2090], float)
        check("joined steps 0..90, each once", np.array_equal(t.step, want_step), t.step)
        check("restart samples replace the later ones", np.array_equal(t.value, want_value),
              t.value)
        check("joined time", close(t.time, 0.1 * want_step), t.time)
        check("step stays an integer dataset", t.step.dtype == np.int64, t.step.dtype)
        v = run.series("velocity_profile")
        check("joined [T][bins][d] values", v.value.shape == (10, 4, 2) and
              np.array_equal(v.value[:, 0, 0], want_value), v.value.shape)
        check("bins from the newest file", close(v.bins, np.arange(4) + 2.5), v.bins)
        a = run.series("axial_fields")
        check("joined fields of a group without value (axial_fields)",
              a.value is None and np.array_equal(a.step, want_step) and
              np.array_equal(a["phi"][:, 1], want_value) and
              np.array_equal(a["velocity"][:, 2], -want_value) and close(a.bins, np.arange(3) + 0.5),
              {k: np.shape(a[k]) for k in a.keys()})
        check("a per_sample dataset beside value is joined as value",
              v["contacts"].shape == (10, 2) and np.array_equal(v["contacts"][:, 1], want_value),
              v.get("contacts"))
        r = run.series("colloid_vacf")
        check("result of the whole run: from the file of the latest step",
              r.is_result and r.number("samples") == 90.0 and np.all(r.value == 2000.0),
              (r.is_result, r.get("samples")))
        check("lags of a result", np.array_equal(r.lags, np.arange(3.0)), r.lags)
        check("names of the chain", run.names() ==
              ["axial_fields", "temperature", "velocity_profile", "colloid_vacf"], run.names())

        check("open_run(folder) reads the whole chain by default",
              np.array_equal(narrows_h5.open_run(run_dir).series("temperature").step,
                             run.series("temperature").step))
        # the first file alone (chain=False)
        first = narrows_h5.open_run(run_dir, chain=False)
        t1 = first.series("temperature")
        check("open_run(folder, chain=False): observables.h5 alone",
              np.array_equal(t1.step, np.arange(0, 51, 10)) and first.path.endswith(
                  "observables.h5"), t1.step)
        check("open_run(file) reads that file",
              narrows_h5.open_run(chain[2]).series("temperature").step[0] == 70)

        # the scene: text and dict (of the newest file of a chain)
        check("scene text", run.scene_text() == SCENE + "# observables-0000000060.h5\n")
        scene = run.scene()
        check("scene dict", scene["domain"]["size"] == [8.0, 4.0] and
              scene["fluid"]["collision"] == "srd", scene)

        # the joined file (module and tool) reads back as the chain
        joined = os.path.join(tmp, "joined.h5")
        n = run.write_joined(joined)
        check("write_joined counts series and results", n == (3, 1), n)
        back = narrows_h5.open_run(joined)
        for name in ("temperature", "velocity_profile", "axial_fields"):
            a, b = run.series(name), back.series(name)
            check(f"joined file: {name}", all(np.array_equal(a[k], b[k]) for k in a.keys())
                  and sorted(a.keys()) == sorted(b.keys()), sorted(b.keys()))
        check("joined file: result copied whole",
              back.series("colloid_vacf").number("samples") == 90.0)
        check("joined file: scene of the newest file", back.scene_text() == run.scene_text())
        tool = subprocess.run([sys.executable, os.path.join(HERE, "join_observables.py"),
                               run_dir], capture_output=True, text=True)
        check("join_observables.py exits 0", tool.returncode == 0, tool.stderr)
        out = os.path.join(run_dir, narrows_h5.JOINED)
        check("join_observables.py writes observables-joined.h5 as the chain",
              os.path.isfile(out) and np.array_equal(
                  narrows_h5.open_run(out).series("temperature").value, want_value))
        check("the joined file is no part of the chain",
              narrows_h5.chain_files(run_dir) == chain)
        only_joined = os.path.join(tmp, "only_joined")
        os.makedirs(only_joined)
        os.replace(out, os.path.join(only_joined, narrows_h5.JOINED))
        check("open_run(chain=True) of a folder with only the joined file",
              np.array_equal(narrows_h5.open_run(only_joined, chain=True)
                             .series("temperature").value, want_value))

        # errors: one type, naming the file and the missing dataset or observable
        path = os.path.join(run_dir, "observables.h5")
        raises("missing observable", lambda: first.series("shock_position"), path,
               "no /observables/shock_position", "output.observables")
        raises("missing observable of a chain", lambda: run.series("shock_position"),
               run_dir, "no /observables/shock_position")
        raises("missing observable, the tool's hint",
               lambda: first.series("charge_profile", "a kmc run with a shock"),
               "no /observables/charge_profile; allowed: a kmc run with a shock")
        raises("missing dataset of an observable", lambda: t1["error"], path,
               "no /observables/temperature/error")
        raises("missing run folder", lambda: narrows_h5.open_run(os.path.join(tmp, "none")),
               os.path.join(tmp, "none", "observables.h5"), "not found")
        raises("missing chain", lambda: narrows_h5.open_run(os.path.join(tmp, "none"),
                                                            chain=True), "not found")
        text_file = os.path.join(tmp, "notes.h5")
        with open(text_file, "w") as f:
            f.write("not HDF5\n")
        raises("not an HDF5 file", lambda: narrows_h5.open_run(text_file), text_file,
               "not an HDF5 file")
        bad = os.path.join(tmp, "bad_scene.h5")
        narrows_h5.write_observables(bad, scene="[run\nsteps = ")
        raises("scene that is not TOML", lambda: narrows_h5.open_run(bad).scene(), bad,
               "/parameters/scene is not valid TOML")
        no_scene = os.path.join(tmp, "no_scene.h5")
        narrows_h5.write_observables(no_scene, series={})
        raises("no scene", lambda: narrows_h5.open_run(no_scene).scene_text(), no_scene,
               "no /parameters/scene")
        check("no scene, not required", narrows_h5.open_run(no_scene).scene_text(False) is None)
        first.require_engine("mpcd")  # the scene says mpcd: no error
        raises("a run of another engine", lambda: first.require_engine("kmc"), path,
               'a run of run.engine = "mpcd"; allowed: a run of run.engine = "kmc"')
        raises("missing trajectory", lambda: narrows_h5.open_trajectory(run_dir),
               os.path.join(run_dir, "trajectory.h5"), "not found")

        # the one way a tool reports it: one line on stderr, exit code 2
        def tool_main():
            first.series("shock_position")

        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            code = narrows_h5.run_tool("some_tool", tool_main)
        lines = err.getvalue().splitlines()
        check("run_tool: exit code 2", code == 2, code)
        check("run_tool: one line 'some_tool: FILE: no /observables/...'",
              len(lines) == 1 and lines[0].startswith(f"some_tool: {path}: no /observables/"),
              lines)
        flat = os.path.join(tmp, "flat")  # a run without velocity_profile
        os.makedirs(flat)
        narrows_h5.write_observables(os.path.join(flat, "observables.h5"), scene=SCENE,
                                     series={"temperature": segment(0, 10, 0, 0)[0]["temperature"]})
        for tool, args, want in (("plot_profile", [flat], "no /observables/velocity_profile"),
                                 ("h5summary", [text_file], "not an HDF5 file"),
                                 ("join_observables", [os.path.join(tmp, "none")], "not found")):
            done = subprocess.run([sys.executable, os.path.join(HERE, tool + ".py")] + args,
                                  capture_output=True, text=True)
            lines = done.stderr.splitlines()
            check(f"{tool}.py: exit 2, one line '{tool}: ... {want}'",
                  done.returncode == 2 and len(lines) == 1 and lines[0].startswith(tool + ": ")
                  and want in lines[0], (done.returncode, lines))


if __name__ == "__main__":
    sys.exit(main())
