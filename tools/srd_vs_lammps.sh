#!/usr/bin/env bash
# 2D SRD of a pure solvent in narrows and in Debian's LAMMPS (`fix srd`), the same fluid, one
# core each, run back to back (issue 34, acceptance 3).
#
# Usage: bash tools/srd_vs_lammps.sh [NARROWS] [DIR] [SIZES] [STEPS]
#   defaults: build/narrows, out/srd_vs_lammps, "1e6 1e7" particles, 100 timed steps at each
#   size (after 20 steps of warm-up in both codes)
#
# The fluid: n = 10 particles per cell of size 1, mass 1, kT = 1, dt = 1 (mean free path 1),
# rotation by +-90 degrees about z in every cell (LAMMPS' fix srd rotates by 90 degrees only,
# so narrows runs at that angle too: `bench --angle 90`), the collision grid shifted at random
# every step, in the periodic box `narrows bench --case srd-2d` builds for that many particles
# (a 4:1 rectangle of whole cells; the same number of particles in LAMMPS). narrows sorts its
# particles by cell every 20 steps; LAMMPS is told to sort its atoms in bins of one cell every
# 20 steps too (atom_modify sort 20 1.0; its default is every 1000 steps, and create_atoms
# leaves them in random order).
#
# LAMMPS' cheapest pure-SRD setup found here: atom_style atomic, no pair style (no ghost atoms,
# no neighbour lists), and `fix srd 1 NULL 1.0 1.0 SEED shift yes SEED`: N = 1 (a collision
# every step), no big particles (the group NULL), T_srd = 1, grid 1. fix srd streams the SRD
# particles itself (no time integrator), and, as it must, re-bins them every step (LAMMPS counts
# each step as a neighbour-list build: its atoms migrate between processors' domains then).
# Rates are particle-steps per second of wall time of the timed loop (narrows' loop, LAMMPS'
# "Loop time") and per CPU second (narrows: getrusage of the loop; LAMMPS: its loop time times
# the "% CPU use" it prints), since on a shared machine the wall time counts the other
# processes' turns too. Nothing is asserted: times depend on the machine and its load.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
narrows=${1:-$here/build/narrows}
dir=${2:-out/srd_vs_lammps}
sizes=${3:-1e6 1e7}
steps=${4:-100}
mkdir -p "$dir"

if ! command -v lmp >/dev/null 2>&1; then
  echo "srd_vs_lammps: installing Debian's lammps"
  sudo=()
  ((EUID != 0)) && sudo=(sudo)
  "${sudo[@]}" apt-get update
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends lammps
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

for size in $sizes; do
  "$narrows" bench --case srd-2d --particles "$size" --steps "$steps" --angle 90 \
    --json >"$dir/narrows_$size.json"
  read -r n lx ly < <(/usr/bin/python3 -c '
import json, sys
c = json.load(open(sys.argv[1]))["cases"][0]
print(int(c["particles"]), int(c["box"][0]), int(c["box"][1]))' "$dir/narrows_$size.json")
  cat >"$dir/in_$size.srd" <<LMP
units lj
dimension 2
atom_style atomic
boundary p p p
region box block 0 $lx 0 $ly -0.5 0.5
create_box 1 box
create_atoms 1 random $n 4711 NULL
mass 1 1.0
velocity all create 1.0 8121 loop local dist gaussian
timestep 1.0
neighbor 0.3 bin
atom_modify sort 20 1.0
fix solvent all srd 1 NULL 1.0 1.0 49893 shift yes 54979
thermo $steps
run 20
run $steps
LMP
  lmp -in "$dir/in_$size.srd" -log "$dir/log_$size.lammps" -screen none
  /usr/bin/python3 - "$dir" "$size" <<'PY'
import json, re, sys
d, size = sys.argv[1], sys.argv[2]
c = json.load(open(f"{d}/narrows_{size}.json"))["cases"][0]
log = open(f"{d}/log_{size}.lammps").read()
loops = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", log)
cpu = re.findall(r"([0-9.]+)% CPU use", log)
seconds, steps, atoms = float(loops[-1][0]), int(loops[-1][1]), int(loops[-1][2])
per_cell = re.findall(r"SRD per actual grid cell = ([0-9.]+)", log)
lammps = atoms * steps / seconds
lammps_cpu = lammps / (float(cpu[-1]) / 100.0)
print(f"{atoms} particles in {c['box'][0]:.0f} x {c['box'][1]:.0f} cells "
      f"(LAMMPS: {per_cell[-1]} per cell), {steps} steps, one core each, run back to back")
print(f"  narrows: {c['particle_steps_per_s']:.4g} particle-steps/s "
      f"({c['per_cpu_second']:.4g} per CPU second; {c['loop_seconds']:.4g} s)")
print(f"  lammps:  {lammps:.4g} particle-steps/s ({lammps_cpu:.4g} per CPU second; "
      f"{seconds:.4g} s at {cpu[-1]} % CPU)")
print(f"  ratio narrows / lammps: {c['particle_steps_per_s'] / lammps:.3g} "
      f"(per CPU second {c['per_cpu_second'] / lammps_cpu:.3g}; goal >= 4)")
PY
done
