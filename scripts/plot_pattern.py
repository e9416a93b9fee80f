#!/usr/bin/env python3
"""Fig. 7-style picture of a simulated far-field pattern (called by `plumage simulate --pattern`).

Inputs: strips CSV (row, phi_o_deg, r, g, b: display sRGB of the reflection along the specular
cone, one row per strip: instance mean, then single instances) and lines CSV (lambda_nm,
phi_o_deg, density: instance-mean reflectance density per radian, Eq. 10, at a few wavelengths).
"""
import argparse
import csv

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("strips")
    ap.add_argument("lines")
    ap.add_argument("png")
    ap.add_argument("--title", default="")
    args = ap.parse_args()

    rows = {}
    with open(args.strips, newline="") as f:
        for r in csv.DictReader(f):
            rows.setdefault(r["row"], []).append(
                (float(r["phi_o_deg"]), int(r["r"]), int(r["g"]), int(r["b"])))
    lines = {}
    with open(args.lines, newline="") as f:
        for r in csv.DictReader(f):
            xs, ys = lines.setdefault(r["lambda_nm"], ([], []))
            xs.append(float(r["phi_o_deg"]))
            ys.append(float(r["density"]))

    names = list(rows)
    fig = plt.figure(figsize=(8.0, 1.0 + 0.55 * len(names) + 2.8))
    grid = fig.add_gridspec(len(names) + 1, 1, height_ratios=[0.55] * len(names) + [2.8], hspace=0.35)
    for i, name in enumerate(names):
        ax = fig.add_subplot(grid[i, 0])
        data = rows[name]
        img = np.array([[c[1:] for c in data]], dtype=np.uint8)
        ax.imshow(img, aspect="auto", extent=(data[0][0], data[-1][0], 0, 1))
        ax.set_yticks([])
        ax.set_ylabel(name, rotation=0, ha="right", va="center", fontsize=8)
        ax.set_xticks([] if i + 1 < len(names) else [-90, -45, 0, 45, 90])
        if i + 1 == len(names):
            ax.set_xlabel("outgoing azimuth on the specular cone, phi_o (deg)")
    ax = fig.add_subplot(grid[len(names), 0])
    for lam, (xs, ys) in lines.items():
        ax.plot(xs, ys, label=f"{float(lam):g} nm", linewidth=1.2)
    ax.set_xlim(-90, 90)
    ax.set_xlabel("phi_o (deg)")
    ax.set_ylabel("mean reflectance per rad (Eq. 10)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    if args.title:
        fig.suptitle(args.title)
    fig.savefig(args.png, dpi=110, format="png", bbox_inches="tight")


if __name__ == "__main__":
    main()
