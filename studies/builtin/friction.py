"""Study "friction": every integrator on the Coulomb friction problems (docs/method.md section 6);
the schemes that do not treat friction decline the problem and get one n/a row per table, with
their reason.

    nsbench-study friction --out reports        (or: python3 studies/builtin/friction.py --out reports)

Cases (CASES, one line of data each), each run at its steps:
- sliding mass, alpha = 30 deg, v0 = 2 m/s down the slope: mu = 0.8 (stops at t_s and sticks,
  tan alpha < mu) and mu = 0.3 (slides on for ever); steps 1e-2, 1e-3, 1e-4 (--full: and
  1e-5), to t = 2 s.
- rolling disk on the floor: h0 = 0, v0 = 1, omega0 = 0, mu = 0.3, kappa = 1/2; same steps, to
  t = 0.5 s (rolling from t* = 0.113 s on).
- block-2d at its defaults (8 x 4 Q4) with mu = 0.5 and vx = 1 (it lands sliding), dt = 1e-4
  (--full: and 5e-5), to t = 0.3 s: the momentum identities.
- hard cases, dt = 1e-3: sticking below the friction angle for 10^5 steps, mu = tan alpha, a
  sliding reversal, mu = 10, a disk dropped with spin at e = 0 and e = 0.5.

Measures, all from one run per case with its states and impulses at every step (the problem's
observables by name: x, v, v_exact, px; the slip u_T = T v - w of the contacts' rows):
- stop time (as studies/slip_stop.hpp, the study files' stop-time and onset-time measures): the
  first step at which |u_T| <= SLIP_TOL after which it stays so (rest, or rolling for the disk);
  where the exact solution does not stay at rest (the reversal), the first step at which u_T has
  lost its initial sign. Against the exact solution's slip_stop (sliding mass) or roll_onset.
- stop distance: the contact point's tangential path sum |T (U_{k+1} - U_k)| up to the stop time,
  against the exact stop_distance.
- max |v - v_exact| over the steps; the final speed error at t_end; the speed just after the
  first impact (end of the first step with a normal impulse) against first_rebound_speed.
- energy gain: max over steps of (E_{k+1} - E_k) / E scale, E the integrator's own energy,
  E scale = |E0| (m g (1 m) when E0 = 0): no case has an energy source.
- creep, where the exact solution rests for the whole run: |x(t_end) - x(0)| / t_end, and the
  same over the second half of the run (a sustained creep, not a start-up step).
- block: max over steps of |P_x,k - P_x,0 - sum_{j<=k} sum_i Lambda_T,i| / sum m |v0|, and over
  the steps where every closed contact slides the same way s, max |Delta P_x + s sum mu
  Lambda_N| / sum m |v0| (Coulomb: a sliding contact's impulse is -s mu Lambda_N).
Orders: log-log slope between consecutive steps. Each run has a budget of STEP_BUDGET F_int
evaluations per step (an adaptive scheme whose step collapses stops, "over budget").
Trajectory (table and figure friction_disk_trajectory): the disk's slip after every step at
dt = TRAJECTORY_STEP, each scheme in its panel over the exact s(t). Ranking: the cheapest
integrator reaching a stop-time error (sliding mass, mu = 0.8) and a rolling-onset error (disk) of
1e-2, 1e-3 and 1e-4 s, cost the median CPU time of 3 unobserved runs.

This study was studies/friction.cpp; its tables verify against that study's report at --rtol 0.
The sums below are formed in the C++ code's order (eigen_sum, np.cumsum), so the round-off
residuals are the same bits.
"""
import functools
import math
from collections import namedtuple

import numpy as np

import nsbench
from nsbench import study

STEP_BUDGET = 20  # F_int evaluations allowed per step of the requested size
HARD_STEP = 1e-3
RANKING_TARGETS = [1e-2, 1e-3, 1e-4]  # [s]
TRAJECTORY_CASE, TRAJECTORY_STEP, EXACT_SAMPLES = "disk", 1e-2, 500  # the coarsest step tells schemes apart
SLIP_TOL = 1e-9  # [m/s]: at rest or rolling (studies/slip_stop.hpp, kSlipTol)
STEPS, FULL_STEPS = [1e-2, 1e-3, 1e-4], [1e-2, 1e-3, 1e-4, 1e-5]
TAN30 = "0.57735026918962573"  # tan(30 deg) to the last digit: the sliding mass's own tan alpha

