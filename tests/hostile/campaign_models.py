"""The classes of issue 35 in the hostile-input campaign (tests/hostile/campaign.py runs them):

  colloid checkpoints   no-slip colloids without contacts, with hard contacts (2D and 3D) and
                        with spring contacts: a checkpoint written on 1, 2 or 3 ranks, edited as a
                        hostile user would (tests/hostile/edit_checkpoint.py rewrites the
                        checksums, so only the restart's state check can refuse it) into an
                        impossible state, restarted on 1, 2 or 3 ranks;
  continuum checkpoints conservation law (Burgers, TASEP), jamming and segregation, likewise;
  extreme model values  colloids.spring.*, the keys of hard-contact and no-slip scenes and
                        continuum.* at 0, -1, 1e300, 5e-324, nan, inf (and a few more), through
                        `check` and, when accepted, a short `run` on 1, 2 or 3 ranks;
  signals               SIGTERM early and late into no-slip, hard, spring and continuum runs.

An impossible state must be refused: exit 2, one line on stderr, nothing in --out. Exit 0 is an
impossible state accepted, exit 3 (an invariant stop after the first step) one not refused: both
fail the campaign, as do crashes (a signal, an exit other than 0, 2, 3) and hangs. Cases marked
"either" (edits of values a restart may legitimately recompute or accept) need only a clean end.
Each untouched checkpoint must restart (the control).
"""
import os
import shutil
import signal
import subprocess
import tempfile
import time

import h5py
import numpy as np

import edit_checkpoint

C = "/particles/colloids"
K = "/particles/contacts"
WALL_IDS = (2**64 - 2, 2**64 - 1)
EXTREMES = ["0", "-1", "1e300", "5e-324", "nan", "inf"]
EXTRA = ["-inf", "-1e300", "1e-300", '"x"']

# (label, scene in run/, --set overrides of the first (writing) run, --set of the restart (3
# steps beyond the checkpoint: an edited /parameters/step = run.steps would answer "nothing to
# run" before the data are read),
#  kind): small and short versions of the scenes of run/.
COLLOID_SCENES = [
    ("hard 2D", "segregation_reduced_2d.toml", ["run.steps=3"], ["run.steps=6"], "hard"),
    ("hard 3D", "suspension_viscosity_fig5_4.toml", ["run.steps=3"], ["run.steps=6"], "hard"),
    ("spring", "pulses_vss_short.toml", ["run.steps=3", "domain.size=[100.0, 50.0]"],
     ["run.steps=6", "domain.size=[100.0, 50.0]"], "spring"),
    ("no-slip", "colloid_diffusion_fig4_9_2d.toml",
     ["run.steps=3", "domain.size=[20.0, 20.0]"], ["run.steps=6", "domain.size=[20.0, 20.0]"],
     "none"),
]
B = ["continuum.time=40", "continuum.samples=4", "output.checkpoint_every=100"]
CONTINUUM_SCENES = [
    ("burgers", "continuum_burgers_riemann.toml", B, "burgers"),
    ("tasep", "continuum_burgers_riemann.toml", B + ['continuum.flux="tasep"'], "tasep"),
    ("jamming", "continuum_jamming_pulses.toml",
     ["continuum.time=1", "continuum.samples=2", "continuum.cells=512",
      "output.checkpoint_every=100"], "jamming"),
    ("segregation", "continuum_segregation_2d.toml",
     ["continuum.time=2000", "continuum.samples=2", "output.checkpoint_every=1000"],
     "segregation"),
]


def sets(pairs):
    out = []
    for p in pairs:
        out += ["--set", p]
    return out


def launch(narrows, ranks, args):
    """The command of narrows ARGS on `ranks` ranks (1: a singleton, without mpirun)."""
    if ranks == 1:
        return [narrows] + args
    cmd = ["mpirun", "--quiet", "--oversubscribe", "-n", str(ranks)]
    if os.geteuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd + [narrows] + args


