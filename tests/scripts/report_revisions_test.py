#!/usr/bin/env python3
"""scripts/report_revisions.py: passes on reports that are one run of the committed code, fails
on a mixed, dirty or unstamped set and on code changed after the reports' revision (each on a
scratch git repository), and then checks the source tree's own reports/."""
import os
import pathlib
import subprocess
import sys
import tempfile

SOURCE = pathlib.Path(sys.argv[1])
CHECK = SOURCE / "scripts" / "report_revisions.py"
ENV = dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@t", GIT_COMMITTER_NAME="t", GIT_COMMITTER_EMAIL="t@t")


def check(root):
    return subprocess.run([sys.executable, str(CHECK), str(root / "reports")], capture_output=True, text=True)


def git(root, *args):
    return subprocess.run(["git", "-C", str(root), *args], capture_output=True, text=True, env=ENV, check=True).stdout.strip()


def commit(root, files, message):
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    git(root, "add", "-A")
    git(root, "commit", "-q", "-m", message)
    return git(root, "rev-parse", "--short=12", "HEAD")


def reports(revision, other=None):
    """A report set: a CSV, a Markdown table, a LaTeX table, index.md and a benchmark's JSON."""
    return {"reports/a.csv": f"# study: a\n# git_revision: {revision}\nx,y\n1,2\n",
            "reports/a.md": f"## A\n\n| x |\n|---|\n| 1 |\n\n<sub>study = a; git_revision = {other or revision}</sub>\n",
            "reports/a.tex": f"% git_revision: {revision}\n\\begin{{table}}\\end{{table}}\n",
            "reports/index.md": f"# Reports\n\n<sub>nsbench 0.1.0 revision {revision}. Rerun: ...</sub>\n",
            "reports/benchmarks/bar-2.json": '{"context": {"git_revision": "%s"}, "benchmarks": []}\n' % revision}


def scratch():
    root = pathlib.Path(tempfile.mkdtemp())
    git(root, "init", "-q")
    code = commit(root, {"core/a.cpp": "int a;\n", "README.md": "x\n"}, "code")
    return root, code


def expect(result, code, text):
    assert result.returncode == code, (result.returncode, result.stdout, result.stderr)
    assert text in result.stdout + result.stderr, (text, result.stdout, result.stderr)


# One run of the committed code, then prose, docs and tests changed after it: passes.
root, code = scratch()
commit(root, reports(code), "reports")
commit(root, {"README.md": "y\n", "docs/a.md": "z\n", "tests/a_test.cpp": "int t;\n"}, "prose")
expect(check(root), 0, f"every report file carries revision {code}")
# The code changed after the reports' revision: fails, naming the file.
commit(root, {"core/a.cpp": "int a = 1;\n"}, "code again")
expect(check(root), 1, "the code changed since: core/a.cpp")

# Two revisions in one set; a "-dirty" or "unknown" set; a file without a stamp; an unknown commit.
root, code = scratch()
commit(root, reports(code, other="0123456789ab"), "mixed")
expect(check(root), 1, "revision 0123456789ab: 1 files")
for bad in (code + "-dirty", "unknown"):
    root, code = scratch()
    commit(root, reports(bad), "dirty")
    expect(check(root), 1, "not a committed revision")
root, code = scratch()
commit(root, {**reports(code), "reports/b.md": "## B\n\nno stamp\n"}, "unstamped")
expect(check(root), 1, "b.md: no revision stamp")
root, code = scratch()
commit(root, reports("fedcba987654"), "unknown commit")
expect(check(root), 1, "not a commit of this repository")

# Outside a git checkout it cannot tell: skipped (77), not passed.
plain = pathlib.Path(tempfile.mkdtemp())
for name, text in reports("fedcba987654").items():
    (plain / name).parent.mkdir(parents=True, exist_ok=True)
    (plain / name).write_text(text)
expect(check(plain), 77, "SKIPPED")

# The source tree's own reports.
real = check(SOURCE)
print(real.stdout + real.stderr, end="")
sys.exit(real.returncode)
