# Shared preamble of the command-line test scripts (sourced; not a test itself: ctest runs
# only tests/cli/*.sh). Sets narrows, src, a temporary directory removed on exit, the mpirun
# command (as root it needs --allow-run-as-root), and check NAME EXPRESSION, which counts
# passes and failures; runs/exits check the exit status of the command they run; started/waited
# do the same for background commands; refused checks a bad-input exit; finish prints the tally
# and returns non-zero on any failure. A pipe fails when any of its commands fails (pipefail).
# Never test `$?` after a `check "label $(...)"`: the substitution resets it.
set -o pipefail
narrows=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mpi=(mpirun --quiet --oversubscribe) # --quiet: only narrows speaks on stderr
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
pass=0 fail=0
# FAIL lines go to fd 9, the script's stdout, even from inside `runs ... > /dev/null`.
exec 9>&1
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1" >&9; fi; }
# runs [--err FILE] NAME COMMAND...: runs COMMAND, keeps its exit status in $code and checks it
# is 0. Redirections written after the call apply to COMMAND; with --err its stderr goes to FILE,
# and the start of FILE is shown when the check fails.
runs() { exits 0 "$@"; }
# exits N [--err FILE] NAME COMMAND...: the same for an expected exit status N.
exits() {
  local want=$1 err=
  shift
  if [ "$1" = --err ]; then
    err=$2
    shift 2
  fi
  local name=$1
  shift
  if [ -n "$err" ]; then "$@" 2> "$err"; else "$@"; fi
  code=$?
  local detail=
  [ -n "$err" ] && [ "$code" -ne "$want" ] && detail=": $(head -c 300 "$err")"
  check "$name: exit $want (got $code)$detail" '[ "$code" -eq "$want" ]'
}
# started NAME COMMAND...: starts COMMAND in the background (redirections after the call apply
# to it); waited waits for each started command by its PID and checks that it exited 0.
bg_pids=() bg_names=()
started() {
  local name=$1
  shift
  "$@" &
  bg_pids+=("$!")
  bg_names+=("$name")
}
waited() {
  local i
  for i in "${!bg_pids[@]}"; do
    wait "${bg_pids[i]}"
    code=$?
    check "${bg_names[i]}: exit 0 (got $code)" '[ "$code" -eq 0 ]'
  done
  bg_pids=() bg_names=()
}
# refused NAME PATTERN COMMAND...: the command exits 2 with one line on stderr matching PATTERN.
refused() {
  local name=$1 pattern=$2
  shift 2
  "$@" > "$tmp/rout" 2> "$tmp/rerr"
  local code=$?
  check "$name: exit 2 (got $code)" '[ "$code" -eq 2 ]'
  check "$name: one line on stderr" '[ "$(grep -c . "$tmp/rerr")" -eq 1 ] || { cat "$tmp/rerr"; false; }'
  check "$name: message matches '$pattern'" 'grep -q -- "$pattern" "$tmp/rerr" || { cat "$tmp/rerr"; false; }'
}
# Waits (up to $2 s) until the file $1 exists.
wait_for() {
  local i
  for ((i = 0; i < $2 * 100; ++i)); do
    [ -e "$1" ] && return 0
    sleep 0.01
  done
  return 1
}

finish() {
  echo "$1: $pass passed, $fail failed"
  [ "$fail" -eq 0 ]
}
