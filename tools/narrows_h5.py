"""The one reader (and writer) of narrows output for the tools in this folder.

Every tool here reads narrows' HDF5 files through this module, and only this module imports
h5py. What a run writes (docs/scenes.md): DIR/observables.h5 with the scene text at
/parameters/scene and /observables/<name>/{step, time, value} (bin centres in .../bins, lags of
correlations in .../lags; a group of several sampled fields, such as axial_fields' phi,
velocity and fluid_velocity [T][bins], has them in place of value); a result of the whole run
(colloid statistics, the lgca VACFs, steady_density) has a scalar step. Each restart writes
DIR/observables-<step>.h5 with the samples after the checkpoint it started from;
tools/join_observables.py writes DIR/observables-joined.h5.

Reading:
  run = open_run("out/x")                   # the run's restart chain, joined (a fresh run:
                                            # DIR/observables.h5); a .h5 file given is read alone
  run = open_run("out/x", chain=False)      # DIR/observables.h5 alone, without the restarts
  run.scene()                                # the scene as a dict; run.scene_text() the TOML
  s = run.series("velocity_profile")         # s.step, s.time, s.value, s.bins, s["error"], ...
Missing or unreadable data raise NarrowsDataError, whose message names the file and the
dataset; a tool reports it with one line on stderr and exit code 2 (report(), or run_tool()).
Writing: write_observables() (the layout the tools read, used by join_observables.py and the
self-test tools/test_narrows_h5.py); write_table() (a table of results, tools/sweep.py).
Plots: pyplot() (matplotlib with the Agg backend).
"""

import glob
import os
import re
import sys

import h5py
import numpy as np

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # older Pythons: the tomli package has the same interface
    try:
        import tomli as tomllib
    except ModuleNotFoundError:
        tomllib = None

OBSERVABLES = "observables.h5"
JOINED = "observables-joined.h5"
TRAJECTORY = "trajectory.h5"
AXES = ("bins", "lags")  # datasets of an observable that are axes, not samples
_RESTART = re.compile(r"observables-(\d+)\.h5$")


# ---- errors --------------------------------------------------------------------------------


class NarrowsDataError(Exception):
    """Missing or unreadable narrows output. The message names the file (path) and what is
    missing in it (what), and optionally what would do (allowed): "PATH: WHAT; allowed: ..."."""

    def __init__(self, path, what, allowed=None):
        self.path, self.what, self.allowed = path, what, allowed
        text = f"{path}: {what}" if path else str(what)
        if allowed:
            text += f"; allowed: {allowed}"
        super().__init__(text)


def report(tool, error, code=2):
    """Prints the one line "TOOL: MESSAGE" on stderr and returns code (a tool's exit code)."""
    print(f"{tool}: {' '.join(str(error).split())}", file=sys.stderr)
    return code


def run_tool(tool, main, *args):
    """main(*args), with a NarrowsDataError reported as one line on stderr and exit code 2.
    Returns main's return value otherwise: sys.exit(run_tool("plot_profile", main, sys.argv))."""
    try:
        return main(*args)
    except NarrowsDataError as e:
        return report(tool, e)


def missing_observable(path, name, allowed=None):
    """The error of a run without /observables/<name> (default hint: list it in the scene)."""
    return NarrowsDataError(path, f"no /observables/{name}",
                            allowed or f'a run that lists "{name}" in output.observables')


# ---- files ---------------------------------------------------------------------------------


def open_h5(path):
    """The HDF5 file at path, read-only (use it in a with statement). NarrowsDataError if it
    does not exist or is not HDF5."""
    if not os.path.isfile(path):
        raise NarrowsDataError(path, "not found")
    if not h5py.is_hdf5(path):
        raise NarrowsDataError(path, "not an HDF5 file")
    return h5py.File(path, "r")


def chain_files(run_dir):
    """DIR/observables.h5 (if there) and DIR/observables-<step>.h5 in step order: a run and its
    restarts. observables-joined.h5 is not one of them."""
    first = os.path.join(run_dir, OBSERVABLES)
    later = [p for p in glob.glob(os.path.join(glob.escape(run_dir), "observables-[0-9]*.h5"))
             if _RESTART.search(p)]
    later.sort(key=lambda p: int(_RESTART.search(p).group(1)))
    return ([first] if os.path.isfile(first) else []) + later


