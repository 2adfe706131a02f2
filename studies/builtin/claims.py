"""Study "claims": the seven claims of the CD-Lagrange talk's last slide, each judged under the
talk's own conditions ("as claimed") and beyond them, by a rule written in the caption.

    nsbench-study claims --out reports        (or: python3 studies/builtin/claims.py --out reports)

The conditions (docs/method.md section 7, quoted from the talk): as claimed = a deformable
hyperelastic body against a rigid obstacle, a diagonal (lumped) mass with M^{-1}, a diagonal H
(each contact on its own dofs), the talk's inelastic LCP (e = 0), no friction. Beyond = the rest
the suite runs: the singular mass, e > 0, rigid bodies, friction, contact between bodies, the
adaptive variants. The runs (cd-lagrange unless named):

  bouncing bar   Doyen-Ern-Piperno's drop (problems/bouncing_bar.hpp: L 10, c 30, g 10, g0 5),
                 lumped, e = 0, dt = 0.9 h / c. Its exact solution bounces for ever with period
                 T_b = 2 L / c + 2 v_imp / g = 2.667 s (a contact of 2 L / c, a flight of
                 2 v_imp / g; v_imp = sqrt(v0^2 + 2 g g0)); the first impact at t_1 = 1 s.
  Signorini bar  L 1, c 1, v0 1, lumped, N 100, dt 0.9 h / c, to 1.5 contact durations (t = 3).
  2D block       block-2d: SVK Q4 8 x 4, lumped, frictionless floor, e = 0, dropped tilted.
  (1), (6)  work counters of every run of the study that steps cd-lagrange as claimed, and
            beyond (the singular bar, the rolling disk, two bars, two blocks, the adaptive step)
  (2)       the Hausdorff distance of four graphs of each bar to the exact ones (u, v of the
            contact node, the contact force, the bar's momentum), space and time refined
            together (N = 12 .. 400, dt = 0.9 h / c), in time alone (N = 100, dt = 0.9 h / c / 2^k,
            k = 0 .. 5), the semi-discrete problem's own (modal-exact, the mesh error alone),
            and the CFL ratio 0.5, 0.9, 1.0 at N = 100
  (3)       the block's linear and angular momentum identities (mesh-momentum: the impulses'
            moments at the step's positions), in free flight and on the floor; block-3d's vector
  (4)       the discrete energy balance (energy-balance: the scheme's energy change minus the
            work of the loads and impulses along its velocities) over 50 T_b of the bar at
            N = 100, 200, 400 and 20 s of the block; the adaptive step over 10 T_b and 10 s
  (5)       cd-lagrange-adaptive on the bar to t_1 + T_b: the talk's update as transcribed and
            the published variable-step form (energy-balance root, variational momentum)
  (7)       the bar (N = 25) over 10^4 exact periods; beyond, the singular bar likewise and the
            rigid bouncing mass (e = 1, dt 0.02 s) to its 10^5-th impact
"""
import math

import numpy as np

import nsbench
from nsbench import study

FIXED, ADAPTIVE = "cd-lagrange", "cd-lagrange-adaptive"
BAR = {"mass": "lumped"}  # the bouncing bar's defaults are Doyen-Ern-Piperno's, e = 0
OBSERVABLES = ("u_contact", "v_contact", "contact_force", "momentum")
LONG_PERIODS, ENERGY_PERIODS, ADAPTIVE_PERIODS = 10_000, 50, 10
ENERGY_MESHES = (100, 200, 400)
JOINT_MESHES = (12, 25, 50, 100, 200, 400)
TIME_LEVELS = 6
MASS_IMPACTS = 100_000

# Thresholds, each with why it is that value (the captions repeat them).
MIN_ORDER = 0.5          # (2) a graph converges: Hausdorff order >= 1/2 (the order of a jump located a step late
                         #     in scaled coordinates is 1; 1/2 leaves room for the fit) with the interval above 0
MOMENTUM_TOL = 1e-10     # (3) residual / momentum scale: 1e5 x double round-off, far below any scheme's defect
GROWTH_FACTOR = math.sqrt(10)  # (7) penetration over the run against its first tenth: 1 when bounded, 10 when it
                               #     grows linearly; half a decade between them


DEFORMABLE = ("signorini-bar", "bouncing-bar", "block-2d", "block-3d", "bar-3d")  # hyperelastic bodies, rigid obstacles


def as_claimed_violation(c):
    """Why a case is not under the talk's conditions ('' when it is): a deformable body against a
    rigid obstacle, the lumped mass, e = 0, no friction (docs/method.md section 7)."""
    if c["problem"] not in DEFORMABLE:
        return f"{c['problem']} is not a deformable body against a rigid obstacle"
    names = nsbench.Problem(c["problem"]).parameters
    given = dict(item.removeprefix("problem.").split("=", 1) for item in c["set"])
    p = nsbench.Problem(c["problem"], **{k: v for k, v in given.items() if k in names}).parameters
    for key, wanted in (("mass", "lumped"), ("e", 0.0), ("mu", 0.0)):
        if key in p and p[key] != wanted:
            return f"{c['problem']} {key} = {p[key]}, the talk's is {wanted}"
    return ""


