#!/usr/bin/env bash
# tools/accuracy_map.py --tiny (seconds): every engine gives its rows and its Pareto PNG, and
# --readme rewrites the table between the markers of a copy of the README, so the tool cannot
# rot unnoticed.
source "$(dirname "$0")/common.bash"

cp "$src/README.md" "$tmp/README.md"
/usr/bin/python3 "$src/tools/accuracy_map.py" --tiny --narrows "$narrows" --out "$tmp/map" \
  --readme "$tmp/README.md" > "$tmp/table.md" 2> "$tmp/err"
code=$?
check "accuracy_map --tiny exits 0 (got $code)" '[ "$code" -eq 0 ] || { tail -5 "$tmp/err"; false; }'
for engine in mpcd md_energy md_settling fhp kmc; do
  check "$engine: Pareto PNG written" '[ -s "$tmp/map/accuracy_$engine.png" ]'
  check "$engine: rows with a finite error in the table" \
    'grep "^| ${engine/_/ } |" "$tmp/table.md" | grep -q "| [+-][0-9.e+-]* % |"'
done
check "table header says the cost is CPU time of the child" 'grep -q "CPU time" "$tmp/table.md"'
check "--readme put the table between the markers" \
  '[ "$(sed -n "/<!-- accuracy-map -->/,/<!-- \/accuracy-map -->/p" "$tmp/README.md" | sed "1d;\$d")" = "$(cat "$tmp/table.md")" ]'
check "--readme left the rest of the README alone" \
  '[ "$(sed "/<!-- accuracy-map -->/,/<!-- \/accuracy-map -->/d" "$tmp/README.md")" = "$(sed "/<!-- accuracy-map -->/,/<!-- \/accuracy-map -->/d" "$src/README.md")" ]'
finish accuracy_map_tiny
