# Shared preamble of the command-line test scripts (sourced; not a test itself: ctest runs
# only tests/cli/*.sh). Sets narrows, src, a temporary directory removed on exit, the mpirun
# command (as root it needs --allow-run-as-root), and check NAME EXPRESSION, which counts
# passes and failures; finish prints the tally and returns non-zero on any failure.
narrows=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mpi=(mpirun --quiet --oversubscribe) # --quiet: only narrows speaks on stderr
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
pass=0 fail=0
check() { if eval "$2"; then pass=$((pass + 1)); else fail=$((fail + 1)); echo "FAIL: $1"; fi; }
finish() {
  echo "$1: $pass passed, $fail failed"
  [ "$fail" -eq 0 ]
}
