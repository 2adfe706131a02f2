"""Study "peers": our schemes against a peer's implementation of the same scheme (docs/method.md
section 2, "Peers run side by side"), e.g. moreau-jean against siconos-moreau-jean.

    nsbench-study peers --out reports        (or: python3 studies/builtin/peers.py --out reports)

Pairs (PAIRS; a pair whose integrator is not registered is skipped, e.g. without the Siconos
peers) x problems (PROBLEMS): the bouncing mass (e = 0.9, dt = 1e-3, to t = 3: four impacts), the
Signorini bar (N = 100, lumped, g0 = 0.4937, dt = 2e-3 = 0.2 h/c, to t = 3.5: one contact phase),
a 10-mass spring chain hitting a wall (e = 1, dt = 1e-3, to t = 1: six impacts), and with Coulomb
friction the sliding mass (30 degrees, mu = 0.8, v0 = 2, dt = 1e-3, to t = 2: slides, stops at
t = 1.06, sticks) and the rolling disk dropped spinning (h0 = 0.05, omega0 = 20, e = 0.5,
mu = 0.3, dt = 1e-3, to t = 1: slipping impacts, then at rest). Same theta, e and dt on both sides
(each pair states its parameters). The 3D problems, run by the FrictionContact(3) pair only: the
sphere on the incline (mu = 0.3: the slip turns, then it rolls; dt = 1e-3, to t = 0.5) and bar-3d
(N = 10, lumped, sides held, dt = 1e-2, to t = 2.5: one contact phase, 4 contacts). The pairs at a
given gamma run on the problems with impacts only.

Each side is one run with its state and impulses recorded at every step (both deterministic,
the same steps: the lockstep of the two); per step, the largest difference of the displacements
and of the velocities (max norm over the dofs, over the largest |u| and |v| of ours along the
run, t > 0), of the energies (over |E_0|) and of the contact impulses, normal and tangential
(over the largest impulse of ours). Cost per step: CPU of each integrator alone, the median of 3
unobserved runs after a warm-up, over its steps; same process, same machine (BLAS serial:
scripts/run.sh sets OPENBLAS_NUM_THREADS=1).

What it shows (Siconos kernel 4.4.0, Debian):
  - moreau-jean and MoreauJeanOSI, theta = 1/2: the same numbers to round-off (<= 1e-12): same
    W = M + h^2 theta^2 K, same free velocity, same Newton law on the LCP.
  - theta = 1: they differ at impacts, by the active-set forecast alone. Both activate a contact
    when g_k + gamma h g'_k <= 0, but with gamma unset ours takes 1 - theta (the known part of the
    theta-method's own position update) and MoreauJeanOSI::addInteractionInIndexSet 1/2 whatever
    theta. At theta = 1 ours is g_k <= 0: a contact acts only once penetrated.
  - The same gamma on both sides: the same numbers to round-off at theta = 1/2 and 1 alike.
  - With friction (FrictionContact(2), 2D NSGS to 1e-12): the same numbers to round-off at
    theta = 1/2, normal and tangential impulses included; the Schatzman-Paoli and D1MinusLinear
    pairs are n/a there (both decline friction).
  - FrictionContact(3) with Siconos' 3D NSGS, theta = 1/2: the same numbers to round-off on the
    sphere's cone and on bar-3d.
  - Siconos' cost per step is 15-80x ours: it hands the problem to dense uBLAS matrices, O(n^2)
    per step where ours is sparse O(n).
"""
import os

import numpy as np

import nsbench
from nsbench import study

IMPACT_PROBLEMS = ("bouncing-mass", "signorini-bar", "spring-chain", "rolling-disk")

