#!/usr/bin/env bash
# A scene with fewer cell columns than ranks is refused before anything runs: exit code 2,
# one line naming domain.size[0], and no output directory. Then a 2-rank run of a small
# scene works and writes its observables.
set -u
source "$(dirname "$0")/common.bash"

cat > "$tmp/narrow.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 2
steps = 10
[domain]
size = [2.0, 8.0]
[fluid]
collision = "srd"
dt = 0.5
TOML
exits 2 "3 ranks on 2 columns" "${mpi[@]}" -n 3 "$narrows" run "$tmp/narrow.toml" --out "$tmp/out3" \
  > "$tmp/stdout" 2> "$tmp/stderr"
check "one line on stderr" '[ "$(grep -c . "$tmp/stderr")" -eq 1 ]'
check "names domain.size[0] and the allowed ranks" 'grep -q "domain.size\[0\] = 2 cells.*found 3 ranks; allowed: 1 to 2" "$tmp/stderr"'
check "no output directory" '[ ! -e "$tmp/out3" ]'

runs "2 ranks on 2 columns" "${mpi[@]}" -n 2 "$narrows" run "$tmp/narrow.toml" --out "$tmp/out2" \
  > "$tmp/stdout2" 2> "$tmp/stderr2"
check "loop time line names 2 ranks" 'grep -q "on 2 ranks for 10 steps" "$tmp/stdout2"'
check "observables written" '[ -s "$tmp/out2/observables.h5" ]'
finish "too many ranks"
