#!/usr/bin/env python3
"""Draws a long-format CSV (panel, series, x, y) as a grid of line-chart panels.

Called by the plumage executable for every line chart it writes (`--plot`). One panel per
distinct `panel` value, one line per `series` within a panel, in file order; a series whose rows
have style "dashed" (a measurement beside predictions) is drawn dashed.
"""
import argparse
import csv
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("png")
    ap.add_argument("--title", default="")
    ap.add_argument("--xlabel", default="")
    ap.add_argument("--ylabel", default="")
    args = ap.parse_args()

    panels = {}
    with open(args.csv, newline="") as f:
        for row in csv.DictReader(f):
            series = panels.setdefault(row["panel"], {})
            xs, ys, style = series.setdefault(row["series"], ([], [], {}))
            style["dashed"] = row.get("style") == "dashed"
            xs.append(float(row["x"]))
            ys.append(float(row["y"]))

    n = max(1, len(panels))
    cols = min(n, 2)
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(6.0 * cols, 3.6 * rows), squeeze=False)
    for ax, (panel, series) in zip(axes.flat, panels.items()):
        for name, (xs, ys, style) in series.items():
            ax.plot(xs, ys, label=name, linewidth=1.4, linestyle="--" if style["dashed"] else "-")
        ax.set_title(panel, fontsize=10)
        ax.set_xlabel(args.xlabel)
        ax.set_ylabel(args.ylabel)
        ax.grid(alpha=0.3)
        if len(series) > 1:
            ax.legend(fontsize=8)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110, format="png")


if __name__ == "__main__":
    main()
