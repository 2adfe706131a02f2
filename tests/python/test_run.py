"""nsbench.run: the same run as `nsbench run`, its series bit for bit and its summary."""
import csv
import json
import pathlib
import subprocess

import numpy as np
import pytest

import nsbench

CASES = [
    ("bouncing-bar", "cd-lagrange", "2e-3", "1", {"N": 20, "g0": 3}, 3),
    ("bouncing-mass", "moreau-jean", "1e-3", "0.7", {"theta": 0.6}, 1),
    ("block-2d", "cd-lagrange", "1e-4", "0.01", {"nx": 4, "ny": 2}, 7),
]


def cli_run(exe, tmp_path, problem, integrator, dt, t_end, params, every):
    out = tmp_path / f"{problem}-{integrator}"
    cmd = [exe, "run", "--problem", problem, "--integrator", integrator, "--dt", dt, "--t-end", t_end,
           "--sample-every", str(every), "--out", str(out)]
    for k, v in params.items():
        cmd += ["--set", f"{k}={v}"]
    subprocess.run(cmd, check=True, capture_output=True)
    with open(out / "series.csv") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]]), json.loads((out / "summary.json").read_text())


@pytest.mark.parametrize("problem,integrator,dt,t_end,params,every", CASES)
def test_arrays_equal_the_command_lines_series_bit_for_bit(nsbench_exe, tmp_path, problem, integrator, dt, t_end, params,
                                                           every):
    columns, rows, summary = cli_run(nsbench_exe, tmp_path, problem, integrator, dt, t_end, params, every)
    r = nsbench.run(problem, integrator, dt=float(dt), t_end=float(t_end), sample_every=every, **params)
    assert r.columns == columns
    assert r.rows.shape == rows.shape
    assert np.array_equal(r.rows, rows, equal_nan=True)  # bit for bit (series.csv: shortest round trip)
    for j, name in enumerate(columns):
        assert np.array_equal(r.series[name], rows[:, j], equal_nan=True)
    for key in ("status", "steps", "t_final", "work", "problem_parameters", "integrator_parameters", "max_penetration"):
        assert r.summary[key] == summary[key], key
    assert r.u.shape == (rows.shape[0], nsbench.Problem(problem, **{k: v for k, v in params.items()
                                                                     if k in nsbench.Problem(problem).parameters}).ndof)
    assert np.array_equal(r.state_t, r.t)


def test_observables_and_states():
    r = nsbench.run("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=0.5)
    assert r.status == "ok"
    assert np.array_equal(r.q, r.series["q"]) and np.array_equal(r.u[:, 0], r.q)
    assert np.max(np.abs(r.q - r.q_exact)) < 1e-2
    assert r.summary["work"]["force_evaluations"] >= r.summary["steps"] > 0
    assert r.summary["step_cpu_seconds"] > 0


def test_a_problem_object_and_integrator_parameters():
    bar = nsbench.Problem("bouncing-bar", N=10)
    a = nsbench.run(bar, "moreau-jean", dt=1e-3, t_end=0.1, theta=0.7)
    b = nsbench.run("bouncing-bar", "moreau-jean", dt=1e-3, t_end=0.1, N=10, theta=0.7)
    assert np.array_equal(a.rows, b.rows)
    assert a.summary["integrator_parameters"]["theta"] == 0.7
    with pytest.raises(ValueError, match="N: a parameter of the problem"):
        nsbench.run(bar, "moreau-jean", dt=1e-3, t_end=0.1, N=20)


def test_states_off_and_budget():
    r = nsbench.run("bouncing-bar", "cd-lagrange", dt=1e-3, t_end=1, N=20, states=False, max_force_evaluations=50)
    assert r.u.shape[0] == 0
    assert r.status == "over budget" and "budget of 50" in r.summary["message"]
