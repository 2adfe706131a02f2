#!/usr/bin/python3
"""Renders the figures declared by the studies (REPORTS/figures.json) from their CSV tables.

    python3 scripts/figures.py REPORTS
    nsbench-figures REPORTS        (the same script, installed with nsbench)

Writes REPORTS/figures/<id>.png and .pdf, each stamped with the revision and build read from
the CSV's '#' metadata lines. Rows whose x is not a number (n/a, diverged) are skipped; where
y is not a number (or not positive on a log scale) the line has a gap. A line keeps its colour
and dashes in every panel and figure of a table; one legend, outside the panels, says which is
which. A line labelled 'exact' is the reference: black, dashed, drawn over the others.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
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


def line_styles(names):
    """One colour and dash pattern per line label, the same in every panel; the dashes tell
    apart lines drawn over each other (and in black and white). 'exact' is black and dashed."""
    cmap = plt.get_cmap("tab10")
    dashes = ["-", "--", "-.", ":", (0, (3, 1, 1, 1, 1, 1))]
    # Past ten lines the colours repeat with another dash pattern.
    return {name: {"color": cmap(i % 10), "linestyle": dashes[(i + i // 10) % len(dashes)]}
            for i, name in enumerate(names)}


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
    with nothing to draw are left out."""
    panels = {}
    for row in rows:
        x, y = number(row[spec["x"]]), number(row[spec["y"]])
        if x is None or (spec["log_x"] and not 0 < x <= LOG_MAX):
            continue
        if y is None or (spec["log_y"] and not 0 < y <= LOG_MAX):
            y = math.nan  # nothing to draw here: a gap in a history, not a line across it
        lines = panels.setdefault(tuple(row[c] for c in spec["panels"]), {})
        lines.setdefault(label(row, spec["series"]), []).append((x, y))
    return {key: {name: sorted(pts) for name, pts in lines.items() if any(not math.isnan(y) for _, y in pts)}
            for key, lines in panels.items()}


def draw(spec, reports):
    meta, rows = read_table(os.path.join(reports, spec["csv"]))
    panels = panel_lines(spec, rows)
    # Styles follow the table's rows (the registry's order), drawn or not: a line keeps its
    # colour in every figure of the table. The legend lists the lines drawn.
    styles = line_styles([name for name in dict.fromkeys(label(row, spec["series"]) for row in rows) if name != "exact"])
    names = list(dict.fromkeys(name for lines in panels.values() for name in lines))
    n = len(panels)
    cols = min(n, 3)
    nrows = math.ceil(n / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.6 * cols, 3.6 * nrows + 0.5), squeeze=False, layout="constrained")
    handles = {}
    for ax, (key, lines) in zip(axes.flat, panels.items()):
        drawn = []
        for name, pts in lines.items():
            ys = [p[1] for p in pts]
            # Histories (dense) are lines, markers would hide them, but a point between two gaps
            # has no line to be drawn with: it gets a dot.
            dense = len(pts) > 50
            alone = [i for i, y in enumerate(ys) if not math.isnan(y) and
                     (i == 0 or math.isnan(ys[i - 1])) and (i + 1 == len(ys) or math.isnan(ys[i + 1]))]
            marks = {"marker": ".", "markersize": 3, "markevery": alone} if dense else {"marker": "o", "markersize": 3.5}
            style = ({"color": "black", "linestyle": "--", "linewidth": 1.0, "zorder": 3} if name == "exact"
                     else styles[name])
            ax.plot([p[0] for p in pts], ys, **marks, **{"linewidth": 1.2, **style})
            handles[name] = Line2D([], [], marker=None if dense else "o", markersize=3.5, **{"linewidth": 1.2, **style})
            drawn += [p for p in pts if not math.isnan(p[1])]
        if not lines:
            ax.text(0.5, 0.5, "nothing to draw\n(no positive values)" if spec["log_y"] else "nothing to draw",
                    ha="center", va="center", transform=ax.transAxes, color="0.4")
        ax.set_xscale("log" if spec["log_x"] else "linear")
        ax.set_yscale("log" if spec["log_y"] else "linear")
        if drawn and spec["log_x"]:
            ax.set_xlim(*log_limits([p[0] for p in drawn]))
        if drawn and spec["log_y"]:
            ax.set_ylim(*log_limits([p[1] for p in drawn]))
        for axis, log in ((ax.xaxis, spec["log_x"]), (ax.yaxis, spec["log_y"])):
            if not log:
                axis.get_major_formatter().set_useOffset(False)  # plain values, no "1e-6 + 0.99999"
        ax.set_xlabel(spec["x"])
        ax.set_ylabel(spec["y"])
        if spec["panels"]:
            ax.set_title(", ".join(f"{short(c)} = {v}" for c, v in zip(spec["panels"], key)), fontsize=10)
        ax.grid(True, which="major", alpha=0.4)
        ax.grid(True, which="minor", alpha=0.12)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fig.suptitle(spec["title"], fontsize=12)
    # One legend for every panel, outside the data: right of a single panel, below several.
    title = ", ".join(short(c) for c in spec["series"])
    if n == 1:
        legend = fig.legend([handles[name] for name in names], names, title=title, loc="center left",
                            bbox_to_anchor=(1.0, 0.5), fontsize=8, title_fontsize=8, frameon=False)
    else:  # in as many columns as fit in the figure's width
        for ncol in range(max(len(names), 1), 0, -1):
            legend = fig.legend([handles[name] for name in names], names, title=title, loc="upper center",
                                bbox_to_anchor=(0.5, 0.0), ncol=ncol, fontsize=8, title_fontsize=8, frameon=False)
            if ncol == 1 or legend.get_window_extent(fig.canvas.get_renderer()).width <= fig.bbox.width:
                break
            legend.remove()
    # The stamp goes below everything else.
    fig.canvas.draw()
    below = min(0.0, legend.get_window_extent().transformed(fig.transFigure.inverted()).y0)
    stamp = "nsbench rev {} ({}, {})".format(meta.get("git_revision", "?"), meta.get("build_type", "?"),
                                             meta.get("compiler", "?"))
    fig.text(0.99, below - 0.01, stamp, ha="right", va="top", fontsize=7, color="0.4")
    out_dir = os.path.join(reports, "figures")
    os.makedirs(out_dir, exist_ok=True)
    for ext in ("png", "pdf"):
        final = os.path.join(out_dir, f"{spec['id']}.{ext}")
        tmp = os.path.join(out_dir, f".{spec['id']}.tmp.{ext}")
        fig.savefig(tmp, dpi=150, bbox_inches="tight")  # the legend and stamp below the panels included
        os.replace(tmp, final)  # whole or not at all
    plt.close(fig)


def main():
    if len(sys.argv) == 2 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return
    if len(sys.argv) != 2:
        sys.exit("usage: figures.py REPORTS_DIR")
    reports = sys.argv[1]
    with open(os.path.join(reports, "figures.json")) as f:
        specs = json.load(f)
    for spec in specs:
        draw(spec, reports)
    print(f"figures: {len(specs)} written to {os.path.join(reports, 'figures')}", file=sys.stderr)


if __name__ == "__main__":
    main()
