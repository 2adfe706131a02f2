#!/usr/bin/python3
"""Tests of scripts/figures.py: the style map and a smoke test of both looks on a small report.

    figures_test.py NSBENCH   (the nsbench binary: its list names every registered integrator)

Exit 77 (CTest: skipped) without matplotlib (Debian python3-matplotlib)."""
import json
import os
import subprocess
import sys
import tempfile

try:
    import matplotlib  # noqa: F401
except ImportError:
    print("SKIPPED: matplotlib absent (Debian python3-matplotlib)")
    sys.exit(77)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import figures  # noqa: E402

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)


def registered(nsbench):
    """(name, kind) of every integrator `nsbench list` names; kind from its description."""
    out = subprocess.run([nsbench, "list"], check=True, capture_output=True, text=True).stdout
    lines = out.split("\nintegrators (")[1].splitlines()[1:]  # the section title, not a wrapped line of it
    found = []
    for line in lines:
        if line.startswith("  ") and not line.startswith("    ") and line.strip():
            name, _, rest = line.strip().partition(" ")
            description = rest.strip()
            kind = "reference" if description.startswith("reference:") else "peer" if description.startswith("peer:") else "scheme"
            found.append((name, kind))
    return found


def style_key(style):
    return (style["color"], style["marker"], str(style["linestyle"]), style["markerfacecolor"])


def test_style_map(nsbench):
    names = registered(nsbench)
    check(len(names) >= 10, f"nsbench list named {len(names)} integrators")
    plugins = ["symplectic-euler", "my-plugin", "another-scheme", "x"]
    styles = {name: figures.scheme_style(name) for name, _ in names}
    styles.update({name: figures.scheme_style(name) for name in plugins})
    keys = {}
    for name, style in styles.items():
        keys.setdefault(style_key(style), []).append(name)
    for key, same in keys.items():
        check(len(same) == 1, f"one style for {same}: {key}")
    for name, kind in names:
        check(styles[name]["kind"] == kind, f"{name} is a {kind} but styled as a {styles[name]['kind']}")
        if kind == "peer" and name in figures.ENGINES:  # no scheme of ours: hollow, dotted
            check(styles[name]["markerfacecolor"] == "none" and styles[name]["linestyle"] == ":",
                  f"engine peer {name} not marked as a peer")
        elif kind == "peer":  # the colour and marker of the scheme it reimplements, hollow
            base = figures.scheme_style(name[len(figures.PEER_PREFIX):])
            check((styles[name]["color"], styles[name]["marker"]) == (base["color"], base["marker"]) and
                  styles[name]["markerfacecolor"] == "none", f"peer {name} not marked against its scheme")
        if kind == "reference":
            check(styles[name]["color"] in ("black", "0.35", "0.55"), f"reference {name} not in black or grey")
    # Stable: the same name, the same style, whatever else is drawn.
    check(figures.scheme_style("my-plugin") == figures.scheme_style("my-plugin"), "plugin style not stable")
    check(len({style_key(figures.scheme_style(f"p{i}")) for i in range(40)}) > 30, "plugin styles collide")


def test_distinct_series(nsbench):
    """20 schemes in one figure (every registered one that fits, then plugins and a study file's
    labels, whose hashed styles collide with one another): no two share colour, marker and
    fill; the registered ones keep their own styles."""
    names = [name for name, _ in registered(nsbench)][:8]
    names += ["symplectic-euler", "my-plugin", "Moreau-Jean, theta = 1/2", "Moreau-Jean, theta = 1"]
    names += [f"plugin-{i}" for i in range(20 - len(names))]
    check(len(names) == 20, f"{len(names)} series")
    spec = {"series": ["integrator"]}
    rows = [{"integrator": name} for name in names]
    styles = figures.line_styles(spec, rows)
    keys = {}
    for name in names:
        keys.setdefault((styles[name]["color"], styles[name]["marker"], styles[name]["markerfacecolor"]), []).append(name)
    for key, same in keys.items():
        check(len(same) == 1, f"series {same} share colour and marker {key}")
    for name in names:
        if figures.registered(name):
            check(styles[name] == figures.scheme_style(name), f"registered {name} restyled")
    # Without the figure's resolution the hashed styles do collide: the test above can fail.
    hashed = {(figures.scheme_style(n)["color"], figures.scheme_style(n)["marker"]) for n in names}
    check(len(hashed) < len(names), "no collision among the hashed styles: the test proves nothing")


