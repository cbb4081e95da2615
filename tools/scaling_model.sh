#!/usr/bin/env bash
# Measures what tools/scaling_model.py needs and prints its prediction for the full Table 6.1
# channel (l = 12000 b) on 64, 512 and 3072 ranks (issue 21, acceptance 7).
#
# Usage: bash tools/scaling_model.sh [NARROWS] [DIR] [MODEL OPTIONS...]
#   defaults: build/narrows, out/scaling_model; options go to scaling_model.py (e.g. --ranks)
#
# Runs run/pulses_table6_1.toml (l = 600 b) on 1 rank for 200 steps (the one-rank cost per fluid
# particle-step) and on 3 ranks for 20 and 70 steps with tools/mpi_calls.c preloaded, which
# counts every MPI call and the bytes it sends; the difference of the two counts is per step.
# Nothing is asserted: the network parameters are the model's (see scaling_model.py).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
narrows=${1:-$here/build/narrows}
dir=${2:-out/scaling_model}
shift $(($# < 2 ? $# : 2))
mkdir -p "$dir"
mpicc -shared -fPIC -O2 -o "$dir/mpi_calls.so" "$here/tools/mpi_calls.c"
mpi=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
# SCENE, ONE_STEPS and LENGTH (the scene's channel length along x) may name another channel:
#   SCENE=run/segregation_fig5_10_3d.toml LENGTH=40 ONE_STEPS=50 bash tools/scaling_model.sh \
#     build/narrows out/model3d --substeps 0 --particles 1.28e6 --length 40 --ranks 4 8 13
scene=${SCENE:-$here/run/pulses_table6_1.toml}
steps1=${ONE_STEPS:-200}
length=${LENGTH:-600}
"$narrows" run "$scene" --set run.steps=$steps1 --set output.every=100000 --set output.checkpoint_every=0 \
  --out "$dir/one" --overwrite >"$dir/one.log" 2>&1
rate=$(sed -n 's/^Loop time .*(\([0-9.e+]*\) particle-steps\/s)$/\1/p' "$dir/one.log")
# the contacts' seconds per colloid-step (the "contacts" stage over the colloids and steps)
contacts=$(sed -n 's/^no-slip coupling stages.* contacts \([0-9.e+-]*\),.*/\1/p' "$dir/one.log")
colloids=$(sed -n 's/^packing: \([0-9]*\) colloids.*/\1/p' "$dir/one.log" | head -1)
cost=$(/usr/bin/python3 -c "import sys; print(float(sys.argv[1]) / int(sys.argv[2]) / int(sys.argv[3]))" \
  "$contacts" "$steps1" "$colloids")
per_length=$(/usr/bin/python3 -c "import sys; print(int(sys.argv[1]) / float(sys.argv[2]))" "$colloids" "$length")
for steps in 20 70; do
  rm -f "$dir/calls_$steps.txt"
  MPI_CALLS_OUT=$dir/calls_$steps.txt "${mpi[@]}" -n 3 -x LD_PRELOAD="$dir/mpi_calls.so" \
    -x MPI_CALLS_OUT "$narrows" run "$scene" --set run.steps=$steps \
    --set output.checkpoint_every=100000 --out "$dir/three_$steps" --overwrite >"$dir/three_$steps.log" 2>&1
done
/usr/bin/python3 "$here/tools/scaling_model.py" "$dir/calls_20.txt" "$dir/calls_70.txt" \
  --steps 50 --rate "$rate" --contact-cost "$cost" --colloids-per-length "$per_length" "$@"
