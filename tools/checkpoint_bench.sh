#!/usr/bin/env bash
# Checkpoint throughput next to the disk's own figure (issue 5, acceptance 5).
#
# Usage: bash tools/checkpoint_bench.sh [NARROWS] [DIR] [RANKS] [PARTICLES]
#   defaults: build/narrows, out/checkpoint_bench, 2 ranks, 1e7 fluid particles (2D)
#
# Writes a checkpoint of PARTICLES fluid particles on RANKS ranks (a run of 0 steps writes one
# at its end), reads it back (a restart of 1 step), and measures the disk with
#   dd if=/dev/zero of=DIR/dd.bin bs=1M count=2000 oflag=direct
# in the same directory. Prints MB/s of each (1 MB = 1e6 bytes; the checkpoint time includes
# the fsync before the rename) and the ratio. Nothing is asserted: times depend on the
# machine and its load.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
narrows=${1:-$here/build/narrows}
dir=${2:-out/checkpoint_bench}
ranks=${3:-2}
particles=${4:-10000000}
mkdir -p "$dir"
mpi=(mpirun --quiet --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)

# A square 2D box at density 10 holding at least PARTICLES particles.
side=$(/usr/bin/python3 -c "import math; print(math.ceil(math.sqrt($particles / 10)))")
cat > "$dir/scene.toml" <<TOML
[run]
engine = "mpcd"
dimensions = 2
steps = 0
[domain]
size = [$side.0, $side.0]
[fluid]
collision = "srd"
dt = 0.1
[output]
observables = ["temperature"]
checkpoint_keep = 1
progress = false
TOML
rm -f "$dir"/checkpoint-*.h5 "$dir"/dd.bin
"${mpi[@]}" -n "$ranks" "$narrows" run "$dir/scene.toml" --out "$dir" > "$dir/write.log"
write_line=$(grep "^checkpoint " "$dir/write.log" | tail -1)
write_mbs=$(echo "$write_line" | sed -n 's/.*(\([0-9.]*\) MB\/s).*/\1/p')
bytes=$(stat -c %s "$dir/checkpoint-0000000000.h5")

# Read back: a restart of one step reads (and validates) the whole file, then writes it again
# (a restart of 0 steps would answer "nothing to run" before reading).
sync
start=$(date +%s.%N)
"${mpi[@]}" -n "$ranks" "$narrows" run "$dir/scene.toml" --restart "$dir" --out "$dir" \
  --set run.steps=1 > "$dir/read.log"
total=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')

dd_line=$(dd if=/dev/zero of="$dir/dd.bin" bs=1M count=2000 oflag=direct 2>&1 | tail -1)
rm -f "$dir/dd.bin"
dd_bytes=$(echo "$dd_line" | awk '{print $1}')
dd_seconds=$(echo "$dd_line" | sed -n 's/.* copied, \([0-9.]*\) s,.*/\1/p')
dd_mbs=$(awk -v b="$dd_bytes" -v s="$dd_seconds" 'BEGIN { print b / s / 1e6 }')

printf 'particles          %s on %s ranks, checkpoint file %.1f MB\n' \
  "$(grep -o 'with [0-9]* particles' "$dir/write.log" | awk '{print $2}')" "$ranks" \
  "$(awk -v b="$bytes" 'BEGIN { print b / 1e6 }')"
printf 'checkpoint write   %.0f MB/s   (%s)\n' "$write_mbs" "$write_line"
printf 'restart (read + write again, incl. start-up) %.2f s\n' "$total"
printf 'dd oflag=direct    %.0f MB/s   (%s)\n' "$dd_mbs" "$dd_line"
printf 'ratio              %.0f %% of the disk figure (goal >= 50 %%)\n' \
  "$(awk -v w="$write_mbs" -v d="$dd_mbs" 'BEGIN { print 100 * w / d }')"
