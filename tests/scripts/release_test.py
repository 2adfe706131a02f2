#!/usr/bin/python3
"""The release a paper cites names one version everywhere: CMake's project VERSION.

    release_test.py VERSION NSBENCH NSBENCH_STUDY SOURCE_DIR

VERSION is CMake's PROJECT_VERSION (tests/CMakeLists.txt passes it). Checked: both programs'
--version print "<program> VERSION (revision ...)" and exit 0; CITATION.cff parses (with
python3-yaml when it is installed, else line by line) as Citation File Format 1.2.0 with a
title, authors, the release's version and references that each have a type, title and
authors; CHANGELOG.md has a section for VERSION; LICENSE is the BSD 3-Clause licence. The
report stamps are checked where they are written (tests/studies/study_test.cpp)."""
import os
import re
import subprocess
import sys


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def check_version_flag(program, name, version):
    r = subprocess.run([program, "--version"], capture_output=True, text=True, timeout=30)
    if r.returncode != 0:
        fail(f"{name} --version exited {r.returncode}: {r.stderr.strip()}")
    line = r.stdout.strip()
    if not re.fullmatch(re.escape(f"{name} {version} (revision ") + r"\S+, .+ build, .+\)", line):
        fail(f"{name} --version printed {line!r}, expected '{name} {version} (revision ..., ... build, ...)'")


def citation(path):
    """CITATION.cff as a dict: YAML when python3-yaml is there, else the top-level scalars and
    the references' keys read line by line (enough for the checks below)."""
    text = open(path, encoding="utf-8").read()
    try:
        import yaml
        return yaml.safe_load(text)
    except ImportError:
        data, references = {}, []
        for line in text.splitlines():
            top = re.match(r"^([a-z-]+):\s*(.*)$", line)
            if top:
                data[top.group(1)] = top.group(2).strip().strip('"') or None
            item = re.match(r"^  - type:\s*(\S+)", line)
            if item:
                references.append({"type": item.group(1)})
            key = re.match(r"^    (title|authors):", line)
            if key and references:
                references[-1][key.group(1)] = True
        data["references"] = references
        data["authors"] = data.get("authors") is None and "authors:" in text
        return data


def check_citation(path, version):
    d = citation(path)
    if str(d.get("cff-version")) != "1.2.0":
        fail(f"{path}: cff-version {d.get('cff-version')!r}, expected 1.2.0")
    for key in ("message", "title", "authors"):
        if not d.get(key):
            fail(f"{path}: no '{key}'")
    if str(d.get("version")) != version:
        fail(f"{path}: version {d.get('version')!r}, CMake's project VERSION is {version}")
    references = d.get("references") or []
    if len(references) < 3:
        fail(f"{path}: {len(references)} references, expected the talk and the papers the suite implements")
    for i, r in enumerate(references):
        for key in ("type", "title", "authors"):
            if not r.get(key):
                fail(f"{path}: reference {i + 1} has no '{key}'")


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    version, nsbench, study, source = sys.argv[1:]
    check_version_flag(nsbench, "nsbench", version)
    check_version_flag(study, "nsbench-study", version)
    check_citation(os.path.join(source, "CITATION.cff"), version)
    changelog = open(os.path.join(source, "CHANGELOG.md"), encoding="utf-8").read()
    if not re.search(r"^## \[" + re.escape(version) + r"\]", changelog, re.M):
        fail(f"CHANGELOG.md has no section '## [{version}]'")
    licence = open(os.path.join(source, "LICENSE"), encoding="utf-8").read()
    if not licence.startswith("BSD 3-Clause License") or "Neither the name of the copyright holder" not in licence:
        fail("LICENSE is not the BSD 3-Clause licence")
    print(f"release {version}: --version of both programs, CITATION.cff, CHANGELOG.md and LICENSE agree")


if __name__ == "__main__":
    main()