Case = namedtuple("Case", "id group label problem params steps full_steps t_end ranked")
CASES = [
    Case("slide-stop", "sliding", "alpha 30, mu 0.8, v0 2: stops, sticks", "sliding-mass",
         {"alpha": "30", "mu": "0.8", "v0": "2"}, STEPS, FULL_STEPS, 2.0, True),
    Case("slide-on", "sliding", "alpha 30, mu 0.3, v0 2: slides on", "sliding-mass",
         {"alpha": "30", "mu": "0.3", "v0": "2"}, STEPS, FULL_STEPS, 2.0, False),
    Case("disk", "disk", "h0 0, v0 1, omega0 0, mu 0.3, kappa 1/2", "rolling-disk",
         {"h0": "0", "v0": "1", "omega0": "0", "mu": "0.3", "kappa": "0.5"}, STEPS, FULL_STEPS, 0.5, True),
    Case("block", "block", "block-2d 8x4, mu 0.5, vx 1", "block-2d", {"mu": "0.5", "vx": "1"}, [1e-4], [1e-4, 5e-5], 0.3,
         False),
    Case("stick", "hard", "stick below the friction angle (alpha 20, mu 0.5, v0 0), 10^5 steps", "sliding-mass",
         {"alpha": "20", "mu": "0.5", "v0": "0"}, [HARD_STEP], [HARD_STEP], 1e5 * HARD_STEP, False),
    Case("tan-alpha", "hard", "mu = tan alpha (alpha 30, v0 1): slides at v0", "sliding-mass",
         {"alpha": "30", "mu": TAN30, "v0": "1"}, [HARD_STEP], [HARD_STEP], 2.0, False),
    Case("reversal", "hard", "reversal (alpha 30, mu 0.3, v0 -2 up the slope): stops, slides down", "sliding-mass",
         {"alpha": "30", "mu": "0.3", "v0": "-2"}, [HARD_STEP], [HARD_STEP], 2.0, False),
    Case("mu-10", "hard", "mu 10 (alpha 30, v0 2)", "sliding-mass", {"alpha": "30", "mu": "10", "v0": "2"},
         [HARD_STEP], [HARD_STEP], 2.0, False),
    Case("drop-e0", "hard", "disk dropped with spin (h0 0.1, omega0 20, v0 0), e 0", "rolling-disk",
         {"h0": "0.1", "omega0": "20", "v0": "0", "e": "0"}, [HARD_STEP], [HARD_STEP], 1.0, False),
    Case("drop-e05", "hard", "disk dropped with spin (h0 0.1, omega0 20, v0 0), e 0.5", "rolling-disk",
         {"h0": "0.1", "omega0": "20", "v0": "0", "e": "0.5"}, [HARD_STEP], [HARD_STEP], 1.0, False),
]
BY_ID = {c.id: c for c in CASES}


def text(x):
    """A number as the C++ tables' "{}" writes it: the shortest text that reads back, 2 not 2.0."""
    s = repr(float(x))
    return s[:-2] if s.endswith(".0") else s


def cases(full):
    out = []
    for entry in nsbench.integrators():
        for fc in CASES:
            # What the measures read, no more (a run of 10^5 steps hands each of its numbers to Python):
            # u for the stop distance, reported for the sliding group only; Lambda_T for the P_x balance.
            observables = problem_of(fc.id).observables
            series = ["t", "total_energy"] + [name for name in ("x", "v", "v_exact", "px") if name in observables]
            states = ["v", "impulses"] + (["u"] if fc.group == "sliding" else []) + (
                ["tangential_impulses"] if "px" in observables else [])
            for dt in fc.full_steps if full else fc.steps:
                params = {f"problem.{k}": v for k, v in fc.params.items()}
                out.append(study.case(fc.problem, entry["name"], dt=dt, t_end=fc.t_end, states=states, series=series,
                                      max_force_evaluations=STEP_BUDGET * math.ceil(fc.t_end / dt),
                                      cpu_repeats=3 if fc.ranked else 0, labels={"case": fc.id}, **params))
    return out


@functools.cache
def problem_of(case_id):
    """The case's problem, built once (its contacts, exact solution and captions' numbers)."""
    fc = BY_ID[case_id]
    return nsbench.Problem(fc.problem, **fc.params)


