#!/usr/bin/env bash
# Runs every scene in run/ shortened (a few output samples, one checkpoint at the end) on P
# ranks and keeps the outputs, so that a behaviour-preserving change can be proven bitwise:
#   bash tools/scene_snapshot.sh BUILD/narrows OUTDIR [P]    # before and after the change
#   bash tools/scene_snapshot.sh --compare OUTDIR_A OUTDIR_B [--exclude /path ...]
#                                       # h5diff of every HDF5 file, without the objects named
#                                       # (e.g. a dataset one side adds on purpose)
# SCENES='run/sedimentation_*.toml' limits the run to the scenes the glob names (default run/*.toml).
# Timing lines of the logs differ between runs; only the HDF5 files are compared.
set -uo pipefail
cd "$(dirname "$0")/.."

if [[ "${1:-}" == "--compare" ]]; then
  a=$2 b=$3 same=0 differ=0
  shift 3
  exclude=()
  while [[ $# -gt 0 ]]; do
    [[ "$1" == --exclude && $# -ge 2 ]] || { echo "usage: --compare A B [--exclude /path ...]"; exit 2; }
    exclude+=(--exclude-path "$2")
    shift 2
  done
  while IFS= read -r -d '' f; do
    rel=${f#"$a"/}
    if [[ ! -f "$b/$rel" ]]; then
      echo "missing in $b: $rel"
      differ=$((differ + 1))
      continue
    fi
    # h5diff exits 0 when equal, 1 when different, 2 on error.
    if h5diff -q "${exclude[@]}" "$f" "$b/$rel" >/dev/null 2>&1; then
      same=$((same + 1))
    else
      echo "differs: $rel"
      differ=$((differ + 1))
    fi
  done < <(find "$a" -name '*.h5' -print0 | sort -z)
  echo "$same identical, $differ different"
  [[ $differ -eq 0 ]]
  exit
fi

bin=$(realpath "$1")
out=$2
ranks=${3:-1}
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
failed=0
for scene in ${SCENES:-run/*.toml}; do
  name=$(basename "$scene" .toml)
  engine=$(grep -E '^\s*engine\s*=' "$scene" | head -1 | sed -E 's/.*"(.*)".*/\1/')
  case "$engine" in
    kmc) sets=(--set kmc.time=20.0 --set kmc.warmup=5.0 --set kmc.replicas=4) ;;
    lgca) sets=(--set run.steps=40 --set output.every=20 --set output.checkpoint_every=0) ;;
    *) sets=(--set run.steps=40 --set output.every=20 --set output.checkpoint_every=0) ;;
  esac
  if grep -q 'trajectory_every' "$scene"; then
    sets+=(--set output.trajectory_every=20)
  fi
  if grep -q 'max_lag' "$scene" && [[ "$engine" == lgca ]]; then
    if grep -q 'dhumieres' "$scene"; then sets+=(--set tagged.max_lag=10); fi
  fi
  rm -rf "${out:?}/$name"
  mpirun -n "$ranks" --oversubscribe "$bin" run "$scene" \
    "${sets[@]}" --out "$out/$name" >"$out/$name.stdout" 2>&1
  status=$?
  echo "$name: exit $status"
  [[ $status -eq 0 ]] || failed=$((failed + 1))
done
echo "$failed scenes failed"
