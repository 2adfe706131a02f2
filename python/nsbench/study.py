"""Studies written in Python on the C++ engine: cases declared as data, run in the C++ case pool
without the GIL, measured in NumPy or with the measures library, written as the suite's tables.

    from nsbench import study
    cases = [study.case("bouncing-bar", "cd-lagrange", cfl=0.9, t_end=2.0, N=n) for n in (50, 100, 200)]
    results = study.run(cases)                      # in parallel (NSBENCH_JOBS), no GIL
    r = results[0]; r.status, r.t, r.series["total_energy"], r.summary["steps"]

A study that writes a report is a Study: its cases (a function of `full`) and its tables (a
function of the results and `full`, returning study.Table objects); Study.main() gives it the
command line of nsbench-study (--out, --full, --jobs, --shard I/N, --merge, --verify DIR, --rtol,
--atol, --plugin), through the same driver (studies/driver.hpp): the same report directory,
index, shards and verification as a built-in study.

A case (studies/case_run.hpp) runs as `nsbench run` does, its numbers the command line's bit for
bit: an integrator that declines the problem gives status "n/a" with its reason, a diverged run
status "diverged" with its message; neither stops the others.
"""
import argparse
import base64
import json
import os
import sys

import numpy as np

from . import _nsbench
from ._nsbench import (Column, Figure, Table, above_round_off, compared_impacts, contact_phases, drift_rule, fit_line, fit_order,
                       hausdorff, observed_order, ranking_table, run_measures, to_csv, to_latex, to_markdown,
                       verify_table)

__all__ = ["Column", "Figure", "Result", "Study", "Table", "above_round_off", "case", "compared_impacts",
           "contact_phases", "drift_rule", "fit_line", "fit_order", "hausdorff", "observed_order", "ranking_table", "run", "run_measures", "to_csv", "to_latex",
           "to_markdown", "verify_table"]

_RUN_KEYS = ("dt", "cfl", "sample_every", "states", "series", "cpu_repeats", "max_force_evaluations")


def case(problem, integrator, *, t_end, dt=None, cfl=None, sample_every=1, states=False, series=None, cpu_repeats=0,
         max_force_evaluations=0, observe=None, measures=None, reference=None, labels=None, **parameters):
    """A case: `integrator` on `problem` (names) to t_end, at step dt or at cfl times the problem's
    stable step. Keyword arguments other than the run options are the problem's and the
    integrator's parameters, as in nsbench.run ("problem.key" or "integrator.key" where both
    declare key). states: True records u, v and the impulses at the samples, a list of some of
    "u", "v", "impulses", "tangential_impulses", "tangential_impulses2" those only; series: a list
    of the series' columns to keep (default: all), e.g. ["t", "total_energy"] (what a long run
    hands to Python is then that much smaller). observe: a list of dicts {"kind": K, ...its parameters} of the run measures
    (study.run_measures(): "mesh-momentum", "momentum-balance", ...), each fed after every step;
    their figures are Result.observed, in order (no series). measures: a list of dicts, each a [[measure]] table of the study-file language
    (docs/study_files.md: kind = "error", "impact-time", "energy", "momentum", "hausdorff", ...),
    and reference: its [reference] table; the run's Result then holds each measure's value
    (Result.values, in order; Result.measure(label)) and no series. labels: a dict of the study's
    own (JSON) values, kept with the case. Returns the case as a dict (JSON), checked when it runs."""
    c = {"problem": problem, "integrator": integrator, "t_end": t_end, "set": _nsbench._assignments(parameters)}
    for key, value in (("dt", dt), ("cfl", cfl)):
        if value is not None:
            c[key] = value
    if sample_every != 1:
        c["sample_every"] = sample_every
    if states:
        c["states"] = True if states is True else list(states)
    if series is not None:
        c["series"] = list(series)
    if cpu_repeats:
        c["cpu_repeats"] = cpu_repeats
    if max_force_evaluations:
        c["max_force_evaluations"] = max_force_evaluations
    if observe is not None:
        c["observe"] = [dict(o) for o in observe]
    if measures is not None:
        c["measures"] = [dict(m) for m in measures]
    if reference is not None:
        c["reference"] = dict(reference)
    if labels:
        c["labels"] = dict(labels)
    return c


def _array(values):
    """A result's array: packed ({"shape", "float64": base64 of the doubles}, studies/case_run.cpp)
    or a list (None, a value that was not finite, reads NaN)."""
    if isinstance(values, dict):
        return np.frombuffer(base64.b64decode(values["float64"]), dtype="<f8").reshape(values["shape"]).copy()
    return np.array(values, dtype=float)


def _rows(values, samples):
    if isinstance(values, dict):
        return _array(values)
    width = len(values[0]) if values else 0
    return np.array(values, dtype=float).reshape(samples, width)


