#!/usr/bin/env bash
# The README's two commands share one build folder in either order: the quickstart's configure
# step followed by the test command's configure step leaves a build folder in which ctest finds
# the tests (the quickstart once switched them off and the test command ran none, exit 0).
# Configure only, in a scratch folder (NARROWS_BUILD_DIR); .ci/run calls exactly the README's
# test command.
source "$(dirname "$0")/common.bash"

export NARROWS_BUILD_DIR=$tmp/build
bash "$src/tools/quickstart.sh" --configure-only > "$tmp/qs.log" 2>&1
code=$?
check "quickstart configure step exits 0 (got $code)" '[ "$code" -eq 0 ] || { tail -5 "$tmp/qs.log"; false; }'
bash "$src/tools/run_tests.sh" --configure-only > "$tmp/rt.log" 2>&1
code=$?
check "test command configure step exits 0 (got $code)" '[ "$code" -eq 0 ] || { tail -5 "$tmp/rt.log"; false; }'
check "tests are switched on in the cache" \
  'grep -qx "NARROWS_TESTS:BOOL=ON" "$tmp/build/CMakeCache.txt"'
ctest --test-dir "$tmp/build" -N > "$tmp/ctest.log" 2>&1
code=$?
check "ctest -N exits 0 (got $code)" '[ "$code" -eq 0 ]'
count=$(sed -n 's/^Total Tests: \([0-9]*\)$/\1/p' "$tmp/ctest.log")
check "ctest finds tests after both configure steps (found '${count}')" '[ "${count:-0}" -gt 0 ]'
check "the cli tests are among them" 'grep -q "cli.readme_commands" "$tmp/ctest.log"'

# The README names the two commands; .ci/run runs exactly the test command.
check "README names bash tools/quickstart.sh" 'grep -qx "bash tools/quickstart.sh" "$src/README.md"'
check "README names bash tools/run_tests.sh" 'grep -qx "bash tools/run_tests.sh" "$src/README.md"'
check ".ci/run calls exactly the README's test command" \
  '[ "$(grep -v "^#\|^set \|^cd \|^$" "$src/.ci/run")" = "bash tools/run_tests.sh" ]'
check "the test command fails when no test ran" 'grep -q -- "--no-tests=error" "$src/tools/run_tests.sh"'
finish readme_commands
