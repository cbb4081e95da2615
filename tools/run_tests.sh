#!/usr/bin/env bash
# One command for all tests: install what is missing, build, run unit, 2-rank MPI,
# command-line and validation tests under ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
# Open MPI refuses root without these; CI runs as root.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
start=$(date +%s)
ctest --test-dir build --output-on-failure -j"$(nproc)" "$@"
echo "test suite wall time: $(( $(date +%s) - start )) s"