def observables_path(path):
    """The observables file a tool argument names: the argument itself if it is a file or ends
    in .h5, else DIR/observables.h5."""
    if path.endswith(".h5") or os.path.isfile(path):
        return path
    return os.path.join(path, OBSERVABLES)


def open_run(path, chain=True):
    """A run's observables: path is a run folder or an observables file.

    A folder gives its whole restart chain: observables.h5 and every observables-<step>.h5,
    joined as tools/join_observables.py joins them (a later file replaces the samples from its
    first step on), or DIR/observables-joined.h5 when the folder holds nothing else; with
    chain=False DIR/observables.h5 alone. A file is read alone. NarrowsDataError when nothing is found."""
    if chain and not (path.endswith(".h5") or os.path.isfile(path)):
        paths = chain_files(path)
        if not paths and os.path.isfile(os.path.join(path, JOINED)):
            paths = [os.path.join(path, JOINED)]
        if not paths:
            raise NarrowsDataError(os.path.join(path, OBSERVABLES), "not found",
                                   "a run folder with observables.h5 or observables-<step>.h5")
        for p in paths:
            open_h5(p).close()
        return Run(paths)
    p = observables_path(path)
    if not os.path.isfile(p):
        raise NarrowsDataError(p, "not found", "a run folder holding observables.h5, or an "
                               "observables .h5 file")
    open_h5(p).close()
    return Run([p])


def _read_group(g):
    """{name: value} of the datasets of an HDF5 group, as stored (numpy arrays, scalars)."""
    return {k: g[k][()] for k in g if isinstance(g[k], h5py.Dataset)}


def _text(value):
    """A stored string (bytes or str) as str."""
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


def parse_scene(text, path=None):
    """The scene TOML text as a dict. NarrowsDataError (naming path) if it is not TOML."""
    if tomllib is None:
        raise NarrowsDataError(path, "/parameters/scene: no TOML reader in this Python",
                               "Python >= 3.11 (tomllib) or the tomli package")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise NarrowsDataError(path, f"/parameters/scene is not valid TOML: {e}") from e


class Series:
    """One observable: step, time, value (None where the group has none), the axes (bins,
    lags) and every other dataset of its group by name: s["error"], s.get("corrected"),
    "plateau" in s. number(key) is the first element of a stored one-element array as a float
    (e.g. samples, width). is_result: a result of the whole run (scalar step)."""

    def __init__(self, name, path, data):
        self.name, self.path, self.data = name, path, data

    def __getitem__(self, key):
        if key not in self.data:
            raise NarrowsDataError(self.path, f"no /observables/{self.name}/{key}")
        return self.data[key]

    def __contains__(self, key):
        return key in self.data

    def get(self, key, default=None):
        return self.data.get(key, default)

    def keys(self):
        return self.data.keys()

    def number(self, key):
        return float(np.ravel(self[key])[0])

    step = property(lambda self: self.data.get("step"))
    time = property(lambda self: self.data.get("time"))
    value = property(lambda self: self.data.get("value"))
    bins = property(lambda self: self.data.get("bins"))
    lags = property(lambda self: self.data.get("lags"))
    is_result = property(lambda self: np.ndim(self.data.get("step", 0)) == 0)


