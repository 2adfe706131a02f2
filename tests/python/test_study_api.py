"""nsbench.study: cases run in the C++ pool as nsbench.run runs them, in parallel and without the
GIL; declined and diverged runs recorded; a Study's report, shards, merge and --verify through
the driver of nsbench-study; the table writer and the measures' bindings."""
import os
import pathlib
import threading
import time

import numpy as np
import pytest

import nsbench
from nsbench import study

BAR = dict(N=40)


def same(a, b):
    return a.shape == b.shape and np.array_equal(a, b, equal_nan=True)


def test_a_case_runs_as_nsbench_run_bit_for_bit():
    [r] = study.run([study.case("bouncing-bar", "cd-lagrange", dt=2e-4, t_end=0.3, states=True, **BAR)])
    direct = nsbench.run("bouncing-bar", "cd-lagrange", dt=2e-4, t_end=0.3, **BAR)
    assert r.status == "ok" and r.columns == direct.columns
    for name in direct.columns:
        assert same(r.series[name], direct.series[name]), name
    assert same(r.u, direct.u) and same(r.v, direct.v) and same(r.state_t, direct.state_t)
    assert r.steps == direct.summary["steps"] == r.summary["steps"]



def test_a_case_keeps_the_states_and_columns_it_names_bit_for_bit():
    """states=[...] and series=[...]: those arrays and columns only, the same numbers as the whole run's."""
    whole, few = study.run([study.case("bouncing-bar", "cd-lagrange", dt=2e-4, t_end=0.3, states=True, **BAR),
                            study.case("bouncing-bar", "cd-lagrange", dt=2e-4, t_end=0.3, states=["v", "impulses"],
                                       series=["total_energy", "t"], **BAR)])
    assert few.columns == ["total_energy", "t"] and set(few.series) == {"total_energy", "t"}
    for name in few.columns:
        assert same(few.series[name], whole.series[name]), name
    assert same(few.v, whole.v) and same(few.impulses, whole.impulses) and same(few.state_t, whole.state_t)
    assert not hasattr(few, "u") and not hasattr(few, "tangential_impulses")
    with pytest.raises(ValueError, match=r'case states \["v","w"\]: "w" is not one of u, v, impulses'):
        study.run([study.case("bouncing-bar", "cd-lagrange", dt=2e-4, t_end=0.01, states=["v", "w"], **BAR)])
    with pytest.raises(ValueError, match=r'case series \["E"\]: "E" is not one of t, dt, kinetic'):
        study.run([study.case("bouncing-bar", "cd-lagrange", dt=2e-4, t_end=0.01, series=["E"], **BAR)])

def test_cfl_takes_its_fraction_of_the_stable_step():
    [r] = study.run([study.case("bouncing-bar", "cd-lagrange", cfl=0.5, t_end=0.1, **BAR)])
    assert r.dt == 0.5 * nsbench.Problem("bouncing-bar", **BAR).stable_step()
    assert r.series["dt"][1] == r.dt


def test_declined_and_diverged_runs_are_recorded_and_the_others_run():
    cases = [study.case("bouncing-bar", "cd-lagrange", dt=1e-4, t_end=0.05, mass="consistent", **BAR),
             study.case("bouncing-bar", "cd-lagrange", cfl=3.0, t_end=5.0, **BAR),
             study.case("bouncing-bar", "moreau-jean", dt=1e-3, t_end=0.05, **BAR)]
    declined, diverged, fine = study.run(cases)
    assert declined.status == "n/a" and "diagonal" in declined.message
    assert diverged.status == "diverged" and diverged.message
    assert fine.ok and fine.series["t"][-1] == pytest.approx(0.05)


@pytest.mark.parametrize("change, key", [({"t_end": -1.0}, "t_end"), ({"dt": None}, "dt"), ({"problem": "no-such"}, "no-such"),
                                          ({"set": ["N=0"]}, "N")])
