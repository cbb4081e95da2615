#!/usr/bin/env python3
"""Checks that the repository names its sources (docs/references.md).

Usage: check_citations.py REPO_ROOT

Fails (exit 1, one line per finding) when
- a file cites a source document by its working name ("seed" and its number, SEED below), which
  means nothing to a reader;
- a citation key of the form "Author (2008)", "Author et al. (1993)", "A & B (2016)" or
  "Author (thesis)" is not a bold key of docs/references.md;
- a file cites DESIGN.md, which is not part of the repository (docs/architecture.md is).
Prints "citations: N keys used, all listed" otherwise.
"""
import pathlib
import re
import subprocess
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
refs = (root / "docs" / "references.md").read_text(encoding="utf-8")
keys = set(re.findall(r"\*\*([^*]+)\*\*", refs))

SCOPE = ("src", "include", "run", "tools", "tests", "docs", "README.md", "jobscripts")
files = subprocess.run(["git", "-C", str(root), "ls-files", "--", *SCOPE], check=True,
                       capture_output=True, text=True).stdout.split()
# Untracked files that git does not ignore count too (a check before the commit).
files += subprocess.run(["git", "-C", str(root), "ls-files", "--others", "--exclude-standard",
                         "--", *SCOPE], check=True, capture_output=True, text=True).stdout.split()

NAME = r"(?:d'|van der |van |de )?[A-Z][\w'\u00c0-\u017f-]+"
CITE = re.compile(rf"\b({NAME}(?: et al\.| & {NAME})?) \((\d{{4}}|thesis)\)")
SEED = re.compile(r"seed ?0{2}[0-2]", re.IGNORECASE)
DESIGN = re.compile(r"\bDESIGN\.md\b")
# Words that look like an author before a year but are not citations.
NOT_AUTHORS = {"LAMMPS", "Debian", "Until", "Since", "In", "On"}

this = pathlib.Path(__file__).resolve()
problems, used = [], set()
for name in sorted(set(files)):
    path = root / name
    if not path.is_file() or path.resolve() == this or path.suffix in (".png", ".h5"):
        continue
    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        continue
    for number, line in enumerate(text.splitlines(), 1):
        if SEED.search(line):
            problems.append(f"{name}:{number}: cites a source by its working name: "
                            f"{SEED.search(line).group(0)!r} (cite author and place, "
                            f"docs/references.md)")
        if DESIGN.search(line) and name != "docs/references.md":
            problems.append(f"{name}:{number}: cites DESIGN.md, which is not in the repository "
                            f"(docs/architecture.md)")
        for match in CITE.finditer(line) if name != "docs/references.md" else ():
            author, year = match.group(1), match.group(2)
            if author in NOT_AUTHORS:
                continue
            key = f"{author} ({year})"
            used.add(key)
            if key not in keys:
                problems.append(f"{name}:{number}: citation key {key!r} is not in "
                                f"docs/references.md")

for p in problems:
    print(p)
if problems:
    print(f"citations: {len(problems)} problems")
    sys.exit(1)
print(f"citations: {len(used)} keys used, all listed in docs/references.md")