def write_report(root):
    """A small report: a convergence table (orders 1 and 2 exact) and an energy history."""
    with open(os.path.join(root, "conv.csv"), "w") as f:
        f.write("# git_revision: test\nintegrator,dt [s],err,F_int evals\n")
        for dt in (1e-2, 5e-3, 2.5e-3, 1.25e-3):
            f.write(f"cd-lagrange,{dt},{dt},{int(1 / dt)}\n")
            f.write(f"moreau-jean,{dt},{10 * dt * dt},{int(3 / dt)}\n")
            f.write(f"siconos-moreau-jean,{dt},{10 * dt * dt},{int(3 / dt)}\n")
            f.write(f"modal-exact,{dt},1e-14,{int(1 / dt)}\n")
    with open(os.path.join(root, "hist.csv"), "w") as f:
        f.write("# git_revision: test\nintegrator,mass,t [s],E/E0\n")
        for k in range(200):
            t = k / 100
            f.write(f"cd-lagrange,lumped,{t},{1 + 1e-3 * (k % 7 - 3)}\n")
            f.write(f"cd-lagrange,singular,{t},{1 - 1e-4 * t}\n")
            f.write(f"newmark-lm,lumped,{t},{1 + 100 * t}\n")
    # Pictures of the motion: a trajectory over the exact one, a space-time field, deformed cells.
    with open(os.path.join(root, "traj.csv"), "w") as f:
        f.write("# git_revision: test\nintegrator,ball,t [s],x [m]\n")
        for k in range(101):
            t = k / 100
            for name, x in (("cd-lagrange", t), ("moreau-jean", 1.01 * t), ("exact", t)):
                f.write(f"{name},ball 1,{t},{x}\n{name},ball 2,{t},{1 - x}\n")
    with open(os.path.join(root, "field.csv"), "w") as f:
        f.write("# git_revision: test\nintegrator,mass,t,s(0.25),s(0.75)\n")
        for k in range(20):
            f.write(f"exact,,{k / 10},-1,0\n")
            f.write(f"cd-lagrange,lumped,{k / 10},{-1 + 0.3 * (-1) ** k},0.1\n")
            f.write(f"cd-lagrange,singular,{k / 10},-1,n/a\n")
    with open(os.path.join(root, "cells.csv"), "w") as f:
        f.write("# git_revision: test\nintegrator,instant,x1,y1,x2,y2,x3,y3,x4,y4,sigma_yy [Pa]\n")
        for instant, dy in (("t = 0.1", 0.1), ("t = 0.2", 0.0)):
            for i in range(2):
                f.write(f"cd-lagrange,{instant},{i},{dy},{i + 1},{dy},{i + 1},{dy + 1},{i},{dy + 1},{-1e5 * i - 1}\n")
    with open(os.path.join(root, "arrows.csv"), "w") as f:
        f.write("# git_revision: test\nintegrator,instant,x [m],y [m],Lambda_x [N s],Lambda_y [N s]\n")
        f.write("cd-lagrange,t = 0.2,0,0,0.1,2\ncd-lagrange,t = 0.2,2,0,0,1\n")
    # A verdict heat map (the properties matrix): every verdict and an unknown word (drawn as n/a).
    with open(os.path.join(root, "verdicts.csv"), "w") as f:
        f.write("# git_revision: test\nintegrator,explicit,momentum\n")
        f.write("cd-lagrange,holds,conditional\nmoreau-jean,fails,n/a\n")
    # Grouped bars (claims (1) and (6)): a bar per value of the series column, a panel per
    # problem; n/a draws no bar.
    with open(os.path.join(root, "work.csv"), "w") as f:
        f.write("# git_revision: test\nintegrator,problem,quantity,per step\n")
        f.write("cd-lagrange,bar,solves,0\nmoreau-jean,bar,solves,1\nmoreau-jean,bar,factorisations,0.01\n"
                "cd-lagrange,block,solves,0\nmoreau-jean,block,solves,n/a\n")
    specs = [
        {"id": "work", "title": "work", "csv": "work.csv", "x": "integrator", "y": "per step", "series": ["quantity"],
         "panels": ["problem"], "log_x": False, "log_y": False, "kind": "bars", "values": [], "positions": [],
         "value_label": ""},
        {"id": "traj", "title": "traj", "csv": "traj.csv", "x": "t [s]", "y": "x [m]", "series": ["integrator", "ball"],
         "panels": [], "log_x": False, "log_y": False, "small_multiples": True, "overlay": "exact"},
        {"id": "field", "title": "field", "csv": "field.csv", "x": "", "y": "t", "series": [], "panels": ["integrator", "mass"],
         "log_x": False, "log_y": False, "kind": "space_time", "values": ["s(0.25)", "s(0.75)"], "positions": [0.25, 0.75],
         "value_label": "sigma / (rho c v0)"},
        {"id": "cells", "title": "cells", "csv": "cells.csv", "x": "", "y": "sigma_yy [Pa]", "series": [],
         "panels": ["integrator", "instant"], "log_x": False, "log_y": False, "kind": "deformed",
         "values": ["x1", "y1", "x2", "y2", "x3", "y3", "x4", "y4"], "positions": [], "value_label": "sigma_yy [Pa]",
         "arrows_csv": "arrows.csv"},
        {"id": "verdicts", "title": "verdicts", "csv": "verdicts.csv", "x": "", "y": "integrator", "series": [],
         "panels": ["integrator"], "log_x": False, "log_y": False, "kind": "verdict_map", "values": ["explicit", "momentum"],
         "positions": [], "value_label": ""},
        {"id": "conv", "title": "conv", "csv": "conv.csv", "x": "dt [s]", "y": "err", "series": ["integrator"],
         "panels": [], "log_x": True, "log_y": True, "slopes": [1, 2], "small_multiples": False, "deviation": False},
        {"id": "evals", "title": "evals", "csv": "conv.csv", "x": "F_int evals", "y": "err", "series": ["integrator"],
         "panels": [], "log_x": True, "log_y": True},
        {"id": "hist", "title": "hist", "csv": "hist.csv", "x": "t [s]", "y": "E/E0", "series": ["integrator"],
         "panels": ["mass"], "log_x": False, "log_y": False, "slopes": [], "small_multiples": True, "deviation": True},
    ]
    with open(os.path.join(root, "figures.json"), "w") as f:
        json.dump(specs, f)


