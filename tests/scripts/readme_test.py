#!/usr/bin/env python3
"""README is a front page: at most 200 lines, no commit hash (timings with their revisions live in
docs/measurements.md), and every file it links exists."""
import pathlib
import re
import sys

SOURCE = pathlib.Path(sys.argv[1])
text = (SOURCE / "README.md").read_text()
lines = text.split("\n")
problems = []
if len(lines) > 200:
    problems.append(f"README.md has {len(lines)} lines; at most 200 (the manual is docs/)")
for n, line in enumerate(lines, 1):
    for word in re.findall(r"\b[0-9a-f]{7,40}\b", line):
        if re.search(r"[a-f]", word) and re.search(r"[0-9]", word):
            problems.append(f"README.md:{n}: '{word}' looks like a commit hash; timings and their revisions go in docs/measurements.md")
for target in re.findall(r"\]\(([^)#]+)\)", text):
    if not target.startswith("http") and not (SOURCE / target).exists():
        problems.append(f"README.md links {target}, which does not exist")
for p in problems:
    print(p, file=sys.stderr)
print(f"README.md: {len(lines)} lines" + ("" if problems else ", no commit hash, every link resolves"))
sys.exit(1 if problems else 0)