def execute(cmd, budget, grace=15.0, cwd=None):
    """(outcome, exit code, seconds, stderr lines): outcome refused/accepted/invariant/crash/
    hang/stopped; SIGTERM at the budget, SIGKILL (a hang) after the grace period."""
    start = time.monotonic()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=cwd,
                         start_new_session=True)
    stopped = False
    try:
        _, err = p.communicate(timeout=budget)
    except subprocess.TimeoutExpired:
        stopped = True
        os.killpg(p.pid, signal.SIGTERM)
        try:
            _, err = p.communicate(timeout=grace)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.communicate()
            return "hang", None, time.monotonic() - start, []
    seconds = time.monotonic() - start
    lines = [l for l in err.decode("utf-8", "replace").splitlines() if l.strip()]
    code = p.returncode
    if code < 0 or code not in (0, 2, 3):
        return "crash", code, seconds, lines
    if stopped:
        return "stopped", code, seconds, lines
    return {0: "accepted", 2: "refused", 3: "invariant"}[code], code, seconds, lines


def ranks_of(pid):
    """The pids of the narrows processes below `pid` (mpirun's ranks)."""
    children = {}
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/stat") as f:
                    fields = f.read().rsplit(")", 1)[1].split()
                with open(f"/proc/{d}/comm") as f:
                    comm = f.read().strip()
            except OSError:
                continue
            children.setdefault(int(fields[1]), []).append((int(d), comm))
    out, todo = [], [pid]
    while todo:
        for child, comm in children.get(todo.pop(), []):
            todo.append(child)
            if comm == "narrows":
                out.append(child)
    return out


def catches_sigterm(pid):
    """Whether process pid has a handler of SIGTERM (SigCgt of /proc/pid/status)."""
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith("SigCgt:"):
                    return bool(int(line.split()[1], 16) >> (signal.SIGTERM - 1) & 1)
    except OSError:
        pass
    return False


def signalled(cmd, ranks, delay, bound=20.0):
    """(outcome, exit code, seconds, stderr lines) of cmd sent SIGTERM `delay` s after its
    handlers were installed (main() does it first, before MPI_Init; until then the dynamic
    loader runs, 0.06 s after exec and over 0.1 s on a loaded machine, and the default action
    kills: no program can help it). On N ranks the signal goes to each rank, as a batch system
    sends it (mpirun itself dies by a signal that comes before it has set up its handlers).
    "accepted" if it ended with exit 0 within `bound` s of the signal, "invariant" if it stopped
    with exit 3 (a broken invariant: one line, before or after the signal), "crash" if a signal
    killed it or it exited otherwise, "hang" past the bound."""
    start = time.monotonic()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                         start_new_session=True)
    pids = [p.pid]
    while time.monotonic() - start < 20 and p.poll() is None:
        if ranks > 1:
            pids = ranks_of(p.pid)
        if len(pids) == ranks and all(catches_sigterm(q) for q in pids):
            break
        time.sleep(0.002)
    time.sleep(delay)
    for pid in pids:
        try:
            os.kill(pid, signal.SIGTERM)
        except ProcessLookupError:
            pass
    try:
        _, err = p.communicate(timeout=bound)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        return "hang", None, time.monotonic() - start, []
    lines = [l for l in err.decode("utf-8", "replace").splitlines() if l.strip()]
    outcome = {0: "accepted", 3: "invariant"}.get(p.returncode, "crash")
    if outcome == "invariant" and len(lines) != 1:
        outcome = "crash"
    return outcome, p.returncode, time.monotonic() - start, lines


def written(out):
    return os.path.isdir(out) and bool(os.listdir(out))


class State:
    """What the edits need of an untouched colloid checkpoint."""

    def __init__(self, path, kind):
        with h5py.File(path, "r") as f:
            self.pos = f[C + "/position/value"][()]
            self.radius = f[C + "/radius/value"][()]
            self.mass = f[C + "/mass/value"][()]
            self.ids = f[C + "/id/value"][()]
            self.edges = f[C + "/box/edges"][()]
            self.step = int(f["/parameters/step"][()])
            self.scene = bytes(f["/parameters/scene"][()]).decode()
            self.canonical = bytes(f["/parameters/canonical_scene"][()]).decode()
            self.colloid_fields = sorted(k for k in f[C] if k != "box")
            self.contacts = K in f
            if self.contacts:
                self.owner = f[K + "/owner_id/value"][()]
                self.partner = f[K + "/partner_id/value"][()]
                self.contact_fields = sorted(k for k in f[K] if k != "box")
        self.kind = kind
        self.n, self.dim = self.pos.shape
        self.walls = kind != "none"  # the channels have walls at y = 0 and y = L_y