def test_figures():
    import matplotlib.pyplot as plt
    with tempfile.TemporaryDirectory() as root:
        write_report(root)
        script = os.path.join(os.path.dirname(figures.__file__), "figures.py")
        # One process or several: the same bytes (PNG and PDF, which carries no creation date);
        # the screen look drawn by default and by --style screen. These two drawings are the
        # screen look checked below (drawing it once more would check the same files).
        drawn = {}
        for jobs, style in (("1", []), ("3", ["--style", "screen"])):
            subprocess.run(["/usr/bin/python3", script, root] + style, check=True, capture_output=True,
                           env=dict(os.environ, NSBENCH_JOBS=jobs))
            drawn[jobs] = {name: open(os.path.join(root, "figures", name), "rb").read()
                           for name in sorted(os.listdir(os.path.join(root, "figures"))) if name.endswith((".png", ".pdf"))}
        check(len(drawn["1"]) == 16 and drawn["1"] == drawn["3"], "figures differ between 1 and 3 processes")
        subprocess.run(["/usr/bin/python3", script, root, "--style", "paper"], check=True, capture_output=True)
        for style, sub in (("screen", "figures"), ("paper", os.path.join("figures", "paper"))):
            for fid in ("conv", "evals", "hist", "traj", "field", "cells", "verdicts", "work"):
                for ext in ("png", "pdf"):
                    path = os.path.join(root, sub, f"{fid}.{ext}")
                    check(os.path.getsize(path) > 1000, f"{path} missing or empty")
            with open(os.path.join(root, sub, "conv.pdf"), "rb") as f:
                pdf = f.read()
            check(b"/Type3" not in pdf and b"/FontFile2" in pdf, f"{style}: fonts not embedded as TrueType")
        bad = subprocess.run(["/usr/bin/python3", script, root, "--only", "nope"], capture_output=True, text=True)
        check(bad.returncode != 0 and "--only nope" in bad.stderr, "an unknown --only id is not one clear error")
        for jobs in ("0", "two"):
            bad = subprocess.run(["/usr/bin/python3", script, root], capture_output=True, text=True,
                                 env=dict(os.environ, NSBENCH_JOBS=jobs))
            check(bad.returncode != 0 and f"NSBENCH_JOBS='{jobs}'" in bad.stderr, f"NSBENCH_JOBS={jobs} is not one clear error")
    # Log ticks: an axis of F_int evaluations over less than two decades shows several labels.
    fig, ax = plt.subplots()
    ax.set_xscale("log")
    ax.set_xlim(300, 20000)
    fig.canvas.draw()
    figures.log_tick_labels(ax.xaxis)
    fig.canvas.draw()
    labels = [t.get_text() for t in ax.xaxis.get_ticklabels() if t.get_text() and 300 <= t.get_position()[0] <= 20000]
    check(len(labels) >= 4, f"log axis over 1.8 decades labelled {labels}")
    check(not figures.tick_labels_overlap(ax.xaxis), f"log axis labels {labels} overlap on a wide panel")
    plt.close(fig)
    # Issue 57, item 7: on a narrow panel (a paper figure's) the 1-2-5 labels overlapped; fewer
    # are labelled there, none overlapping, on either axis.
    fig, ax = plt.subplots(figsize=(1.6, 1.2))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(300, 20000)
    ax.set_ylim(2e-6, 3e-4)
    fig.canvas.draw()
    for axis in (ax.xaxis, ax.yaxis):
        figures.log_tick_labels(axis)
        lo, hi = sorted(axis.get_view_interval())
        drawn = [t.get_text() for x, t in zip(axis.get_majorticklocs(), axis.get_majorticklabels()) if t.get_text() and lo <= x <= hi]
        check(not figures.tick_labels_overlap(axis), f"log axis labels {drawn} overlap on a narrow panel")
        check(len(drawn) >= 2, f"a narrow log axis kept {drawn}")
    plt.close(fig)
    # Small multiples: one panel per scheme, the mass models lines within it, deviations signed.
    spec = {"x": "t [s]", "y": "E/E0", "series": ["integrator"], "panels": ["mass"], "log_x": False, "log_y": False,
            "small_multiples": True, "deviation": True}
    rows = [{"integrator": "a", "mass": "m1", "t [s]": "0", "E/E0": "0.5"},
            {"integrator": "a", "mass": "m2", "t [s]": "0", "E/E0": "1.5"},
            {"integrator": "b", "mass": "m1", "t [s]": "0", "E/E0": "1"}]
    panels = figures.panel_lines(spec, rows)
    check(sorted(panels) == [("a",), ("b",)], f"panels {sorted(panels)}")
    # An overlay (the exact solution) is no panel of its own but a line in every panel.
    over = dict(spec, deviation=False, overlay="exact")
    overlaid = figures.panel_lines(over, rows + [{"integrator": "exact", "mass": "m1", "t [s]": "0", "E/E0": "1"}])
    check(sorted(overlaid) == [("a",), ("b",)], f"overlay panels {sorted(overlaid)}")
    check(all(any(line["overlay"] for line in lines.values()) for lines in overlaid.values()), "overlay not in every panel")
    # Space-time grids: the exact solution (no mass model) heads its column; the colour scale is
    # diverging and centred on 0 for signed values, its limit at a high percentile of |value|.
    where, nrows, ncols = figures.panel_grid([("exact", ""), ("s", "lumped"), ("s", "singular")])
    check((where[("exact", "")], where[("s", "singular")], nrows, ncols) == ((0, 0), (1, 1), 2, 2), f"grid {where}")
    cmap, lo, hi, extend = figures.colour_scale([-1.0] * 2000 + [0.5, 40.0])
    check(cmap == "RdBu_r" and lo == -hi and hi == 1.0 and extend == "both", f"colour scale {cmap} {lo} {hi} {extend}")
    check(sorted(line["pts"][0][1] for line in panels[("a",)].values()) == [-0.5, 0.5], "deviation not signed")
    # Bars: one per value of the series column, a group per category, a panel per problem; a
    # cell that is no number is no bar, a category with none in a panel no group; order kept.
    spec = {"x": "integrator", "y": "n", "series": ["contact"], "panels": ["problem"]}
    rows = [{"integrator": "b", "problem": "bar", "contact": "floor", "n": "0"},
            {"integrator": "a", "problem": "bar", "contact": "floor", "n": "1"},
            {"integrator": "a", "problem": "bar", "contact": "blocks", "n": "14.7"},
            {"integrator": "b", "problem": "block", "contact": "floor", "n": "n/a"},
            {"integrator": "a", "problem": "block", "contact": "floor", "n": "3"}]
    groups = figures.bar_groups(spec, rows)
    check(groups == {("bar",): {"b": {"floor": 0.0}, "a": {"floor": 1.0, "blocks": 14.7}}, ("block",): {"a": {"floor": 3.0}}},
          f"bars {groups}")
    check(list(groups[("bar",)]) == ["b", "a"], "bar categories not in the table's order")

