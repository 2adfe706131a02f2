"""What a run hands to Python, and how a run ends (issue 56): a Problem, state or view kept past
the run cannot corrupt memory, bind() is refused outside init, Ctrl-C and a KeyboardInterrupt in
step() reach the caller, a step is bounded below and above, and bad arguments are named."""
import os
import signal
import threading

import numpy as np
import pytest

import nsbench


class Free(nsbench.Integrator):
    """Test: free flight (u += h v), its hooks set per test"""

    kept = []
    on_step = None
    step_taken = None

    def init(self, problem, initial):
        self.bind(problem, initial)
        Free.kept.append(problem)

    def step(self, h):
        if Free.on_step:
            Free.on_step(self)
        self.state.u[:] += h * self.state.v
        return Free.step_taken if Free.step_taken is not None else h


nsbench.register_integrator("py-test-free", Free)


@pytest.fixture(autouse=True)
def reset_hooks():
    Free.kept, Free.on_step, Free.step_taken = [], None, None
    yield
    Free.kept, Free.on_step, Free.step_taken = [], None, None


def test_a_problem_kept_from_init_raises_after_the_run_instead_of_crashing():
    r = nsbench.run("bouncing-mass", "py-test-free", dt=1e-2, t_end=0.1)
    assert r.status == "ok"
    with pytest.raises(RuntimeError, match="used after the run it belonged to ended"):
        Free.kept[0].mass_matrix()
    # A Problem built in Python is the caller's: it stays usable.
    p = nsbench.Problem("bouncing-mass")
    nsbench.run(p, "py-test-free", dt=1e-2, t_end=0.1)
    assert Free.kept[1].mass_matrix().shape == (1, 1)


def test_views_and_state_kept_past_the_run_touch_no_other_memory():
    views = []
    Free.on_step = lambda self: views.append((self.state.u, self.impulses, self.state, self.work, self._core)) if not views else None
    nsbench.run("bouncing-mass", "py-test-free", dt=1e-2, t_end=0.1)
    u, impulses, state, work, core = views[0]
    other = np.zeros(1000)
    u[:] = 42.0  # its buffer is kept alive with the view: no other array changes
    impulses[:] = 42.0
    assert not other.any()
    assert u[0] == 42.0
    # Every use of a kept self.state or self.work raises: read as empty ones, they passed for results.
    for use in [lambda: state.u, lambda: state.v, lambda: state.t, lambda: repr(state), lambda: work.steps,
                lambda: work.lcp_unconverged]:
        with pytest.raises(RuntimeError, match=r"used after the run it belonged to ended \(.*self\.state, self\.work\)"):
            use()
    with pytest.raises(RuntimeError, match="used after the run"):
        state.t = 1.0
    with pytest.raises(RuntimeError, match="used after the run"):
        work.steps = 3
    # A State Python owns, and the counters of a live run, are left usable.
    assert nsbench.Problem("bouncing-mass").initial_state().u[0] == 1.0
    with pytest.raises(RuntimeError, match="used after the run"):
        core.state
    with pytest.raises(RuntimeError, match="used after the run"):
        core.bind(nsbench.Problem("bouncing-mass"), nsbench.Problem("bouncing-mass").initial_state())


def test_impact_times_past_the_known_ones_are_refused_not_capped():
    # e = 1 bounces for ever: 1e12 s gave the first 1,000 impacts as if they were all.
    elastic = nsbench.Problem("bouncing-mass", e=1)
    with pytest.raises(ValueError, match=r"impact_times\(t_end = 1e\+12\) asks past its 100000th impact .*; valid: t_end <= "):
        elastic.impact_times(1e12)
    assert len(elastic.impact_times(5000.0)) == 5537
    assert len(nsbench.Problem("bouncing-mass", e=0.99).impact_times(1e12)) > 1000


def test_bind_outside_init_is_refused():
    Free.on_step = lambda self: self.bind(nsbench.Problem("bouncing-mass"), nsbench.Problem("bouncing-mass").initial_state())
    r = nsbench.run("bouncing-mass", "py-test-free", dt=1e-2, t_end=0.1)
    assert r.status == "diverged"
    assert "bind(problem, initial) is called from init(problem, initial)" in r.summary["message"]