def colloid_edits(s, rng, rounds):
    """(label, edit words, must_refuse) of the impossible states of colloid checkpoint s;
    `rounds` draws of the random ones (rows, pairs)."""
    out = []
    pv, rv, mv, iv = C + "/position/value", C + "/radius/value", C + "/mass/value", C + "/id/value"

    def setpos(row, p):
        words = []
        for c in range(s.dim):
            words += ["set", pv, f"{row},{c}", repr(float(p[c]))]
        return words

    for _ in range(rounds):
        r = rng.randrange(s.n)
        if s.n >= 2:
            i, j = rng.sample(range(s.n), 2)
            out.append((f"row {j} on the centre of row {i}", setpos(j, s.pos[i]), True))
            d = rng.uniform(0.05, 0.4) * min(s.radius[i], s.radius[j])
            u = np.array([rng.gauss(0, 1) for _ in range(s.dim)])
            p = s.pos[i] + d * u / np.linalg.norm(u)
            out.append((f"rows {i} and {j} {d:.3g} apart", setpos(j, p), True))
        out.append((f"radius of row {r} x0.1", ["set", rv, str(r), repr(s.radius[r] * 0.1)], True))
        out.append((f"radius of row {r} x10", ["set", rv, str(r), repr(s.radius[r] * 10)], True))
        out.append((f"radius of row {r} 1e-300", ["set", rv, str(r), "1e-300"], True))
        out.append((f"radius of row {r} 0", ["set", rv, str(r), "0"], True))
        out.append((f"radius of row {r} negative", ["set", rv, str(r), repr(-s.radius[r])], True))
        for v in ["1e300", "1e-300", "0", repr(-s.mass[r])]:
            out.append((f"mass of row {r} {v}", ["set", mv, str(r), v], True))
        c = rng.randrange(s.dim)
        for v in [s.edges[c] + 5, -5.0, s.edges[c] * 1e10, -1e300]:
            out.append((f"position of row {r} component {c} = {v:g} (outside the box)",
                        ["set", pv, f"{r},{c}", repr(float(v))], True))
        if s.walls:
            for v in [0.0, s.edges[1], -0.5 * s.radius[r], s.edges[1] + 0.5 * s.radius[r]]:
                out.append((f"centre of row {r} at y = {v:g} (on or in a wall)",
                            ["set", pv, f"{r},1", repr(float(v))], True))
            if s.kind == "hard":
                out.append((f"row {r} overlapping a wall", ["set", pv, f"{r},1",
                            repr(0.5 * s.radius[r])], True))
        for field, shape in [("velocity", 2), ("angular_velocity_z", 1)]:
            for v in ["1e300", "-1e300"]:
                idx = f"{r},{rng.randrange(s.dim)}" if shape == 2 else str(r)
                out.append((f"{field} of row {r} {v}", ["set", f"{C}/{field}/value", idx, v],
                            True))
        # NaN and inf in every float field
        for field in s.colloid_fields:
            if field == "id":
                continue
            for v in ["nan", "inf", "-inf"]:
                idx = f"{r},{rng.randrange(s.dim)}" if field in ("position", "velocity") \
                    else str(r)
                out.append((f"{field} of row {r} {v}", ["set", f"{C}/{field}/value", idx, v],
                            True))
        out.append((f"orientation_w of row {r} 0.5", ["set", C + "/orientation_w/value", str(r),
                                                     "0.5"], True))
        out.append((f"orientation_x of row {r} 1 (|q| = sqrt 2)",
                    ["set", C + "/orientation_x/value", str(r), "1"], True))
        if s.n >= 2:
            i, j = rng.sample(range(s.n), 2)
            out.append((f"id of row {j} that of row {i}", ["set", iv, str(j), str(int(s.ids[i]))],
                        True))
        if s.contacts:
            out += contact_edits(s, rng)
    # the edits without a random choice, once
    for v in ["nan", "inf"]:
        out.append((f"box edge 0 {v}", ["set", C + "/box/edges", "0", v], True))
    out.append(("box edge 0 x2 and a colloid beyond the scene's box",
                ["set", C + "/box/edges", "0", repr(2 * s.edges[0]),
                 "set", pv, "0,0", repr(1.5 * s.edges[0])], True))
    out.append(("every radius x0.1", ["scale", rv, "0.1"], True))
    out.append(("every mass 0", ["fill", mv, "0"], True))
    out.append(("every orientation 0", ["fill", C + "/orientation_w/value", "0",
                                         "fill", C + "/orientation_x/value", "0",
                                         "fill", C + "/orientation_y/value", "0",
                                         "fill", C + "/orientation_z/value", "0"], True))
    if s.n >= 2:
        out.append(("all colloids at one point", ["fill", pv, repr(float(s.edges[1] / 2))], True))
    for field in s.colloid_fields:
        out.append((f"{field} deleted", ["delete", f"{C}/{field}"], True))
        if s.n >= 2:
            out.append((f"{field}: a row removed", ["drop", f"{C}/{field}/value"], True))
        out.append((f"{field}: a row added", ["append", f"{C}/{field}/value"], True))
    out.append(("the colloids' group deleted", ["delete", C], True))
    out.append(("one colloid more in every field (a copy of the last)",
                [w for fld in s.colloid_fields for w in ["append", f"{C}/{fld}/value"]], True))
    st = s.step
    for v in [st - 1, st + 1, 0, 2**62]:
        out.append((f"/parameters/step {v}", ["set", "/parameters/step", "", str(v)], True))
    for v in ["0.5", "nan", "1e300"]:
        out.append((f"/parameters/time {v}", ["set", "/parameters/time", "", v], True))
    out.append(("position step one less", ["set", C + "/position/step", "", str(st - 1)], True))
    out.append(("mass time 1e300", ["set", C + "/mass/time", "", "1e300"], True))
    for old, new in [("dt = 0.02", "dt = 0.03"), ("seed = ", "seed = 9")]:
        if old in s.scene:
            out.append((f"/parameters/scene: '{old}' -> '{new}'",
                        ["replace", "/parameters/scene", old, new], True))
    if "fluid.dt = 0.02" in s.canonical:
        out.append(("/parameters/canonical_scene: fluid.dt 0.03",
                    ["replace", "/parameters/canonical_scene", "fluid.dt = 0.02",
                     "fluid.dt = 0.03"], True))
        out.append(("scene and canonical scene both fluid.dt 0.03",
                    ["replace", "/parameters/canonical_scene", "fluid.dt = 0.02",
                     "fluid.dt = 0.03", "replace", "/parameters/scene", "dt = 0.02",
                     "dt = 0.03"], True))
    return out