def test_shared_mathtext():
    """share_mathtext_layouts: log axes' tick labels (mathtext) parsed once for every renderer,
    the same bytes drawn as with matplotlib's per-renderer caches."""
    from matplotlib import mathtext
    with tempfile.TemporaryDirectory() as root:
        write_report(root)
        with open(os.path.join(root, "figures.json")) as f:
            specs = [s for s in json.load(f) if s["id"] in ("conv", "evals")]

        def drawn():
            for spec in specs:
                figures.draw_one((spec, root, False))
            return {name: open(os.path.join(root, "figures", name), "rb").read()
                    for name in sorted(os.listdir(os.path.join(root, "figures")))}
        own = drawn()
        before = mathtext.MathTextParser._parse_cached
        figures.share_mathtext_layouts()
        check(mathtext.MathTextParser._parse_cached is not before, "mathtext layouts not shared (matplotlib changed?)")
        shared = drawn()
        check(len(own) == 4 and own == shared, "shared mathtext layouts draw other bytes")


def test_damaged_inputs():
    """Issue 56: a figure id './../../x' wrote outside the report, an absolute csv read any file,
    and every damaged input ended in a traceback: now one line naming the file and the key."""
    with tempfile.TemporaryDirectory() as top:
        root = os.path.join(top, "a", "report")
        os.makedirs(root)
        write_report(root)
        script = os.path.join(os.path.dirname(figures.__file__), "figures.py")
        with open(os.path.join(root, "figures.json")) as f:
            good = json.load(f)
        conv = next(s for s in good if s["id"] == "conv")
        damages = [
            ([dict(conv, id="./../../escaped_fig")], "id './../../escaped_fig' is not a file name"),
            ([dict(conv, csv="/etc/passwd")], "csv '/etc/passwd' is outside the report"),
            ([dict(conv, csv="../../x.csv")], "csv '../../x.csv' is outside the report"),
            ([dict(conv, csv="missing.csv")], "figure 'conv': cannot read"),
            ([dict(conv, y="no such column")], "figure 'conv': its entry or its table conv.csv has no key or column"),
            ([dict(conv, id=5)], "figure 0: key 'id' missing or not a string"),
            ({"id": "conv"}, "expected a list of figures"),
            ("[{", "not JSON"),
        ]
        for figures_json, expected in damages:
            with open(os.path.join(root, "figures.json"), "w") as f:
                f.write(figures_json if isinstance(figures_json, str) else json.dumps(figures_json))
            r = subprocess.run(["/usr/bin/python3", script, root], capture_output=True, text=True)
            check(r.returncode != 0 and expected in r.stderr and r.stderr.count("\n") == 1 and "Traceback" not in r.stderr,
                  f"{expected}: exit {r.returncode}, stderr {r.stderr!r}")
        check(not any(name.startswith("escaped") for name in os.listdir(top)), "a figure was written outside the report")


if __name__ == "__main__":
    test_style_map(sys.argv[1])
    test_distinct_series(sys.argv[1])
    test_figures()
    test_shared_mathtext()
    test_damaged_inputs()
    for f in failures:
        print("FAILED:", f)
    print(f"figures_test: {len(failures)} failures")
    sys.exit(1 if failures else 0)