def exact_stop(p):
    """studies/slip_stop.cpp's exact_stop: (stop time, stop distance, stays, never stops); NaN where
    the solution does not time it (a disk's onset that equals a rest time > 0 may follow a bounce)."""
    finite = lambda x: x if x is not None and math.isfinite(x) else math.nan
    stop = p.exact_event("slip_stop")
    if stop is not None:
        return finite(stop), finite(p.exact_value("stop_distance")), p.exact_value("stays_stopped") == 1.0, math.isinf(stop)
    onset, rest = p.exact_event("roll_onset"), p.exact_event("rest")
    if onset is not None and rest is not None:
        return finite(onset) if onset > rest or rest == 0.0 else math.nan, math.nan, True, math.isinf(onset)
    return math.nan, math.nan, True, False


def eigen_sum(x):
    """Eigen's Vec::sum() of each row of x, in its order (SSE2, packets of 2: two packet accumulators
    over blocks of 4, their sum, a last packet, the packet's two halves, then the scalar tail)."""
    n = x.shape[1]
    if n < 2:
        return x[:, 0].copy() if n else np.zeros(len(x))
    aligned, aligned2 = n // 2 * 2, n // 4 * 4
    p0 = x[:, 0:2].copy()
    if aligned > 2:
        p1 = x[:, 2:4].copy()
        for i in range(4, aligned2, 4):
            p0, p1 = p0 + x[:, i:i + 2], p1 + x[:, i + 2:i + 4]
        p0 = p0 + p1
        if aligned > aligned2:
            p0 = p0 + x[:, aligned2:aligned2 + 2]
    s = p0[:, 0] + p0[:, 1]
    for i in range(aligned, n):
        s = s + x[:, i]
    return s


def slip_stop(p, r, stays):
    """studies/slip_stop.hpp on the run's states: (the stop time, the path up to it), each step's slip."""
    c = p.contacts
    slip = (c["T"] @ r.v.T).T - c["w"]
    if hasattr(r, "u"):
        path = np.concatenate([[0.0], np.cumsum(np.abs((c["T"] @ np.diff(r.u, axis=0).T)[0]))])
    else:
        path = np.full(len(r.state_t), math.nan)  # not recorded: no table reports the distance
    t = r.state_t
    at_rest0 = np.max(np.abs(slip[0])) <= SLIP_TOL
    if stays:
        moving = np.flatnonzero(np.max(np.abs(slip[1:]), axis=1) > SLIP_TOL) + 1
        k = moving[-1] + 1 if len(moving) else (0 if at_rest0 else 1)
    else:
        sign0 = float(np.sign(slip[0, 0]))
        stopped = np.flatnonzero(sign0 * slip[1:, 0] <= SLIP_TOL) + 1
        k = 0 if at_rest0 else (stopped[0] if len(stopped) else len(t))
    return (t[k], path[k]) if k < len(t) else (math.nan, math.nan), slip


def observable(r, name):
    return r.series[name] if name in r.series else np.full(len(r.series["t"]), math.nan)


def energy_gain(p, r):
    """The largest step increase of the scheme's energy over E scale, and the end of that step."""
    E = r.series["total_energy"]
    scale = abs(E[0]) if E[0] != 0.0 else p.parameters["m"] * p.parameters["g"] * 1.0
    gains = np.nan_to_num((E[1:] - E[:-1]) / scale, nan=-math.inf)
    k = int(np.argmax(gains))
    return (gains[k], r.series["t"][k + 1]) if gains[k] > 0.0 else (0.0, math.nan)


def momentum_identities(p, r, slip):
    """The block's P_x balance with the tangential impulses and, on the steps where every closed
    contact slides the same way s, Delta P_x + s sum mu Lambda_N; relative to sum m |v0|."""
    m = p.mass_matrix().diagonal()
    p_scale = eigen_sum((m * np.abs(p.initial_state().v))[None, :])[0]
    px, normal, mu = r.series["px"], r.impulses, p.contacts["mu"]
    px_residual = np.max(np.abs(px[1:] - px[0] - np.cumsum(eigen_sum(r.tangential_impulses[1:]))) / p_scale)
    # Per step (row) from 1 on: each closed contact's way, 2 where it does not slide; a step counts
    # when its closed contacts share one way +-1. sum mu Lambda_N over them in the contacts' order.
    closed = normal[1:] > 0.0
    ways = np.where(np.abs(slip[1:]) <= SLIP_TOL, 2, np.where(slip[1:] > 0.0, 1, -1))
    lowest, highest = np.where(closed, ways, 3).min(axis=1), np.where(closed, ways, -3).max(axis=1)
    sliding = closed.any(axis=1) & (lowest == highest) & (lowest != 2)
    mu_normal = np.cumsum(np.where(closed, mu * normal[1:], 0.0), axis=1)[:, -1]
    residuals = np.abs(px[1:] - px[:-1] + lowest * mu_normal)[sliding] / p_scale
    slide_steps = int(sliding.sum())
    return px_residual, slide_steps, float(np.max(residuals, initial=0.0)) if slide_steps else math.nan


