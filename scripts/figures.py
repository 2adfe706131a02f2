#!/usr/bin/python3
"""Renders the figures declared by the studies (REPORTS/figures.json) from their CSV tables.

    python3 scripts/figures.py REPORTS [--style paper] [--only ID]
    nsbench-figures REPORTS ...    (the same script, installed with nsbench)

Writes REPORTS/figures/<id>.png and .pdf, each stamped with the revision and build read from
the CSV's '#' metadata lines; --style paper writes REPORTS/figures/paper/<id>.png and .pdf
without title or stamp, at a journal column's width. Rows whose x is not a number (n/a, diverged) are skipped; where
y is not a number (or not positive on a log scale) the line has a gap. A scheme keeps its colour,
marker and dashes in every panel, figure and report (scheme_style); one legend, outside the
panels, says which is which. A line labelled 'exact' is the reference: black, dashed, drawn
over the others. Convergence plots carry slope triangles, energy histories are small
multiples of the signed deviation, one panel per scheme (figures.json says which).
"""
import argparse
import csv
import json
import math
import multiprocessing
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.axis  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402


def read_table(path):
    meta, lines = {}, []
    with open(path, newline="") as f:
        for line in f:
            if line.startswith("# "):
                key, _, value = line[2:].partition(": ")
                meta[key] = value.strip()
            else:
                lines.append(line)
    return meta, list(csv.DictReader(lines))


def number(text):
    try:
        v = float(text)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def short(column):
    """A column's name without its unit."""
    return column.split(" [")[0]


def label(row, columns):
    """A line's legend entry: its series values (the legend's title names the columns)."""
    return ", ".join(row[c] for c in columns)


# One style per scheme, defined here once and used by every figure of every report: colour
# (Okabe & Ito's colour-blind-safe palette, black kept for the references), marker and dash
# pattern. The registered schemes have fixed entries; any other name (a plugin, a study file's
# label) gets one of the remaining combinations from a hash of its name, so its style too is
# the same in every figure and report, unless it would share colour and marker with another
# series of the same figure: then it takes the first pair no series there has (line_styles).
# References are black or grey with crosses; a peer (siconos-*) takes the colour and marker of
# the scheme it reimplements, hollow and dotted, so the two curves are told apart where they
# lie on each other.
PALETTE = ["#D55E00", "#0072B2", "#009E73", "#E69F00", "#CC79A7", "#56B4E9"]
MARKERS = ["o", "s", "^", "D", "v", "P", "X", "<", ">"]
DASHES = ["-", "--", "-.", (0, (5, 1.5, 1, 1.5, 1, 1.5))]
# Lines within one scheme's panel (small multiples): its variants, its mass models.
INNER_DASHES = ["-", "--", "-.", ":", (0, (5, 1.5, 1, 1.5, 1, 1.5)), (0, (8, 2)), (0, (1, 3)), (0, (3, 1, 1, 1))]
SCHEMES = ["cd-lagrange", "moreau-jean", "schatzman-paoli", "nsga", "d1-minus-linear", "newmark-lm",
           "cd-penalty", "cd-lagrange-adaptive", "central-difference", "symplectic-euler"]
REFERENCES = {"exact": ("black", None, "--"), "modal-exact": ("black", "x", "--"),
              "event-driven": ("0.35", "+", (0, (1, 1))), "penalty-bdf": ("0.55", "1", "-.")}
PEER_PREFIX = "siconos-"
# Physics engines run as peers of no scheme of ours (their own contact models): hollow and
# dotted like the Siconos peers, on colours and markers of their own.
ENGINES = ["mujoco", "bullet", "ode"]

# Every (colour, marker) pair, 6 x 9 = 54: first the 18 that colours and markers cycling
# together give (the registered schemes' and engines' styles), then the others, the colour
# changing at each.
_CYCLED = [(i % len(PALETTE), i % len(MARKERS)) for i in range(math.lcm(len(PALETTE), len(MARKERS)))]
PAIRS = _CYCLED + [(c, (c + d) % len(MARKERS)) for d in range(len(MARKERS)) for c in range(len(PALETTE))
                   if (c, (c + d) % len(MARKERS)) not in _CYCLED]
FIXED = len(SCHEMES) + len(ENGINES)  # the pairs the registered names hold


