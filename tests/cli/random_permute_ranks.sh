#!/usr/bin/env bash
# random-permute permutes the velocities within the particle array of one rank, so on several
# ranks it would not be Tabatabaei's permutation of all velocities (nor the same run as on one):
# it is refused on 2 and 3 ranks with one line naming fluid.collision, the rank count and the
# alternative random-maxwell, exit 2 and no output directory; on 1 rank it runs, and
# random-maxwell runs on 3 ranks.
set -u
source "$(dirname "$0")/common.bash"

cat > "$tmp/permute.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 2
steps = 5
[domain]
size = [13.0, 6.0]
[fluid]
collision = "random-permute"
dt = 0.5
TOML
for p in 2 3; do
  refused "$p ranks" "permute.toml: fluid.collision = \"random-permute\".*found $p ranks; allowed: 1 rank, or fluid.collision = \"random-maxwell\"" \
    "${mpi[@]}" -n "$p" "$narrows" run "$tmp/permute.toml" --out "$tmp/out$p"
  check "$p ranks: no output directory" '[ ! -e "$tmp/out$p" ]'
done
"$narrows" run "$tmp/permute.toml" --out "$tmp/out1" > "$tmp/stdout1" 2>&1
code=$?
check "1 rank runs (exit $code)" '[ "$code" -eq 0 ]'
check "1 rank: pipeline permutes all velocities" 'grep -q "permute all velocities" "$tmp/stdout1"'
"${mpi[@]}" -n 3 "$narrows" run "$tmp/permute.toml" --set fluid.collision=random-maxwell \
  --out "$tmp/out3m" > "$tmp/stdout3" 2>&1
code=$?
check "random-maxwell on 3 ranks runs (exit $code)" '[ "$code" -eq 0 ]'
finish "random-permute ranks"
