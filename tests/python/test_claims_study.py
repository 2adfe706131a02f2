"""The claims study's rules (studies/builtin/claims.py) on synthetic data both sides of their
thresholds, and its as-claimed runs checked against the problems' parameters."""
import importlib.util
import math
import pathlib

import numpy as np

from nsbench import study

ROOT = pathlib.Path(__file__).resolve().parents[2]
spec = importlib.util.spec_from_file_location("claims", ROOT / "studies" / "builtin" / "claims.py")
claims = importlib.util.module_from_spec(spec)
spec.loader.exec_module(claims)

WINDOWS = np.arange(1.0, 51.0)  # 50 windows, as the bar's 50 periods


def growth_of(envelope, round_off=1e-9):
    return claims.grows(study.drift_rule(list(WINDOWS), list(envelope), round_off), round_off)


def test_a_linear_drift_grows_and_a_bounded_or_falling_envelope_does_not():
    rng = np.random.default_rng(1)  # fixed: the same numbers on every machine
    noise = 0.01 * rng.standard_normal(WINDOWS.size)
    assert growth_of(0.1 + 1e-3 * WINDOWS + noise)                       # a drift of 1e-3 per window
    assert not growth_of(0.1 + 0.05 * np.sin(WINDOWS) + noise)           # bounded, oscillating
    assert not growth_of(0.2 * np.exp(-WINDOWS / 10) + 0.05 + noise)     # falling (a transient dying out)
    assert not growth_of(1e-12 * WINDOWS, round_off=1e-9)                # exactly linear, within round-off


def test_the_penetration_and_convergence_thresholds_sit_between_their_two_cases():
    assert 1.0 < claims.GROWTH_FACTOR < 10.0  # bounded (1) and linear growth over 10x the time (10)
    h = [2.0 ** -k for k in range(6)]
    late_jump = study.fit_order(h, h)                     # a jump a step late: distance ~ dt, order 1
    stuck = study.fit_order(h, [0.3 + 1e-3 * x for x in h])  # a distance that does not fall
    assert late_jump["order"] >= claims.MIN_ORDER and late_jump["low"] > 0
    assert not (stuck["order"] >= claims.MIN_ORDER and stuck["low"] > 0)


def test_every_as_claimed_run_is_under_the_talks_conditions():
    cases = claims.cases(False)
    as_claimed = [c for c in cases if c["labels"]["conditions"] == "as claimed"]
    assert as_claimed and all(claims.as_claimed_violation(c) == "" for c in as_claimed)
    assert {c["labels"]["claim"] for c in as_claimed} == {"work", "hausdorff", "momentum", "energy", "adaptive", "long"}


def test_a_run_outside_the_talks_conditions_is_named():
    bar = study.case("bouncing-bar", "cd-lagrange", cfl=0.9, t_end=1.0, N=25, mass="singular")
    assert "mass = singular" in claims.as_claimed_violation(bar)
    bouncy = study.case("bouncing-bar", "cd-lagrange", cfl=0.9, t_end=1.0, N=25, mass="lumped", e=0.5)
    assert "e = 0.5" in claims.as_claimed_violation(bouncy)
    rigid = study.case("bouncing-mass", "cd-lagrange", dt=1e-3, t_end=1.0)
    assert "not a deformable body" in claims.as_claimed_violation(rigid)


def test_the_bars_exact_period_is_its_contact_plus_its_flight():
    t1, tb = claims.bar_times(mass="lumped")
    assert math.isclose(t1, 1.0) and math.isclose(tb, 2 * 10 / 30 + 2 * 10 / 10)


def test_a_verdict_counts_its_conditions():
    assert claims.verdict([True, True]) == "holds"
    assert claims.verdict([True, False]) == "holds on 1 of 2"
    assert claims.verdict([False]) == "fails"
