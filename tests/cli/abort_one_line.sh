#!/usr/bin/env bash
# Issue 35 item 4, "every refusal one line" on N ranks: when several ranks find a broken
# invariant inside the same step (each alone, while the others wait in the step's messages), the
# run ends with exit 3 and one line on stderr, not one per failing rank, and none of Open MPI's
# (mpirun without --quiet). The fault: the three colloids of the MD channel, one in each rank's
# slab, restarted at 5000 along x (within the restart's speed limit): each runs deep into the
# fluid within its first MD sub-step, on its own rank.
source "$(dirname "$0")/common.bash"
source "$(dirname "$0")/restart_checks.bash"

checkpoint_of md
loud=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && loud+=(--allow-run-as-root)
"${edit[@]}" "$tmp/md/checkpoint-0000000004.h5" "$tmp/fast.h5" set $C/velocity/value 0,0 5000 \
  set $C/velocity/value 1,0 5000 set $C/velocity/value 2,0 5000
for attempt in 1 2 3; do
  exits 3 --err "$tmp/err$attempt" "three failing ranks, attempt $attempt: exit 3" timeout 60 \
    "${loud[@]}" -n 3 "$narrows" run "$tmp/md.toml" --restart "$tmp/fast.h5" --set run.steps=6 \
    --out "$tmp/fast$attempt" > /dev/null
  check "three failing ranks, attempt $attempt: one line on stderr, narrows' own" \
    '[ "$(grep -c . "$tmp/err$attempt")" -eq 1 ] && grep -q "^narrows: invariant broken at step 4 on rank [0-2]: .*ran deep into a colloid" "$tmp/err$attempt" || { cat "$tmp/err$attempt"; false; }'
done
finish abort_one_line