def contact_edits(s, rng):
    out = []
    pairs = [k for k in range(len(s.owner)) if int(s.partner[k]) not in WALL_IDS]
    walls = [k for k in range(len(s.owner)) if int(s.partner[k]) in WALL_IDS]
    where = {int(i): n for n, i in enumerate(s.ids)}
    if pairs:
        k = rng.choice(pairs)
        a = where[int(s.owner[k])]
        far = [n for n in range(s.n) if np.linalg.norm(s.pos[n] - s.pos[a]) >
               s.radius[n] + s.radius[a] + 2 and n != a]
        if far:
            b = rng.choice(far)
            out.append((f"contact row {k} between distant colloid ids {int(s.ids[a])} and "
                        f"{int(s.ids[b])}", ["set", K + "/partner_id/value", str(k),
                                             str(int(s.ids[b]))], True))
        out.append((f"contact row {k} of a colloid with itself",
                    ["set", K + "/partner_id/value", str(k), str(int(s.owner[k]))], True))
        out.append((f"contact row {k} with a colloid id that does not exist",
                    ["set", K + "/partner_id/value", str(k), str(10**9)], True))
        out.append((f"contact row {k}: tangential displacement 1e300",
                    ["set", K + "/tangential_displacement/value", f"{k},0", "1e300"], True))
        out.append((f"contact row {k}: tangential displacement nan",
                    ["set", K + "/tangential_displacement/value", f"{k},1", "nan"], True))
    if walls:
        k = rng.choice(walls)
        mid = int(np.argmin(np.abs(s.pos[:, 1] - s.edges[1] / 2)))
        out.append((f"wall contact row {k} moved to colloid id {int(s.ids[mid])} mid-channel",
                    ["set", K + "/owner_id/value", str(k), str(int(s.ids[mid]))], True))
    # an overlapping pair without its contact row
    if pairs:
        k = rng.choice(pairs)
        out.append((f"contact row {k} removed from every field",
                    ["set", K + "/owner_id/value", str(k), str(int(s.owner[-1])),
                     "set", K + "/partner_id/value", str(k), str(int(s.partner[-1]))] +
                    [w for f in s.contact_fields for w in ["drop", f"{K}/{f}/value"]], True))
    return out