def test_a_bad_case_is_one_line_naming_its_key(change, key):
    c = study.case("bouncing-bar", "cd-lagrange", dt=1e-3, t_end=0.1)
    c.update(change)
    c = {k: v for k, v in c.items() if v is not None}
    with pytest.raises(ValueError, match=key):
        study.run([c])


def rendezvous_cases(n, wait):
    plugin = os.environ.get("NSBENCH_RENDEZVOUS_PLUGIN")
    if not plugin:
        pytest.skip("NSBENCH_RENDEZVOUS_PLUGIN (tests/plugins/rendezvous.cpp) is not set")
    if "rendezvous" not in {e["name"] for e in nsbench.integrators()}:
        nsbench.load_plugin(plugin)
    return [study.case("bouncing-bar", "rendezvous", dt=1e-3, t_end=0.01, parties=n, wait=wait, **BAR) for _ in range(n)]


def with_jobs(jobs, f):
    before = os.environ.get("NSBENCH_JOBS")
    os.environ["NSBENCH_JOBS"] = str(jobs)
    try:
        return f()
    finally:
        if before is None:
            del os.environ["NSBENCH_JOBS"]
        else:
            os.environ["NSBENCH_JOBS"] = before


def test_the_pool_runs_cases_side_by_side():
    # Each rendezvous run waits in init for the other: both end ok only when they ran at once.
    results = with_jobs(2, lambda: study.run(rendezvous_cases(2, wait=60.0)))
    assert [r.status for r in results] == ["ok", "ok"], [r.message for r in results]


def test_the_rendezvous_fails_when_the_pool_serialises():
    results = with_jobs(1, lambda: study.run(rendezvous_cases(2, wait=0.2)))
    assert [r.status for r in results] == ["n/a", "n/a"]


def test_a_second_thread_progresses_while_the_pool_runs():
    stamps, stop = [], threading.Event()
    thread = threading.Thread(target=lambda: [stamps.append(time.perf_counter()) for _ in iter(stop.is_set, True)])
    thread.start()
    try:
        time.sleep(0.05)
        start = time.perf_counter()
        study.run([study.case("bouncing-bar", "cd-lagrange", dt=1e-5, t_end=4.0, N=400, sample_every=1000)
                   for _ in range(2)])
        end = time.perf_counter()
    finally:
        stop.set()
        thread.join()
    elapsed = end - start
    middle = [s for s in stamps if start + 0.25 * elapsed < s < end - 0.25 * elapsed]
    assert len(middle) > 1000, f"the other thread made {len(middle)} steps in the middle half of a {elapsed:.2f} s pool"


def energy_study():
    def cases(full):
        return [study.case("bouncing-bar", name, cfl=f, t_end=0.5, labels={"cfl": f}, **BAR)
                for name in ("cd-lagrange", "moreau-jean") for f in (0.25, 0.5, 0.9)]

    def tables(results, full):
        t = study.Table("api_energy", title="Energy at t_end", caption="E(t_end) - E0")
        t.columns = [study.Column("integrator", format="{}"), study.Column("cfl", format="{:.2f}"),
                     study.Column("energy change", unit="J", format="{:.3e}"), study.Column("steps", format="{}")]
        for r in results:
            e = r.series["total_energy"] if r.ok else np.array([np.nan])
            t.add_row([r.case["integrator"], r.case["labels"]["cfl"], float(e[-1] - e[0]), r.steps])
        return [t]

    return study.Study("api-energy", "a test study of the Python API", cases, tables, source="tests/python/test_study_api.py")


def test_a_study_writes_a_report_that_verifies_and_shards_merge_to_it(tmp_path):
    s = energy_study()
    whole, sharded = tmp_path / "whole", tmp_path / "sharded"
    assert s.main(["--out", str(whole)]) == 0
    csv = (whole / "api_energy.csv").read_text()
    assert "cd-lagrange" in csv and (whole / "api_energy.md").exists() and "api-energy" in (whole / "index.md").read_text()
    assert s.main(["--verify", str(whole), "--rtol", "0"]) == 0
    for i in (1, 2):
        assert s.main(["--out", str(sharded), "--shard", f"{i}/2"]) == 0
    assert s.main(["--out", str(sharded), "--merge"]) == 0
    body = [line for line in csv.splitlines() if not line.startswith("#")]
    merged = [line for line in (sharded / "api_energy.csv").read_text().splitlines() if not line.startswith("#")]
    assert merged == body


