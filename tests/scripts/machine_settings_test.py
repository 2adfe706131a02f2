#!/usr/bin/env python3
"""The same run gives the same bits whatever the machine: `nsbench run` with glibc's own
variants of sin, cos, exp, ... (its FMA and AVX2 ones, chosen at load time by the processor's
features) and without them (GLIBC_TUNABLES masks those features, as on a processor that lacks
them), and on one or two threads. Before nsbench called deterministic functions
(core/deterministic_math.hpp), modal-exact's hex8 bar, the rocking block and the Painleve rod
differed in the last bits between the two. Skipped (77) where masking the features changes
nothing in glibc itself (a processor with no FMA variant to choose).

    machine_settings_test.py NSBENCH_CLI
"""
import os
import pathlib
import subprocess
import sys
import tempfile

CLI = sys.argv[1]
NO_FMA = "glibc.cpu.hwcaps=-AVX2,-FMA,-AVX512F"
CASES = [
    ("bar-3d", "modal-exact", ["N=40", "mass=consistent"], "0.0112", "2.5"),
    ("rocking-block", "cd-lagrange", [], "1e-3", "1"),
    ("painleve-rod", "cd-lagrange", [], "1e-3", "1"),
    ("bouncing-mass", "moreau-jean", ["e=0.9"], "1e-3", "3"),
]


def env(tunables=None, threads=None):
    e = dict(os.environ)
    e.pop("GLIBC_TUNABLES", None)
    if tunables:
        e["GLIBC_TUNABLES"] = tunables
    if threads:
        e["NSBENCH_THREADS"] = str(threads)
    return e


def glibc_sin_bits(tunables):
    probe = "import math, struct; print(hash(b''.join(struct.pack('d', math.sin(0.001 * k + 0.123)) for k in range(200000))))"
    return subprocess.run([sys.executable, "-c", probe], env=env(tunables), capture_output=True, text=True, check=True).stdout


def run(case, settings):
    problem, integrator, sets, dt, t_end = case
    out = pathlib.Path(tempfile.mkdtemp())
    args = [CLI, "run", "--problem", problem, "--integrator", integrator, "--dt", dt, "--t-end", t_end, "--out", str(out)]
    for s in sets:
        args += ["--set", s]
    done = subprocess.run(args, env=env(**settings), capture_output=True, text=True)
    assert done.returncode == 0, (args, done.stderr)
    return {name: (out / name).read_bytes() for name in ("series.csv", "events.csv") if (out / name).exists()}


if glibc_sin_bits(None) == glibc_sin_bits(NO_FMA):
    print("SKIPPED: masking FMA and AVX2 changes nothing in this machine's glibc")
    sys.exit(77)
failed = []
for case in CASES:
    base = run(case, {})
    for settings in ({"tunables": NO_FMA}, {"threads": 1}, {"threads": 2}):
        if run(case, settings) != base:
            failed.append(f"{case[0]} / {case[1]} under {settings}: other bits than with the default settings")
for f in failed:
    print(f"machine_settings: {f}", file=sys.stderr)
if not failed:
    print(f"machine_settings: {len(CASES)} runs bit-identical with and without glibc's FMA variants, on 1 and 2 threads")
sys.exit(1 if failed else 0)