class Result:
    """A case's result: case (the dict), status ('ok', 'diverged', 'over budget', 'n/a'), message,
    dt (the step taken), steps, summary (the run's summary.json as a dict; empty for n/a), series
    (column name -> 1-D array, as series.csv: t, dt, kinetic, potential, total_energy, min_gap,
    impulse, ... then the problem's observables; every column also an attribute), and with
    states=True state_t, u, v (samples x ndof) and the impulses of the step ending at each sample,
    impulses, tangential_impulses, tangential_impulses2 (samples x contacts), those named where
    states is a list; with measures,
    values (one per measure, in order; measure(label)) and run_figures (the engine's figures of the
    run: contact phases, smallest and largest step, ...) instead of the series; cpu and cpu_spread with cpu_repeats. A value
    that was not finite (NaN, an overflow) reads NaN."""

    def __init__(self, the_case, data):
        self.case = the_case
        self.status = data["status"]
        self.message = data.get("message", "")
        self.dt = data.get("dt", np.nan)
        self.steps = data.get("steps", 0)
        self.summary = data.get("summary", {})
        self.columns = data.get("columns", [])
        self.series = {name: _array(values) for name, values in zip(self.columns, data.get("series", []))}
        if "state_t" in data:
            self.state_t = _array(data["state_t"])
            for key in ("u", "v", "impulses", "tangential_impulses", "tangential_impulses2"):
                if key in data:
                    setattr(self, key, _rows(data[key], len(self.state_t)))
        self.values = _array(data.get("values", []))
        self.observed = data.get("observed", [])
        self.run_figures = data.get("run", {})
        self.cpu = np.nan if data.get("cpu") is None else data["cpu"]
        self.cpu_spread = np.nan if data.get("cpu_spread") is None else data["cpu_spread"]

    def measure(self, label):
        """The value of the case's measure of that label (its "label" key, else its "kind"); NaN
        where it was not measured (a declined or diverged run)."""
        labels = [m.get("label", m.get("kind")) for m in self.case.get("measures", [])]
        if label not in labels:
            raise KeyError(f"no measure '{label}' (measures: {', '.join(map(str, labels))})")
        return self.values[labels.index(label)] if len(self.values) else np.nan

    @property
    def ok(self):
        return self.status == "ok"

    def __getattr__(self, name):
        series = self.__dict__.get("series", {})
        if name in series:
            return series[name]
        raise AttributeError(f"Result has no attribute or column '{name}' (columns: {', '.join(series)})")

    def __repr__(self):
        c = self.case
        return f"Result({c['integrator']} on {c['problem']}: {self.status}, {self.steps} steps)"


def run(cases, label="nsbench.study.run"):
    """Runs the cases (study.case dicts) in the C++ case pool, NSBENCH_JOBS at a time (default: the
    cores), without the GIL (an integrator written in Python takes it for its own steps, so such
    cases run one at a time); returns their Results in the cases' order. ValueError naming the
    key for a bad case."""
    cases = list(cases)
    texts = _nsbench._run_cases([json.dumps(c) for c in cases], label)
    return [Result(c, json.loads(t)) for c, t in zip(cases, texts)]


class Study:
    """A study that writes a report: name, description, cases(full) -> list of case dicts,
    tables(results, full) -> list of Table; source: the file that defines it (for the index)."""

    def __init__(self, name, description, cases, tables, source=None):
        self.name, self.description = name, description
        self._cases, self._tables = cases, tables
        if source is None:
            source = os.path.relpath(sys.argv[0]) if sys.argv and sys.argv[0] else name
        self.source = source

    def cases(self, full=False):
        return list(self._cases(full))

    def tables(self, results, full=False):
        return list(self._tables(results, full))

    def main(self, argv=None):
        """nsbench-study's options for this study; returns the exit status (0; 1 when --verify
        found differences; 2 for bad input, its one-line message on stderr)."""
        argv = sys.argv[1:] if argv is None else list(argv)
        args = _parser(self).parse_args(argv)
        try:
            if args.jobs is not None:
                os.environ["NSBENCH_JOBS"] = str(args.jobs)
            for plugin in args.plugin:
                _nsbench.load_plugin(plugin)
            return _nsbench._drive_study(
                self.name, self.description, self.source, lambda full: [json.dumps(c) for c in self.cases(full)],
                lambda cases, results, full: self.tables(_results(cases, results), full),
                _command(argv), args.out, args.full, args.shard or "", args.merge,
                args.verify or "", args.rtol, args.atol)
        except ValueError as e:
            print(f"{self.name}: error: {e}", file=sys.stderr)
            return 2


def _results(cases, texts):
    """The Results of the driver's JSON texts, each text dropped once read (a long study's texts
    are the bulk of what it holds)."""
    results = []
    for k, (c, text) in enumerate(zip(cases, texts)):
        results.append(Result(json.loads(c), json.loads(text)))
        texts[k] = None
    return results


def _command(argv):
    """The command the report's footer names: nsbench-study's when it runs this study (it sets
    NSBENCH_STUDY_COMMAND), else this script's."""
    given = os.environ.get("NSBENCH_STUDY_COMMAND")
    if given:
        return given.split(" ")
    return [sys.argv[0] if sys.argv and sys.argv[0] != "-c" else "python3"] + argv


def _parser(s):
    ap = argparse.ArgumentParser(prog=s.name, description=s.description)
    ap.add_argument("--out", default="reports", help="output directory (default reports)")
    ap.add_argument("--full", action="store_true", help="run the long sweeps")
    ap.add_argument("--jobs", type=int, help="cases run at once (NSBENCH_JOBS; default: the cores)")
    ap.add_argument("--shard", help="run only shard I of N of the cases (job arrays), e.g. 3/8")
    ap.add_argument("--merge", action="store_true", help="merge the shards' results in OUT/shards and write the report")
    ap.add_argument("--verify", help="recompute and compare with the report in this directory; writes nothing")
    ap.add_argument("--rtol", type=float, default=1e-9, help="--verify: relative tolerance on reals (default 1e-9)")
    ap.add_argument("--atol", type=float, default=0.0, help="--verify: absolute tolerance on reals (default 0)")
    ap.add_argument("--plugin", action="append", default=[], help="load integrators/problems from a plugin (repeatable)")
    return ap
