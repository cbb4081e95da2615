#!/usr/bin/env bash
# Strong and weak scaling on this machine (1 and 2 ranks), printed as tables.
# Usage: bash tools/scaling_local.sh [steps, default 1500]   (build first)
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-1500} # shorter runs are dominated by the first, whole-box migration
out=out/scaling_local
mkdir -p "$out"
mpi=(mpirun --quiet --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
for p in 1 2; do
  "${mpi[@]}" -n "$p" ./build/narrows run run/strong_scaling.toml --set run.steps="$steps" \
    --out "$out/strong_p$p" > "$out/strong_p$p.log"
  "${mpi[@]}" -n "$p" ./build/narrows run run/strong_scaling.toml --set run.steps="$steps" \
    --set "domain.size=[$((500 * p)).0, 50.0]" --out "$out/weak_p$p" > "$out/weak_p$p.log"
done
echo "strong scaling (1000 x 50 cells, n = 20, SRD 2D):"
/usr/bin/python3 tools/scaling_table.py "$out"/strong_p1.log "$out"/strong_p2.log
echo "weak scaling (500 x 50 cells per rank):"
/usr/bin/python3 tools/scaling_table.py --weak "$out"/weak_p1.log "$out"/weak_p2.log
