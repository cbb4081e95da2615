#!/usr/bin/env bash
# tools/accuracy_map.py --tiny (about a minute): every engine and colloid model gives its rows and its Pareto PNG, and
# --readme rewrites the table between the markers of a copy of the README, so the tool cannot
# rot unnoticed.
source "$(dirname "$0")/common.bash"

cp "$src/README.md" "$tmp/README.md"
/usr/bin/python3 "$src/tools/accuracy_map.py" --tiny --narrows "$narrows" --out "$tmp/map" \
  --readme "$tmp/README.md" > "$tmp/table.md" 2> "$tmp/err"
code=$?
check "accuracy_map --tiny exits 0 (got $code)" '[ "$code" -eq 0 ] || { tail -5 "$tmp/err"; false; }'
# Every row group of issue 33 item 3: the engines and the colloid models (hard spheres are a
# cost-only group: no error column, so only their PNG and a row are checked).
for engine in mpcd md_energy md_settling fhp kmc continuum noslip_D noslip_spin noslip_slip \
  springs; do
  check "$engine: Pareto PNG written" '[ -s "$tmp/map/accuracy_$engine.png" ]'
  check "$engine: rows with a finite error in the table" \
    'grep "^| ${engine//_/ } |" "$tmp/table.md" | grep -q "| [+-][0-9.e+-]* % |"'
done
check "hard_spheres: PNG written" '[ -s "$tmp/map/accuracy_hard_spheres.png" ]'
check "hard spheres: a row with its events per step" \
  'grep "^| hard spheres |" "$tmp/table.md" | grep -q "events per step"'
check "continuum: a measured order in a note" 'grep "^| continuum |" "$tmp/table.md" | grep -q "order"'
check "noslip D: against Stokes-Einstein at the measured nu" \
  'grep "^| noslip D |" "$tmp/table.md" | grep -q "measured nu"'
check "springs: the deepest overlap in a note" \
  'grep "^| springs |" "$tmp/table.md" | grep -q "deepest overlap"'
check "table header says the cost is CPU time of the child" 'grep -q "CPU time" "$tmp/table.md"'
check "--readme put the table between the markers" \
  '[ "$(sed -n "/<!-- accuracy-map -->/,/<!-- \/accuracy-map -->/p" "$tmp/README.md" | sed "1d;\$d")" = "$(cat "$tmp/table.md")" ]'
check "--readme left the rest of the README alone" \
  '[ "$(sed "/<!-- accuracy-map -->/,/<!-- \/accuracy-map -->/d" "$tmp/README.md")" = "$(sed "/<!-- accuracy-map -->/,/<!-- \/accuracy-map -->/d" "$src/README.md")" ]'
finish accuracy_map_tiny