def contact_once(s):
    out = [("the contact group deleted", ["delete", K], True)]
    for f in s.contact_fields:
        out.append((f"contact field {f} deleted", ["delete", f"{K}/{f}"], True))
        out.append((f"contact field {f}: a row removed", ["drop", f"{K}/{f}/value"], True))
        out.append((f"contact field {f}: a row added", ["append", f"{K}/{f}/value"], True))
    out.append(("one contact row more in every field (a copy of the last)",
                [w for f in s.contact_fields for w in ["append", f"{K}/{f}/value"]], True))
    out.append(("contacts: owner_id step one less",
                ["set", K + "/owner_id/step", "", str(s.step - 1)], True))
    return out


def continuum_edits(path, model, rng, rounds):
    with h5py.File(path, "r") as f:
        fields = sorted(k for k in f["/continuum"] if k != "time_step")
        n = f["/continuum/" + fields[0]].shape[0]
        step = int(f["/parameters/step"][()])
    out = []
    bad = {"burgers": ["1.5", "-1", "2", "nan", "inf", "-inf", "1e300"],
           "tasep": ["1.5", "-0.5", "2", "nan", "inf", "1e300"],
           "jamming": ["1.5", "-1", "2", "1.0000001", "nan", "inf", "1e300"],
           "segregation": ["-0.1", "1.5", "nan", "inf", "1e300"]}[model]
    for _ in range(rounds):
        for v in bad:
            r = rng.randrange(n)
            field = fields[0] if model != "segregation" else rng.choice(fields)
            out.append((f"{field}[{r}] = {v}", ["set", f"/continuum/{field}", str(r), v], True))
        if model == "jamming":
            for v in ["1e10", "-1e10", "nan", "inf"]:
                r = rng.randrange(n)
                out.append((f"velocity[{r}] = {v}", ["set", "/continuum/velocity", str(r), v],
                            True))
        if model == "segregation":
            r = rng.randrange(n)
            out.append((f"fractions at cell {r} both 0.5 (above close packing)",
                        ["set", "/continuum/fraction_0", str(r), "0.5",
                         "set", "/continuum/fraction_1", str(r), "0.5"], True))
    for field in fields:
        out.append((f"{field}: a row removed", ["drop", f"/continuum/{field}"], True))
        out.append((f"{field}: a row added", ["append", f"/continuum/{field}"], True))
        out.append((f"{field} deleted", ["delete", f"/continuum/{field}"], True))
        out.append((f"{field} all nan", ["fill", f"/continuum/{field}", "nan"], True))
    if model == "segregation":
        out.append(("fraction_1 all zero", ["fill", "/continuum/fraction_1", "0"], True))
        out.append(("fraction_0 all zero", ["fill", "/continuum/fraction_0", "0"], True))
        out.append(("fraction_0 x2", ["scale", "/continuum/fraction_0", "2"], True))
    else:
        out.append((f"{fields[0]} all 1.5", ["fill", f"/continuum/{fields[0]}", "1.5"], True))
        out.append((f"{fields[0]} all -1", ["fill", f"/continuum/{fields[0]}", "-1"], True))
    for v in [step - 1, step + 1, 0, 2**62]:
        out.append((f"/parameters/step {v}", ["set", "/parameters/step", "", str(v)], True))
    for v in ["nan", "-1", "1e300"]:
        out.append((f"/parameters/time {v}", ["set", "/parameters/time", "", v], True))
    # the stored time step: a restart may recompute it, but must end cleanly
    for v in ["0", "-1", "nan", "1e300", "5e-324"]:
        out.append((f"time_step {v}", ["set", "/continuum/time_step", "0", v], None))
    out.append(("/parameters/canonical_scene: continuum.cells = 1...",
                ["replace", "/parameters/canonical_scene", "continuum.cells = ",
                 "continuum.cells = 1"], True))
    out.append(("/parameters/scene: cells = 1...",
                ["replace", "/parameters/scene", "cells = ", "cells = 1"], True))
    return out


