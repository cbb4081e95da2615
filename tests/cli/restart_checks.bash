# Shared part of the restart-check tests (tests/cli/restart_*_checks.sh; sourced after
# common.bash, not a test itself): three small channels with no-slip colloids of hard and spring
# contacts and MD colloids, their checkpoints at step 4 (made on first use), and
#   case_ NAME SCENE PATTERN EDIT...
# which edits SCENE's checkpoint as a hostile user would (tests/hostile/edit_checkpoint.py
# rewrites the checksums, so only the state check can refuse it) and checks that a restart on 3
# ranks is refused: exit 2, one line on stderr matching "ck.h5: .*PATTERN", nothing written.
edit=(/usr/bin/python3 "$src/tests/hostile/edit_checkpoint.py")
C=/particles/colloids
K=/particles/contacts
cat > "$tmp/hard.toml" << 'TOML'
[run]
engine = "mpcd"
dimensions = 2
seed = 5
steps = 4
[domain]
size = [24.0, 12.0]
[fluid]
collision = "srd"
density = 5
dt = 0.1
[walls]
[colloids]
radius = 2.0
placement = "list"
positions = [[4.0, 6.0], [10.0, 6.0], [16.0, 3.0]]
coupling = "no-slip"
contacts = "hard"
[output]
every = 2
observables = ["temperature"]
progress = false
TOML
sed -e '/^coupling/d' -e '/^contacts/d' "$tmp/hard.toml" > "$tmp/md.toml"
sed -e 's/^placement = "list"/placement = "packing"\npacking_fraction = 0.6/' -e '/^positions/d' \
  -e 's/^contacts = "hard"/contacts = "spring"/' "$tmp/hard.toml" > "$tmp/spring.toml"
checkpoint_of() {
  [ -e "$tmp/$1/checkpoint-0000000004.h5" ] ||
    runs "$1: first run" "$narrows" run "$tmp/$1.toml" --out "$tmp/$1" > /dev/null 2>&1
}
n=0
case_() {
  local name=$1 s=$2 pattern=$3
  shift 3
  n=$((n + 1))
  local d=$tmp/c$n
  mkdir -p "$d"
  checkpoint_of "$s"
  "${edit[@]}" "$tmp/$s/checkpoint-0000000004.h5" "$d/ck.h5" "$@" || check "$name: edited" false
  local refuse=refused
  [[ " $* " == *" strip "* ]] && refuse=refused_old
  $refuse "$name" "ck.h5: .*$pattern" timeout 60 "${mpi[@]}" -n 3 "$narrows" run "$tmp/$s.toml" \
    --restart "$d/ck.h5" --set run.steps=6 --out "$d/out"
  check "$name: nothing written" '[ ! -e "$d/out" ] || [ -z "$(ls -A "$d/out")" ]'
}
# refused_old: as refused, for a checkpoint without checksums, which is read with a warning line.
refused_old() {
  local name=$1 pattern=$2
  shift 2
  "$@" > "$tmp/rout" 2> "$tmp/rerr"
  local code=$?
  check "$name: exit 2 (got $code)" '[ "$code" -eq 2 ]'
  check "$name: one line besides the warning" \
    '[ "$(grep -v "carries no checksums" "$tmp/rerr" | grep -c .)" -eq 1 ] || { cat "$tmp/rerr"; false; }'
  check "$name: message matches '$pattern'" 'grep -q -- "$pattern" "$tmp/rerr" || { cat "$tmp/rerr"; false; }'
}
# The untouched checkpoint of each scene used restarts on 3 ranks.
untouched() {
  local s
  for s in "$@"; do
    checkpoint_of "$s"
    runs "$s: untouched checkpoint restarts on 3 ranks" timeout 60 "${mpi[@]}" -n 3 "$narrows" \
      run "$tmp/$s.toml" --restart "$tmp/$s" --set run.steps=6 --out "$tmp/$s" > /dev/null 2>&1
  done
}
