#!/usr/bin/env bash
# Bad scenes on the command line: `narrows check` and `narrows run` must exit with code 2, print
# exactly one non-empty line on stderr naming the scene file, and create no output directory.
# A good scene must pass `narrows check`.
#
# usage: bash tests/cli/bad_scenes.sh <path-to-narrows-binary> <source-dir>
set -u

NARROWS=${1:?usage: bad_scenes.sh <narrows-binary> <source-dir>}
SRC=${2:-.}
: "$SRC" # not needed: every scene is written here

TMP=$(mktemp -d "${TMPDIR:-/tmp}/narrows_bad_scenes.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT

passed=0
failed=0

pass() { passed=$((passed + 1)); }
fail() {
  failed=$((failed + 1))
  echo "FAIL: $*"
}

# A valid 2D scene; bad scenes are variations of it.
good_scene() {
  cat <<'EOF'
[run]
engine = "mpcd"
dimensions = 2
seed = 1
steps = 10

[domain]
size = [8.0, 8.0]

[fluid]
collision = "srd"
density = 5
dt = 0.1
angle = 130.0
kT = 1.0

[output]
every = 5
EOF
}

# The good scene with the line starting with "<key> =" replaced by $2 ("" deletes it).
replace_line() {
  good_scene | awk -v key="$1" -v line="$2" '
    $1 == key && $2 == "=" { if (line != "") print line; next }
    { print }'
}

# One bad scene per case: name and text. The file name is the case name.
declare -a NAMES=()
declare -A TEXTS=()
add() {
  NAMES+=("$1")
  TEXTS[$1]=$2
}

add unknown_key "$(good_scene; echo; echo '[body_force]'; echo 'value = [0.001, 0.0]'; echo 'vale = 3')"
add unknown_fluid_key "$(replace_line density 'desnity = 5')"
add wrong_type "$(replace_line dt 'dt = "fast"')"
add negative_density "$(replace_line density 'density = -1.0')"
add angle_400 "$(replace_line angle 'angle = 400.0')"
add angle_0 "$(replace_line angle 'angle = 0')"
add dt_zero "$(replace_line dt 'dt = 0.0')"
add dimensions_4 "$(replace_line dimensions 'dimensions = 4')"
add size_wrong_length "$(replace_line size 'size = [8.0, 8.0, 8.0]')"
add size_not_whole "$(replace_line size 'size = [8.5, 8.0]')"
add unknown_collision "$(replace_line collision 'collision = "srdd"')"
add missing_fluid "$(good_scene | sed '/^\[fluid\]/,/^kT/d')"
add missing_steps "$(replace_line steps '')"
add syntax_error "$(replace_line dt 'dt = = 0.1')"
add unknown_engine "$(replace_line engine 'engine = "lbm"')"
add walls_slip_not_boolean "$(good_scene; echo; echo '[walls]'; echo 'slip = 1')"
add steps_float "$(replace_line steps 'steps = 2.5')"
# [colloids] in the 8 x 8 box (with walls where the wall potential is involved)
colloids() { good_scene; echo; echo '[colloids]'; printf '%s\n' "$@"; }
add colloids_missing_radius "$(colloids 'count = 1')"
add colloids_unknown_key "$(colloids 'radius = 1' 'count = 1' 'substeps = 5')"
add colloids_count_too_many "$(colloids 'radius = 1' 'count = 5')"
add colloids_bad_placement "$(colloids 'radius = 1' 'count = 1' 'placement = "hexagonal"')"
add colloids_gravity_length "$(colloids 'radius = 1' 'count = 1' 'gravity = [0.1, 0.0, 0.0]')"
add colloids_wall_sigma_no_walls "$(colloids 'radius = 1' 'count = 1' 'wall_sigma = 1.0')"
add colloids_too_wide_for_channel "$(good_scene; echo; echo '[walls]'; echo; echo '[colloids]'; echo 'radius = 2'; echo 'count = 1')"
add thermostat_unknown_kind "$(good_scene; echo; echo '[thermostat]'; echo 'kind = "andersen"')"
add colloids_radius_sd_too_wide "$(colloids 'radius = 1' 'count = 1' 'radius_sd = 0.3')"
add colloids_radius_sd_negative "$(colloids 'radius = 1' 'count = 1' 'radius_sd = -0.1')"
add colloids_radius_sd_too_wide_for_channel "$(good_scene; echo; echo '[walls]'; echo; echo '[colloids]'; echo 'radius = 1.5'; echo 'radius_sd = 0.3'; echo 'count = 1')"
add colloids_position_outside "$(colloids 'radius = 1' 'placement = "list"' 'positions = [[9.0, 4.0]]')"
# cores overlap across the periodic x edge (0.5 and 7.0 are 1.5 apart; r_a + r_b = 2)
add colloids_positions_overlap "$(colloids 'radius = 1' 'placement = "list"' 'positions = [[4.0, 2.0], [0.5, 5.0], [7.0, 5.0]]')"

# check_bad NAME CMD...: runs CMD, expects exit 2 and one stderr line naming NAME.toml
check_bad() {
  local name=$1 label=$2
  shift 2
  local err="$TMP/stderr"
  "$@" >"$TMP/stdout" 2>"$err"
  local rc=$?
  local ok=1
  if [[ $rc -ne 2 ]]; then
    fail "$label: exit code $rc, expected 2"
    ok=0
  fi
  local lines
  lines=$(awk 'END { print NR }' "$err")
  if [[ $lines -ne 1 ]] || [[ -n $(tail -c 1 "$err") ]] || [[ -z $(head -n 1 "$err") ]]; then
    fail "$label: stderr is not exactly one non-empty line:"
    sed 's/^/    | /' "$err"
    ok=0
  fi
  if ! grep -qF "$name.toml" "$err"; then
    fail "$label: stderr does not name $name.toml: $(head -c 300 "$err")"
    ok=0
  fi
  [[ $ok -eq 1 ]] && pass
  return 0
}

for name in "${NAMES[@]}"; do
  scene="$TMP/$name.toml"
  printf '%s\n' "${TEXTS[$name]}" >"$scene"

  check_bad "$name" "check $name" "$NARROWS" check "$scene"

  out="$TMP/out_$name"
  check_bad "$name" "run $name" "$NARROWS" run "$scene" --out "$out"
  if [[ -e $out ]]; then
    fail "run $name: created the output directory $out"
  else
    pass
  fi
done

# A missing file is bad input too.
check_bad "no_such_scene" "check missing file" "$NARROWS" check "$TMP/no_such_scene.toml"

# --set errors name --set and the scene.
good_scene >"$TMP/good.toml"
check_bad "good" "run --set without dot" "$NARROWS" run "$TMP/good.toml" --set xyz=1 \
  --out "$TMP/out_set"
if [[ -e $TMP/out_set ]]; then fail "run --set xyz=1: created the output directory"; else pass; fi
check_bad "good" "run --set unknown key" "$NARROWS" run "$TMP/good.toml" --set fluid.desnity=3 \
  --out "$TMP/out_set2"
if [[ -e $TMP/out_set2 ]]; then fail "run --set fluid.desnity=3: created the output directory"; else pass; fi

# check_good NAME: `check` of $TMP/NAME.toml exits 0.
check_good() {
  "$NARROWS" check "$TMP/$1.toml" >"$TMP/stdout" 2>"$TMP/stderr"
  local rc=$?
  if [[ $rc -eq 0 ]]; then
    pass
  else
    fail "check $1.toml: exit code $rc, expected 0: $(head -c 300 "$TMP/stderr")"
  fi
}

# The good scene passes `check`, and so does one with colloids in a channel.
check_good good
{ good_scene; echo; echo '[walls]'; echo; echo '[colloids]'; echo 'radius = 1'; echo 'count = 2'; } >"$TMP/good_colloids.toml"
check_good good_colloids
{ good_scene; echo; echo '[walls]'; echo; echo '[colloids]'; echo 'radius = 1'; echo 'radius_sd = 0.2'; echo 'count = 2'; } >"$TMP/good_colloids_radius_sd.toml"
check_good good_colloids_radius_sd

echo "$passed passed, $failed failed"
[[ $failed -eq 0 ]]
