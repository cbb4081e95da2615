# Shared preamble of the command-line test scripts (sourced; not a test itself: ctest runs
# only tests/cli/*.sh). Sets narrows, src, a temporary directory removed on exit, the mpirun
# command (as root it needs --allow-run-as-root), and check NAME EXPRESSION, which counts
# passes and failures; refused checks a bad-input exit; finish prints the tally and returns non-zero on any failure.
narrows=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mpi=(mpirun --quiet --oversubscribe) # --quiet: only narrows speaks on stderr
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
pass=0 fail=0
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
# refused NAME PATTERN COMMAND...: the command exits 2 with one line on stderr matching PATTERN.
refused() {
  local name=$1 pattern=$2
  shift 2
  "$@" > "$tmp/rout" 2> "$tmp/rerr"
  local code=$?
  check "$name: exit 2 (got $code)" '[ "$code" -eq 2 ]'
  check "$name: one line on stderr" '[ "$(grep -c . "$tmp/rerr")" -eq 1 ]'
  check "$name: message matches '$pattern'" 'grep -q -- "$pattern" "$tmp/rerr" || { cat "$tmp/rerr"; false; }'
}
finish() {
  echo "$1: $pass passed, $fail failed"
  [ "$fail" -eq 0 ]
}