@pytest.mark.parametrize("exception", [KeyboardInterrupt, SystemExit])
def test_a_keyboard_interrupt_or_system_exit_in_step_reaches_the_caller(exception):
    def stop(self):
        raise exception()
    Free.on_step = stop
    with pytest.raises(exception):
        nsbench.run("bouncing-mass", "py-test-free", dt=1e-2, t_end=0.1)


def test_sigint_stops_a_cpp_integrators_run_with_keyboard_interrupt():
    # A run of 1e8 steps (minutes), which went on after Ctrl-C before; the signal comes from
    # another thread once the run has begun, whenever that is.
    timer = threading.Timer(0.2, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            nsbench.run("bouncing-mass", "cd-lagrange", dt=1e-4, t_end=1e4, states=False, sample_every=1000000)
    finally:
        timer.cancel()


def test_a_step_below_the_floor_or_past_t_end_ends_the_run_as_diverged():
    Free.step_taken = 1e-300
    r = nsbench.run("bouncing-mass", "py-test-free", dt=1e-2, t_end=0.5)
    assert r.status == "diverged" and "valid: a finite dt >= 1e-11 (1e-9 of the requested 0.01)" in r.summary["message"]
    Free.step_taken = 1e300
    r = nsbench.run("bouncing-mass", "py-test-free", dt=1e-2, t_end=0.5)
    assert r.status == "diverged" and "longer than the requested dt = 0.01 and t_end = 0.5" in r.summary["message"]
    assert r.summary["t_final"] == 1e300 and r.summary["steps"] == 1


def test_bad_arguments_are_named():
    with pytest.raises(ValueError, match="problem: int given; valid: a problem's name"):
        nsbench.run(5, "cd-lagrange", dt=1e-2, t_end=0.1)
    with pytest.raises(ValueError, match="states 'no': valid: True or False"):
        nsbench.run("bouncing-mass", "cd-lagrange", dt=1e-2, t_end=0.1, states="no")
    with pytest.raises(ValueError, match=r"sample_every 1e\+20: must be an integer >= 1 \(at most 1e\+15\)"):
        nsbench.run("bouncing-mass", "cd-lagrange", dt=1e-2, t_end=0.1, sample_every=1e20)
    for name in ["", "x\ny"]:
        with pytest.raises(ValueError, match="register_integrator .*: valid: a name of printable characters"):
            nsbench.register_integrator(name, Free)


def test_an_energy_that_is_no_pair_of_floats_is_named():
    class Wordy(Free):
        """Test: an energy() of the wrong type"""

        def energy(self):
            return "high"
    nsbench.register_integrator("py-test-wordy", Wordy)
    with pytest.raises(RuntimeError, match=r"py-test-wordy.energy returned no \(kinetic, potential\) pair of floats"):
        nsbench.run("bouncing-mass", "py-test-wordy", dt=1e-2, t_end=0.1)


QUICK_STUDY = {"study": {"title": "a study given as one line of JSON, longer than a file name may be", "t_end": 0.1}, "problem": [{"name": "bouncing-mass"}],
               "integrator": [{"name": "cd-lagrange", "steps": [1e-2]}], "reference": {"solution": "exact"},
               "measure": [{"kind": "error"}]}


def test_run_study_takes_a_path_or_a_text_explicitly(tmp_path):
    import json
    import pathlib
    text = json.dumps(QUICK_STUDY)
    assert len(text) > 255  # a file name that long raised "File name too long"
    assert nsbench.run_study(text=text, out=str(tmp_path / "a"))
    assert nsbench.run_study(text, out=str(tmp_path / "b"))  # a str opening a JSON object is a text
    path = tmp_path / "quick.json"
    path.write_text(text)
    assert nsbench.run_study(pathlib.Path(path), out=str(tmp_path / "c"))
    os.mkfifo(tmp_path / "fifo")
    for bad, why in [(tmp_path / "missing.toml", "no such file"), (tmp_path, "not a regular file"),
                     (tmp_path / "fifo", "not a regular file"), (str(tmp_path / "missing.toml"), "no such file")]:
        with pytest.raises(ValueError, match=f"study file '.*': {why}"):
            nsbench.run_study(bad, out=str(tmp_path / "d"))
    with pytest.raises(ValueError, match="not both"):
        nsbench.run_study(path, out=str(tmp_path / "e"), text=text)