def grows(drift, round_off):
    """Claim (4)'s rule on an envelope's drift (study.drift_rule): it grows when the slope's 95%
    interval lies above 0 and the growth over the run exceeds round-off. One-sided: the talk claims
    an error that does not grow ("décroît exponentiellement"); a falling envelope is bounded."""
    return bool(drift["low"] > 0 and drift["over_run"] > round_off)


def bar_times(problem="bouncing-bar", **p):
    """(t_1, T_b): the exact first impact and the exact period of the bouncing bar."""
    q = nsbench.Problem(problem, **p).parameters
    c, v_imp = math.sqrt(q["E"] / q["rho"]), math.sqrt(q["v0"] ** 2 + 2 * q["g"] * q["g0"])
    return (v_imp - q["v0"]) / q["g"], 2 * q["L"] / c + 2 * v_imp / q["g"]


T1, TB = bar_times(**BAR)


def labelled(c, **labels):
    c["labels"] = labels
    return c


def work_cases():
    """(1), (6): short runs whose every step is recorded (their contact steps counted)."""
    disk = {"h0": 0.05, "omega0": 20, "e": 0.5, "mu": 0.3}
    runs = [("Signorini bar", "as claimed", FIXED, "signorini-bar", {"cfl": 0.9}, 3.0, {"N": 100, **BAR}),
            ("bouncing bar", "as claimed", FIXED, "bouncing-bar", {"cfl": 0.9}, T1 + TB, {"N": 100, **BAR}),
            ("2D block", "as claimed", FIXED, "block-2d", {"cfl": 0.9}, 2.0, {}),
            ("bouncing bar, singular mass", "beyond", FIXED, "bouncing-bar", {"cfl": 0.9}, T1 + TB, {"N": 100, "mass": "singular"}),
            ("rolling disk, e 0.5, mu 0.3", "beyond", FIXED, "rolling-disk", {"dt": 1e-3}, 1.0, disk),
            ("two bars", "beyond", FIXED, "two-bars", {"cfl": 0.9}, 4.0, {}),
            ("two blocks", "beyond", FIXED, "two-blocks", {"dt": 1e-4}, 0.1, {"g": 0, "upper_vx": 0.5}),
            ("bouncing bar, adaptive step", "beyond", ADAPTIVE, "bouncing-bar", {"cfl": 0.9}, T1 + TB, {"N": 100, **BAR})]
    return [labelled(study.case(problem, integrator, t_end=t_end, **step, **p), claim="work", run=run, conditions=cond)
            for run, cond, integrator, problem, step, t_end, p in runs]


def hausdorff_cases():
    """(2): the bars' four graphs measured against the exact solution, per refinement."""
    measures = [{"kind": "hausdorff", "observable": o, "label": o} for o in OBSERVABLES]
    out = []
    for problem, t_end in (("signorini-bar", 3.0), ("bouncing-bar", T1 + TB)):
        def measured(integrator, family, N, cfl, x, mass="lumped"):
            dt = cfl * nsbench.Problem(problem, N=N, mass=mass).stable_step()
            return labelled(study.case(problem, integrator, cfl=cfl, t_end=t_end, N=N, measures=measures,
                                       reference={"solution": "exact"}, mass=mass),
                            claim="hausdorff", problem=problem, family=family, N=N, cfl=cfl, x=x, dt=dt,
                            conditions="as claimed" if mass == "lumped" else "beyond")
        out += [measured(FIXED, "space and time", N, 0.9, 1.0 / N) for N in JOINT_MESHES]
        out += [measured(FIXED, "space and time, singular mass", N, 0.9, 1.0 / N, "singular") for N in JOINT_MESHES]
        out += [measured("modal-exact", "semi-discrete (modal-exact)", N, 0.9, 1.0 / N) for N in JOINT_MESHES]
        out += [measured(FIXED, "time alone, N 100", 100, 0.9 / 2 ** k, 0.9 / 2 ** k) for k in range(TIME_LEVELS)]
        out += [measured(FIXED, "CFL ratio, N 100", 100, cfl, cfl) for cfl in (0.5, 1.0)]
    return out


def momentum_cases():
    """(3): every momentum component of the blocks, free and on the floor."""
    spin = {"spin": 3, "vx": 0.3}
    runs = [("2D block, free flight", "as claimed", FIXED, "block-2d", 10_000, {"g": 0, "height": 10, **spin}, ("px", "py", "jz")),
            ("2D block, on the floor", "as claimed", FIXED, "block-2d", 2_000, spin, ("px", "py", "jz")),
            ("2D block, on the floor, adaptive step", "beyond", ADAPTIVE, "block-2d", 500, spin, ("px", "py", "jz")),
            ("3D block, free flight", "as claimed", FIXED, "block-3d", 2_000, {"g": 0, "height": 10, "spin": 3},
             ("px", "py", "pz", "jx", "jy", "jz")),
            ("3D block, on the floor", "as claimed", FIXED, "block-3d", 2_000, {"spin": 3}, ("px", "py", "pz", "jx", "jy", "jz"))]
    out = []
    for run, cond, integrator, problem, steps, p, components in runs:
        dt = 0.5 * nsbench.Problem(problem, **p).stable_step()
        observe = [{"kind": "mesh-momentum", "component": c} for c in components]
        out.append(labelled(study.case(problem, integrator, dt=dt, t_end=steps * dt, observe=observe, **p),
                            claim="momentum", run=run, conditions=cond, components=list(components)))
    return out


