#!/usr/bin/env bash
# Where the tools and job scripts put their output: lgca_plot.py writes its PNG next to the data
# like the other plot tools, every SLURM --output lands in a folder that exists before the job
# starts (SLURM opens it before the script runs), checkpoint_bench.sh needs no bc, and the MPI
# interposers (mpi_calls.c, mpi_waits.c) build, run and are read by their scripts.
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

# The MPI call counter of the scaling model (tools/mpi_calls.c, scaling_model.py): a 2-rank
# fluid run of 5 and 15 steps; every step migrates particles (one halo exchange at least), and
# the model's table has a row for each rank count asked for.
mpicc -shared -fPIC -O2 -o "$tmp/mpi_calls.so" "$src/tools/mpi_calls.c"
code=$?
check "mpi_calls.c builds (got $code)" '[ "$code" -eq 0 ]'
for steps in 5 15; do
  MPI_CALLS_OUT=$tmp/calls_$steps.txt "${mpi[@]}" -n 2 -x LD_PRELOAD="$tmp/mpi_calls.so" \
    -x MPI_CALLS_OUT "$narrows" run "$src/run/quickstart.toml" --set run.steps=$steps \
    --out "$tmp/calls_run_$steps" > /dev/null 2>&1
done
check "each rank wrote its counts" '[ "$(wc -l < "$tmp/calls_15.txt")" -eq 2 ]'
/usr/bin/python3 "$src/tools/scaling_model.py" "$tmp/calls_5.txt" "$tmp/calls_15.txt" --steps 10 \
  --rate 1e7 --ranks 64 512 > "$tmp/model.txt" 2>&1
code=$?
check "scaling_model.py exits 0 (got $code)" '[ "$code" -eq 0 ] || { cat "$tmp/model.txt"; false; }'
exchanges=$(sed -n 's/^measured per step .*: \([0-9.]*\) halo exchanges.*/\1/p' "$tmp/model.txt")
check "at least one halo exchange per step (got '$exchanges')" \
  '/usr/bin/python3 -c "import sys; sys.exit(not float(sys.argv[1]) >= 1)" "${exchanges:-0}"'
messages=$(sed -n 's/^measured per step .*, \([0-9.]*\) messages of rows sent.*/\1/p' "$tmp/model.txt")
check "rows sent as messages every step (got '$messages')" \
  '/usr/bin/python3 -c "import sys; sys.exit(not float(sys.argv[1]) >= 1)" "${messages:-0}"'
check "one table row per rank count" '[ "$(grep -c "^| [0-9]" "$tmp/model.txt")" -eq 2 ]'

# Where a run waits (tools/mpi_waits.c, mpi_waits.py): the same 2-rank run of 15 steps; each
# rank names its fluid migration (an Exchange's MPI_Waitall) among its call sites.
mpicc -shared -fPIC -O2 -o "$tmp/mpi_waits.so" "$src/tools/mpi_waits.c"
code=$?
check "mpi_waits.c builds (got $code)" '[ "$code" -eq 0 ]'
MPI_WAITS_OUT=$tmp/waits "${mpi[@]}" -n 2 -x LD_PRELOAD="$tmp/mpi_waits.so" -x MPI_WAITS_OUT \
  "$narrows" run "$src/run/quickstart.toml" --set run.steps=15 --out "$tmp/waits_run" \
  > /dev/null 2>&1
code=$?
check "the run with mpi_waits.so exits 0 (got $code)" '[ "$code" -eq 0 ]'
/usr/bin/python3 "$src/tools/mpi_waits.py" "$tmp/waits.0" "$tmp/waits.1" --steps 15 --top 40 \
  > "$tmp/waits.txt" 2>&1
code=$?
check "mpi_waits.py exits 0 (got $code)" '[ "$code" -eq 0 ] || { cat "$tmp/waits.txt"; false; }'
check "both ranks' call sites, the fluid migration among them" \
  '[ "$(grep -c "in blocking MPI calls" "$tmp/waits.txt")" -eq 2 ] &&
   [ "$(grep -c "waitall .*Exchange::exchange_rows < parallel::Exchange::migrate" "$tmp/waits.txt")" -ge 2 ] ||
   { cat "$tmp/waits.txt"; false; }'
finish tool_outputs