class Run:
    """The observables of one run: one file, or a restart chain (paths in step order)."""

    def __init__(self, paths):
        self.paths = list(paths)
        self.path = self.paths[0]  # the file named in messages about the run
        self.newest = self.paths[-1]
        self.label = (self.path if len(self.paths) == 1 else
                      f"{os.path.dirname(self.path) or '.'}/observables*.h5 "
                      f"({len(self.paths)} files)")
        self._joined = None

    def names(self):
        """The observables of the run, in the order the files list them."""
        if len(self.paths) > 1:
            series, results = self._join()
            return list(dict.fromkeys(list(series) + list(results)))
        with h5py.File(self.path, "r") as f:
            return list(f.get("observables", {}))

    def has(self, name):
        return name in self.names()

    def series(self, name, allowed=None):
        """The observable `name` (joined over a chain); NarrowsDataError naming the file and
        /observables/<name> if the run has none (allowed: the hint in the message)."""
        if len(self.paths) > 1:
            series, results = self._join()
            if name in series:  # copies: a tool may change its arrays in place
                return Series(name, self.label, {k: np.copy(v) for k, v in series[name].items()})
            if name in results:
                path = results[name][1]
                with h5py.File(path, "r") as f:
                    return Series(name, path, _read_group(f["observables/" + name]))
            raise missing_observable(self.label, name, allowed)
        with h5py.File(self.path, "r") as f:
            g = f.get("observables/" + name)
            if not isinstance(g, h5py.Group):
                raise missing_observable(self.path, name, allowed)
            return Series(name, self.path, _read_group(g))

    def scene_text(self, required=True):
        """The TOML text of /parameters/scene (of the newest file of a chain); None if there is
        none and not required."""
        with h5py.File(self.newest, "r") as f:
            if "parameters/scene" not in f:
                if required:
                    raise NarrowsDataError(self.newest, "no /parameters/scene")
                return None
            return _text(f["parameters/scene"][()])

    def scene(self):
        """/parameters/scene as a dict (tomllib)."""
        return parse_scene(self.scene_text(), self.newest)

    def require_engine(self, engine):
        """NarrowsDataError unless the scene's run.engine (default "mpcd") is engine."""
        found = self.scene().get("run", {}).get("engine", "mpcd")
        if found != engine:
            raise NarrowsDataError(self.newest, f'a run of run.engine = "{found}"',
                                   f'a run of run.engine = "{engine}"')

    def _join(self):
        """{name: {step, time, value, axes...}} of the time series joined over the files in
        step order (a file's samples replace the earlier ones from its first step on; axes such
        as bins from the latest file that has them), and {name: (step, path)} of the file of
        the latest step of each result of the whole run (scalar step)."""
        if self._joined is not None:
            return self._joined
        series, results = {}, {}
        for path in self.paths:
            with h5py.File(path, "r") as f:
                for name, g in f.get("observables", {}).items():
                    if "step" not in g or g["step"].ndim == 0:
                        step = g["step"][()] if "step" in g else -1
                        if name not in results or step >= results[name][0]:
                            results[name] = (step, path)
                        continue
                    # the sampled datasets: time, value, the datasets of one row per sample
                    # beside value (attribute per_sample = 1), and in a group of several fields
                    # without value (axial_fields' phi, velocity, ...) every dataset other than
                    # the axes whose first dimension is the number of samples
                    step = g["step"][()]
                    sampled = ["time"] + (["value"] if "value" in g else [])
                    sampled += [k for k in g if k not in ("step", "time", "value") + AXES
                                and is_dataset(g[k])
                                and (g[k].attrs.get("per_sample", 0)
                                     or ("value" not in g and g[k].ndim >= 1
                                         and g[k].shape[0] == len(step)))]
                    for key in sampled:
                        if key not in g:
                            raise NarrowsDataError(path, f"no /observables/{name}/{key}")
                    s = series.setdefault(name, {"step": step[:0]})
                    keep = s["step"] < step[0] if len(step) else np.ones(len(s["step"]), bool)
                    s["step"] = np.concatenate([s["step"][keep], step])
                    for key in sampled:  # later samples replace the earlier from their first step
                        data = g[key][()]
                        s[key] = np.concatenate([s[key][keep], data]) if key in s else data
                    for key in g:  # the axes (bins, ...)
                        if key not in ["step"] + sampled and is_dataset(g[key]):
                            s[key] = g[key][()]
        self._joined = (series, results)
        return self._joined

    def write_joined(self, out_path):
        """Writes the joined chain to out_path: /h5md and /parameters of the newest file, every
        time series joined, every result of the whole run copied from the file of its latest
        step. Returns (number of series, number of results)."""
        series, results = self._join()
        write_observables(out_path, series=series,
                          results={name: path for name, (_, path) in results.items()},
                          copy_from=self.newest)
        return len(series), len(results)


# ---- other files: trajectories, the tests' own files, any HDF5 file -----------------------


class Trajectory:
    """DIR/trajectory.h5 (H5MD), open while in a with statement: dataset(name) (read lazily,
    e.g. one frame: t.dataset("particles/fluid/position/value")[k]), array(name) (all of it),
    has(name) (whether the file holds that object), parameter(name) (/parameters/<name>)."""

    def __init__(self, path):
        self.path = path
        self._f = open_h5(path)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._f.close()

    def dataset(self, name):
        d = self._f.get(name)
        if not isinstance(d, h5py.Dataset):
            raise NarrowsDataError(self.path, f"no /{name.lstrip('/')}")
        return d

    def array(self, name):
        return self.dataset(name)[()]

    def has(self, name):
        return name in self._f

    def parameter(self, name):
        value = self.array("parameters/" + name)
        return _text(value) if isinstance(value, bytes) else value