def combination(i):
    """The i-th (colour, marker, dashes): the i-th pair of PAIRS (no two of the first 54 share
    colour and marker), the dashes changing every 6."""
    c, m = PAIRS[i % len(PAIRS)]
    return PALETTE[c], MARKERS[m], DASHES[(i // len(PALETTE)) % len(DASHES)]


def name_hash(name):
    """A stable hash (not Python's salted hash())."""
    h = 0
    for ch in name.encode():
        h = (h * 131 + ch) % 1000003
    return h


def scheme_style(name):
    """{color, marker, linestyle, markerfacecolor, kind} of an integrator's name."""
    if name in REFERENCES:
        color, marker, dashes = REFERENCES[name]
        return {"color": color, "marker": marker, "linestyle": dashes, "markerfacecolor": color, "kind": "reference"}
    if name.startswith(PEER_PREFIX) and name != PEER_PREFIX:
        base = scheme_style(name[len(PEER_PREFIX):])
        return {**base, "linestyle": ":", "markerfacecolor": "none", "kind": "peer"}
    if name in ENGINES:
        color, marker, _ = combination(len(SCHEMES) + ENGINES.index(name))
        return {"color": color, "marker": marker, "linestyle": ":", "markerfacecolor": "none", "kind": "peer"}
    if name in SCHEMES:
        color, marker, dashes = combination(SCHEMES.index(name))
    else:  # a plugin: the hash picks a pair the registered names do not hold, and dashes
        h = name_hash(name)
        free = len(PAIRS) - FIXED
        color, marker, _ = combination(FIXED + h % free)
        dashes = DASHES[(h // free) % len(DASHES)]
    return {"color": color, "marker": marker, "linestyle": dashes, "markerfacecolor": color, "kind": "scheme"}


def registered(name):
    """True for a name whose style is fixed (a built-in scheme, peer, engine or reference)."""
    base = name[len(PEER_PREFIX):] if name.startswith(PEER_PREFIX) else name
    return base in REFERENCES or base in SCHEMES or base in ENGINES


def distinct(styles):
    """The schemes' styles of one figure ({name: style}), none sharing colour, marker and fill
    with another: the registered names keep theirs, every other name that would share them with
    a name before it (registered names first, then the others in order) takes the first pair
    of PAIRS no name of the figure has (past 54 names in one figure, pairs repeat)."""
    def key(style):
        return style["color"], style["marker"], style["markerfacecolor"]
    order = [n for n in styles if registered(n)] + [n for n in styles if not registered(n)]
    taken, out = set(), {}
    for name in order:
        style = styles[name]
        if key(style) in taken and not registered(name):
            free = [(c, m) for c, m, _ in map(combination, range(len(PAIRS))) if (c, m, c) not in taken]
            if free:
                style = {**style, "color": free[0][0], "marker": free[0][1], "markerfacecolor": free[0][0]}
        taken.add(key(style))
        out[name] = style
    return {name: out[name] for name in styles}


def line_styles(spec, rows):
    """The style of each line label of a figure. With an 'integrator' series column a line has
    its scheme's style (distinct() among the figure's schemes); the other series columns (mass,
    variant) change its dashes, in the table's order. Without one (lines by mass, say), lines
    are styled by their order in the table."""
    series = spec["series"]
    labels = list(dict.fromkeys(label(row, series) for row in rows))
    if "integrator" not in series:
        return {name: ({**scheme_style(name), "linestyle": "--"} if name in REFERENCES else
                       dict(zip(("color", "marker", "linestyle"), combination(i)), kind="scheme"))
                for i, name in enumerate(labels)}
    k = series.index("integrator")
    others = list(dict.fromkeys(tuple(v for j, v in enumerate(row_values(row, series)) if j != k) for row in rows))
    schemes = distinct({name: scheme_style(name) for name in dict.fromkeys(row_values(row, series)[k] for row in rows)})
    styles = {}
    for row in rows:
        values = row_values(row, series)
        style = schemes[values[k]]
        if len(others) > 1:  # a reference's mass models too: lumped, consistent, singular told apart
            style = {**style, "linestyle": DASHES[others.index(tuple(v for j, v in enumerate(values) if j != k)) % len(DASHES)]}
        styles[label(row, series)] = style
    return styles


def row_values(row, columns):
    return [row[c] for c in columns]


# matplotlib's log scales overflow (limits, tick locations) near the largest double, which a
# blowing-up energy reaches: larger values are left out of a log axis, as if not numbers.
LOG_MAX = 1e200


def log_limits(values):
    """Axis limits with matplotlib's 5% margins, taken in log space (no overflow)."""
    lo, hi = math.log10(min(values)), math.log10(max(values))
    pad = max(0.05 * (hi - lo), 0.05)  # at least 12%: a near-constant line is not a tick-less sliver
    return 10.0 ** (lo - pad), 10.0 ** (hi + pad)


def panel_lines(spec, rows):
    """The points of each line of each panel: {panel key: {label: [(x, y)]}}, x sorted. A row
    without a usable x is left out; one without a usable y is a gap (NaN) in its line. Lines
    with nothing to draw are left out. Small multiples: one panel per scheme (the first series
    column), its lines told apart by the other series and panel columns."""
    panels = {}
    series, panel_columns = spec["series"], spec["panels"]
    if spec.get("small_multiples"):
        series, panel_columns = series[:1], []
    inner = [c for c in spec["series"] + spec["panels"] if c not in series + panel_columns]
    overlay = spec.get("overlay") if spec.get("small_multiples") else None
    overlaid = {}  # the overlay's lines (the exact solution), drawn in every panel
    for row in rows:
        x, y = number(row[spec["x"]]), number(row[spec["y"]])
        if y is not None and spec.get("deviation"):
            y -= 1.0
        if x is None or (spec["log_x"] and not 0 < x <= LOG_MAX):
            continue
        if y is None or (spec["log_y"] and not 0 < y <= LOG_MAX) or abs(y) > LOG_MAX:
            y = math.nan  # nothing to draw here: a gap in a history, not a line across it
        key = tuple(row[c] for c in (series if spec.get("small_multiples") else panel_columns))
        lines = overlaid if overlay and key == (overlay,) else panels.setdefault(key, {})
        name = label(row, spec["series"] + inner)  # a line per inner value too (lumped, singular)
        lines.setdefault(name, {"style": label(row, spec["series"]), "inner": label(row, inner), "pts": [],
                                "overlay": lines is overlaid})["pts"].append((x, y))
    for lines in panels.values():
        lines.update(overlaid)
    return {key: {name: {**line, "pts": sorted(line["pts"])} for name, line in lines.items()
                  if any(not math.isnan(y) for _, y in line["pts"])}
            for key, lines in panels.items()}


def log_tick_labels(axis):
    """At least three labelled ticks on a log axis where they fit: 1-2-5 (or every integer)
    multiples of each decade when the axis spans too few decades for the decades alone, fewer
    (1-3, then the decades) where those labels would overlap (a narrow panel of a paper figure)."""
    lo, hi = axis.get_view_interval()
    decades = math.log10(hi) - math.log10(lo)
    if decades >= 3:
        return
    choices = ([tuple(float(k) for k in range(1, 10))] if decades < 1 else []) + [(1.0, 2.0, 5.0), (1.0, 3.0), (1.0,)]
    for subs in choices:
        axis.set_major_locator(ticker.LogLocator(base=10, subs=subs))
        axis.set_major_formatter(ticker.LogFormatterSciNotation(labelOnlyBase=False, minor_thresholds=(10, 10)))
        axis.set_minor_formatter(ticker.NullFormatter())
        if not tick_labels_overlap(axis):
            return


def tick_labels_overlap(axis):
    """Whether two of the axis' visible major tick labels overlap, as drawn."""
    figure = axis.figure
    figure.canvas.draw()
    renderer = figure.canvas.get_renderer()
    lo, hi = sorted(axis.get_view_interval())
    horizontal = isinstance(axis, matplotlib.axis.XAxis)
    boxes = sorted((label.get_window_extent(renderer) for tick, label in zip(axis.get_majorticklocs(), axis.get_majorticklabels())
                    if label.get_visible() and label.get_text() and lo <= tick <= hi),
                   key=lambda b: b.x0 if horizontal else b.y0)
    gap = 2.0  # pixels between two labels, at least
    return any((a.x1 + gap > b.x0) if horizontal else (a.y1 + gap > b.y0) for a, b in zip(boxes, boxes[1:]))


def slope_triangles(ax, slopes, drawn, paper):
    """Reference triangles of slope p (y ~ x^p) under the lowest data of a log-log panel, at the
    right of its x range, each one third of a decade... of the panel's x range wide."""
    xs, ys = [p[0] for p in drawn], [p[1] for p in drawn]
    lx0, lx1 = math.log10(min(xs)), math.log10(max(xs))
    ly0 = math.log10(min(ys))
    width = max((lx1 - lx0) / 4, 0.15)
    for i, p in enumerate(sorted(slopes, key=abs)):
        # p > 0 (against dt): triangle at the left end; p < 0 (against N): at the right end.
        a = lx0 + (0.15 + 0.35 * i) * (lx1 - lx0) if p > 0 else lx1 - (0.15 + 0.35 * i) * (lx1 - lx0) - width
        b = a + width
        base = ly0 + 0.2 if p > 0 else ly0 + 0.2 + abs(p) * width
        corner = (b, base) if p > 0 else (a, base)
        xs3 = [10 ** a, 10 ** b, 10 ** corner[0], 10 ** a]
        ys3 = [10 ** base, 10 ** (base + p * width), 10 ** base, 10 ** base] if p > 0 else \
              [10 ** base, 10 ** (base + p * width), 10 ** (base + p * width), 10 ** base]
        ax.plot(xs3, ys3, color="0.3", linewidth=0.8, zorder=1)
        ax.text(10 ** (b + 0.02 * width) if p > 0 else 10 ** (a - 0.02 * width),
                10 ** (base + p * width / 2), f"{abs(p):g}", fontsize=6 if paper else 8, color="0.3",
                ha="left" if p > 0 else "right", va="center")


def symlog_threshold(panels):
    """Shared signed axes over schemes whose deviations differ by orders of magnitude (one
    blows up to 1e3, another stays at 1e-6) would show all but one as a flat zero: past a ratio
    of 1e3 the axis is symmetric-logarithmic, linear below the 10th percentile of |y| (None:
    a linear axis is readable)."""
    values = sorted(abs(y) for lines in panels.values() for line in lines.values()
                    for _, y in line["pts"] if not math.isnan(y) and y != 0)
    if not values or values[-1] <= 1e3 * values[len(values) // 2]:
        return None
    return max(values[len(values) // 10], 1e-12)


def draw(spec, reports, paper=False):
    meta, rows = read_table(os.path.join(reports, spec["csv"]))
    panels = panel_lines(spec, rows)
    # Styles follow the integrator's name (scheme_style): a scheme looks the same in every
    # figure of every report. The legend lists the lines drawn.
    styles = line_styles(spec, rows)
    multiples = bool(spec.get("small_multiples"))
    inner_dashes = {}
    if multiples:  # within a scheme's panel, its lines differ by dashes, the same in every panel
        inner = dict.fromkeys(line["inner"] for lines in panels.values() for line in lines.values())
        inner_dashes = {name: INNER_DASHES[i % len(INNER_DASHES)] for i, name in enumerate(inner)}
    names = list(dict.fromkeys(name for lines in panels.values() for name in lines))
    n = len(panels)
    cols = min(n, 4 if multiples else 3)
    nrows = math.ceil(n / cols)
    if paper:  # a journal's column (3.4 in) for one panel, its page width (7 in) for several
        width = 3.4 if n == 1 else 7.0
        size = (width, (2.4 if n == 1 else width / cols * (0.62 if multiples else 0.8)) * nrows + 0.3)
    else:
        size = (4.6 * cols, (2.6 if multiples else 3.6) * nrows + 0.5)
    fig, axes = plt.subplots(nrows, cols, figsize=size, squeeze=False, layout="constrained",
                             sharex=multiples, sharey=multiples)
    handles = {}
    # A trajectory against the exact one (an overlay) reads on linear axes.
    linthresh = symlog_threshold(panels) if multiples and not spec["log_y"] and not spec.get("overlay") else None
    y_name = f"{spec['y']} − 1" if spec.get("deviation") else spec["y"]
    for ax, (key, lines) in zip(axes.flat, panels.items()):
        drawn = []
        for name, line in lines.items():
            pts = line["pts"]
            ys = [p[1] for p in pts]
            # Histories (dense) are lines, markers would hide them, but a point between two gaps
            # has no line to be drawn with: it gets a dot.
            dense = len(pts) > 50
            alone = [i for i, y in enumerate(ys) if not math.isnan(y) and
                     (i == 0 or math.isnan(ys[i - 1])) and (i + 1 == len(ys) or math.isnan(ys[i + 1]))]
            style = {k: v for k, v in styles[line["style"]].items() if k != "kind"}
            marker = style.pop("marker")
            face = style.pop("markerfacecolor", style["color"])
            if line.get("overlay"):  # the exact solution over the scheme's lines: thin, black, dotted
                style.update(color="black", linestyle=(0, (1.5, 1.5)))
            elif multiples:
                style["linestyle"] = inner_dashes[line["inner"]]
            size_m = 2.5 if paper else 3.5
            marks = ({"marker": ".", "markersize": 3, "markevery": alone} if dense else
                     {"marker": marker or "o", "markersize": size_m, "markerfacecolor": face})
            width_l = (0.8 if paper else 1.2) * (0.75 if line.get("overlay") else 1.0)
            ax.plot([p[0] for p in pts], ys, **marks, **{"linewidth": width_l, **style},
                    zorder=3 if styles[line["style"]]["kind"] == "reference" else 2)
            entry = spec["overlay"] if line.get("overlay") else line["inner"] if multiples else name
            if entry not in handles and line.get("overlay"):
                handles[entry] = Line2D([], [], color="black", linestyle=style["linestyle"], linewidth=width_l)
            elif entry not in handles and multiples:  # the panels say the scheme, the legend the dashes
                handles[entry] = Line2D([], [], color="0.3", linestyle=style["linestyle"], linewidth=width_l)
            elif entry not in handles:
                handles[entry] = Line2D([], [], marker=None if dense else (marker or "o"), markersize=size_m,
                                        markerfacecolor=face, **{"linewidth": width_l, **style})
            drawn += [p for p in pts if not math.isnan(p[1])]
        if not lines:
            ax.text(0.5, 0.5, "nothing to draw\n(no positive values)" if spec["log_y"] else "nothing to draw",
                    ha="center", va="center", transform=ax.transAxes, color="0.4")
        ax.set_xscale("log" if spec["log_x"] else "linear")
        if linthresh:
            ax.set_yscale("symlog", linthresh=linthresh, linscale=1.0)
            # At most about six labelled decades a side: every 10th, 100th... power past that.
            top = max(abs(y) for lines_ in panels.values() for line_ in lines_.values() for _, y in line_["pts"]
                      if not math.isnan(y))
            step = 10 ** max(1, math.ceil(math.log10(top / linthresh) / 6))
            ax.yaxis.set_major_locator(ticker.SymmetricalLogLocator(linthresh=linthresh, base=step))
        else:
            ax.set_yscale("log" if spec["log_y"] else "linear")
        if drawn and spec["log_x"] and not multiples:
            ax.set_xlim(*log_limits([p[0] for p in drawn]))
        if drawn and spec["log_y"] and not multiples:
            ax.set_ylim(*log_limits([p[1] for p in drawn]))
        if drawn and spec["log_x"] and spec["log_y"] and spec.get("slopes"):
            slope_triangles(ax, spec["slopes"], drawn, paper)
        if spec.get("deviation") or multiples:
            ax.axhline(0.0, color="0.5", linewidth=0.6, zorder=1)
        for axis, log in ((ax.xaxis, spec["log_x"]), (ax.yaxis, spec["log_y"])):
            if not log and hasattr(axis.get_major_formatter(), "set_useOffset"):
                axis.get_major_formatter().set_useOffset(False)  # plain values, no "1e-6 + 0.99999"
        if not multiples or ax in axes[-1]:
            ax.set_xlabel(spec["x"])
        if not multiples or ax is axes[ax.get_subplotspec().rowspan.start][0]:
            ax.set_ylabel(y_name + (" (symlog)" if linthresh else ""))
        title = ", ".join(key) if multiples else ", ".join(f"{short(c)} = {v}" for c, v in zip(spec["panels"], key))
        if title:
            ax.set_title(title, fontsize=7 if paper else 10)
        ax.grid(True, which="major", alpha=0.4)
        ax.grid(True, which="minor", alpha=0.12)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fig.canvas.draw()  # the limits settle before the log ticks are chosen
    for ax in list(axes.flat)[:n]:
        for axis, log in ((ax.xaxis, spec["log_x"]), (ax.yaxis, spec["log_y"])):
            if log:
                log_tick_labels(axis)
    if not paper:
        fig.suptitle(spec["title"], fontsize=12)
    # One legend for every panel, outside the data: right of a single panel, below several.
    legend_columns = [c for c in spec["series"] + spec["panels"] if c != spec["series"][0]] if multiples else spec["series"]
    title = ", ".join(short(c) for c in legend_columns)
    entries = [e for e in handles if e]  # a scheme's only line needs no entry: its panel's title names it
    legend = None
    font = 6 if paper else 8
    if not entries:
        pass
    elif n == 1:
        legend = fig.legend([handles[e] for e in entries], entries, title=title, loc="center left",
                            bbox_to_anchor=(1.0, 0.5), fontsize=font, title_fontsize=font, frameon=False)
    else:  # in as many columns as fit in the figure's width
        for ncol in range(max(len(entries), 1), 0, -1):
            legend = fig.legend([handles[e] for e in entries], entries, title=title, loc="upper center",
                                bbox_to_anchor=(0.5, 0.0), ncol=ncol, fontsize=font, title_fontsize=font, frameon=False)
            if ncol == 1 or legend.get_window_extent(fig.canvas.get_renderer()).width <= fig.bbox.width:
                break
            legend.remove()
    save(fig, spec, meta, reports, paper, legend)


def panel_grid(keys):
    """Where each panel goes: (row, column) of a grid whose columns are the first panel column's
    values and rows the second's, in the table's order; a key whose second value is empty (the
    exact solution, the same for every mass model) takes the top row of its column."""
    columns = list(dict.fromkeys(k[0] for k in keys))
    rows = list(dict.fromkeys(k[1] for k in keys if len(k) > 1 and k[1])) or [""]
    return {k: (rows.index(k[1]) if len(k) > 1 and k[1] else 0, columns.index(k[0])) for k in keys}, len(rows), len(columns)


def colour_scale(values, reference=()):
    """A colour map and its limits for values: a diverging map (ColorBrewer RdBu, colour-blind
    safe) centred on 0 when the values take both signs, a sequential one (viridis) otherwise.
    The limit: 1.5 times the reference's largest |value| when there is a reference (the exact
    solution: a scheme that blows up is drawn saturated, not the others washed out), else the
    99.9th percentile of |value|; the colour bar's arrows say when some values lie beyond."""
    finite = sorted(abs(v) for v in values if v is not None)
    if not finite:
        return "RdBu_r", -1.0, 1.0, "neither"
    ref = [abs(v) for v in reference if v is not None]
    limit = (1.5 * max(ref) if ref and max(ref) > 0 else finite[min(len(finite) - 1, int(0.999 * len(finite)))]) or 1.0
    beyond = finite[-1] > limit
    if any(v is not None and v < 0 for v in values) and any(v is not None and v > 0 for v in values):
        return "RdBu_r", -limit, limit, "both" if beyond else "neither"
    if all(v is None or v <= 0 for v in values):
        return "viridis_r", -limit, 0.0, "min" if beyond else "neither"
    return "viridis", 0.0, limit, "max" if beyond else "neither"


def grid_figure(keys, paper, panel_size, labels):
    """The figure and axes of a grid of panels (panel_grid), shared axes labelled (x, y) =
    labels, unused cells hidden."""
    where, nrows, ncols = panel_grid(keys)
    w, h = panel_size
    scale = min(1.0, 7.0 / (w * ncols)) if paper else 1.0  # a page's width at most
    fig, axes = plt.subplots(nrows, ncols, figsize=(w * ncols * scale + 0.9, h * nrows * scale + 0.5), squeeze=False,
                             layout="constrained", sharex=True, sharey=True)
    used = set(where.values())
    for r in range(nrows):
        for c in range(ncols):
            if (r, c) not in used:
                axes[r][c].set_visible(False)
    # Shared axes label only the outer panels: a panel over an empty cell, or the first of its
    # row, shows its own.
    for r, c in used:
        ax = axes[r][c]
        if all((below, c) not in used for below in range(r + 1, nrows)):
            ax.tick_params(labelbottom=True)
            ax.set_xlabel(labels[0])
        if all((r, left) not in used for left in range(c)):
            ax.tick_params(labelleft=True)
            ax.set_ylabel(labels[1])
    return fig, axes, where


def finish_coloured(fig, axes, mappable, extend, spec, meta, reports, paper):
    """One colour bar for every panel (none when no panel drew), the title, then save."""
    if mappable is not None:
        bar = fig.colorbar(mappable, ax=axes.ravel().tolist(), extend=extend, shrink=0.9, pad=0.02)
        bar.set_label(spec.get("value_label", ""))
    if not paper:
        fig.suptitle(spec["title"], fontsize=12)
    save(fig, spec, meta, reports, paper)


def draw_space_time(spec, reports, paper=False):
    """A field over position (horizontal) and time (vertical), one panel per scheme and mass
    model, on one colour scale (colour_scale): spec's `values` columns at `positions`, time in
    column `y`. A panel whose run has no row (declined, diverged) says so."""
    meta, rows = read_table(os.path.join(reports, spec["csv"]))
    keys = list(dict.fromkeys(tuple(row[c] for c in spec["panels"]) for row in rows))
    data = {}
    for row in rows:
        t = number(row[spec["y"]])
        if t is not None:
            data.setdefault(tuple(row[c] for c in spec["panels"]), []).append((t, [number(row[c]) for c in spec["values"]]))
    cmap, vmin, vmax, extend = colour_scale([v for series in data.values() for _, vs in series for v in vs],
                                            [v for key, series in data.items() if key[0] in REFERENCES
                                             for _, vs in series for v in vs])
    fig, axes, where = grid_figure(keys, paper, (1.15, 1.7) if paper else (2.3, 3.2), ("x", spec["y"]))
    xs = spec["positions"]
    mesh = None
    for key in keys:
        r, c = where[key]
        ax = axes[r][c]
        series = sorted(data.get(key, []), key=lambda p: p[0])
        if series:
            ts = [t for t, _ in series]
            z = [[math.nan if v is None else v for v in vs] for _, vs in series]
            mesh = ax.pcolormesh(xs, ts, z, cmap=cmap, vmin=vmin, vmax=vmax, shading="nearest", rasterized=True)
        else:
            ax.text(0.5, 0.5, "no run", ha="center", va="center", transform=ax.transAxes, color="0.4")
        ax.set_title("\n".join(k for k in key if k), fontsize=7 if paper else 9)  # narrow panels: a line each
    finish_coloured(fig, axes, mesh, extend, spec, meta, reports, paper)


def draw_deformed(spec, reports, paper=False):
    """Deformed quadrilateral cells (corners in spec's `values` columns) coloured by column `y`
    on one colour scale, one panel per value of the panel columns (scheme, instant), with the
    contact impulses of the `arrows_csv` table as arrows, all scaled by the largest impulse."""
    from matplotlib.collections import PolyCollection
    meta, rows = read_table(os.path.join(reports, spec["csv"]))
    keys = list(dict.fromkeys(tuple(row[c] for c in spec["panels"]) for row in rows))
    cells = {}
    for row in rows:
        corners = [number(row[c]) for c in spec["values"]]
        if None not in corners:
            cells.setdefault(tuple(row[c] for c in spec["panels"]), []).append(
                (list(zip(corners[0::2], corners[1::2])), number(row[spec["y"]])))
    arrows = {}
    if spec.get("arrows_csv"):
        _, arrow_rows = read_table(os.path.join(reports, spec["arrows_csv"]))
        for row in arrow_rows:
            x, y, ax_, ay = (number(row[c]) for c in list(row)[len(spec["panels"]):len(spec["panels"]) + 4])
            if None not in (x, y, ax_, ay):
                arrows.setdefault(tuple(row[c] for c in spec["panels"]), []).append((x, y, ax_, ay))
    cmap, vmin, vmax, extend = colour_scale([v for cs in cells.values() for _, v in cs])
    points = [p for cs in cells.values() for quad, _ in cs for p in quad]
    x_min, x_max = min(p[0] for p in points), max(p[0] for p in points)
    y_min, y_max = min(p[1] for p in points), max(p[1] for p in points)
    span = max(x_max - x_min, y_max - y_min)
    largest = max((math.hypot(a[2], a[3]) for arr in arrows.values() for a in arr), default=0.0)
    fig, axes, where = grid_figure(keys, paper, (1.7, 1.5) if paper else (3.0, 2.6), ("x [m]", "y [m]"))
    coll = None
    for key in keys:
        r, c = where[key]
        ax = axes[r][c]
        quads = cells.get(key, [])
        coll = PolyCollection([q for q, _ in quads], array=[math.nan if v is None else v for _, v in quads], cmap=cmap,
                              edgecolors="0.25", linewidths=0.3)
        coll.set_clim(vmin, vmax)
        ax.add_collection(coll)
        for x, y, lx, ly in arrows.get(key, []):
            if largest > 0 and math.hypot(lx, ly) > 1e-3 * largest:
                k = 0.25 * span / largest
                ax.annotate("", xy=(x, y), xytext=(x - k * lx, y - k * ly),
                            arrowprops={"arrowstyle": "-|>", "color": "black", "linewidth": 0.8, "shrinkA": 0, "shrinkB": 0,
                                        "mutation_scale": 6 if paper else 8})
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_title(", ".join(k for k in key if k), fontsize=7 if paper else 9)
        ax.axhline(0.0, color="0.4", linewidth=0.8, zorder=0)  # the floor
    for ax in axes.flat:
        ax.set_xlim(x_min - 0.05 * span, x_max + 0.05 * span)
        ax.set_ylim(min(y_min, 0.0) - 0.3 * span, y_max + 0.05 * span)
    finish_coloured(fig, axes, coll, extend, spec, meta, reports, paper)


def draw_verdict_map(spec, reports, paper=False):
    """A heat map of verdicts: one row per value of spec's `y` column (the scheme), one column
    per `values` column (a property's verdict), coloured holds / conditional / fails / n/a."""
    from matplotlib.colors import ListedColormap
    meta, rows = read_table(os.path.join(reports, spec["csv"]))
    levels = {"holds": 0, "conditional": 1, "fails": 2}
    names = [row[spec["y"]] for row in rows]
    z = [[levels.get(row[c], 3) for c in spec["values"]] for row in rows]
    fig, ax = plt.subplots(figsize=(1.0 + 0.9 * len(spec["values"]), 0.8 + 0.32 * len(names)))
    ax.imshow(z, cmap=ListedColormap(["#4daf4a", "#ffb000", "#e41a1c", "#bbbbbb"]), vmin=-0.5, vmax=3.5, aspect="auto")
    for i, row in enumerate(rows):
        for j, c in enumerate(spec["values"]):
            ax.text(j, i, row[c], ha="center", va="center", fontsize=6 if paper else 7)
    ax.set_xticks(range(len(spec["values"])), spec["values"], rotation=30, ha="right", fontsize=8)
    ax.set_yticks(range(len(names)), names, fontsize=8)
    if not paper:
        fig.suptitle(spec["title"], fontsize=11)
    save(fig, spec, meta, reports, paper)


def bar_groups(spec, rows):
    """The bars of each panel: {panel key: {category: {series: value}}}, categories (the `x`
    column, the scheme) and series (the `series` columns' labels) in the table's order, the
    value in `y`. A cell that is no number is no bar; a category without one in a panel is left
    out of it."""
    panels = {}
    for row in rows:
        value = number(row[spec["y"]])
        if value is not None:
            key = tuple(row[c] for c in spec["panels"])
            panels.setdefault(key, {}).setdefault(row[spec["x"]], {})[label(row, spec["series"])] = value
    return panels


def draw_bars(spec, reports, paper=False):
    """Grouped bars: per panel (the `panels` columns), one group per category (the `x` column,
    the scheme), one bar per series, each labelled with its value (a 0 is a count too)."""
    meta, rows = read_table(os.path.join(reports, spec["csv"]))
    panels = bar_groups(spec, rows)
    series = list(dict.fromkeys(name for groups in panels.values() for bars in groups.values() for name in bars))
    colours = {name: plt.get_cmap("tab10")(i % 10) for i, name in enumerate(series)}
    n = max(len(panels), 1)
    width_in = (3.4 if n == 1 else 7.0) if paper else 5.5 * n
    fig, axes = plt.subplots(1, n, figsize=(width_in, 2.6 if paper else 4.2), squeeze=False, layout="constrained")
    width = 0.8 / max(len(series), 1)
    font = 5 if paper else 7
    for ax, (key, groups) in zip(axes.flat, panels.items()):
        for i, (category, bars) in enumerate(groups.items()):
            for j, name in enumerate(series):
                if name not in bars:
                    continue
                x = i - 0.4 + width * (j + 0.5)
                ax.bar(x, bars[name], width, color=colours[name], label=name)
                ax.text(x, bars[name], f"{bars[name]:.3g}", ha="center", va="bottom", fontsize=font, rotation=90)
        ax.set_xticks(range(len(groups)), list(groups), rotation=30, ha="right", fontsize=font + 2)
        ax.set_ylabel(spec["y"])
        ax.margins(y=0.25)
        ax.grid(True, axis="y", alpha=0.4)
        title = ", ".join(f"{short(c)} = {v}" for c, v in zip(spec["panels"], key))
        if title:
            ax.set_title(title, fontsize=7 if paper else 10)
    if not panels:
        axes[0][0].text(0.5, 0.5, "nothing to draw", ha="center", va="center", transform=axes[0][0].transAxes, color="0.4")
    if not paper:
        fig.suptitle(spec["title"], fontsize=12)
    handles = [plt.Rectangle((0, 0), 1, 1, color=colours[name]) for name in series]
    legend = fig.legend(handles, series, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=len(series),
                        fontsize=font + 1, frameon=False) if series else None
    save(fig, spec, meta, reports, paper, legend)


DRAWERS = {"space_time": draw_space_time, "deformed": draw_deformed, "verdict_map": draw_verdict_map,
           "bars": draw_bars}


def save(fig, spec, meta, reports, paper, legend=None):
    """Stamps (screen look) and writes REPORTS/figures[/paper]/<id>.png and .pdf, each whole or
    not at all."""
    if not paper:  # the stamp goes below everything else
        fig.canvas.draw()
        below = min(0.0, legend.get_window_extent().transformed(fig.transFigure.inverted()).y0) if legend else 0.0
        stamp = "nsbench {} rev {} ({}, {})".format(meta.get("nsbench_version", "?"), meta.get("git_revision", "?"),
                                                    meta.get("build_type", "?"), meta.get("compiler", "?"))
        fig.text(0.99, below - 0.01, stamp, ha="right", va="top", fontsize=7, color="0.4")
    out_dir = os.path.join(reports, "figures", "paper") if paper else os.path.join(reports, "figures")
    os.makedirs(out_dir, exist_ok=True)
    for ext in ("png", "pdf"):
        final = os.path.join(out_dir, f"{spec['id']}.{ext}")
        tmp = os.path.join(out_dir, f".{spec['id']}.tmp.{ext}")
        # No creation date in the PDF: the same report draws the same bytes.
        fig.savefig(tmp, dpi=300 if paper else 150, bbox_inches="tight",  # legend and stamp below the panels included
                    metadata={"CreationDate": None} if ext == "pdf" else None)
        os.replace(tmp, final)  # whole or not at all
    plt.close(fig)


def share_mathtext_layouts():
    """One cache of mathtext layouts for the whole run. matplotlib (3.6) keeps them per parser,
    50 at most, and every renderer has its own parser: each savefig (PNG at one dpi, PDF at
    another, each with its tight-bbox pass) parsed the log axes' tick labels ($10^{-3}$...)
    again with pyparsing, a third of a figure's time. A layout depends on nothing of the parser
    but its output type (raster or vector), so it is keyed on that and the parser's arguments
    (string, dpi, font): the same objects come back as from matplotlib's own cache on a hit,
    the same bytes are drawn. rcParams do not change after main() sets them. Left as it is
    where matplotlib has no such method."""
    from matplotlib import mathtext
    parse = getattr(getattr(mathtext.MathTextParser, "_parse_cached", None), "__wrapped__", None)
    if parse is None:
        return
    layouts = {}

    def shared(self, *args):
        key = (self._output_type, *args)
        if key not in layouts:
            layouts[key] = parse(self, *args)
        return layouts[key]
    mathtext.MathTextParser._parse_cached = shared


class Damaged(Exception):
    """A figure that cannot be drawn from what the report holds: one line, naming it."""


def draw_one(task):
    spec, reports, paper = task
    try:
        DRAWERS.get(spec.get("kind"), draw)(spec, reports, paper)
    except OSError as e:
        raise Damaged(f"figure '{spec['id']}': cannot read '{e.filename}': {e.strerror}") from None
    except KeyError as e:
        raise Damaged(f"figure '{spec['id']}': its entry or its table {spec['csv']} has no key or column {e}") from None
    except (TypeError, ValueError, IndexError, AttributeError) as e:
        raise Damaged(f"figure '{spec['id']}': its entry or its table {spec['csv']} is damaged ({type(e).__name__}: {e})") from None


def checked_specs(reports):
    """The entries of REPORTS/figures.json, each an object with a string id, csv and title; an id
    is a file name (letters, digits, _ . -, not starting with '.') and csv a table of the report
    itself: a figure id './../../x' wrote outside it, an absolute csv read any file. Exits with one
    line naming the file and the key otherwise."""
    path = os.path.join(reports, "figures.json")
    try:
        with open(path) as f:
            specs = json.load(f)
    except OSError as e:
        sys.exit(f"figures.py: {path}: cannot be read: {e.strerror}")
    except json.JSONDecodeError as e:
        sys.exit(f"figures.py: {path}: not JSON ({e.msg} at line {e.lineno}): damaged or cut short")
    if not isinstance(specs, list):
        sys.exit(f"figures.py: {path}: expected a list of figures, got {type(specs).__name__}")
    root = os.path.realpath(reports)
    for k, spec in enumerate(specs):
        where = f"figures.py: {path}: figure {k}"
        if not isinstance(spec, dict):
            sys.exit(f"{where}: not an object")
        for key in ("id", "csv", "title"):
            if not isinstance(spec.get(key), str):
                sys.exit(f"{where}: key '{key}' missing or not a string")
        if not re.fullmatch(r"[A-Za-z0-9_][A-Za-z0-9_.-]*", spec["id"]):
            sys.exit(f"{where}: id '{spec['id']}' is not a file name; valid: letters, digits, _ . - (not first)")
        for key in ("csv", "arrows_csv"):
            given = spec.get(key, "")
            table = os.path.realpath(os.path.join(reports, str(given)))
            if os.path.isabs(str(given)) or os.path.commonpath([root, table]) != root:
                sys.exit(f"{where} ('{spec['id']}'): {key} '{given}' is outside the report; valid: a table of {reports}")
    return specs


def study_jobs():
    """NSBENCH_JOBS as the studies read it (a whole number >= 1), else the number of cores."""
    text = os.environ.get("NSBENCH_JOBS", "")
    if not text:
        return os.cpu_count() or 1
    if not text.isdigit() or not 1 <= int(text) <= 4096:
        sys.exit(f"figures.py: NSBENCH_JOBS='{text}': expected a whole number of parallel figures; valid: 1 to 4096 "
                 "(unset: the number of cores)")
    return int(text)


def main():
    parser = argparse.ArgumentParser(description="Renders the figures of REPORTS/figures.json.")
    parser.add_argument("reports", metavar="REPORTS_DIR")
    parser.add_argument("--style", choices=("screen", "paper"), default="screen",
                        help="screen (default): titled, stamped with the revision, to REPORTS/figures; "
                             "paper: no title or stamp, column-width sizes, 8 pt, to REPORTS/figures/paper")
    parser.add_argument("--only", metavar="ID", action="append", help="draw only this figure (repeatable)")
    args = parser.parse_args()
    paper = args.style == "paper"
    # TrueType (Type 42) fonts embedded in the PDF, as journals ask, not Type 3.
    matplotlib.rcParams.update({"pdf.fonttype": 42, "ps.fonttype": 42})
    if paper:
        matplotlib.rcParams.update({"font.size": 8, "axes.labelsize": 8, "xtick.labelsize": 7, "ytick.labelsize": 7,
                                    "axes.titlesize": 7})
    share_mathtext_layouts()  # before the pool: its processes inherit it
    specs = checked_specs(args.reports)
    if args.only:
        unknown = set(args.only) - {s["id"] for s in specs}
        if unknown:
            sys.exit(f"figures.py: --only {sorted(unknown)[0]}: no such figure in {args.reports}/figures.json")
        specs = [s for s in specs if s["id"] in args.only]
    # The figures are independent: drawn by NSBENCH_JOBS processes (default: the cores), each
    # figure by one, so a figure's bytes do not depend on the number of processes.
    jobs = max(1, min(len(specs), study_jobs()))
    tasks = [(spec, args.reports, paper) for spec in specs]
    try:
        if jobs == 1:
            for task in tasks:
                draw_one(task)
        else:
            with multiprocessing.get_context("fork").Pool(jobs) as pool:
                pool.map(draw_one, tasks, chunksize=1)
    except Damaged as e:
        sys.exit(f"figures.py: {args.reports}: {e}")
    out = os.path.join(args.reports, "figures", "paper") if paper else os.path.join(args.reports, "figures")
    print(f"figures: {len(specs)} written to {out}", file=sys.stderr)


if __name__ == "__main__":
    main()
