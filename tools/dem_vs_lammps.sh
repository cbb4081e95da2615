#!/usr/bin/env bash
# The spring-contact (DEM) kernel against LAMMPS on the same packing (issue 21, acceptance 6).
#
# Usage: bash tools/dem_vs_lammps.sh [NARROWS] [DIR] [DISKS] [STEPS]
#   defaults: build/narrows, out/dem_vs_lammps, 1.8e5 disks, 20 MPCD steps (200 sub-steps)
#
# `narrows bench --dem DISKS --dem-data DIR/packing.data` times narrows' spring contacts alone
# (no fluid, one core) on Kanehl (thesis) Table 6.1's bidisperse mixture at phi = 0.8 between
# walls and writes the same packing with its thermal velocities as a LAMMPS data file, atoms in
# narrows' order (each kind numbered along x, as every narrows packing; LAMMPS also sorts its
# atoms in space itself). LAMMPS (Debian's
# `lammps`, installed here if missing) then runs the same model on it, one process:
# pair gran/hooke/history and fix wall/gran hooke/history with k_n = k_t = 2500, no damping,
# mu = 1, fix nve/sphere disc (the disc's moment of inertia), the same sub-step 0.002 and the same
# number of them. Contact updates/s = contacts per sub-step x sub-steps / seconds, for the whole
# step (narrows' loop against LAMMPS' loop time) and for the contact kernel alone (narrows'
# contact forces against LAMMPS' Pair time, the gran/hooke/history style; its wall contacts,
# a fix, are not in it, so this ratio leans towards LAMMPS). LAMMPS does not count wall
# contacts, so its rates use narrows' contacts per sub-step after checking that the pair contacts
# at the end agree (printed). Nothing is asserted: times depend on the machine and its load.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
narrows=${1:-$here/build/narrows}
dir=${2:-out/dem_vs_lammps}
disks=${3:-1.8e5}
steps=${4:-20}
mkdir -p "$dir"

if ! command -v lmp >/dev/null 2>&1; then
  echo "dem_vs_lammps: installing Debian's lammps"
  sudo=()
  ((EUID != 0)) && sudo=(sudo)
  "${sudo[@]}" apt-get update
  "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends lammps
fi

"$narrows" bench --dem "$disks" --steps "$steps" --dem-data "$dir/packing.data" \
  --json >"$dir/narrows.json"
cat "$dir/narrows.json"

substeps=$((steps * 10))
# The density-matched masses n pi a^2 (n = 25) of the two kinds, as narrows has them.
cat >"$dir/in.dem" <<LMP
units lj
dimension 2
atom_style sphere
boundary p f p
newton off
comm_modify vel yes
read_data $dir/packing.data
set type 1 mass $(/usr/bin/python3 -c "import math; print(repr(25 * math.pi * 2.1**2))")
set type 2 mass $(/usr/bin/python3 -c "import math; print(repr(25 * math.pi * 2.94**2))")
pair_style gran/hooke/history 2500 2500 0 0 1.0 0
pair_coeff * *
neighbor 0.3 bin
neigh_modify delay 0 every 1 check yes
fix integrate all nve/sphere disc
fix walls all wall/gran hooke/history 2500 2500 0 0 1.0 0 yplane 0.0 50.0
fix flat all enforce2d
timestep 0.002
compute touching all contact/atom
compute pairs all reduce sum c_touching
variable pair_contacts equal c_pairs/2
thermo_style custom step v_pair_contacts
thermo $substeps
run 10
run $substeps
LMP
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
lmp -in "$dir/in.dem" -log "$dir/log.lammps" -screen none
/usr/bin/python3 - "$dir" <<'PY'
import json, re, sys
d = sys.argv[1]
n = json.load(open(f"{d}/narrows.json"))["dem"]
log = open(f"{d}/log.lammps").read()
loops = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps", log)
seconds, steps = float(loops[-1][0]), int(loops[-1][1])
pair_line = re.findall(r"Pair\s+\|\s+([0-9.eE+-]+)\s+\|\s+([0-9.eE+-]+)\s+\|\s+([0-9.eE+-]+)\s+\|[^|]*\|\s*([0-9.]+)", log)
contacts = [float(m) for m in re.findall(r"^\s+\d+\s+([0-9.eE+-]+)\s*$", log, re.M)]
lammps_rate = n["contacts_per_substep"] * steps / seconds
pair_seconds = float(pair_line[-1][1]) if pair_line else float("nan")  # the average of ranks
kernel_rate = n["contacts_per_substep"] * n["substeps"] / n["force_seconds"]
lammps_kernel = n["contacts_per_substep"] * steps / pair_seconds
print(f"narrows: {n['disks']} disks, {n['contacts_per_substep']:.6g} contacts per sub-step "
      f"({n['pair_contacts_end']} pairs at the end), {n['contact_updates_per_s']:.4g} contact "
      f"updates/s ({n['seconds']:.4g} s for {n['substeps']:.0f} sub-steps); contact forces alone "
      f"{n['force_seconds']:.4g} s: {kernel_rate:.4g} contact updates/s")
print(f"lammps:  pair contacts at the start {contacts[0]:.0f}, at the end {contacts[-1]:.0f}; "
      f"{steps} sub-steps in {seconds:.4g} s: {lammps_rate:.4g} contact updates/s; pair style "
      f"alone {pair_seconds:.4g} s: {lammps_kernel:.4g} contact updates/s")
print(f"ratio narrows / lammps: {n['contact_updates_per_s'] / lammps_rate:.3g} whole step, "
      f"{kernel_rate / lammps_kernel:.3g} contact kernel alone (goal >= 3)")
PY
