#!/usr/bin/python3
"""Prints the command lines a Markdown file shows, so that tests run them as written.

    python3 scripts/doc-commands.py FILE.md [--smoke]
    python3 scripts/doc-commands.py FILE.md --block NAME

A command block is an indented (4 spaces) block after a blank line, or a fenced block marked
sh, bash, shell or console; a line ending in a backslash continues on the next. Blocks of
the source tree (an indented block whose first line is not a command, e.g. the layout) are
told apart by the marker below, not by guessing: put

    <!-- docs-test: not-commands -->

on the line before such a block. A command that takes minutes is marked with

    <!-- docs-test: smoke -->

before its block: its commands are printed with --smoke and run only at --help level (the
program named, given --help; a bash script checked with bash -n). Every other block runs
verbatim. Output: one command per line, continuation lines joined with a space.

A block may also carry a name, for a test that runs it whole elsewhere (README's Slurm job
script, run by tests/scripts/slurm_test.sh on a real Slurm):

    <!-- docs-test: smoke block=slurm-job -->

--block NAME prints that block's lines as they are (comments and #SBATCH lines kept), exit
status 1 when the file has no block of that name.
"""
import re
import shlex
import sys

MARKER = re.compile(r"<!--\s*docs-test:\s*([a-z-]+)(?:\s+block=([a-z0-9-]+))?\s*-->")


def blocks(text):
    """(marker, name, [lines]) for every command block of a Markdown text."""
    lines = text.split("\n")
    out, marker, name, i = [], None, None, 0
    while i < len(lines):
        line = lines[i]
        m = MARKER.search(line)
        if m:
            marker, name = m.group(1), m.group(2)
            i += 1
            continue
        fence = re.match(r"^```\s*(\w*)", line)
        if fence:
            j = i + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            if fence.group(1) in ("sh", "bash", "shell", "console"):
                out.append((marker, name, [l for l in lines[i + 1:j]]))
            marker, name, i = None, None, j + 1
            continue
        if line.startswith("    ") and (i == 0 or lines[i - 1].strip() == "" or MARKER.search(lines[i - 1])):
            j = i
            while j < len(lines) and (lines[j].startswith("    ") or lines[j].strip() == ""):
                j += 1
            block = [l[4:] for l in lines[i:j] if l.strip()]
            out.append((marker, name, block))
            marker, name, i = None, None, j
            continue
        if line.strip():
            if not line.lstrip().startswith("<!--"):
                marker, name = None, None
        i += 1
    return out


def commands(block):
    joined, cur = [], ""
    for l in block:
        l = l.rstrip()
        if l.startswith("$ "):
            l = l[2:]
        if l.endswith("\\"):
            cur += l[:-1].rstrip() + " "
            continue
        cur += l.strip() if cur else l
        joined.append(cur)
        cur = ""
    if cur:
        joined.append(cur.strip())
    return [c for c in joined if c and not c.startswith("#")]


def smoke(command):
    """The --help-level form of a long command."""
    words = shlex.split(command, comments=True)
    env = []
    while words and re.match(r"^[A-Z_]+=", words[0]):
        env.append(words.pop(0))
    if words[0] == "export":
        return "bash -n -c " + shlex.quote(command)
    if words[0] == "bash":
        return " ".join(env + ["bash", "-n", words[1]])
    if words[0].endswith("python3"):
        return " ".join(env + [words[0], words[1], "--help"])
    return " ".join(env + [words[0], "--help"])


def main():
    if len(sys.argv) < 2:
        sys.exit("usage: doc-commands.py FILE.md [--smoke | --block NAME]")
    with open(sys.argv[1], encoding="utf-8") as f:
        text = f.read()
    if sys.argv[2:3] == ["--block"] and len(sys.argv) == 4:
        named = [block for _, name, block in blocks(text) if name == sys.argv[3]]
        if not named:
            sys.exit(f"{sys.argv[1]}: no block named {sys.argv[3]} (<!-- docs-test: ... block={sys.argv[3]} -->)")
        print("\n".join(line for block in named for line in block))
        return
    want_smoke = "--smoke" in sys.argv[2:]
    for marker, _, block in blocks(text):
        if marker == "not-commands":
            continue
        for c in commands(block):
            if marker == "smoke":
                if want_smoke:
                    print(smoke(c))
            elif not want_smoke:
                print(c)


if __name__ == "__main__":
    main()
