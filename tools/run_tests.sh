#!/usr/bin/env bash
# One command for all tests: install what is missing, build, run unit, MPI, command-line and
# validation tests under ctest. Fails when no test ran (--no-tests=error).
#
# The build folder is build/ (NARROWS_BUILD_DIR overrides it), shared with tools/quickstart.sh
# in either order: the tests are switched on here explicitly, whatever the cache holds.
# --configure-only stops after the configure step; other arguments go to ctest (e.g. -L hard).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${NARROWS_BUILD_DIR:-build}
bash tools/install-deps.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DNARROWS_TESTS=ON >/dev/null
[ "${1:-}" = "--configure-only" ] && exit 0
cmake --build "$build" -j"$(nproc)"
# Open MPI refuses root without these; CI runs as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
start=$(date +%s)
ctest --test-dir "$build" --output-on-failure --no-tests=error -j"$(nproc)" "$@"
echo "test suite wall time: $(( $(date +%s) - start )) s"