def energy_cases():
    """(4): the discrete energy balance over long runs, observed every step."""
    def balance(run, cond, integrator, problem, t_end, window, **p):
        return labelled(study.case(problem, integrator, cfl=0.9, t_end=t_end, observe=[{"kind": "energy-balance", "window": window}],
                                   **p), claim="energy", run=run, conditions=cond, windows=round((t_end - (T1 if "bar" in problem else 0)) / window))
    out = [balance(f"bouncing bar, N {n}", "as claimed", FIXED, "bouncing-bar", T1 + ENERGY_PERIODS * TB, TB, N=n, **BAR)
           for n in ENERGY_MESHES]
    out += [balance("2D block, 20 s", "as claimed", FIXED, "block-2d", 20.0, 1.0),
            balance("bouncing bar, N 100, adaptive step", "as claimed", ADAPTIVE, "bouncing-bar", T1 + ADAPTIVE_PERIODS * TB, TB,
                    N=100, **BAR),
            balance("2D block, 10 s, adaptive step", "as claimed", ADAPTIVE, "block-2d", 10.0, 1.0),
            balance("bouncing bar, N 100, singular mass", "beyond", FIXED, "bouncing-bar", T1 + ENERGY_PERIODS * TB, TB, N=100,
                    mass="singular"),
            balance("bouncing bar, N 100, e 1", "beyond", FIXED, "bouncing-bar", T1 + ENERGY_PERIODS * TB, TB, N=100, e=1, **BAR)]
    return out


def adaptive_cases():
    """(5): the talk's update as transcribed beside the published form, recorded and observed."""
    rules = {"the talk's update (as transcribed)": ("as claimed", {"step_rule": "talk", "momentum": "talk", "energy_target": "no-work"}),
             "energy-balance root (published form)": ("beyond", {})}
    fixed_steps = round((T1 + TB) / (0.9 * nsbench.Problem("bouncing-bar", N=100, **BAR).stable_step()))
    out = []
    for rule, (cond, p) in rules.items():
        common = dict(cfl=0.9, t_end=T1 + TB, N=100, max_force_evaluations=100 * fixed_steps, **BAR, **p)
        out.append(labelled(study.case("bouncing-bar", ADAPTIVE, **common), claim="adaptive", rule=rule, kind="steps", conditions=cond))
        out.append(labelled(study.case("bouncing-bar", ADAPTIVE, observe=[{"kind": "energy-balance", "window": TB / 8},
                                                                          {"kind": "mesh-momentum", "component": "px"}], **common),
                            claim="adaptive", rule=rule, kind="balances", conditions=cond))
    return out


def long_cases(full):
    """(7): many contact phases, counted every step (a flight shorter than the bar's wave time L / c
    is chatter within one phase), with the penetration per tenth of the run."""
    def phases(problem, dt_or_cfl, t_end, min_flight, run, cond, exact_phases, **p):
        observe = [{"kind": "contact-phases", "min_flight": min_flight, "t_end": t_end}]
        return labelled(study.case(problem, FIXED, t_end=t_end, observe=observe, **dt_or_cfl, **p),
                        claim="long", run=run, conditions=cond, exact_phases=exact_phases)
    wave = 10 / 30  # L / c of Doyen-Ern-Piperno's bar
    period = 2 * math.sqrt(2 * 1.0 / 9.81)
    return [phases("bouncing-bar", {"cfl": 0.9}, T1 + LONG_PERIODS * TB, wave, "bouncing bar, N 25", "as claimed", LONG_PERIODS,
                   N=25, **BAR),
            phases("bouncing-bar", {"cfl": 0.9}, T1 + LONG_PERIODS * TB, wave, "bouncing bar, N 25, singular mass", "beyond",
                   LONG_PERIODS, N=25, mass="singular"),
            phases("bouncing-mass", {"dt": 0.02}, MASS_IMPACTS * period, 0.0, "rigid mass, e 1, dt 0.02 s", "beyond", MASS_IMPACTS,
                   e=1, h0=1)]


def cases(full):
    out = work_cases() + hausdorff_cases() + momentum_cases() + energy_cases() + adaptive_cases() + long_cases(full)
    for c in out:
        if c["labels"]["conditions"] == "as claimed" and (why := as_claimed_violation(c)):
            raise ValueError(f"claims: a case labelled as claimed is not: {why}")
    return out


def finite(x):
    return None if x is None or not np.isfinite(x) else float(x)


def by_claim(results, claim):
    return [r for r in results if r.case["labels"]["claim"] == claim]