# (ours, peer, our parameters, the peer's, what is compared, the problems it runs on: None = every
# problem not marked named_only). moreau-jean: gamma unset is 1 - theta in ours, 1/2 in Siconos'.
# Schatzman-Paoli: theta = 0 on both sides (Siconos' theta is not ours; they coincide at 0 only).
PAIRS = [
    ("moreau-jean", "siconos-moreau-jean", {"theta": "0.5"}, {"theta": "0.5"}, "theta = 1/2", None),
    ("moreau-jean", "siconos-moreau-jean", {"theta": "1"}, {"theta": "1"}, "theta = 1", None),
    ("moreau-jean", "siconos-moreau-jean", {"theta": "0.5", "gamma": "0"}, {"theta": "0.5", "gamma": "0"},
     "theta = 1/2, gamma = 0", IMPACT_PROBLEMS),
    ("moreau-jean", "siconos-moreau-jean", {"theta": "1", "gamma": "0"}, {"theta": "1", "gamma": "0"},
     "theta = 1, gamma = 0", IMPACT_PROBLEMS),
    ("moreau-jean", "siconos-moreau-jean", {"theta": "1", "gamma": "0.5"}, {"theta": "1", "gamma": "0.5"},
     "theta = 1, gamma = 1/2", IMPACT_PROBLEMS),
    ("schatzman-paoli", "siconos-schatzman-paoli", {"theta": "0"}, {"theta": "0"}, "theta = 0", None),
    ("d1-minus-linear", "siconos-d1-minus-linear", {}, {}, "defaults", None),
    ("moreau-jean", "siconos-moreau-jean", {"theta": "0.5"}, {"theta": "0.5", "one_step_problem": "fc3d"},
     "theta = 1/2, FrictionContact(3) on every contact", ("sphere", "bar-3d")),
]

# (label, problem, parameters, dt, t_end, named_only: run only by the pairs that name it)
PROBLEMS = [
    ("bouncing mass, e = 0.9", "bouncing-mass", {"e": "0.9"}, 1e-3, 3.0, False),
    ("Signorini bar, N = 100, lumped", "signorini-bar", {"N": "100", "mass": "lumped", "g0": "0.4937"}, 2e-3, 3.5, False),
    ("spring chain, 10 masses, wall", "spring-chain", {"n": "10", "wall": "left"}, 1e-3, 1.0, False),
    ("sliding mass, 30 deg, mu = 0.8, v0 = 2", "sliding-mass", {"alpha": "30", "mu": "0.8", "v0": "2"}, 1e-3, 2.0, False),
    ("rolling disk dropped, h0 = 0.05, omega0 = 20, e = 0.5, mu = 0.3", "rolling-disk",
     {"h0": "0.05", "omega0": "20", "e": "0.5", "mu": "0.3"}, 1e-3, 1.0, False),
    ("sphere on the 20 deg incline, mu = 0.3: slips, turning, then rolls", "sphere", {}, 1e-3, 0.5, True),
    ("bar-3d, N = 10, lumped, sides held", "bar-3d", {"N": "10"}, 1e-2, 2.5, True),
]


def side(pair, problem, k, p, which):
    ours, peer, ours_params, peer_params = pair[:4]
    label, name, params, dt, t_end, _ = problem
    integrator, own = (ours, ours_params) if which == "ours" else (peer, peer_params)
    parameters = {f"problem.{key}": value for key, value in params.items()}
    parameters.update({f"integrator.{key}": value for key, value in own.items()})
    return study.case(name, integrator, dt=dt, t_end=t_end, states=True, cpu_repeats=3,
                      labels={"pair": k, "problem": p, "side": which}, **parameters)


def cases(full):
    registered = {e["name"] for e in nsbench.integrators()}
    out = []
    for k, pair in enumerate(PAIRS):
        if pair[0] not in registered or pair[1] not in registered:
            continue
        for p, problem in enumerate(PROBLEMS):
            runs_here = (not problem[5]) if pair[5] is None else problem[1] in pair[5]
            if runs_here:
                out += [side(pair, problem, k, p, "ours"), side(pair, problem, k, p, "peer")]
    return out


def largest(x):
    return float(np.max(x)) if x.size else 0.0