def test_verify_finds_a_changed_cell(tmp_path):
    s = energy_study()
    assert s.main(["--out", str(tmp_path)]) == 0
    csv = tmp_path / "api_energy.csv"
    lines = csv.read_text().splitlines()
    row = next(i for i, line in enumerate(lines) if line.startswith("moreau-jean"))
    cells = lines[row].split(",")
    cells[3] = str(int(cells[3]) + 1)
    lines[row] = ",".join(cells)
    csv.write_text("\n".join(lines) + "\n")
    assert s.main(["--verify", str(tmp_path), "--rtol", "0"]) == 1


def test_a_bad_option_is_one_line_and_exit_2(tmp_path, capsys):
    assert energy_study().main(["--out", str(tmp_path), "--shard", "3/2"]) == 2
    assert "shard" in capsys.readouterr().err


def test_the_table_writer_and_its_checks():
    t = study.Table("t", title="T", caption="c")
    t.columns = [study.Column("name", format="{}"), study.Column("x", unit="m", format="{:.2f}"), study.Column("n", format="{}")]
    t.add_row(["a", 1.25, 3])
    t.add_row(["b", None, 4])
    md, csv = study.to_markdown(t), study.to_csv(t)
    assert "| a" in md and "1.25" in md and "n/a" in md and "x [m]" in csv
    assert study.verify_table(t, csv, rtol=0.0) == (6, [])
    with pytest.raises(ValueError, match="2 cells for 3 columns"):
        t.add_row(["c", 1.0])
    with pytest.raises(ValueError, match="no field 'colour'"):
        study.Column("y", colour="red")


def test_the_measures_bindings_on_known_answers():
    h = [0.1, 0.05, 0.025, 0.0125]
    fit = study.fit_order(h, [3.0 * x**2 for x in h])
    assert fit["order"] == pytest.approx(2.0, abs=1e-12) and fit["points"] == 4
    line = study.fit_line([0.0, 1.0, 2.0, 3.0], [1.0, 3.0, 5.0, 7.0])
    assert line["slope"] == pytest.approx(2.0, abs=1e-12)
    assert study.observed_order(0.1, 1e-2, 0.05, 2.5e-3) == pytest.approx(2.0)
    # Two horizontal lines 0.5 apart: their Hausdorff distance is 0.5 (scaled by value_scale 2: 0.25).
    assert study.hausdorff([0, 1], [0, 0], [0, 1], [0.5, 0.5]) == pytest.approx(0.5, rel=1e-9)
    assert study.hausdorff([0, 1], [0, 0], [0, 1], [0.5, 0.5], value_scale=2.0) == pytest.approx(0.25, rel=1e-9)
    assert study.contact_phases([0.1, 0.2, 0.3, 0.4, 0.5], [0, 1, 1, 0, 2]) == [0.2, 0.5]


def test_the_ranking_says_the_winner_or_a_tie():
    def curve(name, costs, errors, spread):
        return {"integrator": name, "points": [{"run": f"dt = {c}", "cost": c, "error": e, "spread": spread}
                                               for c, e in zip(costs, errors)]}

    problem = {"label": "p", "error_source": "exact", "targets": [1e-3],
               "curves": [curve("fast", [1.0, 2.0], [1e-2, 1e-4], 0.01), curve("slow", [3.0, 6.0], [1e-2, 1e-4], 0.01),
                          curve("twin", [1.005, 2.01], [1e-2, 1e-4], 0.01)]}
    t = study.ranking_table("r", "R", study.Column("error", format="{:.1e}"), "CPU", [problem])
    winner = [c.name for c in t.columns].index("winner")
    assert t.rows[0][winner] == "tie: fast, twin"
    problem["curves"].pop()
    t = study.ranking_table("r", "R", study.Column("error", format="{:.1e}"), "CPU", [problem])
    assert t.rows[0][winner] == "fast"