# The extreme-value targets: (scene, --set of a short run, keys). The run shortening leaves the
# key under test alone.
def extreme_targets():
    spring = ["colloids.spring.kn", "colloids.spring.kt", "colloids.spring.mu_cc",
              "colloids.spring.mu_cw", "colloids.spring.substeps", "colloids.packing_fraction",
              "fluid.density", "fluid.dt", "fluid.kT", "colloids.exchange"]
    hard = ["colloids.radius", "colloids.mass", "colloids.packing_fraction", "fluid.density",
            "fluid.dt", "fluid.kT", "colloids.radius_sd", "colloids.gravity"]
    hard_random = ["fluid.density", "fluid.dt", "fluid.kT", "colloids.kde_width",
                   "colloids.statistics_from", "domain.size"]
    noslip = ["colloids.radius", "colloids.mass", "colloids.count", "fluid.density", "fluid.dt",
              "fluid.kT"]
    common = ["continuum.length", "continuum.cells", "continuum.time", "continuum.samples",
              "continuum.cfl", "continuum.max_work", "continuum.diffusion"]
    burgers = common + ["continuum.initial.left", "continuum.initial.right",
                        "continuum.initial.position", "continuum.reservoirs"]
    tasep = burgers + ['continuum.rates."10->01"', 'continuum.rates."01->10"']
    jamming = common + ["continuum.drive", "continuum.initial.mean",
                        "continuum.initial.amplitude", "continuum.initial.seed"]
    segregation = ["continuum.half_width", "continuum.cells", "continuum.time",
                   "continuum.samples", "continuum.cfl", "continuum.max_work",
                   "continuum.centre_speed", "continuum.k_c", "continuum.k_eta", "continuum.k_d",
                   "continuum.max_packing", "continuum.dimensions"]
    return [
        ("pulses_vss_short.toml", ["run.steps=3", "domain.size=[100.0, 50.0]"], [], spring),
        ("suspension_viscosity_fig5_4.toml", ["run.steps=3"], [], hard),
        ("segregation_reduced_2d.toml", ["run.steps=3"], [], hard_random),
        ("colloid_diffusion_fig4_9_2d.toml", ["run.steps=3", "domain.size=[20.0, 20.0]"], [],
         noslip),
        ("continuum_burgers_riemann.toml", ["continuum.time=20", "continuum.samples=2"], [],
         burgers),
        ("continuum_burgers_riemann.toml", ["continuum.time=20", "continuum.samples=2"],
         ['continuum.flux="tasep"'], tasep),
        ("continuum_jamming_pulses.toml", ["continuum.time=0.5", "continuum.samples=2",
                                           "continuum.cells=512"], [], jamming),
        ("continuum_segregation_2d.toml", ["continuum.time=1000", "continuum.samples=2"], [],
         segregation),
    ]


def extreme_cases(values, rng):
    """(label, scene, set of check, set of the short run)."""
    out = []
    for scene, short, fixed, keys in extreme_targets():
        for key in keys:
            for v in values:
                mine = fixed + [f"{key}={v}"]
                run_sets = [x for x in short if x.split("=")[0] != key] + mine
                tag = f" ({fixed[0]})" if fixed else ""
                out.append((f"{scene}{tag}: {key} = {v}", scene, mine, run_sets,
                            rng.choice([1, 2, 3])))
    return out


class Classes:
    """Per-class and per-rank-count tallies."""
    OUTCOMES = ["cases", "refused", "accepted", "invariant", "crash", "hang",
                "impossible accepted", "messy refusal", "stopped"]

    def __init__(self, verbose):
        self.t = {}
        self.failures = []
        self.verbose = verbose

    def add(self, cls, ranks, name, outcome, detail="", fail=False):
        if self.verbose:
            print(f"{cls:22} n={ranks} {outcome:10} {name} {detail}".rstrip(), flush=True)
        for key in [(cls, "all"), (cls, ranks)]:
            row = self.t.setdefault(key, {k: 0 for k in self.OUTCOMES})
            row["cases"] += 1
            row[outcome] += 1
        if fail or outcome in ("crash", "hang", "impossible accepted", "messy refusal",
                               "stopped"):
            self.failures.append(f"{cls}, {ranks} rank(s): {outcome}: {name} {detail}".strip())

    def total(self):
        return sum(v["cases"] for (c, r), v in self.t.items() if r == "all")

    def report(self):
        lines = []
        for (cls, r), v in sorted(self.t.items(),
                                  key=lambda kv: (kv[0][0], 0 if kv[0][1] == "all" else kv[0][1])):
            head = f"{cls}" if r == "all" else f"  on {r} rank(s)"
            lines.append(f"{head}: {v['cases']} cases, {v['refused']} refused, {v['accepted']} "
                         f"accepted, {v['invariant']} invariant stops, {v['crash']} crashes, "
                         f"{v['hang']} hangs, {v['impossible accepted']} impossible accepted, "
                         f"{v['messy refusal']} refusals not clean, {v['stopped']} stopped at "
                         f"the budget")
        return lines