def measure(fc, r):
    """Every measure of an ok run, by key (math.nan: does not apply)."""
    p = problem_of(fc.id)
    t_exact, d_exact, stays, never_stops = exact_stop(p)
    (t_stop, d_stop), slip = slip_stop(p, r, stays)
    x, v, v_exact, t = observable(r, "x"), observable(r, "v"), observable(r, "v_exact"), r.series["t"]
    impacts = np.flatnonzero(np.max(r.impulses[1:], axis=1, initial=0.0) > 0.0) + 1
    v_impact = v[impacts[0]] if len(impacts) else math.nan
    rebound = p.exact_value("first_rebound_speed")
    half = np.flatnonzero(t[1:] >= 0.5 * fc.t_end)[0] + 1
    rests = t_exact == 0.0 and stays
    m = {"t_stop": t_stop, "never_stops": never_stops, "t_stop_err": abs(t_stop - t_exact), "d_stop_err": abs(d_stop - d_exact),
         "v_err": np.fmax.reduce(np.abs(v[1:] - v_exact[1:])), "v_final_err": abs(v[-1] - v_exact[-1]),
         "v_impact_err": abs(v_impact - (math.nan if rebound is None else rebound)),
         "creep": abs(x[-1] - x[0]) / t[-1] if rests else math.nan,
         "late_creep": abs(x[-1] - x[half]) / (t[-1] - t[half]) if rests else math.nan, "slip": slip[:, 0]}
    m["energy_gain"], m["energy_gain_t"] = energy_gain(p, r)
    if "px" in r.series:
        m["px_residual"], m["slide_steps"], m["slide_residual"] = momentum_identities(p, r, slip)
    return m


def number(x):
    return None if x is None or not np.isfinite(x) else float(x)


def column(name, unit="", fmt="", description="", timing=False):
    return study.Column(name, unit=unit, format=fmt, description=description, timing=timing)


def group_columns(own):
    """Every group table's columns: integrator, case, dt, the group's own, then the run's largest
    energy gain and when, steps, CPU time and the note."""
    return ([column("integrator"), column("case"), column("dt", "s", "{:.0e}", "step")] + own +
            [column("max E gain", "", "{:.1e}", "max over steps of (E_{k+1} - E_k) / E scale"),
             column("at t", "s", "{:.4g}", "end of the step of the largest gain"), column("steps"),
             column("CPU", "s", "{:.2e}", "thread CPU time of the stepping of the observed run (observer excluded)", True),
             column("note", "", "", "why a run is n/a, diverged or over budget, or a stop where the exact solution has none")])


def note(r, m):
    if not r.ok:
        return f"{r.status}: {r.message}"
    if m["never_stops"] and np.isfinite(m["t_stop"]):
        return f"stops at {m['t_stop']:.4g} s; the exact solution never does"
    return ""


def add_group_rows(t, group, runs, own):
    """One row per run of the group, integrator by integrator (studies/study.cpp, add_integrator_rows):
    one n/a row with the reason for an integrator that declines them all. own(run, previous) gives
    the group's cells, previous the run of the same case at the previous step (or None)."""
    for name in dict.fromkeys(run.r.case["integrator"] for run in runs):
        mine = [run for run in runs if run.r.case["integrator"] == name and run.fc.group == group]
        if mine and all(run.r.status == "n/a" for run in mine):
            t.add_row([name, "n/a"] + [None] * (len(t.columns) - 3) + [mine[0].r.message])
            continue
        for j, run in enumerate(mine):
            previous = mine[j - 1] if j > 0 and mine[j - 1].fc.id == run.fc.id else None
            m = run.m
            t.add_row([name, run.fc.label, run.r.case["dt"]] + own(run, previous) +
                      [number(m.get("energy_gain")), number(m.get("energy_gain_t")), run.r.steps,
                       run.r.summary.get("step_cpu_seconds"), note(run.r, m)])


def convergence_table(tid, title, caption, group, measures, runs):
    """A convergence group's table: each measure (key, its column) and its order."""
    t = study.Table(tid, title=title, caption=caption)
    own = []
    for _, col in measures:
        own += [col, column("order", "", "{:#.2g}", f"log-log slope of {col.name} against the previous dt")]
    t.columns = group_columns(own)

    def cells(run, previous):
        out = []
        for key, _ in measures:
            e = run.m.get(key, math.nan)
            out.append(number(e))
            out.append(None if previous is None else number(study.observed_order(
                previous.r.case["dt"], study.above_round_off(previous.m.get(key, math.nan)), run.r.case["dt"],
                study.above_round_off(e))))
        return out
    add_group_rows(t, group, runs, cells)
    return t


STOP_RULE = (f"t_stop: the first step at which |u_T| <= {text(SLIP_TOL)} m/s (u_T = T v - w, the slip) and after which "
             "it stays so; for a mass that does not stay (the reversal) the first step at which u_T has lost its initial sign")
ENERGY_RULE = ("max E gain: max over steps of (E_{k+1} - E_k) / E scale, E the integrator's own energy (CD-Lagrange: its "
               "discrete energy), E scale = |E0| (m g (1 m) when E0 = 0), 0 when it never increased; no case has an energy "
               "source")
ORDER_RULE = "Orders: log-log slope against the previous dt; errors below 1e-11 are round-off and carry none"
V_RULE = ("max |v - v_exact|: largest over the steps of the reported velocity (CD-Lagrange: v = M^-1 P_{k+3/2}, half a step "
          "ahead) against the exact one")


def sliding_table(runs):
    stopping = problem_of("slide-stop")
    caption = (f"m = 1 kg, g = 9.81 m/s^2, alpha = 30 deg, v0 = 2 m/s down the slope, to t = 2 s. Exact: while sliding "
               f"x'' = a1 = g (sin alpha - mu cos alpha), stop at t_s = -v0 / a1 after d_s = v0^2 / (2 |a1|) (mu = 0.8: t_s = "
               f"{stopping.exact_event('slip_stop'):.6f} s, d_s = {stopping.exact_value('stop_distance'):.6f} m, then sticks, "
               f"tan alpha < mu); mu = 0.3 never stops. {STOP_RULE}. d_stop: the contact's tangential path sum |T (U_k+1 - "
               f"U_k)| up to t_stop. {V_RULE}. {ENERGY_RULE}. {ORDER_RULE}. n/a: the scheme declines friction (its reason in "
               "the note), or the measure does not apply.")
    return convergence_table(
        "friction_sliding", "Sliding mass on a slope with Coulomb friction: stop time, stop distance, velocity", caption,
        "sliding", [("t_stop_err", column("t_stop err", "s", "{:.2e}", "|t_stop - t_s|")),
                    ("d_stop_err", column("d_stop err", "m", "{:.2e}", "|d_stop - d_s|")),
                    ("v_err", column("max |v - v_exact|", "m/s", "{:.2e}", "along the slope"))], runs)


def disk_table(runs):
    disk = problem_of("disk")
    caption = (f"m = 1 kg, R = 0.1 m, kappa = 1/2 (inertia kappa m R^2), g = 9.81 m/s^2, on the floor (h0 = 0) at v0 = 1 "
               f"m/s, omega0 = 0, mu = 0.3, restitution e = {text(disk.parameters['e'])} (the problem's default), to t = 0.5 s. "
               "Exact: the slip s = x' + R theta' falls at mu g (1 + 1/kappa) until t* = |s0| / (mu g (1 + 1/kappa)) = "
               f"{disk.exact_event('roll_onset'):.6f} s, then the disk rolls at v_f = (v0 - kappa R omega0) / (1 + kappa) = "
               f"{disk.exact_state(BY_ID['disk'].t_end).v[0]:.6f} m/s. t_roll: as t_stop of friction_sliding ({STOP_RULE}). "
               f"v_f err: |v - v_exact| at t = 0.5 s. {V_RULE}. {ENERGY_RULE}. {ORDER_RULE}.")
    return convergence_table(
        "friction_disk", "Rolling disk on the floor: rolling onset and final speed", caption, "disk",
        [("t_stop_err", column("t_roll err", "s", "{:.2e}", "|t_roll - t*|")),
         ("v_final_err", column("v_f err", "m/s", "{:.2e}", "|v(t_end) - v_f|")),
         ("v_err", column("max |v - v_exact|", "m/s", "{:.2e}", "centre velocity"))], runs)


