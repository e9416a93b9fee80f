#!/usr/bin/env python3
"""Projected-hemisphere plots of a feather BSDF (called by `plumage brdf plot`), paper Fig. 10.

Input: a manifest CSV (row, col, title, file) naming one PNG panel per incident direction (row)
and BRDF (col: mean, then instances), relative to the manifest's folder. Each panel shows the
unit disk of (omega_o,x, omega_o,y) with +x to the right and +y up.
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("manifest")
    ap.add_argument("png")
    ap.add_argument("--title", default="")
    args = ap.parse_args()
    base = os.path.dirname(os.path.abspath(args.manifest))
    with open(args.manifest, newline="") as f:
        rows = list(csv.DictReader(f))
    nr = 1 + max(int(r["row"]) for r in rows)
    nc = 1 + max(int(r["col"]) for r in rows)
    fig, axes = plt.subplots(nr, nc, figsize=(2.6 * nc, 2.75 * nr + 0.4), squeeze=False)
    for r in rows:
        ax = axes[int(r["row"])][int(r["col"])]
        ax.imshow(mpimg.imread(os.path.join(base, r["file"])), extent=(-1, 1, -1, 1))
        ax.set_title(r["title"], fontsize=7)
        ax.set_xticks([-1, 0, 1])
        ax.set_yticks([-1, 0, 1])
        ax.tick_params(labelsize=6)
        if int(r["row"]) == nr - 1:
            ax.set_xlabel("omega_o,x (across the barbule)", fontsize=7)
        if int(r["col"]) == 0:
            ax.set_ylabel("omega_o,y (along the barbule)", fontsize=7)
    if args.title:
        fig.suptitle(args.title, fontsize=8)
    fig.tight_layout()
    fig.savefig(args.png, dpi=110, format="png")


if __name__ == "__main__":
    main()
