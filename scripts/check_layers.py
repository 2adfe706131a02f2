#!/usr/bin/env python3
"""Fails on an include that runs up a layer.

The layers, lowest first; a directory may include its own headers and those of any lower
layer, never a higher one or another directory of its own rank:

    core < problems < solvers < integrators < peers, run < reference < check
         < studies < app, python

Usage: check_layers.py [SOURCE_DIR]   (default: the repository this script is in)
"""
import pathlib
import re
import sys

RANK = {"core": 0, "problems": 1, "solvers": 2, "integrators": 3, "peers": 4, "run": 4,
        "reference": 5, "check": 6, "studies": 7, "app": 8, "python": 8}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')


def upward_includes(root):
    for layer, rank in RANK.items():
        for path in sorted((root / layer).rglob("*")):
            if path.suffix not in (".hpp", ".cpp", ".h"):
                continue
            for number, line in enumerate(path.read_text(errors="replace").splitlines(), 1):
                match = INCLUDE.match(line)
                if not match or match.group(1) not in RANK or match.group(1) == layer:
                    continue
                if RANK[match.group(1)] >= rank:
                    yield f"{path.relative_to(root)}:{number}: {layer}/ includes {match.group(1)}/ " \
                          f"(a layer at or above its own; valid: {', '.join(sorted(d for d, r in RANK.items() if r < rank)) or 'none'})"


def main():
    root = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent
    if not any((root / layer).is_dir() for layer in RANK):
        print(f"check_layers.py: SOURCE_DIR '{root}' has none of the layer directories "
              f"(valid: the nsbench source tree, with {', '.join(RANK)})")
        return 2
    found = list(upward_includes(root))
    for line in found:
        print(line)
    print(f"{len(found)} upward include(s)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
