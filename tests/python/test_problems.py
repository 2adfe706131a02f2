"""nsbench.problems(), nsbench.integrators() and nsbench.Problem: every problem built with its
defaults, its operators of consistent shapes, the listing as `nsbench list` prints it."""
import subprocess

import numpy as np
import pytest
import scipy.sparse

import nsbench


def test_every_problem_is_constructible_with_defaults():
    names = [p["name"] for p in nsbench.problems()]
    assert "bouncing-bar" in names and "block-2d" in names
    for name in names:
        p = nsbench.Problem(name)
        n = p.ndof
        assert p.name == name and n > 0
        M = p.mass_matrix()
        assert scipy.sparse.issparse(M) and M.shape == (n, n)
        s = p.initial_state()
        assert s.u.shape == (n,) and s.v.shape == (n,)
        f = p.internal_force(s.u)
        out = np.full(n, np.nan)
        assert p.internal_force(s.u, out=out) is None
        assert np.array_equal(f, out), name
        assert p.tangent_stiffness(s.u).shape == (n, n)
        c = p.contacts
        m = c["g0"].shape[0]
        assert c["L"].shape == (m, n) and c["T"].shape == (m, n) and c["mu"].shape == (m,)
        assert 0.0 <= c["e"] <= 1.0
        assert np.all(c["g0"] + c["L"] @ s.u >= -1e-12), name  # initially open or touching
        assert p.stable_step() > 0
        assert np.isfinite(p.strain_energy(s.u) + p.load_potential(s.u) + p.kinetic_energy(s.v))
        assert set(p.parameters) == {q["name"] for q in nsbench.problems()[names.index(name)]["parameters"]}


def test_parameters_set_by_keyword_and_exact_state():
    p = nsbench.Problem("bouncing-mass", e=0.5)
    assert p.parameters["e"] == 0.5 and p.contacts["e"] == 0.5
    exact = p.exact_state(0.1)
    assert exact is not None and exact.t == 0.1
    assert nsbench.Problem("bouncing-bar", N=20).ndof > nsbench.Problem("bouncing-bar", N=10).ndof
    assert nsbench.Problem("block-2d").exact_state(0.1) is None



def test_exact_events_and_values_by_name():
    """The exact solution's events and values (what a study's stop, onset and rebound errors are
    against): the sliding mass's closed form, inf for a stop that never comes, None where untimed."""
    stops = nsbench.Problem("sliding-mass", alpha=30, mu=0.8, v0=2)
    a1 = 9.81 * (np.sin(np.pi / 6) - 0.8 * np.cos(np.pi / 6))
    assert stops.exact_event("slip_stop") == pytest.approx(-2 / a1, rel=1e-12)
    assert stops.exact_value("stop_distance") == pytest.approx(4 / (2 * abs(a1)), rel=1e-12)
    assert stops.exact_value("stays_stopped") == 1.0
    assert nsbench.Problem("sliding-mass", alpha=30, mu=0.3, v0=2).exact_event("slip_stop") == np.inf
    disk = nsbench.Problem("rolling-disk", h0=0.1, omega0=20, v0=0, e=0.5)
    assert disk.exact_event("roll_onset") > 0 and disk.exact_value("first_rebound_speed") is not None
    assert stops.exact_event("jam") is None and stops.exact_value("wave_time") is None
    assert nsbench.Problem("block-2d").exact_event("rest") is None  # no exact solution
    with pytest.raises(ValueError, match=r"exact_event 'stop': unknown; valid: contact_start, slip_stop"):
        stops.exact_event("stop")

def test_listing_matches_nsbench_list(nsbench_exe):
    listing = subprocess.run([nsbench_exe, "list"], check=True, capture_output=True, text=True).stdout
    for entry in nsbench.problems() + [e for e in nsbench.integrators() if not e["origin"]]:  # not those of the tests
        assert f"  {entry['name']:<22} {entry['description']}" in listing
        for q in entry["parameters"]:
            assert q["range"] in listing
    bar = next(e for e in nsbench.problems() if e["name"] == "bouncing-bar")
    N = next(q for q in bar["parameters"] if q["name"] == "N")
    assert N["kind"] == "integer" and isinstance(N["default"], int) and N["range"] == "integer in [1, 100000000]"
    cd = next(e for e in nsbench.integrators() if e["name"] == "cd-lagrange")
    assert cd["origin"] == "" and not cd["reference"]
