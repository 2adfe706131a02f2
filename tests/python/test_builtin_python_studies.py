"""The built-in Python studies (studies/builtin/*.py) run from nsbench-study with its options: the
peers study writes its report, and its theta = 1/2 Moreau-Jean rows agree with Siconos to
round-off as its header states; `show` prints the script; --verify reaches it (shards and merge of a Python study:
test_study_api.py)."""
import csv
import os
import pathlib
import subprocess

import pytest

import nsbench

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

