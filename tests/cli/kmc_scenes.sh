#!/usr/bin/env bash
# Every kmc scene in run/ passes `check` and runs briefly; the observables file has the kmc
# series with their shapes; 2 ranks give the same numbers as 1; a bad kmc key exits 2 with
# one line.
set -u
narrows=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mpi=(mpirun --quiet --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
pass=0 fail=0
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1"; fi; }

short=(--set kmc.length=40 --set kmc.time=50 --set kmc.warmup=5 --set kmc.replicas=3)
for scene in "$src"/run/*kmc*.toml "$src"/run/tasep*.toml; do
  [ -e "$scene" ] || continue
  name=$(basename "$scene" .toml)
  "$narrows" check "$scene" > "$tmp/$name.check" 2>&1
  check "$name: check exits 0" '[ $? -eq 0 ]'
  "$narrows" run "$scene" "${short[@]}" --out "$tmp/$name" > "$tmp/$name.out" 2>&1
  code=$?
  check "$name: run exits 0 (got $code)" '[ "$code" -eq 0 ]'
  check "$name: Loop time line" 'grep -q "^Loop time of .* events/s)" "$tmp/$name/log.txt"'
  check "$name: observables" '/usr/bin/python3 - "$tmp/$name/observables.h5" <<PY
import sys, h5py
f = h5py.File(sys.argv[1], "r")["observables"]
L = 40
c = f["current/value"].shape
d = f["density_profile/value"].shape
assert c[0] == 1 and c[1] in (L - 1, L), c
assert d == (1, L, 3), d
assert f["current_error/value"].shape == c
assert f["current_mean/value"].shape == (1,)
PY'
  "${mpi[@]}" -n 2 "$narrows" run "$scene" "${short[@]}" --out "$tmp/$name-2" > /dev/null 2>&1
  check "$name: 2 ranks give the 1-rank mean current" \
    '[ "$(grep "mean current" "$tmp/$name/log.txt")" = "$(grep "mean current" "$tmp/$name-2/log.txt")" ]'
done

"$narrows" check "$src/run/tasep_open.toml" --set 'kmc.rates={"10->01"=1.0,"w99"=1.0}' \
  > /dev/null 2> "$tmp/bad.err"
code=$?
check "bad rate key exits 2 (got $code)" '[ "$code" -eq 2 ]'
check "one line naming kmc.rates.\"w99\"" \
  '[ "$(grep -c . "$tmp/bad.err")" -eq 1 ] && grep -q "kmc.rates.\"w99\"" "$tmp/bad.err"'

echo "kmc_scenes: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
