"""nsbench from Python: the problems, integrators, runs and study files of the C++ suite.

    import nsbench
    nsbench.problems(), nsbench.integrators()        # names, descriptions, parameters (as `nsbench list`)
    bar = nsbench.Problem("bouncing-bar", N=100)     # operators as NumPy / scipy.sparse
    r = nsbench.run("bouncing-bar", "cd-lagrange", dt=1e-3, t_end=2, N=100)
    r.t, r.u, r.v, r.total_energy, r.summary         # the series as arrays, the summary as a dict
    nsbench.check(integrator="cd-lagrange")          # the conformance checks of `nsbench check`
    nsbench.run_study("studies/examples/bouncing_quick.toml", out="reports/quick")

An integrator written in Python subclasses nsbench.Integrator and is registered under a name
(nsbench.register_integrator); it then runs wherever a C++ one does (examples/python/).

Names, parameters, checks and messages are the command line's: a bad value raises ValueError with
the command line's one-line message (the parameter and its valid range).
"""
import json

from . import _nsbench
from ._nsbench import (Parameter, Problem, State, StepInfo, WorkCounters, check, integrators, load_plugin,
                       problems, run_study)

__all__ = ["Integrator", "Parameter", "Problem", "RunResult", "State", "StepInfo", "WorkCounters", "check",
           "integrators", "load_plugin", "problems", "register_integrator", "run", "run_study"]


class RunResult:
    """A run's series and summary.

    t, and one attribute per column of the command line's series.csv (dt, kinetic, potential,
    total_energy, min_gap, impulse, active_contacts, tangential_impulse, then the problem's
    observables): 1-D arrays, views of `rows` (samples x columns, the series.csv values bit for
    bit). u, v: the states at the samples (samples x ndof; taken at state_t, which is t unless the
    run stopped on a non-finite state; empty with states=False). `series` maps every column name
    to its array (an observable named like an attribute, e.g. the bouncing mass's v, is reached
    there). summary: the command line's summary.json as a dict (status, message, work counters,
    cpu_seconds, step_cpu_seconds, energies ...).
    """

    def __init__(self, columns, rows, state_t, u, v, summary):
        self.columns = list(columns)
        self.rows = rows
        self.series = {name: rows[:, j] for j, name in enumerate(self.columns)}
        self.t = self.series["t"]
        self.state_t = state_t[:, 0]
        self.u = u
        self.v = v
        self.summary = json.loads(summary)

    def __getattr__(self, name):
        series = self.__dict__.get("series", {})
        if name in series:
            return series[name]
        raise AttributeError(f"RunResult has no attribute or column '{name}' (columns: {', '.join(series)})")

    @property
    def status(self):
        """'ok', 'diverged', 'over budget' or 'interrupted'."""
        return self.summary["status"]

    def __repr__(self):
        s = self.summary
        return (f"RunResult({s['integrator']} on {s['problem']}: {s['status']}, {s['steps']} steps, "
                f"{len(self.t)} samples)")


def run(problem, integrator, dt, t_end, **kwargs):
    """Runs `integrator` (a name) on `problem` (a name, or a Problem already built) from t = 0 to t_end.

    Keyword arguments: the run options sample_every (record every k-th step, and the first and
    last; default 1), max_force_evaluations (a work budget, 0: none) and states (record u and v,
    default True); every other one is a parameter of the problem or the integrator, as `--set` on
    the command line ("problem.key" or "integrator.key" where both declare key). The C++ steps run
    without the GIL. Returns a RunResult; a diverged run returns too, with summary["status"] and
    summary["message"] saying why. ValueError for bad input.
    """
    return RunResult(*_nsbench._run(problem, integrator, dt, t_end, **kwargs))


class Integrator:
    """Base class of an integrator written in Python; register it with register_integrator.

    The contract is the C++ one (integrators/integrator.hpp):
      __init__(self, params)  params: the validated parameters (a dict, declared at registration).
      init(self, problem, initial)  calls self.bind(problem, initial) first (stores the problem,
                  the state, self.mass, sizes the impulses); raises ValueError to decline a
                  problem it cannot run (shown as n/a in the studies).
      step(self, dt)  advances self.state by one step: u and v updated in place
                  (self.state.u[:] = ..., or assign self.state.u = array); adds the F_int
                  evaluations made to self.work.force_evaluations; fills self.impulses (one Lambda_i >= 0 per
                  contact, 0 on an open one) every step. Returns the step taken (a float) or a
                  StepInfo. nsbench then advances self.state.t by the step taken and adds 1 to
                  self.work.steps (Integrator::step, as for every integrator). An exception, or a
                  non-finite state or step, ends the run as diverged with its message.
      energy(self)  optional: (kinetic, potential) of the scheme's own balance.
    Class attributes: conditionally_stable (explicit scheme), treats_friction (fills
    self.tangential_impulses; otherwise problems with mu > 0 are declined),
    treats_friction_cone (3D contacts with friction, problem.contacts["cone"]: also fills
    self.tangential_impulses2, along T2; otherwise such problems are declined) and
    treats_moving_contacts (reads the contacts through problem.evaluate_contacts(u) where
    problem.contacts_move; otherwise such problems are declined) are read when the class is
    registered (its capabilities, integrators/capabilities.hpp); impact_lag_steps and
    restitution_exact (integrators/integrator.hpp, ImpactAccuracy).
    self.state.u, .v, self.impulses are views of the C++ integrator's own vectors: no copy.
    """

    conditionally_stable = False
    treats_friction = False
    treats_friction_cone = False
    treats_moving_contacts = False
    impact_lag_steps = 2.0
    restitution_exact = True

    def __init__(self, params):
        self.params = params

    def init(self, problem, initial):
        raise NotImplementedError(f"{type(self).__name__}.init")

    def step(self, dt):
        raise NotImplementedError(f"{type(self).__name__}.step")

    def bind(self, problem, initial):
        """The common part of init (Integrator::bind): checks the contacts, stores problem and state."""
        self._core.bind(problem, initial)
        self.mass = self._core.mass

    @property
    def problem(self):
        return self._core.problem

    @property
    def state(self):
        return self._core.state

    @property
    def impulses(self):
        return self._core.impulses

    @property
    def tangential_impulses(self):
        return self._core.tangential_impulses

    @property
    def tangential_impulses2(self):
        return self._core.tangential_impulses2

    @property
    def work(self):
        return self._core.work


def register_integrator(name, cls, description=None, parameters=(), reference=False):
    """Registers `cls` (a subclass of Integrator) as the integrator `name`, through the registry
    plugins use: it then runs in run(), in study files (run_study), in check() and in
    `integrators()`, its rows marked "(python)" in the studies' tables. parameters: a list of
    Parameter.real/integer/choice declarations (the ranges are checked before __init__ runs).
    ValueError when the name is taken.
    """
    if not (isinstance(cls, type) and issubclass(cls, Integrator)):
        raise TypeError(f"register_integrator '{name}': {cls!r} is not a subclass of nsbench.Integrator")
    if description is None:
        description = (cls.__doc__ or name).strip().splitlines()[0]
    _nsbench._register_integrator(name, cls, description, list(parameters), reference)
