#!/usr/bin/env bash
# `narrows bench` of the MPCD engine (issue 34, item 3): the working set of each case beside the
# last-level cache, the triad measured at that size, which figure a cluster node sees, and the
# coupled Table 6.1 channel (pulses-2d) with its no-slip coupling's share of the loop. Small
# boxes and two steps: the lines and their fields, never a time.
source "$(dirname "$0")/common.bash"

runs "bench srd-2d" "$narrows" bench --case srd-2d --particles 2e4 --steps 2 > "$tmp/srd.txt" 2>&1
check "the cache and the triad in it" \
  'grep -Eq "^last-level cache: [0-9]+ MiB \(L[23], (sysconf|sysfs)\); memory bandwidth \(STREAM triad, one core\): [0-9.e+]+ GB/s in the cache" "$tmp/srd.txt" || { cat "$tmp/srd.txt"; false; }'
check "srd-2d: working set beside the cache, the triad at that size" \
  'grep -Eq "^srd-2d +n=10, 2e\+04 particles, working set [0-9.e+]+ MiB = [0-9.e+-]+ x LLC \((in cache|near the cache size|beyond cache)\), one core: [0-9.e+]+ particle-steps/s .* of the triad at this size, [0-9.e+]+ GB/s\)$" "$tmp/srd.txt"'
check "which figure a cluster node sees" 'grep -q "^a cluster node (~2 MB of L3 per core) sees the beyond-cache figures" "$tmp/srd.txt"'

runs "bench pulses-2d" "$narrows" bench --case pulses-2d --particles 2e4 --steps 2 \
  > "$tmp/pulses.txt" 2>&1
check "pulses-2d: the Table 6.1 channel, its disks and fluid particle-steps/s" \
  'grep -Eq "^pulses-2d Kanehl \(thesis\) Table 6.1 channel, l = 64 b, [1-9][0-9]* disks, [0-9.e+]+ fluid particles, working set .* x LLC .*, one core, 2 steps: [0-9.e+]+ fluid particle-steps/s" "$tmp/pulses.txt" || { cat "$tmp/pulses.txt"; false; }'
check "pulses-2d: the no-slip coupling's share of the loop" \
  'grep -Eq "^pulses-2d +no-slip coupling: [0-9.e+-]+ s of the loop \([0-9.]+ %\)$" "$tmp/pulses.txt"'

runs "bench --json" "$narrows" bench --case pulses-2d --case srd-2d --particles 2e4 --steps 2 \
  --angle 90 --json > "$tmp/b.json" 2>&1
check "JSON: cache, working sets, the coupling share between 0 and 1, the angle" \
  '/usr/bin/python3 -c "
import json, sys
b = json.load(open(sys.argv[1]))
assert b[\"last_level_cache_bytes\"] > 0 and b[\"triad_in_cache_bytes_per_s\"] > 0
srd, pulses = b[\"cases\"]
assert srd[\"name\"] == \"srd-2d\" and srd[\"angle_deg\"] == 90 and srd[\"working_set_bytes\"] > 0 and srd[\"triad_bytes_per_s\"] > 0
assert srd[\"box\"][0] * srd[\"box\"][1] * 10 == srd[\"particles\"], srd
assert pulses[\"name\"] == \"pulses-2d\" and pulses[\"colloids\"] > 0
assert 0 < pulses[\"coupling_share\"] < 1, pulses
" "$tmp/b.json" || { cat "$tmp/b.json"; false; }'
refused "an unknown case" "command line: --case 'pulses-3d'; allowed: .*pulses-2d" \
  "$narrows" bench --case pulses-3d
finish "mpcd bench"