def verdict(met):
    """holds (every condition met), fails (none), or holds on k of n."""
    k, n = sum(bool(m) for m in met), len(met)
    return "holds" if n and k == n else "fails" if k == 0 else f"holds on {k} of {n}"


def contact_steps(r):
    return int(np.count_nonzero(r.impulse[1:] > 0)) if r.ok else 0


def work_rows(results):
    """(1), (6) per run: steps, F_int and energy evaluations, factorisations, solves, LCP iterations."""
    rows = []
    for r in by_claim(results, "work"):
        w = r.summary.get("work", {})
        explicit = r.ok and w["factorizations"] == 0 and w["linear_solves"] == 0 and w["force_evaluations"] <= w["steps"] + 1
        closed = r.ok and contact_steps(r) > 0 and w["lcp_iterations"] == 0
        matrix_free = r.ok and w["factorizations"] == 0 and w["linear_solves"] == 0
        rows.append({"run": r.case["labels"]["run"], "conditions": r.case["labels"]["conditions"], "steps": w.get("steps"),
                     "F_int": w.get("force_evaluations"), "energy evaluations": int(w.get("energy_iterations", 0)),
                     "factorisations": w.get("factorizations"), "solves": w.get("linear_solves"), "contact steps": contact_steps(r),
                     "LCP iterations": w.get("lcp_iterations"), "explicit": explicit, "closed form": closed, "matrix-free": matrix_free})
    return rows


def hausdorff_orders(results):
    """(2) per bar, family and observable: the Hausdorff order in the refinement's x with its interval."""
    families = {}
    for r in by_claim(results, "hausdorff"):
        key = (r.case["labels"]["problem"], r.case["labels"]["family"])
        families.setdefault(key, []).append(r)
    rows = []
    for (problem, family), runs in families.items():
        if family.startswith("CFL"):
            continue
        x = [r.case["labels"]["x"] for r in runs]
        for j, o in enumerate(OBSERVABLES):
            d = [r.values[j] if r.ok and len(r.values) else np.nan for r in runs]
            f = study.fit_order(x, d)
            rows.append({"problem": problem, "family": family, "observable": o, "levels": len(runs), "order": f["order"],
                         "low": f["low"], "high": f["high"], "finest": d[-1],
                         "converges": bool(f["order"] >= MIN_ORDER and f["low"] > 0)})
    return rows


def momentum_rows(results):
    rows = []
    for r in by_claim(results, "momentum"):
        rel = [o["relative"] for o in r.observed] if r.ok else [np.nan]
        rows.append({"run": r.case["labels"]["run"], "conditions": r.case["labels"]["conditions"], "steps": r.steps,
                     "components": ", ".join(r.case["labels"]["components"]), "largest": max(rel),
                     "kept": bool(r.ok and max(rel) <= MOMENTUM_TOL), "note": "" if r.ok else f"{r.status}: {r.message}"})
    return rows


def energy_rows(results):
    """(4) per run: the balance's envelope over E_scale, its growth per window with its interval."""
    rows = []
    for r in by_claim(results, "energy"):
        scale = r.summary.get("energy_error_scale", np.nan)
        o = r.observed[0] if r.ok else {"envelope": {"maxima": [np.nan]}, "drift": {}, "round_off": np.nan, "cumulative": np.nan}
        d, window = o["drift"], r.case["observe"][0]["window"]
        growing = r.ok and grows(d, o["round_off"])
        largest = max(o["envelope"]["maxima"])
        rows.append({"run": r.case["labels"]["run"], "conditions": r.case["labels"]["conditions"], "integrator": r.case["integrator"],
                     "steps": r.steps, "windows": d.get("windows"), "largest": largest / scale,
                     "growth": d.get("drift", np.nan) * window / scale, "low": d.get("low", np.nan) * window / scale,
                     "high": d.get("high", np.nan) * window / scale, "round-off": o["round_off"] / scale,
                     "total": r.summary.get("final_energy_error", np.nan), "grows": growing,
                     "exact": bool(r.ok and largest <= o["round_off"])})
    return rows


