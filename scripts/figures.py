#!/usr/bin/python3
"""Renders the figures declared by the studies (REPORTS/figures.json) from their CSV tables.

    python3 scripts/figures.py REPORTS

Writes REPORTS/figures/<id>.png and .pdf, each stamped with the revision and build read from
the CSV's '#' metadata lines. Rows whose x or y is not a number (n/a, diverged) are skipped.
A line labelled 'exact' is the reference: black, dashed, drawn over the others.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


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


def label(row, columns):
    """A line's legend: the series value alone, or name = value pairs when several columns."""
    if len(columns) == 1:
        return row[columns[0]]
    return ", ".join(f"{c.split(' [')[0]} = {row[c]}" for c in columns)


def draw(spec, reports):
    meta, rows = read_table(os.path.join(reports, spec["csv"]))
    panels = {}
    for row in rows:
        panels.setdefault(tuple(row[c] for c in spec["panels"]), []).append(row)
    n = len(panels)
    cols = min(n, 3)
    nrows = math.ceil(n / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.6 * cols, 3.6 * nrows + 0.5), squeeze=False)
    for ax, (key, prow) in zip(axes.flat, panels.items()):
        lines = {}
        for row in prow:
            x, y = number(row[spec["x"]]), number(row[spec["y"]])
            if x is None or y is None or (spec["log_x"] and x <= 0) or (spec["log_y"] and y <= 0):
                continue
            lines.setdefault(label(row, spec["series"]), []).append((x, y))
        for name, pts in lines.items():
            pts.sort()
            dense = len(pts) > 50  # histories: a line, markers would hide it
            style = {"color": "black", "linestyle": "--", "linewidth": 1.0, "zorder": 3} if name == "exact" else {}
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=None if dense else "o", markersize=3.5,
                    **{"linewidth": 1.2, **style}, label=name)
        ax.set_xscale("log" if spec["log_x"] else "linear")
        ax.set_yscale("log" if spec["log_y"] else "linear")
        for axis, log in ((ax.xaxis, spec["log_x"]), (ax.yaxis, spec["log_y"])):
            if not log:
                axis.get_major_formatter().set_useOffset(False)  # plain values, no "1e-6 + 0.99999"
        ax.set_xlabel(spec["x"])
        ax.set_ylabel(spec["y"])
        if spec["panels"]:
            ax.set_title(", ".join(f"{c.split(' [')[0]} = {v}" for c, v in zip(spec["panels"], key)), fontsize=10)
        ax.grid(True, which="major", alpha=0.4)
        ax.grid(True, which="minor", alpha=0.12)
        if lines:
            ax.legend(fontsize=8)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fig.suptitle(spec["title"], fontsize=12)
    stamp = "nsbench rev {} ({}, {})".format(meta.get("git_revision", "?"), meta.get("build_type", "?"),
                                             meta.get("compiler", "?"))
    fig.text(0.99, 0.005, stamp, ha="right", va="bottom", fontsize=7, color="0.4")
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    out_dir = os.path.join(reports, "figures")
    os.makedirs(out_dir, exist_ok=True)
    for ext in ("png", "pdf"):
        final = os.path.join(out_dir, f"{spec['id']}.{ext}")
        tmp = os.path.join(out_dir, f".{spec['id']}.tmp.{ext}")
        fig.savefig(tmp, dpi=150)
        os.replace(tmp, final)  # whole or not at all
    plt.close(fig)


def main():
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
