#!/usr/bin/env bash
# Self-test of the helpers in common.bash that the other scripts trust: runs, exits, started/
# waited and pipefail each turn a failing command into a failed check (counted in $fail), and a
# passing one into a pass. Each case runs in a subshell, so its tally does not leak into ours.
set -u
source "$(dirname "$0")/common.bash"

# tally COMMANDS: runs the helper calls in a fresh tally and prints "passes failures".
tally() { (pass=0 fail=0; exec 9> /dev/null; eval "$1" > /dev/null; echo "$pass $fail"); }

check "runs: a command exiting 1 is a failure" '[ "$(tally "runs one false")" = "0 1" ]'
check "runs: a command exiting 0 is a pass" '[ "$(tally "runs zero true")" = "1 0" ]'
check "runs: the status checked is that of the command, not of a substitution in the label" \
  '[ "$(tally "runs \"label \$(true)\" bash -c \"exit 1\"")" = "0 1" ]'
check "runs: redirections after the call apply to the command" \
  '[ "$(tally "runs out bash -c \"echo hi; exit 1\" > \"$tmp/o\"")" = "0 1" ] && [ "$(cat "$tmp/o")" = hi ]'
check "runs: a FAIL line is shown even when the command's stdout is redirected" \
  '(pass=0 fail=0; exec 9>&1; runs quiet false > /dev/null) | grep -q "^FAIL: quiet: exit 0 (got 1)"'
check "runs --err: stderr goes to the file, the failure shows it" \
  'tally "runs --err \"$tmp/e\" name bash -c \"echo oops >&2; exit 1\"" > "$tmp/t" &&
   [ "$(cat "$tmp/t")" = "0 1" ] && [ "$(cat "$tmp/e")" = oops ]'
check "runs --err: the FAIL line quotes the stderr" \
  '(pass=0 fail=0; exec 9>&1; runs --err "$tmp/e" name bash -c "echo oops >&2; exit 1" > /dev/null) | grep -q "^FAIL: name: exit 0 (got 1): oops"'
check "exits 3: status 3 passes, 1 and 0 fail" \
  '[ "$(tally "exits 3 a bash -c \"exit 3\"; exits 3 b bash -c \"exit 1\"; exits 3 c true")" = "1 2" ]'
check "started/waited: one of three background commands exiting 1 is one failure" \
  '[ "$(tally "started a true; started b bash -c \"sleep 0.2; exit 1\"; started c true; waited")" = "2 1" ]'
check "started/waited: a late failure is waited for" \
  '[ "$(tally "started slow bash -c \"sleep 0.5; exit 4\"; waited")" = "0 1" ]'
check "pipefail: a failing command before a pipe fails the check" \
  '[ "$(tally "check pipe \"bash -c \\\"exit 1\\\" | cat\"")" = "0 1" ]'
check "finish: returns non-zero after one failure" '! (pass=0 fail=1; finish self > /dev/null)'
finish "check helpers"