def adaptive_rows(results, fixed_steps):
    """(5) per rule: the steps against the fixed step's and the stable step, and the same runs'
    balances (claims 3 and 4 on them)."""
    runs = by_claim(results, "adaptive")
    bar = nsbench.Problem("bouncing-bar", N=100, **BAR)
    stable, q = bar.stable_step(), bar.parameters
    impact_momentum = q["rho"] * q["A"] * q["L"] * math.sqrt(q["v0"] ** 2 + 2 * q["g"] * q["g0"])  # the drop starts at rest
    tau_min = 1e-3 * 0.9 * stable  # tau_min_ratio's default x the first requested step
    rows = []
    for steps, balances in zip(runs[0::2], runs[1::2]):
        w = steps.summary.get("work", {})
        dt = steps.series["dt"][steps.series["dt"] > 0] if steps.ok else np.array([])
        ok = steps.ok and balances.ok
        energy, momentum = (balances.observed if balances.ok else [{}, {}])
        exact = ok and max(energy["envelope"]["maxima"]) <= energy["round_off"]
        momentum_error = momentum["largest"] / impact_momentum if ok else np.nan
        kept = ok and momentum_error <= MOMENTUM_TOL
        row = {"rule": steps.case["labels"]["rule"], "status": steps.status, "steps": steps.steps,
               "steps / fixed": steps.steps / fixed_steps, "no root": int(w.get("no_root_steps", 0)), "F_int": w.get("force_evaluations"),
               "energy evaluations": int(w.get("energy_iterations", 0)),
               "largest / stable": float(np.max(dt)) / stable if dt.size else np.nan,
               "smallest / tau_min": float(np.min(dt)) / tau_min if dt.size else np.nan,
               "at tau_min": int(np.count_nonzero(dt <= tau_min * (1 + 1e-9))) if dt.size else 0,
               "balance": max(energy["envelope"]["maxima"]) / steps.summary.get("energy_error_scale", np.nan) if ok else np.nan,
               "momentum": momentum_error}
        failed = [why for why, met in (
            (f"{steps.status}, {row['no root']} without root", steps.ok),
            ("a step above the stable step", steps.ok and row["largest / stable"] <= 1),
            ("a constant step", steps.ok and np.max(dt) > (1 + 1e-6) * np.min(dt)),
            (f"{row['at tau_min']} steps at tau_min", row["at tau_min"] == 0),
            (f"balance {row['balance']:.1e} E_s, not exact", exact),
            (f"momentum residual {row['momentum']:.1e}", kept)) if not met]
        row["holds"], row["why"] = not failed, failed[0] if failed else ""
        rows.append(row)
    return rows


def long_rows(results):
    """(7) per run: phases seen against the exact count, the phase error, penetration growth."""
    rows = []
    for r in by_claim(results, "long"):
        o = r.observed[0] if r.ok else {"phases": 0, "starts": [], "max_penetration": np.nan, "penetration_by_tenth": [np.nan]}
        starts, exact_n = np.array(o["starts"], dtype=float), r.case["labels"]["exact_phases"]
        if r.case["problem"] == "bouncing-bar":
            exact = T1 + TB * np.arange(exact_n)
        else:
            exact = np.array(nsbench.Problem("bouncing-mass", e=1, h0=1).impact_times(math.inf))  # its first 10^5
            exact = exact[exact <= r.case["t_end"]]
        n = min(len(starts), len(exact))
        tenths = o["penetration_by_tenth"]
        # No penetration at all (a massless contact node): below 1e-12 m, round-off of O(10 m) positions.
        growth = max(tenths) / tenths[0] if tenths[0] > 0 else 1.0 if max(tenths) <= 1e-12 else np.inf
        rows.append({"run": r.case["labels"]["run"], "conditions": r.case["labels"]["conditions"], "status": r.status,
                     "steps": r.steps, "phases": o["phases"], "exact phases": len(exact),
                     "phase error": abs(starts[n - 1] - exact[n - 1]) if n else np.nan,
                     "penetration": o["max_penetration"], "penetration growth": growth,
                     "energy": r.summary.get("final_energy_error", np.nan),
                     "holds": bool(r.ok and o["phases"] >= 10_000 and growth <= GROWTH_FACTOR)})
    return rows


CLAIMS = [(1, "Intégrateur explicite de type « time stepping »"),
          (2, "Convergence spatio-temporelle en non-régulier au sens de Hausdorff"),
          (3, "forme discrétisée multi-symplectique (conservation de la résultante et du moment)"),
          (4, "conservation de l'énergie discrète"),
          (5, "Pas de temps adaptatif automatique (avec vérification de la condition CFL)"),
          (6, "Matrix free (LCP explicite) pour les contacts de type déformable / rigide"),
          (7, "Grande robustesse sur les temps longs avec un très grand nombre d'impacts")]


WHAT = {"u_contact": "displacement", "v_contact": "velocity", "contact_force": "force", "momentum": "momentum"}


def explicit_cell(work, conditions):
    chosen = [r for r in work if r["conditions"] == conditions]
    v = verdict([r["explicit"] for r in chosen])
    energy = max(r["energy evaluations"] / r["steps"] for r in chosen if r["steps"])
    return f"{v}: 1 F_int/step, 0 solves" + (f", {energy:.2g} V_int" if energy else "")


def momentum_cell(rows, conditions):
    chosen = [r for r in rows if r["conditions"] == conditions]
    return f"{verdict([r['kept'] for r in chosen])}: residuals <= {max(r['largest'] for r in chosen):.1e}"


def lcp_cell(work, conditions):
    chosen = [r for r in work if r["conditions"] == conditions and r["contact steps"] > 0]
    closed, free = sum(r["closed form"] for r in chosen), sum(r["matrix-free"] for r in chosen)
    if closed == free == len(chosen):
        return "holds: closed form and matrix-free"
    return f"closed form {closed}/{len(chosen)}, matrix-free {free}/{len(chosen)}"


def summary(work, orders, momentum, energy, adaptive, long):
    """The 7 x 2 verdicts, each cell at most 40 characters."""
    joint = [o for o in orders if o["family"] == "space and time"]
    singular = [o for o in orders if o["family"] == "space and time, singular mass"]

    def converged(rows):
        names = [WHAT[o] for o in OBSERVABLES if any(r["converges"] and r["observable"] == o for r in rows)]
        k, n = sum(r["converges"] for r in rows), len(rows)
        return ("holds" if k == n else "fails" if k == 0 else f"{', '.join(names)} only: {k} of {n}")[:40]

    fixed = [r for r in energy if r["integrator"] == FIXED]
    adaptive_energy = [r for r in energy if r["integrator"] == ADAPTIVE]
    bars = [r for r in fixed if r["run"].startswith("bouncing bar, N") and r["conditions"] == "as claimed"]
    falls = all(a["largest"] > b["largest"] for a, b in zip(bars, bars[1:]))
    no_growth = all(not r["grows"] for r in fixed if r["conditions"] == "as claimed")
    exact = all(r["exact"] for r in adaptive_energy)
    e_claimed = verdict([no_growth and falls, exact])
    if e_claimed != "holds":
        bound = max(r["largest"] for r in bars)
        e_claimed = (f"fixed holds, <= {bound:.2f} E_s; adaptive fails" if no_growth and falls and not exact else
                     "fixed fails, adaptive exact" if exact else "fails")
    beyond = [r for r in fixed if r["conditions"] == "beyond"]
    e_beyond = "holds: no growth" if not any(r["grows"] for r in beyond) else f"fails: grows on {sum(r['grows'] for r in beyond)} of {len(beyond)}"
    talk, published = adaptive
    return [
        (explicit_cell(work, "as claimed"), explicit_cell(work, "beyond")),
        (converged(joint), converged(singular)),
        (momentum_cell(momentum, "as claimed"), momentum_cell(momentum, "beyond")),
        (e_claimed, e_beyond),
        tuple("holds" if rule["holds"] else f"fails: {rule['why']}"[:40] for rule in (talk, published)),
        (lcp_cell(work, "as claimed"), lcp_cell(work, "beyond")),
        ("holds" if long[0]["holds"] else f"fails: {long[0]['phases']} of {long[0]['exact phases']} phases seen"[:40],
         long_cell([r for r in long if r["conditions"] == "beyond"]))]


def long_cell(rows):
    v = verdict([r["holds"] for r in rows])
    failed = next((r for r in rows if not r["holds"]), None)
    return v if failed is None else f"{v}: {failed['run'].split(', ')[-1].split()[0]} {failed['phases']} phases"[:40]


def table(id, title, caption, rows, columns):
    """A table of dict rows; columns: (key, format, description)."""
    t = study.Table(id, title=title, caption=caption)
    t.columns = [study.Column(key, format=fmt, description=description) for key, fmt, description in columns]
    def value(x):
        return ("yes" if x else "no") if isinstance(x, bool) else finite(x) if isinstance(x, float) else x
    for r in rows:
        t.add_row([value(r[k]) for k, _, _ in columns])
    return t


RUN = [("run", "{}", "the run (docstring: studies/builtin/claims.py)"), ("conditions", "{}", "as claimed or beyond (docs/method.md 7)")]
SUMMARY_CAPTION = (
    "Each claim of the talk's last slide (quoted) judged on runs under the talk's own conditions (as claimed: a deformable "
    "hyperelastic body against a rigid obstacle, diagonal mass with M^-1, diagonal H, the inelastic LCP e = 0, no friction) and "
    "beyond them (singular mass, e > 0, rigid bodies, friction, contact between bodies, the adaptive variants); docs/method.md "
    "section 7 quotes the conditions. Rules: (1) 0 factorisations and solves, F_int evaluations <= steps + 1 (the start-up "
    "F_int(U_0)); (2) a graph converges when its Hausdorff order >= 0.5 with the 95% interval above 0, 8 graphs (4 per bar) "
    "refined in space and time; (3) every momentum identity residual <= 1e-10 of the momentum scale; (4) fixed step: the energy-"
    "balance envelope does not grow (its slope's 95% interval not above 0, or the growth below round-off) and its bound falls "
    "with N; adaptive step: exact (the envelope within round-off); (5) the run completes, steps <= the stable step and varying, "
    "none at tau_min, and the same runs meet (3) and (4); (6) closed form: 0 LCP iterations; matrix-free: 0 factorisations and "
    "solves; (7) >= 10^4 contact phases, finite, penetration not growing (whole run <= sqrt(10) x the first tenth). The tables "
    "below hold every figure.")


def figure_table(id, title, caption, columns, rows, figure):
    t = study.Table(id, title=title, caption=caption)
    t.columns = [study.Column(name, unit=unit, format=fmt) for name, unit, fmt in columns]
    for row in rows:
        t.add_row([finite(x) if isinstance(x, float) else x for x in row])
    t.csv_only, t.figures = True, [figure]
    return t