def open_trajectory(path):
    """The trajectory of a run folder (DIR/trajectory.h5) or the .h5 file given."""
    return Trajectory(path if path.endswith(".h5") else os.path.join(path, TRAJECTORY))


def read_datasets(path, group="/"):
    """{name: value} of the datasets in one group of any HDF5 file (strings as str)."""
    with open_h5(path) as f:
        g = f[group]
        return {k: _text(v) if isinstance(v, bytes) else v for k, v in _read_group(g).items()}


# What h5summary.py and compare_outputs.py need to walk any file.
def is_group(obj):
    return isinstance(obj, h5py.Group)


def is_dataset(obj):
    return isinstance(obj, h5py.Dataset)


def link_target(group, name):
    """"path" of a soft link, "file:path" of an external link, None for a hard link."""
    link = group.get(name, getlink=True)
    if isinstance(link, h5py.SoftLink):
        return link.path
    if isinstance(link, h5py.ExternalLink):
        return f"{link.filename}:{link.path}"
    return None


def objects(f):
    """{"/path": object} of every group, dataset and named datatype of an open file, "/" too."""
    found = {"/": f}
    f.visititems(lambda name, obj: found.__setitem__("/" + name, obj))
    return found


def attribute_type(obj, name):
    """(dtype, shape) of the attribute `name` of obj as stored in the file (obj.attrs[name]
    gives the value, converted)."""
    aid = h5py.h5a.open(obj.id, name.encode())
    return aid.dtype, aid.shape


def string_info(dtype):
    """None for a non-string dtype, else an object whose .length is None (variable length) or
    the fixed length."""
    return h5py.check_string_dtype(dtype)


# ---- writing -------------------------------------------------------------------------------


def write_observables(path, series=None, results=None, scene=None, copy_from=None):
    """Writes an observables file as the tools read it (and as narrows lays it out).

    series: {name: {"step": [T], "time": [T], "value": [T][...], "bins": ..., ...}}, each key a
    dataset of /observables/<name> in the order given; results: {name: {key: array}} written
    the same way (give "step" a scalar), or {name: FILE} to copy /observables/<name> whole from
    FILE; copy_from: a file whose /h5md and /parameters are copied whole; scene: TOML text
    written to /parameters/scene (a variable-length UTF-8 string, as narrows writes it) unless
    copy_from brought one."""
    with h5py.File(path, "w") as out:
        if copy_from is not None:
            with h5py.File(copy_from, "r") as src:
                for group in ("h5md", "parameters"):
                    if group in src:
                        src.copy(group, out)
        if scene is not None and "parameters/scene" not in out:
            out.create_dataset("parameters/scene", data=scene, dtype=h5py.string_dtype("utf-8"))
        obs = out.create_group("observables")
        for name, data in (series or {}).items():
            g = obs.create_group(name)
            for key, value in data.items():
                g.create_dataset(key, data=value)
        for name, data in (results or {}).items():
            if isinstance(data, str):
                with h5py.File(data, "r") as src:
                    src.copy("observables/" + name, obs)
            else:
                g = obs.create_group(name)
                for key, value in data.items():
                    g.create_dataset(key, data=value)


def write_table(path, columns):
    """Writes a table {column: [values]} (all columns one length) to path as /table/<column>:
    a float64 dataset where every value is a number, bool or None (None as NaN), else a
    variable-length UTF-8 string dataset (None as ""). Column names with "/" get "_"."""
    with h5py.File(path, "w") as out:
        g = out.create_group("table")
        for name, values in columns.items():
            key = name.replace("/", "_")
            if all(v is None or isinstance(v, (int, float, bool, np.number)) for v in values):
                data = np.array([np.nan if v is None else float(v) for v in values], float)
                g.create_dataset(key, data=data)
            else:
                g.create_dataset(key, data=["" if v is None else str(v) for v in values],
                                 dtype=h5py.string_dtype("utf-8"))


# ---- plots ---------------------------------------------------------------------------------


def pyplot():
    """matplotlib.pyplot with the Agg backend (PNG files, no display), as every tool draws.
    The figures keep matplotlib's default style; each tool sets its own size and dpi."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt
