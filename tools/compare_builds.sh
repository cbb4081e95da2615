#!/usr/bin/env bash
# Proves that a change (a refactor) preserves behaviour bitwise: runs every scene of run/,
# shortened, with two narrows binaries on 1 and on 3 MPI ranks and compares the outputs.
#
#   bash tools/compare_builds.sh BEFORE_BINARY AFTER_BINARY [OUTDIR]   # OUTDIR: /tmp/compare_builds
#   SCENES='run/sed*.toml' RANKS='1 3' bash tools/compare_builds.sh ...  # (these are the defaults:
#                                                                        #  run/*.toml and "1 3")
# Both binaries run the same scene files (from this checkout's run/) with the same --set
# overrides (SHORTEN below), into OUTDIR/before/SCENE/nR and OUTDIR/after/SCENE/nR (stdout,
# stderr and exit code next to them as nR.stdout, nR.stderr, nR.rc). Each pair of folders is
# compared by tools/compare_outputs.py: every .h5 file dataset by dataset and attribute by
# attribute bitwise (except the program version), log.txt line by line without its timing lines,
# any other file byte by byte. One line per (scene, ranks) (details follow it indented):
#   same                    both ran (exit 0), every output is identical, and so is what narrows
#                           wrote to stderr
#   refused alike           both refused on more than one rank (the same exit code 1-125 and the
#                           same `narrows:` line on stderr, no .h5 written), e.g. random-permute
#                           on 3 ranks
#   DIFFERENT: <file> <dataset or attribute> <first differing index>   (log.txt: line number)
#   DIFFERENT: BEFORE exit ..., AFTER exit ...   exit codes or refusal lines differ, a run
#                           crashed (signal, timeout, mpirun error) or refused where the other
#                           ran; also a refusal on 1 rank (then the scene is not tested at all)
# and a final line `compare_builds: N same, M refused alike, K different (T s)`, also in
# OUTDIR/report.txt. Exit 1 if anything is different, 0 otherwise (2 on a usage error). Each
# run is limited to RUN_TIMEOUT seconds (default 300; a timeout is a crash). All 34 scenes of
# run/ on 1 and 3 ranks (136 runs, none over 10 s): 75 s on this 2-core machine when idle,
# 4 min with a parallel build loading it (load average 10).
set -uo pipefail

# ---------------------------------------------------------------------------------------------
# Shortening, one line per scene of run/: the scene's file name without .toml, then its --set
# overrides (key=value, no spaces inside a value). Every run stays within ~20 s, writes several
# observables samples and a checkpoint before the final one (but lgca_dhumieres_fig1: the 1D
# model keeps no checkpoints); big boxes are shrunk but keep every feature of the scene
# (walls, colloids, contacts, kinds, trajectories).
# A scene not listed here gets DEFAULT_<engine> (below) instead.
read -r -d '' SHORTEN <<'TABLE'
accuracy_channel                  run.steps=400 output.every=50 output.checkpoint_every=200
ata_fluid_table5_1_2d             run.steps=200 output.every=25 output.checkpoint_every=100 domain.size=[60.0,24.0]
ata_fluid_table5_1_3d             run.steps=150 output.every=25 output.checkpoint_every=100 domain.size=[15.0,20.0,15.0]
colloid_diffusion_fig4_9_2d       run.steps=200 output.every=25 output.checkpoint_every=100 domain.size=[24.0,24.0] colloids.statistics_from=20 colloids.correlation_every=2 colloids.max_lag=40
colloid_diffusion_fig4_9_3d       run.steps=200 output.every=25 output.checkpoint_every=100 domain.size=[15.0,12.0,12.0] colloids.statistics_from=20 colloids.correlation_every=2 colloids.max_lag=40
colloid_kinds_channel             run.steps=200 output.every=20 output.checkpoint_every=100 colloids.statistics_from=40
colloids_conservation             run.steps=400 output.every=25 output.checkpoint_every=200
continuum_burgers_riemann         continuum.time=200.0 continuum.samples=10 output.checkpoint_every=400
continuum_jamming_pulses          continuum.time=40.0 continuum.samples=20 continuum.cells=1024 output.checkpoint_every=2000
continuum_segregation_2d          continuum.time=20000.0 continuum.samples=10 output.checkpoint_every=10000
kmc_family1_periodic              kmc.time=200.0 kmc.warmup=20.0 kmc.replicas=6 output.checkpoint_every=2
kmc_family1_product               kmc.time=200.0 kmc.warmup=20.0 kmc.replicas=6 output.checkpoint_every=2
kmc_family1_shock                 kmc.time=100.0 kmc.samples=10 kmc.replicas=6 output.checkpoint_every=2
kmc_family2_shock                 kmc.time=100.0 kmc.samples=10 kmc.replicas=6 output.checkpoint_every=2
lgca_channel                      run.steps=1000 output.every=100 output.checkpoint_every=500
lgca_colloid_held                 run.steps=4000 output.every=1000 output.checkpoint_every=2000 colloid.max_lag=200 colloid.displacement_lag=1000 colloid.displacement_every=50
lgca_colloid_held_light           run.steps=4000 output.every=1000 output.checkpoint_every=2000 colloid.max_lag=200 colloid.displacement_lag=1000 colloid.displacement_every=50
lgca_colloid_moving               run.steps=4000 output.every=1000 output.checkpoint_every=2000 colloid.max_lag=200 colloid.displacement_lag=1000 colloid.displacement_every=50
lgca_dhumieres_fig1               run.steps=4000 tagged.max_lag=100 tagged.replicas=6
lgca_shear_wave                   run.steps=400 output.every=5 output.checkpoint_every=200
lgca_vacf_tail                    run.steps=1000 output.every=250 output.checkpoint_every=500 tagged.max_lag=100
poiseuille_fig3_6                 run.steps=400 output.every=50 output.checkpoint_every=200
poiseuille_fig3_7                 run.steps=400 output.every=50 output.checkpoint_every=200
pulses_fluid_viscosity            run.steps=200 output.every=25 output.checkpoint_every=100 domain.size=[100.0,25.0]
pulses_table6_1                   run.steps=200 output.every=20 output.checkpoint_every=100 domain.size=[80.0,20.0]
quickstart                        run.steps=400 output.every=50 output.checkpoint_every=200
random_solvent_wake               run.steps=200 output.every=20 output.checkpoint_every=100 output.trajectory_every=50
sedimentation_1000                run.steps=200 output.every=20 output.checkpoint_every=100
sedimentation_chain_31            run.steps=300 output.every=25 output.checkpoint_every=150
sedimentation_fig4_10             run.steps=400 output.every=25 output.checkpoint_every=200
segregation_2d                    run.steps=400 output.every=20 output.checkpoint_every=200 colloids.statistics_from=100
segregation_table5_1_channel_2d   run.steps=150 output.every=25 output.checkpoint_every=100 colloids.statistics_from=50 domain.size=[60.0,40.0] colloids.kind=[{radius=4.0,count=8},{radius=2.0,count=8}]
strong_scaling                    run.steps=100 output.every=20 output.checkpoint_every=50 domain.size=[300.0,50.0]
tasep_open                        kmc.time=500.0 kmc.warmup=50.0 kmc.replicas=6 output.checkpoint_every=2
TABLE

# Default shortening of a scene that is not in the table, by its run.engine. Keys that only
# make sense when the scene has them are added when the scene text names them (see
# default_overrides). A scene with a big box may still be slow: add it to the table.
DEFAULT_mpcd="run.steps=100 output.every=20 output.checkpoint_every=50"
DEFAULT_lgca="run.steps=400 output.every=100 output.checkpoint_every=200"
DEFAULT_kmc="kmc.time=50.0 kmc.replicas=6 output.checkpoint_every=2"
DEFAULT_continuum="continuum.samples=4 output.checkpoint_every=0"   # + continuum.time / 100
# ---------------------------------------------------------------------------------------------

