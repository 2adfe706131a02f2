"""The built-in Python studies (studies/builtin/*.py) run from nsbench-study with its options: the
peers study writes its report, and its theta = 1/2 Moreau-Jean rows agree with Siconos to
round-off as its header states; `show` prints the script; --verify reaches it (shards and merge of a Python study:
test_study_api.py)."""
import csv
import importlib.util
import math
import os
import pathlib
import subprocess

import pytest

import nsbench
from nsbench import study

ROOT = pathlib.Path(__file__).resolve().parents[2]


def run(exe, *args):
    return subprocess.run([exe, *args], capture_output=True, text=True, env=dict(os.environ, OPENBLAS_NUM_THREADS="1"))


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def test_show_prints_the_script(study_exe):
    shown = run(study_exe, "show", "peers")
    assert shown.returncode == 0
    assert shown.stdout == (ROOT / "studies" / "builtin" / "peers.py").read_text()


def test_peers_runs_from_nsbench_study_and_agrees_with_siconos(study_exe, tmp_path):
    if "siconos-moreau-jean" not in {e["name"] for e in nsbench.integrators()}:
        pytest.skip("the Siconos peers are not built")
    done = run(study_exe, "peers", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    assert "peers" in (tmp_path / "index.md").read_text()
    table = rows(tmp_path / "peers.csv")
    half = [r for r in table if r["ours"] == "moreau-jean" and r["parameters"] == "theta = 1/2"]
    assert len(half) == 5  # the five 2D problems
    for r in half:
        assert r["status"] == "ok", r
        for key in ("du", "dv", "dE", "dLambda"):
            assert float(r[key]) <= 1e-12, (r["problem"], key, r[key])
    declined = [r for r in table if r["status"].startswith("n/a:")]
    assert declined and all("friction" in r["status"] for r in declined)
    verified = run(study_exe, "peers", "--verify", str(tmp_path), "--rtol", "0")  # --verify reaches the script
    assert verified.returncode == 0 and "0 differences" in verified.stdout, verified.stdout



def builtin_study(name):
    """The module of studies/builtin/NAME.py (its cases, measures and tables)."""
    spec = importlib.util.spec_from_file_location(f"builtin_{name}", ROOT / "studies" / "builtin" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_friction_stops_within_two_steps_and_sticks_without_creeping():
    """The friction schemes stop the sliding mass within two steps of the exact stop time and hold it
    below the friction angle without creeping (friction.py measures, as studies/friction.cpp did)."""
    friction = builtin_study("friction")
    dt, g = 1e-3, 9.81
    wanted = [c for c in friction.cases(False) if c["integrator"] in ("cd-lagrange", "moreau-jean")
              and c["labels"]["case"] in ("slide-stop", "stick") and c["dt"] == dt]
    assert len(wanted) == 4
    for c, r in zip(wanted, study.run(wanted)):
        assert r.ok, r
        m = friction.measure(friction.BY_ID[c["labels"]["case"]], r)
        if c["labels"]["case"] == "slide-stop":
            assert m["t_stop_err"] <= 2 * dt and m["energy_gain"] <= 1e-15
            continue
        assert r.steps == 100000 and m["late_creep"] == 0.0
        if c["integrator"] == "moreau-jean":
            assert m["creep"] == 0.0
        else:  # CD-Lagrange's start-up half kick moves the mass by tau^2/2 g sin(alpha) before the first impulse
            assert m["creep"] * 1e5 * dt == pytest.approx(0.5 * dt * dt * g * math.sin(math.radians(20)), rel=1e-9)


def test_friction_a_scheme_without_friction_is_one_n_a_row_naming_mu():
    friction = builtin_study("friction")
    wanted = [c for c in friction.cases(False) if c["integrator"] == "schatzman-paoli" and c["labels"]["case"] == "slide-stop"]
    assert len(wanted) == 3
    results = study.run(wanted)
    assert all(r.status == "n/a" for r in results)
    sliding = next(t for t in friction.tables(results, False) if t.id == "friction_sliding")
    assert len(sliding.rows) == 1
    assert sliding.rows[0][:2] == ["schatzman-paoli", "n/a"] and "mu = 0.8" in sliding.rows[0][-1]
