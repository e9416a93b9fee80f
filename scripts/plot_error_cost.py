#!/usr/bin/env python3
"""Error against the reference versus cost, for every method of one or more `plumage compare` runs.

Called by `plumage compare` for its own run (`<name>-error-vs-cost.png`), and by hand to put
several comparisons on one chart (docs/validation.md):

  plot_error_cost.py OUT.png --title T --run LABEL METRICS.csv TIMES.csv [TIMES.csv ...] [--run ...]

METRICS is a `<name>-metrics.csv` of `plumage compare` (or of plugins/bem/tools/merge_compare.py),
TIMES one or more `<name>-times.csv` of the runs that produced it. Per method: the error is the
mean over incident directions and wavelengths of the unpolarised rows (pol = mean) of
rel. L2 of the reflectance density U(phi_o) and of |R - R_ref| / R_ref; the cost is the solve
time per wavelength (both polarizations, all incident directions), averaged over the time files
that hold the method. The reference has no error; it is drawn as a vertical line at its cost.
Errors below 1e-7 (a method identical to the reference up to the solver tolerance) are drawn
at 1e-7. Methods named approx_table_* (a photonic-crystal table instead of the multilayer) share
the marker of the approx_* method with the same options.
"""
import argparse
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def load_run(metrics_path, times_paths):
    errors = defaultdict(lambda: [0.0, 0.0, 0])  # method -> [sum rel_l2, sum |dR|/R_ref, count]
    reference = None
    for r in rows(metrics_path):
        if r["pol"] != "mean":
            continue
        reference = r["reference"]
        if r["method"] == r["reference"]:
            continue
        e = errors[r["method"]]
        e[0] += float(r["rel_l2"])
        r_ref = float(r["R_reference"])
        e[1] += abs(float(r["dR"])) / r_ref if r_ref > 0 else float("nan")
        e[2] += 1
    cost = defaultdict(list)
    for path in times_paths:
        for r in rows(path):
            cost[r["method"]].append(float(r["solve_s_per_wavelength"]))
    if reference is None:
        sys.exit(f"{metrics_path}: no unpolarised (pol = mean) rows")
    points = {}
    for m, (l2, dr, n) in errors.items():
        if m not in cost:
            print(f"{metrics_path}: no time for method {m}; left out", file=sys.stderr)
            continue
        points[m] = (sum(cost[m]) / len(cost[m]), l2 / n, dr / n)
    ref_cost = sum(cost[reference]) / len(cost[reference]) if reference in cost else None
    return reference, ref_cost, points


FLOOR = 1e-7


def marker_key(method):
    return method.replace("approx_table_", "approx_")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("png")
    ap.add_argument("--title", default="")
    ap.add_argument("--run", action="append", nargs="+", required=True, metavar="LABEL METRICS TIMES",
                    help="a label, a metrics CSV and one or more times CSVs")
    args = ap.parse_args()

    fig, axes = plt.subplots(1, 2, figsize=(11.0, 6.2), squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    markers = "osD^v<>pP*hX"
    marker_of = {}
    for k, run in enumerate(args.run):
        if len(run) < 3:
            sys.exit("--run needs LABEL METRICS TIMES [TIMES ...]")
        label, metrics_path, times_paths = run[0], run[1], run[2:]
        reference, ref_cost, points = load_run(metrics_path, times_paths)
        colour = colours[k % len(colours)]
        for ax, idx in ((axes[0][0], 1), (axes[0][1], 2)):
            if ref_cost is not None:
                ax.axvline(ref_cost, color=colour, ls=":", lw=1.2)
            for m, p in points.items():
                mk = marker_of.setdefault(marker_key(m), markers[len(marker_of) % len(markers)])
                ax.scatter([p[0]], [max(p[idx], FLOOR)], color=colour, marker=mk, s=36, alpha=0.85,
                           edgecolors="black", linewidths=0.4)
        axes[0][0].plot([], [], color=colour, ls=":", label=f"{label} (reference {reference}: dotted)")
    for m, mk in marker_of.items():
        shown = m + " (or approx_table_" + m[len("approx_"):] + ")" if m.startswith("approx_") else m
        axes[0][1].scatter([], [], color="0.6", marker=mk, edgecolors="black", linewidths=0.4, label=shown)
    for ax, ylabel in ((axes[0][0], "rel. L2 of U(phi_o), mean over cases (floor 1e-7)"),
                       (axes[0][1], "|R - R_ref| / R_ref, mean over cases (floor 1e-7)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("solve time per wavelength (s, this machine)")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3, which="both")
        # Below the axes: the points span the whole plane.
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16))
    if args.title:
        fig.suptitle(args.title, fontsize=10)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110, format="png")


if __name__ == "__main__":
    main()
