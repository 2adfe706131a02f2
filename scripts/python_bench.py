#!/usr/bin/python3
"""The Python module's overhead, measured side by side in one run (a benchmark, not a test).

    PYTHONPATH=build/python /usr/bin/python3 scripts/python_bench.py [--build build] [--repeats 3]

1. nsbench.run of a C++ integrator against `nsbench run` (the command line) on the same case: the
   stepping CPU time of both (summary step_cpu_seconds: the stepping loop less sampling), the
   least of --repeats runs each, and their ratio (the target: at most 1.05). Cases: the bouncing
   bar at N = 1000 and the 64 x 64 block, CD-Lagrange, one thread (NSBENCH_THREADS=1).
2. The per-step cost of an integrator written in Python on the bouncing mass (1 dof, so the
   figures are the overhead): a step that only advances t (the C++ -> Python call with the GIL
   taken), the same plus one problem.internal_force(u, out=f) (a Python -> C++ call) and the
   example scheme (examples/python/symplectic_euler.py), beside CD-Lagrange's C++ step.
Prints a Markdown table.
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
os.environ["NSBENCH_THREADS"] = "1"
import nsbench  # noqa: E402

sys.path.insert(0, str(ROOT / "examples" / "python"))
import symplectic_euler  # noqa: E402

CASES = [  # problem, integrator, dt, t_end, parameters
    ("bouncing-bar", "cd-lagrange", 1e-4, 10.0, {"N": 1000}),
    ("block-2d", "cd-lagrange", 1e-4, 0.5, {"nx": 64, "ny": 64}),
]


def cli_stepping(exe, problem, integrator, dt, t_end, params, every):
    with tempfile.TemporaryDirectory() as out:
        cmd = [exe, "run", "--problem", problem, "--integrator", integrator, "--dt", repr(dt), "--t-end", repr(t_end),
               "--sample-every", str(every), "--out", out]
        for k, v in params.items():
            cmd += ["--set", f"{k}={v}"]
        subprocess.run(cmd, check=True, capture_output=True, env=dict(os.environ, NSBENCH_THREADS="1"))
        s = json.loads((pathlib.Path(out) / "summary.json").read_text())
    return s["step_cpu_seconds"], s["steps"]


def python_stepping(problem, integrator, dt, t_end, params, every):
    s = nsbench.run(problem, integrator, dt=dt, t_end=t_end, sample_every=every, states=False, **params).summary
    return s["step_cpu_seconds"], s["steps"]


class Advance(nsbench.Integrator):
    """benchmark: advances t only (the cost of the C++ -> Python call)"""

    def init(self, problem, initial):
        self.bind(problem, initial)

    def step(self, dt):
        self.state.t += dt
        self.work.steps += 1
        self.work.force_evaluations += 1
        return dt


class AdvanceWithForce(Advance):
    """benchmark: advances t after one internal_force(u, out=f) (one Python -> C++ call)"""

    def init(self, problem, initial):
        super().init(problem, initial)
        self.f = initial.u.copy()

    def step(self, dt):
        self.problem.internal_force(self.state.u, out=self.f)
        return super().step(dt)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=str(ROOT / "build"), help="the build directory, holding the nsbench command line (default build)")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    exe = str(pathlib.Path(args.build) / "nsbench")
    print(f"| case | steps | command line stepping [s] | nsbench.run stepping [s] | ratio |")
    print(f"|---|---:|---:|---:|---:|")
    for problem, integrator, dt, t_end, params in CASES:
        every = 1000
        cli = min(cli_stepping(exe, problem, integrator, dt, t_end, params, every)[0] for _ in range(args.repeats))
        runs = [python_stepping(problem, integrator, dt, t_end, params, every) for _ in range(args.repeats)]
        py, steps = min(r[0] for r in runs), runs[0][1]
        label = f"{problem} {', '.join(f'{k}={v}' for k, v in params.items())}, {integrator}"
        print(f"| {label} | {steps} | {cli:.3f} | {py:.3f} | {py / cli:.3f} |")
    symplectic_euler.register()
    nsbench.register_integrator("bench-advance", Advance)
    nsbench.register_integrator("bench-advance-force", AdvanceWithForce)
    print()
    print("| step on the bouncing mass (1 dof), 1e5 steps | per step [us] |")
    print("|---|---:|")
    for name, what in [("cd-lagrange", "CD-Lagrange (C++)"), ("bench-advance", "Python step advancing t only"),
                       ("bench-advance-force", "Python step with one internal_force(u, out=f)"),
                       ("py-symplectic-euler", "Python symplectic Euler (examples/python)")]:
        best = min(python_stepping("bouncing-mass", name, 1e-5, 1.0, {}, 1000)[0] for _ in range(args.repeats))
        print(f"| {what} | {best / 1e5 * 1e6:.2f} |")
    p = nsbench.Problem("bouncing-mass")
    u, f = p.initial_state().u, p.initial_state().u.copy()
    n = 100000
    start = time.process_time()
    for _ in range(n):
        p.internal_force(u, out=f)
    per_call = (time.process_time() - start) / n
    print(f"| problem.internal_force(u, out=f) from a Python loop, per call | {per_call * 1e6:.2f} |")


if __name__ == "__main__":
    main()