def block_table(runs):
    t = study.Table("friction_block", title="2D block sliding on a floor with Coulomb friction: momentum identities, energy")
    t.caption = (
        "block-2d defaults (8 x 4 Q4, SVK, E = 1 MPa, tilted 15 deg, lowest corner 0.1 m up, falling at 1 m/s, e = 0) with "
        "mu = 0.5 and vx = 1 m/s, to t = 0.3 s. P_x res.: max over steps of |P_x,k - P_x,0 - sum_j<=k sum_i Lambda_T,i| / "
        "sum m |v0| (the T rows are +1 on the x dofs: round-off expected). Slide res.: over the steps where every closed "
        f"contact (Lambda_N > 0) slides the same way s (|u_T| > {text(SLIP_TOL)} m/s, u_T from the reported velocity), max "
        f"|Delta P_x + s mu sum Lambda_N| / sum m |v0| (round-off expected). {ENERGY_RULE}; E includes the elastic energy, "
        "which the schemes' discretisation changes with or without friction.")
    t.columns = group_columns([column("P_x res.", "", "{:.1e}", "P_x balance with the tangential impulses, relative"),
                               column("sliding steps", "", "", "steps where every closed contact slides the same way"),
                               column("slide res.", "", "{:.1e}", "Delta P_x + s mu sum Lambda_N on those steps, relative")])
    add_group_rows(t, "block", runs, lambda run, _: [number(run.m.get("px_residual")), run.m.get("slide_steps"),
                                                     number(run.m.get("slide_residual"))])
    return t


def hard_table(runs):
    t = study.Table("friction_hard", title="Hard friction cases")
    t.caption = (
        f"dt = {text(HARD_STEP)} s. Sliding mass (m = 1 kg, g = 9.81 m/s^2): sticking below the friction angle (tan 20 deg "
        "< 0.5) for 10^5 steps, creep = |x(t_end) - x(0)| / t_end and late creep = |x(t_end) - x(t_end / 2)| / (t_end / 2) "
        "(exact: 0); mu = tan alpha exactly (exact: v = v0 for ever); reversal (up the slope at 2 m/s, stops at t_s = 2 / "
        "(g (sin alpha + mu cos alpha)), slides down since tan alpha > mu); mu = 10 (stops at t_s = 2 / (g (mu cos alpha - "
        f"sin alpha))). {V_RULE}. Rolling disk (R = 0.1 m, kappa = 1/2, mu = 0.3) dropped from h0 = 0.1 m with spin omega0 "
        "= 20 rad/s: v after impact 1 err: the centre velocity at the end of the first step with a normal impulse against "
        "the exact impact law's (Newton on y', the sticking or the sliding Coulomb impulse); v_f err: |v - v_exact| at "
        "t_end (rolling at (v0 - kappa R omega0) / (1 + kappa) by then). t_stop err: as in friction_sliding (the disk: "
        "rolling onset; n/a at e = 0.5, where the slip ends in a bounce before the disk comes to lie on the floor, which "
        f"the exact solution does not time). {ENERGY_RULE}. n/a: the scheme declines friction (reason in the note) or the "
        "measure does not apply.")
    t.columns = group_columns([
        column("t_end", "s", "{}"), column("t_stop err", "s", "{:.2e}", "|t_stop - exact| (disk: rolling onset)"),
        column("creep", "m/s", "{:.2e}", "|x(t_end) - x(0)| / t_end where the exact mass rests throughout"),
        column("late creep", "m/s", "{:.2e}", "the same over the second half of the run: sustained, not a start-up step"),
        column("max |v - v_exact|", "m/s", "{:.2e}"), column("v after impact 1 err", "m/s", "{:.2e}"),
        column("v_f err", "m/s", "{:.2e}", "|v - v_exact| at t_end")])
    keys = ("t_stop_err", "creep", "late_creep", "v_err", "v_impact_err", "v_final_err")
    add_group_rows(t, "hard", runs, lambda run, _: [run.fc.t_end] + [number(run.m.get(k)) for k in keys])
    return t


