#!/usr/bin/env python3
"""Where the approximate solver holds: a map of its agreement with the full-wave reference.

Issue 28 part 4. One row per (species, incident direction), one column per wavelength; each cell
is the unpolarised (pol = mean) comparison of the default approximate method with the full-wave
reference of a `plumage compare` run (or of plugins/bem/tools/merge_compare.py), coloured by
the Pearson correlation of the reflectance densities U(phi_o) (left) and by rel. L2 of U (right),
the value printed in the cell; grey where nothing was run.

  plot_approx_map.py OUT.png [--csv OUT.csv] --run LABEL METRICS.csv METHOD [METHOD ...] [--run ...]

Of the METHODs listed for a run the first one present in a case is drawn; the methods of one
list must share their patterns (they may differ in normalisation only: the correlation is the
same, rel. L2 is that of the listed method). The CSV holds every drawn cell.
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def parse_runs(items):
    runs = []
    for group in items:
        if len(group) < 3:
            sys.exit("plot_approx_map.py: --run needs LABEL METRICS.csv METHOD [METHOD ...]")
        runs.append((group[0], group[1], group[2:]))
    return runs


def cells_of(label, metrics, methods):
    """{(label, theta, phi): {lambda: (method, correlation, rel_l2)}} for the first listed method per case."""
    by_case = {}
    for r in rows(metrics):
        if r["pol"] != "mean" or r["method"] not in methods:
            continue
        key = (label, float(r["theta_i_deg"]), float(r["phi_i_deg"]))
        lam = float(r["lambda_nm"])
        rank = methods.index(r["method"])
        old = by_case.setdefault(key, {}).get(lam)
        if old is None or rank < methods.index(old[0]):
            by_case[key][lam] = (r["method"], float(r["correlation"]), float(r["rel_l2"]))
    if not by_case:
        sys.exit(f"plot_approx_map.py: {metrics}: no unpolarised rows of {', '.join(methods)}")
    return by_case


def draw(ax, keys, lambdas, cells, index, title, cmap, vmin, vmax, fmt):
    grid = [[math.nan] * len(lambdas) for _ in keys]
    for i, key in enumerate(keys):
        for j, lam in enumerate(lambdas):
            cell = cells[key].get(lam)
            if cell is not None:
                grid[i][j] = cell[index]
    colours = plt.get_cmap(cmap).copy()
    colours.set_bad("0.85")
    image = ax.imshow(grid, cmap=colours, vmin=vmin, vmax=vmax, aspect="auto")
    for i in range(len(keys)):
        for j in range(len(lambdas)):
            v = grid[i][j]
            if not math.isnan(v):
                shade = (v - vmin) / (vmax - vmin)
                ax.text(j, i, fmt.format(v), ha="center", va="center", fontsize=8,
                        color="white" if shade < 0.35 or shade > 0.8 else "black")
    ax.set_xticks(range(len(lambdas)), [f"{lam:g}" for lam in lambdas])
    ax.set_yticks(range(len(keys)), [f"{k[0]}, (θ, φ)_i = ({k[1]:g}°, {k[2]:g}°)" for k in keys])
    ax.set_xlabel("wavelength (nm)")
    ax.set_title(title)
    plt.colorbar(image, ax=ax, fraction=0.04)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--csv")
    ap.add_argument("--title", default="approximate solver against full-wave (unpolarised)")
    ap.add_argument("--run", nargs="+", action="append", required=True)
    a = ap.parse_args()
    cells = {}
    for label, metrics, methods in parse_runs(a.run):
        cells.update(cells_of(label, metrics, methods))
    keys = list(cells)
    lambdas = sorted({lam for c in cells.values() for lam in c})
    fig, axes = plt.subplots(1, 2, figsize=(6 + 1.3 * len(lambdas), 1.2 + 0.45 * len(keys)), sharey=True)
    draw(axes[0], keys, lambdas, cells, 1, "correlation of U(φ_o)", "RdYlGn", 0.0, 1.0, "{:.2f}")
    draw(axes[1], keys, lambdas, cells, 2, "rel. L2 of U(φ_o)", "RdYlGn_r", 0.0, 1.0, "{:.2f}")
    fig.suptitle(a.title)
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["run", "theta_i_deg", "phi_i_deg", "lambda_nm", "method", "correlation", "rel_l2"])
            for key in keys:
                for lam in sorted(cells[key]):
                    m, c, l2 = cells[key][lam]
                    w.writerow([key[0], f"{key[1]:g}", f"{key[2]:g}", f"{lam:g}", m, f"{c:.4f}", f"{l2:.4f}"])


if __name__ == "__main__":
    main()