usage() { echo "usage: bash tools/compare_builds.sh BEFORE_BINARY AFTER_BINARY [OUTDIR]" >&2; exit 2; }
[[ $# -ge 2 && $# -le 3 ]] || usage
before=$(realpath -e "$1") || { echo "compare_builds: no binary $1" >&2; exit 2; }
after=$(realpath -e "$2") || { echo "compare_builds: no binary $2" >&2; exit 2; }
[[ -x "$before" && -x "$after" ]] || { echo "compare_builds: $1 or $2 is not executable" >&2; exit 2; }
outdir=${3:-/tmp/compare_builds}
mkdir -p "$outdir" || exit 2
outdir=$(realpath "$outdir")
cd "$(dirname "$0")/.." || exit 2
ranks_list=${RANKS:-1 3}
run_timeout=${RUN_TIMEOUT:-300}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_pml=ob1

# The value of `key = value` in the scene text (first match, quotes removed), or nothing.
scene_value() {
  sed -nE "s/^[[:space:]]*$2[[:space:]]*=[[:space:]]*\"?([^\"#]*[^\"#[:space:]])\"?.*/\1/p" "$1" | head -n 1
}

default_overrides() {
  local scene=$1 engine=$2 sets time
  case "$engine" in
    mpcd)
      sets=$DEFAULT_mpcd
      grep -qE '^[[:space:]]*trajectory_every' "$scene" && sets+=" output.trajectory_every=25"
      grep -qE '^[[:space:]]*statistics_from' "$scene" && sets+=" colloids.statistics_from=20"
      grep -qE '^[[:space:]]*max_lag' "$scene" && sets+=" colloids.correlation_every=2 colloids.max_lag=20"
      ;;
    lgca)
      sets=$DEFAULT_lgca
      grep -qE '^\[tagged\]' "$scene" && sets+=" tagged.max_lag=40"
      grep -qE '^\[colloid\]' "$scene" &&
        sets+=" colloid.max_lag=50 colloid.displacement_lag=100 colloid.displacement_every=20"
      ;;
    kmc)
      sets=$DEFAULT_kmc
      grep -qE '^[[:space:]]*warmup' "$scene" && sets+=" kmc.warmup=5.0"
      grep -qE '^[[:space:]]*samples' "$scene" && sets+=" kmc.samples=10"
      ;;
    continuum)
      sets=$DEFAULT_continuum
      time=$(scene_value "$scene" time)
      [[ -n "$time" ]] && sets+=" continuum.time=$(awk -v t="$time" 'BEGIN { printf "%.6g", t / 100 }')"
      ;;
    *) sets="" ;;
  esac
  echo "$sets"
}

# The overrides of a scene: its table line, or the default of its engine.
overrides() {
  local scene=$1 name line engine
  name=$(basename "$scene" .toml)
  line=$(awk -v n="$name" '$1 == n { $1 = ""; print; exit }' <<<"$SHORTEN")
  if [[ -n "$line" ]]; then
    echo "$line"
    return
  fi
  engine=$(scene_value "$scene" engine)
  default_overrides "$scene" "${engine:-mpcd}"
}

# run BINARY RANKS SCENE DIR SETS...: one run into DIR; DIR.stdout, DIR.stderr, DIR.rc.
run_one() {
  local binary=$1 ranks=$2 scene=$3 dir=$4 status
  shift 4
  rm -rf "${dir:?}" "$dir.stdout" "$dir.stderr" "$dir.rc"
  mkdir -p "$(dirname "$dir")"
  if [[ "$ranks" -eq 1 ]]; then
    timeout -k 30 "$run_timeout" "$binary" run "$scene" "$@" --out "$dir" >"$dir.stdout" 2>"$dir.stderr"
    status=$?
  else
    timeout -k 30 "$run_timeout" mpirun -n "$ranks" --oversubscribe "$binary" run "$scene" "$@" \
      --out "$dir" >"$dir.stdout" 2>"$dir.stderr"
    status=$?
  fi
  echo "$status" >"$dir.rc"
  return 0
}

# The refusal line of a run: the first line narrows wrote to stderr (mpirun's own report after
# it names process ids that differ from run to run).
refusal_line() { grep -m 1 '^narrows: ' "$1" || true; }
# What narrows itself wrote to stderr (warnings, errors), without mpirun's reports.
narrows_stderr() { grep -E '^(narrows|warning|error)' "$1" || true; }
has_h5() { [[ -n "$(find "$1" -name '*.h5' -print -quit 2>/dev/null)" ]]; }
has_checkpoint() { [[ -n "$(find "$1" -name 'checkpoint-*.h5' -print -quit 2>/dev/null)" ]]; }
describe_exit() {
  case "$1" in
    0) echo "exit 0" ;;
    124) echo "timed out after ${run_timeout} s" ;;
    *) if [[ "$1" -gt 128 ]]; then echo "killed by signal $(($1 - 128))"; else echo "exit $1"; fi ;;
  esac
}

