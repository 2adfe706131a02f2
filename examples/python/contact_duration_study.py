#!/usr/bin/env python3
"""A study of one's own in Python: how long the bouncing bar's contact lasts, per scheme and step.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/contact_duration_study.py --out my-study

The Doyen-Ern-Piperno bar falls 5 m onto the wall (impact at t = 1 s) and stays in contact for
2 L / c = 2/3 s (the wave's trip to the free end and back; its exact solution's contact force is
the series column contact_force_exact). The measure, a few lines of NumPy on the run's series:
the span of the steps with a contact impulse against the span where the exact force is > 0.
Written as nsbench-study writes a report (--out, --full, --shard I/N, --merge, --verify DIR).
"""
import numpy as np

from nsbench import study

SCHEMES = ("cd-lagrange", "moreau-jean", "nsga")


def cases(full):
    fractions = (0.25, 0.5, 0.9, 1.0) if full else (0.5, 0.9)
    return [study.case("bouncing-bar", scheme, cfl=f, t_end=2.0, N=50, labels={"cfl": f})
            for scheme in SCHEMES for f in fractions]


def span(t, on):
    return t[on][-1] - t[on][0] if on.any() else np.nan


def tables(results, full):
    t = study.Table("contact_duration", title="Bouncing bar: contact duration per scheme and step",
                    caption="Duration: last minus first step with a contact impulse; exact: where the exact "
                            "contact force is > 0 (2 L / c = 2/3 s); N = 50, lumped mass, e = 0.")
    t.columns = [study.Column("integrator", format="{}"), study.Column("cfl", format="{:.2f}"),
                 study.Column("duration", unit="s", format="{:.4f}"),
                 study.Column("duration error", unit="s", format="{:.2e}"), study.Column("status", format="{}")]
    for r in results:
        if r.ok:
            duration = span(r.t, r.impulse > 0)
            exact = span(r.t, r.contact_force_exact > 0)
            t.add_row([r.case["integrator"], r.case["labels"]["cfl"], duration, abs(duration - exact), r.status])
        else:
            t.add_row([r.case["integrator"], r.case["labels"]["cfl"], None, None, f"{r.status}: {r.message}"])
    t.figures = [study.Figure("contact_duration", title="Contact duration error", x="cfl", y="duration error",
                              series=["integrator"], log_y=True)]
    return [t]


if __name__ == "__main__":
    raise SystemExit(study.Study("contact-duration", "the bouncing bar's contact duration per scheme and step",
                                 cases, tables).main())