def ranking(runs):
    """The cheapest integrator at each stop-time and rolling-onset error (ranked cases)."""
    registry = {e["name"]: e for e in nsbench.integrators()}
    problems = []
    for fc in (c for c in CASES if c.ranked):
        curves = []
        for name in dict.fromkeys(run.r.case["integrator"] for run in runs):
            points = [{"run": f"dt = {run.r.case['dt']:.0e}", "cost": number(run.r.cpu) if run.r.ok else None,
                       "error": number(run.m.get("t_stop_err")), "spread": number(run.r.cpu_spread) if run.r.ok else None}
                      for run in runs if run.r.case["integrator"] == name and run.fc.id == fc.id and run.r.status != "n/a"]
            curves.append({"integrator": name, "reference": registry[name]["reference"], "peer": registry[name]["peer"],
                           "points": points})
        what = "rolling onset" if fc.group == "disk" else "stop time"
        problems.append({"label": f"{fc.problem}, {fc.label}: {what}", "error_source": "the exact solution", "floor": 0.0,
                         "targets": RANKING_TARGETS, "curves": curves})
    cost = ("median thread CPU time of 3 unobserved runs after a warm-up (one run when the warm-up takes over 1 s); its "
            "spread (largest - least) / median (one run: |run - warm-up| / run)")
    return study.ranking_table("friction_ranking", "Cheapest integrator at each target error: Coulomb friction",
                               column("t err", "s", "", "t_stop err of friction_sliding (mu = 0.8) and t_roll err of friction_disk"),
                               cost, problems)


def trajectory_table(runs):
    """The disk's slip after every step at the coarsest step, each scheme, then the exact slip."""
    disk, t_end = problem_of(TRAJECTORY_CASE), BY_ID[TRAJECTORY_CASE].t_end
    t = study.Table("friction_disk_trajectory", title=f"Rolling disk: slip velocity against the exact one, dt = {text(TRAJECTORY_STEP)} s")
    t.caption = (f"The disk of friction_disk (R = 0.1 m, kappa = 1/2, mu = 0.3, v0 = 1 m/s, omega0 = 0, on the floor): the "
                 f"contact point's slip s = x' + R theta' after every step of dt = {text(TRAJECTORY_STEP)} s (the reported "
                 "velocity), against the exact s(t), which falls linearly to 0 at t* = "
                 f"{disk.exact_event('roll_onset'):.4f} s and stays 0 (rolling).")
    t.columns = [column("integrator"), column("t", "s", "{:.4f}"), column("slip", "m/s", "{:.4e}", "x' + R theta'")]
    t.csv_only = True
    t.figures = [study.Figure("friction_disk_trajectory", title=t.title, x="t", y="slip", series=["integrator"],
                              small_multiples=True, overlay="exact",
                              caption=t.caption + " One panel per scheme; dotted: exact.")]
    for run in runs:
        if run.fc.id == TRAJECTORY_CASE and run.r.case["dt"] == TRAJECTORY_STEP and run.r.ok:
            for time, slip in zip(run.r.state_t, run.m["slip"]):
                t.add_row([run.r.case["integrator"], time, number(slip)])
    T = disk.contacts["T"]
    for k in range(EXACT_SAMPLES + 1):
        time = t_end * k / EXACT_SAMPLES
        t.add_row(["exact", time, float((T @ disk.exact_state(time).v)[0])])
    return t


Run = namedtuple("Run", "fc r m")


def tables(results, full):
    runs = [Run(BY_ID[r.case["labels"]["case"]], r, measure(BY_ID[r.case["labels"]["case"]], r) if r.ok else {})
            for r in results]
    out = [sliding_table(runs), disk_table(runs), block_table(runs), hard_table(runs), ranking(runs), trajectory_table(runs)]
    metadata = [("study", "friction"), ("steps", " ".join(text(dt) for dt in (FULL_STEPS if full else STEPS))),
                ("slip tolerance", text(SLIP_TOL))]
    for t in out:
        t.metadata = metadata
    return out


STUDY = study.Study("friction", "Coulomb friction: sliding mass stop time and distance, rolling disk onset and final speed, "
                    "orders; energy never increasing; block momentum identities; sticking, mu = tan alpha, reversal, mu = "
                    "10, a spinning drop; ranking", cases, tables, source="studies/builtin/friction.py")

if __name__ == "__main__":
    raise SystemExit(STUDY.main())