def differences(a, b):
    """The lockstep differences of two runs of the same steps (row 0, t = 0, left out)."""
    rows = slice(1, None)
    du, dv = largest(np.abs(a.u[rows] - b.u[rows])), largest(np.abs(a.v[rows] - b.v[rows]))
    u_scale, v_scale = largest(np.abs(a.u[rows])), largest(np.abs(a.v[rows]))
    dimp = max(largest(np.abs(a.impulses[rows] - b.impulses[rows])),
               largest(np.abs(a.tangential_impulses[rows] - b.tangential_impulses[rows])))
    imp_scale = max(largest(np.abs(a.impulses[rows])), largest(np.abs(a.tangential_impulses[rows])))
    e0 = abs(a.total_energy[0])
    de = np.abs(a.total_energy[rows] - b.total_energy[rows]) / e0
    return [du / u_scale, dv / v_scale, largest(de), float(de[-1]), dimp / imp_scale if imp_scale > 0.0 else dimp]


def number(x):
    return None if x is None or not np.isfinite(x) else x


def row(a, b):
    ours, peer, _, _, note, _ = PAIRS[a.case["labels"]["pair"]]
    label, _, _, dt, _, _ = PROBLEMS[a.case["labels"]["problem"]]
    cells = [ours, peer, note, label, dt]
    failed = next((r for r in (a, b) if not r.ok), None)
    if failed is not None:
        return cells + [None, f"{failed.status}: {failed.message}"] + [None] * 8
    ours_step, peer_step = a.cpu / a.steps * 1e6, b.cpu / a.steps * 1e6
    return cells + [a.steps, "ok"] + [number(x) for x in differences(a, b)] + [ours_step, peer_step, peer_step / ours_step]


def tables(results, full):
    t = study.Table("peers", title="Peers: our schemes against another code's implementation of the same scheme")
    t.caption = ("Both integrators step in lockstep, same problem, theta, e and dt. du, dv: max over steps of the max-norm "
                 "difference of displacements and velocities, over the largest |u|, |v| of ours; dE: max |E_ours - E_peer| / "
                 "|E0|; dLambda: max difference of the step impulses (normal and tangential) over our largest impulse. Cost: "
                 "CPU per step of each alone (median thread CPU time of 3 unobserved runs after a warm-up (one run when the "
                 "warm-up takes over 1 s); its spread (largest - least) / median (one run: |run - warm-up| / run)), BLAS "
                 "single-threaded. A pair runs when both integrators are registered (peers: see the metadata).")

    def column(name, unit="", fmt="", description="", timing=False):
        return study.Column(name, unit=unit, format=fmt, description=description, timing=timing)

    t.columns = [column("ours"), column("peer"), column("parameters"), column("problem"), column("dt", fmt="{:.1e}", description="step"),
                 column("steps"), column("status"),
                 column("du", fmt="{:.2e}", description="max |u_ours - u_peer| / max |u_ours|"),
                 column("dv", fmt="{:.2e}", description="max |v_ours - v_peer| / max |v_ours|"),
                 column("dE", fmt="{:.2e}", description="max |E_ours - E_peer| / |E0|"),
                 column("dE end", fmt="{:.2e}", description="|E_ours - E_peer| / |E0| at t_end"),
                 column("dLambda", fmt="{:.2e}", description="max |Lambda_ours - Lambda_peer| / max |Lambda_ours|, normal and tangential"),
                 column("ours/step", "us", "{:.3g}", "CPU per step of ours", True),
                 column("peer/step", "us", "{:.3g}", "CPU per step of the peer", True),
                 column("peer/ours", "", "{:.3g}", "cost ratio", True)]
    for a, b in zip(results[0::2], results[1::2]):
        t.add_row(row(a, b))
    t.metadata = [("study", "peers"), ("OPENBLAS_NUM_THREADS", os.environ.get("OPENBLAS_NUM_THREADS", "unset"))]
    return [t]


STUDY = study.Study("peers", "our schemes against a peer code's (Siconos) on the bouncing mass, the lumped bar, the spring "
                    "chain, the sliding mass, the rolling disk, the sphere and bar-3d", cases, tables,
                    source="studies/builtin/peers.py")

if __name__ == "__main__":
    raise SystemExit(STUDY.main())
