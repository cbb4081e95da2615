"""Running the continuum engine from the plot tools: find the narrows binary, write a
conservation-law scene whose flux is a kmc run's preset (its own rates), run it in a temporary
folder and read its observables back. Imported by kmc_plot.py and shock_report.py."""
import os
import shutil
import subprocess
import sys
import tempfile

import narrows_h5


def find_narrows(given):
    """The narrows binary: --narrows, $NARROWS, build/narrows next to tools/, or the PATH."""
    here = os.path.dirname(os.path.abspath(__file__))
    for path in (given, os.environ.get("NARROWS"), os.path.join(here, "..", "build", "narrows"),
                 shutil.which("narrows")):
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return path
    sys.exit("the narrows binary was not found; allowed: --narrows PATH, $NARROWS, "
             "build/narrows or narrows on the PATH")


def toml_value(v):
    """A TOML rendering of a number or a table of numbers (rates, parameters)."""
    if isinstance(v, dict):
        return "{ " + ", ".join(f'"{k}" = {toml_value(x)}' for k, x in v.items()) + " }"
    return repr(float(v))


def kmc_flux_lines(kmc_scene_text):
    """The [continuum] flux keys of a kmc scene's preset (family 1 or 2, with its rates)."""
    kmc = narrows_h5.parse_scene(kmc_scene_text)["kmc"]
    preset = kmc.get("preset", "none")
    if preset == "family1":
        return f'flux = "family1"\nrates = {toml_value(kmc["rates"])}\n'
    if preset == "family2":
        return f'flux = "family2"\nparameters = {toml_value(kmc["parameters"])}\n'
    sys.exit(f"kmc.preset = {preset!r} has no hydrodynamic flux; allowed: family1, family2")


def run_continuum(narrows, continuum_lines, observables=("density", "shock_position")):
    """Runs a conservation-law scene ([continuum] keys given as text); returns
    {name: (time, value)} of its observables."""
    names = ", ".join(f'"{n}"' for n in observables)
    scene = ('[run]\nengine = "continuum"\n[continuum]\nmodel = "conservation-law"\n' +
             continuum_lines + f"[output]\nobservables = [{names}]\nprogress = false\n")
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "continuum.toml")
        with open(path, "w") as f:
            f.write(scene)
        done = subprocess.run([narrows, "run", path, "--out", os.path.join(tmp, "out")],
                              capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"the continuum run failed: {done.stderr.strip()}")
        run = narrows_h5.open_run(os.path.join(tmp, "out"))
        series = {n: run.series(n) for n in observables}
        return {n: (s["time"], s["value"]) for n, s in series.items()}
