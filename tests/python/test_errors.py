"""Bad input arrives as ValueError with the command line's one-line message (the parameter and its
valid range); a Python integrator that raises or goes non-finite ends its run as diverged."""
import numpy as np
import pytest

import nsbench


@pytest.mark.parametrize("call,message", [
    (lambda: nsbench.Problem("bouncing-bar", N=0), r"N.*\[.*\]"),
    (lambda: nsbench.Problem("bouncing-mass", e=1.5), r"'e' = 1\.5 is outside its valid range \[0, 1\]"),
    (lambda: nsbench.Problem("bouncing-mass", nope=1), r"nope"),
    (lambda: nsbench.Problem("bouncing-mas"), r"unknown problem \(nearest: bouncing-mass"),
    (lambda: nsbench.Problem("bouncing-mass", e=True), r"e=True: a number or a string"),
    (lambda: nsbench.run("bouncing-mass", "moreau-jean", dt=1e-3, t_end=1, theta=0.3), r"'theta' = 0\.3 is outside its valid range \[0\.5, 1\]"),
    (lambda: nsbench.run("bouncing-mass", "cd-lagrang", dt=1e-3, t_end=1), r"unknown integrator \(nearest: cd-lagrange"),
    (lambda: nsbench.run("bouncing-mass", "cd-lagrange", dt=-1, t_end=1), r"^dt -1: must be > 0"),
    (lambda: nsbench.run("bouncing-mass", "cd-lagrange", dt=16, t_end=1), r"dt 16 is larger than t_end 1; valid: dt <= t_end"),
    (lambda: nsbench.run("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=1, sample_every=0), r"sample_every 0: must be an integer >= 1"),
    (lambda: nsbench.Problem("bouncing-mass").internal_force(np.zeros(3)), r"u: 3 values given"),
    (lambda: nsbench.load_plugin("/nonexistent.so"), r"plugin /nonexistent.so: no such file"),
    (lambda: nsbench.check(), r"give integrator=NAME or problem=NAME"),
    (lambda: nsbench.run_study("[study]\ntitle = 1\n", out="/tmp/nsbench-bad-study"), r"<text>"),
])
def test_bad_input_is_a_value_error_with_the_range(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_the_range_is_in_the_message():
    with pytest.raises(ValueError) as e:
        nsbench.run("bouncing-bar", "cd-lagrange", dt=1e-3, t_end=1, N=0)
    spec = next(q for q in next(p for p in nsbench.problems() if p["name"] == "bouncing-bar")["parameters"] if q["name"] == "N")
    assert "'N' = 0" in str(e.value) and spec["range"] in str(e.value)


class Raises(nsbench.Integrator):
    """test: raises at its third step"""

    def init(self, problem, initial):
        self.bind(problem, initial)

    def step(self, dt):
        if self.work.steps == 2:
            raise ArithmeticError("no third step")
        self.work.force_evaluations += 1
        return dt


class GoesNaN(Raises):
    """test: a NaN state at its second step"""

    def step(self, dt):
        if self.work.steps == 1:
            self.state.u[:] = np.nan
        return super().step(dt)


class ReturnsNaN(Raises):
    """test: returns dt = NaN"""

    def step(self, dt):
        super().step(dt)
        return float("nan")


class Declines(Raises):
    """test: declines every problem"""

    def init(self, problem, initial):
        raise ValueError(f"declines {problem.name}")


for name, cls in [("test-raises", Raises), ("test-nan", GoesNaN), ("test-returns-nan", ReturnsNaN),
                  ("test-declines", Declines)]:
    if name not in {e["name"] for e in nsbench.integrators()}:
        nsbench.register_integrator(name, cls)


@pytest.mark.parametrize("name,message", [
    ("test-raises", "test-raises.step raised ArithmeticError: no third step"),
    ("test-nan", "non-finite state at t = 0.002"),
    ("test-returns-nan", "test-returns-nan.step returned the step dt = nan"),
])
def test_a_python_integrator_that_fails_is_diverged_with_its_message(name, message):
    r = nsbench.run("bouncing-mass", name, dt=1e-3, t_end=1)
    assert r.status == "diverged"
    assert message in r.summary["message"]


def test_a_declining_python_integrator_is_a_value_error_and_the_name_is_taken_once():
    with pytest.raises(ValueError, match="test-declines: declines bouncing-mass"):
        nsbench.run("bouncing-mass", "test-declines", dt=1e-3, t_end=1)
    with pytest.raises(ValueError, match="integrator 'cd-lagrange' is already registered by nsbench"):
        nsbench.register_integrator("cd-lagrange", Raises)
    with pytest.raises(TypeError):
        nsbench.register_integrator("not-a-class", object)
    with pytest.raises(ValueError, match=r"'k' = 5 is outside its valid range \[0, 1\]"):
        nsbench.register_integrator("bad-default", Raises, parameters=[nsbench.Parameter.real("k", 5, 0, 1, "x")])
