#!/usr/bin/env python3
"""scripts/check_layers.py: the source tree has no upward include, and the check does fail on one."""
import pathlib
import subprocess
import sys
import tempfile

SOURCE = pathlib.Path(sys.argv[1])
CHECK = SOURCE / "scripts" / "check_layers.py"


def run(root):
    return subprocess.run([sys.executable, str(CHECK), str(root)], capture_output=True, text=True)


def tree(files):
    root = pathlib.Path(tempfile.mkdtemp())
    for name, text in files.items():
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text(text)
    return root


real = run(SOURCE)
assert real.returncode == 0, real.stdout

downward = run(tree({"core/a.hpp": "#pragma once\n", "studies/b.cpp": '#include "core/a.hpp"\n'}))
assert downward.returncode == 0, downward.stdout

upward = run(tree({"integrators/a.hpp": '#pragma once\n#include "reference/cache.hpp"\n',
                   "reference/cache.hpp": "#pragma once\n"}))
assert upward.returncode == 1, upward.stdout
assert "integrators/a.hpp:2: integrators/ includes reference/" in upward.stdout, upward.stdout

sideways = run(tree({"peers/a.cpp": '#include "run/run.hpp"\n', "run/run.hpp": "#pragma once\n"}))
assert sideways.returncode == 1, sideways.stdout

not_a_tree = run(pathlib.Path(tempfile.mkdtemp()))
assert not_a_tree.returncode == 2 and "SOURCE_DIR" in not_a_tree.stdout, not_a_tree.stdout
print("layers: ok")
