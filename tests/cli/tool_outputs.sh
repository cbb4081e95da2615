#!/usr/bin/env bash
# Where the tools and job scripts put their output: lgca_plot.py writes its PNG next to the data
# like the other plot tools, every SLURM --output lands in a folder that exists before the job
# starts (SLURM opens it before the script runs), and checkpoint_bench.sh needs no bc.
source "$(dirname "$0")/common.bash"

mkdir -p "$tmp/run" "$tmp/elsewhere"
"$narrows" run "$src/run/lgca_shear_wave.toml" --set run.steps=20 --set 'lattice.size=[64, 16]' \
  --out "$tmp/run" > /dev/null 2>&1
code=$?
check "lgca run exits 0 (got $code)" '[ "$code" -eq 0 ]'
(cd "$tmp/elsewhere" && /usr/bin/python3 "$src/tools/lgca_plot.py" "$tmp/run/observables.h5" \
  --first 1 > "$tmp/plot.log" 2>&1)
code=$?
check "lgca_plot.py exits 0 (got $code)" '[ "$code" -eq 0 ] || { cat "$tmp/plot.log"; false; }'
check "lgca_plot.py PNG next to the data" '[ -s "$tmp/run/lgca.png" ]'
check "nothing in the current folder" '[ -z "$(ls "$tmp/elsewhere")" ]'

for script in "$src"/jobscripts/*.slurm; do
  out=$(sed -n 's/^#SBATCH --output=//p' "$script")
  dir=$(dirname "$out")
  check "$(basename "$script"): --output folder '$dir' exists at submission" \
    '[ -n "$out" ] && { [ "$dir" = "." ] || [ -d "$src/$dir" ]; }'
done
check "checkpoint_bench.sh calls no bc" '! grep -qw "bc" "$src/tools/checkpoint_bench.sh"'
finish tool_outputs
