#!/usr/bin/env python3
"""Accuracy against cost for every backend's ladder (`plumage bench ladder`, issue 9).

  plot_ladder.py LADDER.csv OUT.png --title T

LADDER.csv has the columns backend, case, setting, fidelity, reference, metric, error, wall_s,
cpu_s, pareto. One panel, log-log: error against the rung's wall time, one curve per
(backend, case) in fidelity order, one colour per backend; Pareto-optimal rungs of each curve
(pareto = 1) filled, dominated ones hollow. Errors are in each backend's own metric (the
legend names it), so curves of different backends share axes, not units. Errors below 1e-16
(exact to rounding) are drawn at 1e-16.
"""
import argparse
import csv
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FLOOR = 1e-16
MARKERS = "osD^v<>ph*"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("png")
    ap.add_argument("--title", default="")
    args = ap.parse_args()

    curves = OrderedDict()
    with open(args.csv, newline="") as f:
        for r in csv.DictReader(f):
            curves.setdefault((r["backend"], r["case"]), []).append(r)
    backends = list(OrderedDict.fromkeys(b for b, _ in curves))
    colours = {b: plt.cm.tab10(i % 10) for i, b in enumerate(backends)}
    case_index = {}

    fig, ax = plt.subplots(figsize=(10.0, 7.0))
    for (backend, case), rungs in curves.items():
        rungs.sort(key=lambda r: float(r["fidelity"]))
        k = case_index.setdefault(backend, {}).setdefault(case, len(case_index[backend]))
        marker = MARKERS[k % len(MARKERS)]
        x = [max(float(r["wall_s"]), 1e-7) for r in rungs]
        y = [max(float(r["error"]), FLOOR) for r in rungs]
        c = colours[backend]
        ax.plot(x, y, "-", color=c, lw=1.2, alpha=0.8,
                label=f"{backend}: {case} ({rungs[0]['metric']})")
        for xi, yi, r in zip(x, y, rungs):
            filled = r["pareto"] == "1"
            ax.plot([xi], [yi], marker, color=c, ms=7,
                    markerfacecolor=c if filled else "white", markeredgewidth=1.4)
        # Label the finest rung with its setting (the legend names the curve).
        ax.annotate(rungs[-1]["setting"], (x[-1], y[-1]), textcoords="offset points", xytext=(5, -10),
                    fontsize=7, color=c)
    ax.plot([], [], "o", color="gray", label="filled: Pareto-optimal rung of its curve")
    ax.plot([], [], "o", color="gray", markerfacecolor="white", label="hollow: dominated rung")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the rung (s)")
    ax.set_ylabel("error against the backend's reference (own metric)")
    ax.grid(True, which="both", alpha=0.25)
    ax.set_title(args.title)
    # Below the axes: the curves span the whole plot.
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.11), ncol=1, frameon=False)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110, format="png", bbox_inches="tight")


if __name__ == "__main__":
    main()