def campaign(narrows, src, tmp, rng, full, jobs, verbose, pool_map):
    """Runs the classes; returns the Classes tally. pool_map(fn, items) maps on `jobs` threads."""
    tally = Classes(verbose)
    run_dir = os.path.join(src, "run")
    ranks_all = [1, 2, 3]
    budget = 30.0

    # ---- untouched checkpoints: each colloid scene written on 1, 2, 3 ranks (quick: one) ----
    bases = []  # (label, scene, restart sets, kind, writer ranks, checkpoint)
    todo = []
    # (quick: a hard-contact and a spring-contact scene, a conservation law and segregation,
    # each written once, on 1, 2 or 3 ranks)
    for i, (label, scene, first, again, kind) in enumerate(COLLOID_SCENES):
        if full or i in (0, 2):
            for w in (ranks_all if full else [ranks_all[(i + 1) % 3]]):
                todo.append(("colloid", label, scene, first, again, kind, w))
    for i, (label, scene, first, kind) in enumerate(CONTINUUM_SCENES):
        if full or i in (0, 3):
            for w in (ranks_all if full else [ranks_all[i % 3]]):
                todo.append(("continuum", label, scene, first, first, kind, w))

    def write(item):
        cls, label, scene, first, again, kind, w = item
        out = tempfile.mkdtemp(prefix="base-", dir=tmp)
        outcome, code, secs, lines = execute(
            launch(narrows, w, ["run", os.path.join(run_dir, scene), "--out", out,
                                "--overwrite"] + sets(first)), 120.0)
        cks = sorted(f for f in os.listdir(out) if f.startswith("checkpoint-"))
        if outcome != "accepted" or not cks:
            return item, None, f"(exit {code}) {lines[-1:] }"
        return item, os.path.join(out, cks[0]), ""

    for item, ck, why in pool_map(write, todo):
        cls = f"{item[0]} checkpoints"
        if ck is None:
            tally.add(cls, item[6], f"first run of {item[1]}", "crash", why, fail=True)
        else:
            bases.append((item, ck))

    # ---- the cases ----
    cases = []  # (class, ranks, name, ckpt, edit words or None (control), must_refuse, cmd args)
    n_case = [0]
    for wi, ((cls, label, scene, first, again, kind, w), ck) in enumerate(bases):
        args = ["run", os.path.join(run_dir, scene)] + sets(again)
        if cls == "colloid":
            s = State(ck, kind)
            edits = colloid_edits(s, rng, 1)
            if s.contacts:
                edits += contact_once(s)
        else:
            edits = continuum_edits(ck, kind, rng, 1)
        if full:  # two thirds of them on each of the three checkpoints of a scene
            edits = [e for e in edits if rng.random() < 2 / 3]
        else:
            edits = rng.sample(edits, 3 if cls == "colloid" else 2)
        cclass = f"{cls} checkpoints"
        for r in (ranks_all if full else [rng.choice(ranks_all)]):
            cases.append((cclass, r, f"{label}: untouched, written on {w}", ck, None, None,
                          args))
        for ei, (e_label, words, must) in enumerate(edits):
            # each edit on 1, 2 and 3 ranks over the three checkpoints of a scene
            r = ranks_all[(ei + w) % 3] if full else rng.choice(ranks_all)
            cases.append((cclass, r, f"{label}: {e_label}, written on {w}", ck, words, must,
                          args))

    def restart(case):
        cls, r, name, ck, words, must, args = case
        d = tempfile.mkdtemp(prefix="case-", dir=tmp)
        path = os.path.join(d, "ck.h5")
        try:
            if words is None:
                shutil.copy(ck, path)
            else:
                edit_checkpoint.edit(ck, path, words)
        except (SystemExit, Exception) as e:  # a campaign bug, not narrows'
            shutil.rmtree(d, ignore_errors=True)
            return case, "crash", f"the edit failed: {e}"
        out = os.path.join(d, "out")
        outcome, code, secs, lines = execute(
            launch(narrows, r, args + ["--restart", path, "--out", out]), budget)
        detail = f"(exit {code}, {secs:.1f} s) {lines[-1] if lines else ''}"
        if outcome == "refused" and (len(lines) != 1 or written(out)):
            outcome = "messy refusal"
            detail += f" [{len(lines)} lines on stderr, --out {'written' if written(out) else 'empty'}]"
        shutil.rmtree(d, ignore_errors=True)
        return case, outcome, detail

    for case, outcome, detail in pool_map(restart, cases):
        cls, r, name, _, words, must, _ = case
        fail = False
        if must and outcome == "accepted":
            outcome = "impossible accepted"
        elif must and outcome == "invariant":
            fail = True  # not refused at the restart: the run stopped after it began
        elif must is None and words is None and outcome != "accepted":
            fail = True  # the control must restart
        tally.add(cls, r, name, outcome, detail, fail)

    # ---- extreme model values: check, then a short run of the accepted ones ----
    values = EXTREMES + (EXTRA if full else [])
    ext = extreme_cases(values, rng)
    if not full:
        ext = rng.sample(ext, 4)

    def extreme(case):
        name, scene, mine, run_sets, r = case
        path = os.path.join(run_dir, scene)
        res = [("extreme values: check", 1, "check " + name,
                *execute([narrows, "check", path] + sets(mine), 20.0))]
        if res[0][3] == "accepted":
            d = tempfile.mkdtemp(prefix="ext-", dir=tmp)
            out = os.path.join(d, "out")
            o = execute(launch(narrows, r, ["run", path, "--out", out] + sets(run_sets)), budget)
            if o[0] == "refused" and (len(o[3]) != 1 or written(out)):
                o = ("messy refusal",) + o[1:]
            res.append(("extreme values: run", r, "run " + name, *o))
            shutil.rmtree(d, ignore_errors=True)
        return res

    for res in pool_map(extreme, ext):
        for cls, r, name, outcome, code, secs, lines in res:
            tally.add(cls, r, name, outcome, f"(exit {code}, {secs:.1f} s) "
                      f"{lines[-1] if lines else ''}")

    # ---- stop signals, early (MPI starting, the scene read, the state built, colloids packed)
    # and late (inside the loop): every run ends with exit 0 within 20 s of a SIGTERM, never by
    # the signal's default action. The delays count from the moment the handlers are installed
    # (see signalled()): 0 falls in MPI_Init, which takes 0.8-1.7 s.
    signal_scenes = ["quickstart.toml", "continuum_burgers_riemann.toml",
                     "pulses_long_channel.toml", "lgca_shear_wave.toml",
                     "kmc_family1_product.toml", "continuum_jamming_pulses.toml",
                     "segregation_reduced_2d.toml", "suspension_viscosity_fig5_4.toml",
                     "pulses_vss_short.toml", "colloid_diffusion_fig4_9_2d.toml",
                     "continuum_segregation_2d.toml", "segregation_fig5_6_2d.toml"]
    delays = [0.0, 0.1, 0.3, 0.5, 1.0, 2.0, 3.0]
    sig = [(sc, d, r) for sc in signal_scenes for d in delays for r in ranks_all]
    sig = rng.sample(sig, 120 if full else 2)

    def stop(case):
        scene, delay, r = case
        d = tempfile.mkdtemp(prefix="sig-", dir=tmp)
        cmd = launch(narrows, r, ["run", os.path.join(run_dir, scene), "--out",
                                  os.path.join(d, "out")])
        outcome, code, secs, lines = signalled(cmd, r, delay)
        shutil.rmtree(d, ignore_errors=True)
        return r, f"SIGTERM {delay} s into {scene}", outcome, \
            f"(exit {code}, {secs:.1f} s) {lines[-1] if lines else ''}"

    for r, name, outcome, detail in pool_map(stop, sig):
        tally.add("signals", r, name, outcome, detail)
    return tally