def test_a_measured_case_takes_the_study_file_measures():
    # The engine's impact-time (the largest |t_i - t_i exact| over the first impacts) and penetration
    # against the same from the series of an unmeasured run and the exact impact times.
    measures = [{"kind": "impact-time", "count": 2}, {"kind": "penetration", "label": "pen"}]
    measured, plain = study.run([
        study.case("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=1.5, e=0.9, measures=measures,
                   reference={"solution": "exact"}),
        study.case("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=1.5, e=0.9)])
    exact = nsbench.Problem("bouncing-mass", e=0.9).impact_times(1.5)[:2]
    seen = study.contact_phases(plain.t, plain.impulse)[:2]
    assert len(exact) == 2 and measured.measure("impact-time") == max(abs(a - b) for a, b in zip(seen, exact))
    assert measured.measure("pen") == plain.summary["max_penetration"] > 0
    with pytest.raises(KeyError, match="no measure 'energy'"):
        measured.measure("energy")


def test_a_bad_measure_names_its_key():
    c = study.case("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=0.5, measures=[{"kind": "no-such"}])
    with pytest.raises(ValueError, match=r"measure\[0\].kind"):
        study.run([c])
    with pytest.raises(ValueError, match="states and measures"):
        study.run([study.case("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=0.5, states=True, measures=[{"kind": "penetration"}])])


def test_run_measures_observe_a_run():
    # CD-Lagrange's discrete momentum identities hold exactly: the residuals are round-off.
    assert {"mesh-momentum", "momentum-balance"} <= {m["name"] for m in study.run_measures()}
    block, angular, spatial, chain = study.run([
        study.case("block-2d", "cd-lagrange", cfl=0.9, t_end=0.15, nx=4, ny=4,
                   observe=[{"kind": "mesh-momentum", "component": "px"}, {"kind": "mesh-momentum", "component": "py"}]),
        study.case("block-2d", "cd-lagrange", cfl=0.9, t_end=0.15, nx=4, ny=4, tilt=10, spin=3,
                   observe=[{"kind": "mesh-momentum", "component": "jz"}]),
        study.case("block-2d", "cd-lagrange", cfl=0.9, t_end=0.01, nx=4, ny=4, observe=[{"kind": "mesh-momentum", "component": "pz"}]),
        study.case("spring-chain", "cd-lagrange", dt=1e-3, t_end=1.0, observe=[{"kind": "momentum-balance"}])])
    assert block.ok and len(block.observed) == 2 and all(o["relative"] < 1e-12 and o["scale"] > 0 for o in block.observed)
    # A plane body's angular momentum about the normal, the floor's impulse moments included.
    assert angular.ok and angular.observed[0]["relative"] < 1e-12 and angular.observed[0]["scale"] > 0
    assert spatial.status == "n/a" and "valid: px, py, jz" in spatial.message
    assert chain.ok and chain.observed[0]["relative"] < 1e-12 and chain.observed[0]["momentum"] > 0
    with pytest.raises(ValueError, match="unknown run measure"):
        study.run([study.case("spring-chain", "cd-lagrange", dt=1e-3, t_end=0.1, observe=[{"kind": "mesh-momentm"}])])
    with pytest.raises(ValueError, match="component"):
        study.run([study.case("block-2d", "cd-lagrange", dt=1e-4, t_end=0.01, observe=[{"kind": "mesh-momentum", "component": "qx"}])])


def test_the_momentum_balance_counts_from_the_first_step_and_declines_a_plane_body():
    # Under gravity CD-Lagrange's start is a half kick: P after step 1 differs from P0 + m g dt by
    # m g dt / 2, an offset of the start, not a defect of the balance; from there it is exact.
    bar, block = study.run([
        study.case("bouncing-bar", "cd-lagrange", cfl=0.9, t_end=2.0, N=40, mass="lumped", observe=[{"kind": "momentum-balance"}]),
        study.case("block-2d", "cd-lagrange", cfl=0.9, t_end=0.01, nx=4, ny=4, observe=[{"kind": "momentum-balance"}])])
    assert bar.ok and bar.observed[0]["relative"] < 1e-12 and bar.observed[0]["momentum"] > 0
    assert block.status == "n/a" and "2D" in block.message and "mesh-momentum" in block.message


def test_the_energy_balance_observed_to_round_off_and_as_a_drift():
    # CD-Lagrange's discrete balance is exact on a rigid body, impacts included (studies/measures.hpp);
    # Moreau-Jean at theta = 1 dissipates h^2 m g^2 / 2 a step in flight: a drift the rule must not pass.
    observe = [{"kind": "energy-balance", "window": 0.5}]
    exact, dissipating, other = study.run([
        study.case("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=10.0, e=0.8, observe=observe),
        study.case("bouncing-mass", "moreau-jean", dt=1e-3, t_end=10.0, e=0.8, theta=1, observe=observe),
        study.case("bouncing-mass", "nsga", dt=1e-3, t_end=1.0, observe=observe)])
    balance = exact.observed[0]
    assert abs(balance["cumulative"]) <= balance["round_off"] and balance["drift"]["no_drift"]
    assert balance["drift"]["windows"] >= 8 and len(balance["envelope"]["maxima"]) == balance["drift"]["windows"]
    assert not dissipating.observed[0]["drift"]["no_drift"] and dissipating.observed[0]["drift"]["high"] < 0
    assert other.status == "n/a" and "not derived" in other.message


def test_measured_and_observed_cases_shard_and_merge_to_the_single_run(tmp_path):
    # The merge checks each shard's result against its case's shape: plain, measured or observed.
    def cases(full):
        return [study.case("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=1.0, measures=[{"kind": "penetration"}]),
                study.case("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=1.0, observe=[{"kind": "energy-balance", "window": 0.1}]),
                study.case("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=1.0)]

    def tables(results, full):
        t = study.Table("api_shapes", title="Three shapes", caption="penetration, balance, steps")
        t.columns = [study.Column("penetration", unit="m", format="{:.3e}"), study.Column("balance", unit="J", format="{:.3e}"),
                     study.Column("steps", format="{}")]
        measured, observed, plain = results
        t.add_row([measured.measure("penetration"), observed.observed[0]["cumulative"], plain.steps])
        return [t]

    s = study.Study("api-shapes", "a test study of three result shapes", cases, tables, source="tests/python/test_study_api.py")
    whole, sharded = tmp_path / "whole", tmp_path / "sharded"
    assert s.main(["--out", str(whole)]) == 0
    for i in (1, 2, 3):
        assert s.main(["--out", str(sharded), "--shard", f"{i}/3"]) == 0
    assert s.main(["--out", str(sharded), "--merge"]) == 0
    body = [line for line in (whole / "api_shapes.csv").read_text().splitlines() if not line.startswith("#")]
    assert [line for line in (sharded / "api_shapes.csv").read_text().splitlines() if not line.startswith("#")] == body


def test_a_graph_starts_at_the_problems_initial_state():
    # signorini-bar touches the wall at t = 0 and modal-exact resolves that impact inside init();
    # the measured graph still starts at the initial v_contact = -v0, the exact graph's start, so
    # the Hausdorff distance is the solution's, not v0 (1 in its units) at every N as it was when
    # the graph began after the jump.
    measures = [{"kind": "hausdorff", "observable": "v_contact", "label": "d"}]
    [r] = study.run([study.case("signorini-bar", "modal-exact", cfl=0.9, t_end=3.0, N=25, mass="lumped",
                                measures=measures, reference={"solution": "exact"})])
    assert r.measure("d") < 0.99
