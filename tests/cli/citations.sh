#!/usr/bin/env bash
# The repository names its sources: no source document cited by its working name ("seed" and
# its number), every citation key ("Tabatabaei (2008)", "Kanehl (thesis)", ...) listed in
# docs/references.md, no citation of a design document outside the repository
# (tools/check_citations.py says which file and line when not).
source "$(dirname "$0")/common.bash"

runs "every citation resolves in docs/references.md" /usr/bin/python3 "$src/tools/check_citations.py" "$src"
# The check can fail: a file that cites a source by its working name and an unknown key (both
# put together here, so that this file does not cite them itself).
working="seed 0""01" unknown="Nobody"" (1999)"
mkdir -p "$tmp/repo/docs" "$tmp/repo/src"
cp "$src/docs/references.md" "$tmp/repo/docs/"
printf '// %s eq 4.5; %s eq 3\n' "$working" "$unknown" > "$tmp/repo/src/x.cpp"
git -C "$tmp/repo" init -q
exits 1 "a working name and an unknown key are found" /usr/bin/python3 "$src/tools/check_citations.py" "$tmp/repo" > "$tmp/found.txt"
check "the finding names the working name" "grep -qF \"src/x.cpp:1: cites a source by its working name: '$working'\" '$tmp/found.txt'"
check "the finding names the unknown key" "grep -qF \"src/x.cpp:1: citation key '$unknown'\" '$tmp/found.txt'"
finish citations