def figure_tables(results):
    """The figures of claims (2), (4), (5) and (7), each from a table of what it plots."""
    distances = [(r.case["labels"]["problem"], r.case["labels"]["family"], o, r.case["labels"]["dt"],
                  float(r.values[j]) if r.ok and len(r.values) else np.nan)
                 for r in by_claim(results, "hausdorff") for j, o in enumerate(OBSERVABLES)]
    envelopes = []
    for r in by_claim(results, "energy"):
        if r.ok:
            scale = r.summary["energy_error_scale"]
            envelopes += [(r.case["labels"]["run"], k + 1, m / scale) for k, m in enumerate(r.observed[0]["envelope"]["maxima"])]
    stable = nsbench.Problem("bouncing-bar", N=100, **BAR).stable_step()
    steps = []
    for r in by_claim(results, "adaptive"):
        if r.case["labels"]["kind"] == "steps" and "dt" in r.series:
            t, dt = r.series["t"][1:], r.series["dt"][1:]
            steps += [(r.case["labels"]["rule"], float(a), float(b) / stable) for a, b in zip(t[::20], dt[::20])]
    tenths = [(r.case["labels"]["run"], k + 1, p) for r in by_claim(results, "long") if r.ok
              for k, p in enumerate(r.observed[0]["penetration_by_tenth"])]
    return [
        figure_table("claims_hausdorff_distances", "Claim (2): the Hausdorff distance of each graph against dt",
                     "One row per run and graph.", [("problem", "", "{}"), ("family", "", "{}"), ("observable", "", "{}"),
                                                    ("dt", "s", "{:.4e}"), ("distance", "", "{:.4e}")], distances,
                     study.Figure("claims_hausdorff", title="Claim (2): Hausdorff distance to the exact graph against dt", x="dt",
                                  y="distance", series=["family"], panels=["problem", "observable"], log_x=True, log_y=True, slopes=[0.5, 1.0],
                                  caption="Scaled coordinates (t / t_end, value / the exact graph's largest |value|); modal-exact: the "
                                          "mesh's own error; a graph converges when its order >= 0.5 (slopes 1/2 and 1 drawn).")),
        figure_table("claims_energy_envelope", "Claim (4): the energy balance's envelope per window",
                     "The largest |running sum of the balance| in each window, over E_s.",
                     [("run", "", "{}"), ("window", "", "{}"), ("envelope / E_s", "", "{:.4e}")], envelopes,
                     study.Figure("claims_energy", title="Claim (4): discrete energy balance, largest |sum| per window over E_s",
                                  x="window", y="envelope / E_s", series=["run"], log_y=True,
                                  caption="Windows: T_b = 2.667 s for the bar, 1 s for the block (linear axis); the fixed step's "
                                          "envelope must not grow, the adaptive step's must stay at round-off.")),
        figure_table("claims_adaptive_steps", "Claim (5): the adaptive step against time (every 20th step)",
                     "cd-lagrange-adaptive on the bouncing bar, N 100; dt over the stable step.",
                     [("rule", "", "{}"), ("t", "s", "{:.6e}"), ("dt / stable", "", "{:.4e}")], steps,
                     study.Figure("claims_adaptive", title="Claim (5): the adaptive step over the stable step", x="t",
                                  y="dt / stable", series=["rule"], log_y=True,
                                  caption="The first impact at t = 1 s; the talk's update as transcribed stops at its budget "
                                          "(100 x the fixed step's count).")),
        figure_table("claims_penetration", "Claim (7): the largest penetration per tenth of each long run", "m.",
                     [("run", "", "{}"), ("tenth", "", "{}"), ("penetration", "m", "{:.4e}")], tenths,
                     study.Figure("claims_long_run", title="Claim (7): largest penetration per tenth of the run", x="tenth",
                                  y="penetration", series=["run"], log_y=True,
                                  caption="Bounded: the same level in every tenth; growing: a rise across the tenths (rule: the whole "
                                          "run's <= sqrt(10) x the first tenth's)."))]