shopt -s nullglob
# shellcheck disable=SC2206 # SCENES is a glob (or several): split and expand it on purpose
scenes=(${SCENES:-run/*.toml})
shopt -u nullglob
[[ ${#scenes[@]} -gt 0 ]] || { echo "compare_builds: no scene matches ${SCENES:-run/*.toml}" >&2; exit 2; }

n_same=0 n_refused=0 n_different=0
report="$outdir/report.txt"
: >"$report"
say() { echo "$*" | tee -a "$report"; }

say "compare_builds: BEFORE $before"
say "compare_builds: AFTER  $after"
say "compare_builds: ${#scenes[@]} scenes on ranks ${ranks_list}, outputs in $outdir"
start=$SECONDS
for scene in "${scenes[@]}"; do
  name=$(basename "$scene" .toml)
  read -r -a keys <<<"$(overrides "$scene")"
  sets=()
  for kv in "${keys[@]}"; do sets+=(--set "$kv"); done
  echo "${keys[*]}" >"$outdir/$name.overrides"
  for ranks in $ranks_list; do
    t0=$SECONDS
    a="$outdir/before/$name/n$ranks" b="$outdir/after/$name/n$ranks"
    sum0=$(cksum <"$scene")
    run_one "$before" "$ranks" "$scene" "$a" "${sets[@]}"
    run_one "$after" "$ranks" "$scene" "$b" "${sets[@]}"
    rca=$(<"$a.rc") rcb=$(<"$b.rc")
    label=$(printf '%-34s n%-2s' "$name" "$ranks")
    if [[ "$(cksum <"$scene")" != "$sum0" ]]; then # someone edited it: the runs saw two scenes
      n_different=$((n_different + 1))
      say "$label DIFFERENT: $scene changed while the two builds ran it; run again"
      continue
    fi
    if [[ "$rca" -eq 0 && "$rcb" -eq 0 ]]; then
      result=$(/usr/bin/python3 tools/compare_outputs.py "$a" "$b")
      status=$?
      if [[ $status -eq 0 ]]; then
        ea=$(narrows_stderr "$a.stderr") eb=$(narrows_stderr "$b.stderr")
        if [[ "$ea" != "$eb" ]]; then
          status=1
          result="DIFFERENT: stderr: $(diff <(echo "$ea") <(echo "$eb") | grep -m 2 '^[<>]' | tr '\n' ' ')"
        fi
      fi
      echo "$result" >"$b.compare"
      note=""
      has_checkpoint "$a" || note=", no checkpoint written"
      if [[ $status -eq 0 ]]; then
        n_same=$((n_same + 1))
        say "$label same   ($((SECONDS - t0)) s$note)"
      else
        n_different=$((n_different + 1))
        say "$label $(head -n 1 <<<"$result")"
        while IFS= read -r line; do say "  $line"; done < <(sed -n '2,4p' <<<"$result")
        [[ $(wc -l <<<"$result") -le 4 ]] || say "    (all of them: $b.compare)"
      fi
      continue
    fi
    la=$(refusal_line "$a.stderr") lb=$(refusal_line "$b.stderr")
    # A refusal: exit 1-125 but timeout's 124, a `narrows:` line, nothing written; on more than
    # one rank (a run on one rank must succeed, or the scene is not tested at all).
    if [[ "$rca" -eq "$rcb" && "$rca" -ge 1 && "$rca" -le 125 && "$rca" -ne 124 && -n "$la" &&
          "$la" == "$lb" && "$ranks" -gt 1 ]] && ! has_h5 "$a" && ! has_h5 "$b"; then
      n_refused=$((n_refused + 1))
      say "$label refused alike   (exit $rca: ${la:0:120})"
    else
      n_different=$((n_different + 1))
      if [[ "$rca" -eq "$rcb" && -n "$la" && "$la" == "$lb" && "$ranks" -eq 1 ]]; then
        say "$label DIFFERENT: both refused on $ranks rank(s) ($(describe_exit "$rca")): a run on one rank must succeed: fix the scene or its line in tools/compare_builds.sh"
      else
        say "$label DIFFERENT: BEFORE $(describe_exit "$rca"), AFTER $(describe_exit "$rcb")"
      fi
      say "    BEFORE stderr: ${la:-$(grep -m 1 . "$a.stderr" || echo '(empty)')}"
      say "    AFTER  stderr: ${lb:-$(grep -m 1 . "$b.stderr" || echo '(empty)')}"
    fi
  done
done
say "compare_builds: $n_same same, $n_refused refused alike, $n_different different ($((SECONDS - start)) s)"
[[ $n_different -eq 0 ]]
