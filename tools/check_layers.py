#!/usr/bin/env python3
"""Checks the layers of narrows' source tree against the include graph.

Usage: check_layers.py REPO_ROOT [--graph]

Every file under src/ and include/narrows/ belongs to a module (its folder: core, species,
parallel, io, models/three_state, scene, run, the kernel areas, the engines, app = src/main.cpp).
A module may include only the modules listed for it in ALLOWED below (and itself); an include
against that list, or a module missing from it, is reported as FILE:LINE with the rule, and the
exit status is 1. --graph prints the module graph as it is. docs/architecture.md draws the
same layers; change both together.
"""
import pathlib
import re
import sys

# module -> the modules it may include, lowest layers first.
BASE = ["core"]
ALLOWED = {
    "core": [],
    "species": ["core"],
    "parallel": ["core", "species"],
    "io": ["core", "species"],  # a leaf: HDF5 files, no physics, no scene meanings
    "models/three_state": ["core"],  # the three-state lattice-gas model: rates, presets, theory
    "scene": ["core", "models/three_state"],  # TOML -> validated plain structs
    "run": ["core", "species", "parallel", "io", "scene"],  # the one loop and its shell
    # Kernels: plain loops over arrays, told what to do by plain parameters (no scene types).
    "engines/mpcd/kernels": ["core", "species", "parallel"],
    "engines/mpcd/walls": ["core", "species", "engines/mpcd/kernels"],
    "colloids": ["core", "species", "parallel", "engines/mpcd/kernels"],
    "analysis": ["core", "species", "engines/mpcd/kernels", "colloids"],
    "engines/mpcd/coupling": ["core", "species", "parallel", "engines/mpcd/kernels",
                              "engines/mpcd/walls", "colloids"],
    # Engines: anything below, never another engine.
    "engines/mpcd": ["core", "species", "parallel", "io", "scene", "run", "engines/mpcd/kernels",
                     "engines/mpcd/walls", "engines/mpcd/coupling", "colloids", "analysis"],
    "engines/lgca": ["core", "species", "parallel", "io", "scene", "run", "analysis"],
    "engines/kmc": ["core", "species", "parallel", "io", "scene", "run", "models/three_state"],
    "engines/continuum": ["core", "species", "parallel", "io", "scene", "run",
                          "models/three_state"],
    "app": ["core", "scene", "run", "engines/mpcd", "engines/lgca", "engines/kmc",
            "engines/continuum", "colloids"],
}


def module_of(rel):
    """Module of a path relative to src/ or include/narrows/."""
    parts = rel.split("/")
    if len(parts) == 1:
        return "app"
    if parts[0] == "engines":
        if parts[1] == "mpcd" and len(parts) > 3:
            return "engines/mpcd/" + parts[2]
        return "engines/" + parts[1]
    if parts[0] == "models":
        return "models/" + parts[1]
    return parts[0]


def cycle_in_table():
    """A cycle in ALLOWED itself (the layers must form a DAG), or None."""
    state = {}

    def visit(mod, path):
        state[mod] = "open"
        for dep in ALLOWED.get(mod, []):
            if state.get(dep) == "open":
                return path + [dep]
            if dep not in state:
                found = visit(dep, path + [dep])
                if found:
                    return found
        state[mod] = "done"
        return None

    for mod in ALLOWED:
        if mod not in state:
            found = visit(mod, [mod])
            if found:
                return found
    return None


def main():
    cycle = cycle_in_table()
    if cycle:
        print(f"layers: the layer table has a cycle: {' -> '.join(cycle)}")
        return 1
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    include = re.compile(r'^\s*#\s*include\s+"narrows/([^"]+)"')
    problems, graph = [], {}
    for base in (root / "src", root / "include" / "narrows"):
        for path in sorted(base.rglob("*")):
            if path.suffix not in (".cpp", ".hpp", ".h") or not path.is_file():
                continue
            rel = path.relative_to(base).as_posix()
            mod = module_of(rel)
            shown = path.relative_to(root).as_posix()
            if mod not in ALLOWED:
                problems.append(f"{shown}: module '{mod}' is not in the layer table "
                                f"(tools/check_layers.py ALLOWED)")
                continue
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                m = include.match(line)
                if not m:
                    continue
                target = module_of(m.group(1))
                if target == mod:
                    continue
                graph.setdefault(mod, set()).add(target)
                if target not in ALLOWED[mod]:
                    problems.append(f"{shown}:{number}: {mod} includes {target} "
                                    f"(narrows/{m.group(1)}); {mod} may include only: "
                                    f"{', '.join(ALLOWED[mod]) or 'nothing'}")
    if "--graph" in sys.argv:
        for mod in sorted(graph):
            print(f"{mod} -> {', '.join(sorted(graph[mod]))}")
    for p in problems:
        print(p)
    if problems:
        print(f"layers: {len(problems)} includes against the layers")
        return 1
    print(f"layers: {sum(len(v) for v in graph.values())} module dependencies, all downward")
    return 0


if __name__ == "__main__":
    sys.exit(main())
