#!/usr/bin/env python3
"""The Python scheme of symplectic_euler.py in a work-precision figure beside built-in schemes.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/work_precision.py --out wp.png

Bouncing mass (exact solution known): for every scheme and step, the largest displacement error
over the run against the stepping CPU time (summary step_cpu_seconds) and against the F_int
evaluations. --quick: fewer and larger steps (CI). The Python scheme's CPU time includes the
interpreter: its points sit right of the C++ ones at equal accuracy; the F_int panel compares the
schemes' work without it.
"""
import argparse
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import nsbench  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import symplectic_euler  # noqa: E402

SCHEMES = [("py-symplectic-euler", "symplectic Euler (python)"), ("cd-lagrange", "CD-Lagrange"),
           ("moreau-jean", "Moreau-Jean, theta = 1/2")]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="work_precision.png", help="the figure (PNG or PDF)")
    ap.add_argument("--quick", action="store_true", help="three larger steps (seconds)")
    args = ap.parse_args()
    symplectic_euler.register()
    steps = [1e-2, 3e-3, 1e-3] if args.quick else [1e-2, 3e-3, 1e-3, 3e-4, 1e-4]
    fig, (ax_cpu, ax_evals) = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    print(f"{'scheme':<28} {'dt':>8} {'max |q - q_exact|':>18} {'step CPU [s]':>13} {'F_int evals':>12}")
    for name, label in SCHEMES:
        errors, cpu, evals = [], [], []
        for dt in steps:
            r = nsbench.run("bouncing-mass", name, dt=dt, t_end=1.5, states=False)
            if r.status != "ok":
                raise SystemExit(f"{name} at dt = {dt}: {r.status}: {r.summary['message']}")
            errors.append(np.max(np.abs(r.q - r.q_exact)))
            cpu.append(r.summary["step_cpu_seconds"])
            evals.append(r.summary["work"]["force_evaluations"])
            print(f"{label:<28} {dt:>8.0e} {errors[-1]:>18.3e} {cpu[-1]:>13.3e} {evals[-1]:>12}")
        ax_cpu.loglog(cpu, errors, "o-", label=label)
        ax_evals.loglog(evals, errors, "o-", label=label)
    ax_cpu.set_xlabel("stepping CPU time [s]")
    ax_evals.set_xlabel("F_int evaluations")
    ax_cpu.set_ylabel("max |q - q_exact| [m]")
    ax_cpu.legend()
    fig.suptitle("Bouncing mass (e = 0.9, t_end = 1.5 s): work-precision")
    fig.tight_layout()
    pathlib.Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