def tables(results, full):
    work, orders, momentum = work_rows(results), hausdorff_orders(results), momentum_rows(results)
    energy, long = energy_rows(results), long_rows(results)
    fixed_steps = next(r["steps"] for r in work if r["run"] == "bouncing bar")
    adaptive = adaptive_rows(results, fixed_steps)
    head = study.Table("claims", title="The talk's seven claims: verdicts as claimed and beyond", caption=SUMMARY_CAPTION)
    head.columns = [study.Column("#", format="{}"), study.Column("claim (the talk)", format="{}"),
                    study.Column("as claimed", format="{}"), study.Column("beyond", format="{}")]
    for (k, text), (claimed, beyond) in zip(CLAIMS, summary(work, orders, momentum, energy, adaptive, long)):
        head.add_row([k, text, claimed, beyond])
    head.lead = True
    return [head] + figure_tables(results) + [
            table("claims_work", "Claims (1) and (6): the work of each run", "Counters of the scheme (run summary's work).", work,
                  RUN + [("steps", "{}", ""), ("F_int", "{}", "F_int evaluations"), ("energy evaluations", "{}", "strain-energy "
                         "evaluations of the adaptive step's energy equation"), ("factorisations", "{}", ""), ("solves", "{}", "linear solves"),
                         ("contact steps", "{}", "steps with an impulse"), ("LCP iterations", "{}", "Gauss-Seidel sweeps"),
                         ("explicit", "{}", "rule (1)"), ("closed form", "{}", "0 LCP iterations"), ("matrix-free", "{}", "0 factorisations, 0 solves")]),
            table("claims_hausdorff", "Claim (2): Hausdorff orders of the bars' graphs against the exact ones",
                  "Order of the Hausdorff distance (scaled: t / t_end, value / the exact graph's largest |value|) in x = 1/N (space "
                  "and time, dt = 0.9 h/c), x = dt (time alone, N 100); modal-exact: the semi-discrete solution's own distance (the "
                  "mesh alone). Converges: order >= 0.5 with the 95% interval above 0.", orders,
                  [("problem", "{}", ""), ("family", "{}", "refinement"), ("observable", "{}", ""), ("levels", "{}", ""),
                   ("order", "{:.2g}", ""), ("low", "{:.2g}", "95% interval"), ("high", "{:.2g}", ""), ("finest", "{:.2e}", "distance at the finest level"),
                   ("converges", "{}", "")]),
            table("claims_momentum", "Claim (3): momentum identities of the blocks",
                  "Largest residual over the steps and the components, relative to the momentum scale (mesh-momentum: the "
                  "impulses' moments at the step's positions). Kept: <= 1e-10.", momentum,
                  RUN + [("steps", "{}", ""), ("components", "{}", ""), ("largest", "{:.2e}", ""), ("kept", "{}", ""), ("note", "{}", "")]),
            table("claims_energy", "Claim (4): the discrete energy balance over long runs",
                  "energy-balance per step, its running sum's envelope per window (T_b = 2.667 s for the bar, 1 s for the block), "
                  "over the run's energy scale E_s (the bar: the kinetic energy at impact). Growth: the envelope's slope per window with "
                  "its 95% interval; grows when the interval is above 0 and the growth over the run above round-off (a falling "
                  "envelope is bounded: the claim is that the error does not grow). Exact: the envelope within round-off. Total: "
                  "|E_end - E_0| / E_s of the total energy, which e = 0 dissipates by design. The lumped bar with e = 0 stops "
                  "bouncing after about 40 contact phases (claims_long_run), the block after a few: the last windows of "
                  "their runs are at rest, where the envelope falls; the bound is the envelope's largest value.", energy,
                  RUN + [("integrator", "{}", ""), ("steps", "{}", ""), ("windows", "{}", ""), ("largest", "{:.2e}", "envelope / E_s"),
                         ("growth", "{:.2e}", "per window / E_s"), ("low", "{:.2e}", ""), ("high", "{:.2e}", ""),
                         ("round-off", "{:.1e}", "/ E_s"), ("total", "{:.2e}", ""), ("grows", "{}", ""), ("exact", "{}", "")]),
            table("claims_adaptive", "Claim (5): the adaptive step on the bouncing bar, to t_1 + T_b",
                  f"cd-lagrange-adaptive, N 100, lumped, e = 0; the fixed step takes {fixed_steps} steps. The talk's update of "
                  "tau_{k+2} is taken as transcribed from the slide (docs/method.md 7: the transcription lost brackets); beside it the "
                  "published variable-step form (Kane, Marsden, Ortiz, West 2000). Holds: completes, largest step <= the stable step "
                  "(constant: a linear bar), varying, none at tau_min, energy balance exact and momentum residual <= 1e-10 on the same runs.",
                  adaptive,
                  [("rule", "{}", ""), ("status", "{}", ""), ("steps", "{}", ""), ("steps / fixed", "{:.3g}", ""), ("no root", "{}", "steps whose energy equation had no root"),
                   ("F_int", "{}", ""), ("energy evaluations", "{}", ""), ("largest / stable", "{:.3g}", ""), ("smallest / tau_min", "{:.3g}", ""),
                   ("at tau_min", "{}", "steps"), ("balance", "{:.2e}", "energy-balance envelope / E_s"),
                   ("momentum", "{:.2e}", "largest residual / the momentum at impact"), ("holds", "{}", ""), ("why", "{}", "the first rule not met")]),
            table("claims_long_run", "Claim (7): long runs through many contact phases",
                  "Contact phases counted every step (a flight shorter than L / c is chatter), against the exact solution's; phase "
                  "error: |t - t_exact| of the last phase both have; penetration growth: the whole run's largest over the first tenth's "
                  "(1 bounded, 10 linear growth; sqrt(10) the threshold); energy: |E_end - E_0| / E_s.", long,
                  RUN + [("status", "{}", ""), ("steps", "{}", ""), ("phases", "{}", ""), ("exact phases", "{}", ""),
                         ("phase error", "{:.3g}", "s"), ("penetration", "{:.2e}", "m"), ("penetration growth", "{:.3g}", ""),
                         ("energy", "{:.2e}", ""), ("holds", "{}", "")])]


STUDY = study.Study("claims", "the talk's seven claims judged as claimed and beyond: a 7 x 2 verdict table and the figures behind it",
                    cases, tables, source="studies/builtin/claims.py")

if __name__ == "__main__":
    raise SystemExit(STUDY.main())
