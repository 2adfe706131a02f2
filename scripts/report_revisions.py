#!/usr/bin/env python3
"""Are the reports one run of the committed code?

    python3 scripts/report_revisions.py [REPORTS]      (default: reports)

Reads the revision stamp of every report file under REPORTS (the `git_revision` line of each
CSV, Markdown and LaTeX table, the `revision` of index.md's footer, the `git_revision` context
of each Google Benchmark JSON file) and passes when
  1. every file carries a stamp, all the same revision R, and R is not "-dirty" or "unknown";
  2. no file that builds or runs the suite changed between R and HEAD (git diff R HEAD): only
     the reports themselves, prose (Markdown, docs/), the tests and CI may differ, since none
     of them changes a number.
Otherwise it prints one line per finding and exits 1. Outside a git checkout, or in a shallow
clone that lacks R, it cannot tell: it says so and exits 77 (CTest's skip code here).
"""
import json
import re
import subprocess
import sys
from pathlib import Path

SKIP = 77
# A stamp: "git_revision: R" (CSV, LaTeX), "git_revision = R" (Markdown), "revision R" (index.md).
STAMP = re.compile(r"(?:git_revision\s*[:=]|revision)\s*([0-9a-f]{7,40}(?:-dirty)?|unknown)\b")
STAMPED_SUFFIXES = {".csv", ".md", ".tex"}
# Paths whose change cannot change a report: the reports, prose, the tests, CI.
NOT_CODE_DIRS = ("reports/", "docs/", "tests/", ".ci/")
NOT_CODE_FILES = {"CITATION.cff", "LICENSE", ".gitignore"}


def stamps_of(path):
    """The revisions a report file names (empty when it names none)."""
    if path.suffix == ".json":
        try:
            context = json.loads(path.read_text()).get("context", {})
        except (ValueError, AttributeError):
            return set()
        return {context["git_revision"]} if "git_revision" in context else set()
    return set(STAMP.findall(path.read_text(errors="replace")))


def report_files(reports):
    """Every stamped report file: tables and pages, and the benchmarks' JSON output."""
    for path in sorted(reports.rglob("*")):
        if not path.is_file() or any(part.startswith(".") for part in path.relative_to(reports).parts):
            continue
        if path.suffix in STAMPED_SUFFIXES or (path.suffix == ".json" and path.parent.name == "benchmarks"):
            yield path


def stamp_findings(reports):
    """(the one revision or None, findings) over the report files."""
    findings, revisions = [], {}
    for path in report_files(reports):
        found = stamps_of(path)
        if not found:
            findings.append(f"{path}: no revision stamp")
        for r in found:
            revisions.setdefault(r, []).append(path)
    if not revisions:
        return None, findings + [f"{reports}: no stamped report file"]
    if len(revisions) > 1:
        for r, paths in sorted(revisions.items(), key=lambda kv: -len(kv[1])):
            findings.append(f"revision {r}: {len(paths)} files, e.g. {paths[0]}")
        return None, findings
    (revision,) = revisions
    if revision == "unknown" or revision.endswith("-dirty"):
        findings.append(f"every report carries revision {revision}: not a committed revision")
        return None, findings
    return revision, findings


def is_code(path):
    return not (path.startswith(NOT_CODE_DIRS) or path.endswith(".md") or path in NOT_CODE_FILES)


def git(source, *args):
    return subprocess.run(["git", "-C", str(source), *args], capture_output=True, text=True)


def code_findings(source, revision):
    """Findings on the code changed since `revision`; None when git cannot tell."""
    if git(source, "rev-parse", "--git-dir").returncode != 0:
        return None
    if git(source, "cat-file", "-e", revision + "^{commit}").returncode != 0:
        return None if git(source, "rev-parse", "--is-shallow-repository").stdout.strip() == "true" else [
            f"revision {revision}: not a commit of this repository"]
    changed = git(source, "diff", "--name-only", revision, "HEAD").stdout.split()
    code = [p for p in changed if is_code(p)]
    if not code:
        return []
    more = f" and {len(code) - 5} more" if len(code) > 5 else ""
    return [f"the reports carry revision {revision}, but the code changed since: {', '.join(code[:5])}{more}; "
            "regenerate them (bash scripts/run.sh studies) and commit them"]


def main(argv):
    reports = Path(argv[1] if len(argv) > 1 else "reports")
    if not reports.is_dir():
        print(f"report_revisions: {reports}: no such directory", file=sys.stderr)
        return 2
    revision, findings = stamp_findings(reports)
    if revision is not None:
        code = code_findings(reports.resolve().parent, revision)
        if code is None:
            print(f"report_revisions: SKIPPED: git cannot tell what changed since {revision} (no checkout, or a shallow clone)")
            return SKIP if not findings else 1
        findings += code
    for f in findings:
        print(f"report_revisions: {f}", file=sys.stderr)
    if not findings:
        print(f"report_revisions: every report file carries revision {revision}, and no code changed since")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
