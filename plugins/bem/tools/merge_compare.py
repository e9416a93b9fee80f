#!/usr/bin/env python3
"""Merge the pattern files of several `plumage compare` runs made on the same segment and compare
every method with one reference (paper §6.1, Figs. 8-9).

Why: a full-wave solve of a 5 um hummingbird segment takes ~25-35 min on the shared 2-core machine,
and `plumage compare` re-runs its reference in every invocation; splitting the comparison into one
run per (full-wave method, wavelength) and merging their `<name>-patterns.csv` here gives the same
numbers without solving any full-wave case twice. The metrics are those of core/cli/cmd_compare.cpp:
Pearson correlation of the Eq. 10 densities U(phi_o), ||U - U_ref||_2 / ||U_ref||_2, and
R = sum U * (pi / samples) (Eq. 8 over Eq. 9), dR = R - R_ref.

Usage: /usr/bin/python3 merge_compare.py --reference fullwave_exact --out PREFIX RUN_DIR/name-patterns.csv ...
Writes PREFIX-metrics.csv and PREFIX-patterns-<incident>.png (unpolarised patterns of every
method, one panel per wavelength). A method present in several runs must agree between them
(the approximate solver is deterministic); the first copy is used.
"""
import argparse
import csv
import math
import sys
from collections import defaultdict

import numpy as np


def load(paths):
    data = {}  # (method, theta, phi, lam, pol) -> (phi_o array, density array)
    order = []
    for path in paths:
        rows = defaultdict(list)
        with open(path, newline="") as f:
            for r in csv.DictReader(line for line in f if not line.startswith("#")):
                key = (r["method"], float(r["theta_i_deg"]), float(r["phi_i_deg"]), float(r["lambda_nm"]), r["pol"])
                rows[key].append((float(r["phi_o_deg"]), float(r["density_per_rad"])))
        for key, v in rows.items():
            v.sort()
            arr = (np.array([a for a, _ in v]), np.array([b for _, b in v]))
            if key in data:
                diff = np.max(np.abs(arr[1] - data[key][1])) / max(np.max(np.abs(data[key][1])), 1e-300)
                if diff > 1e-6:
                    sys.exit(f"{key} differs between runs by {diff:.2e}")
                continue
            data[key] = arr
            if key[0] not in order:
                order.append(key[0])
    return data, order


def metrics(a, b):
    corr = float(np.corrcoef(a, b)[0, 1]) if np.std(a) > 0 and np.std(b) > 0 else float("nan")
    l2 = float(np.linalg.norm(a - b) / np.linalg.norm(b))
    dphi = math.pi / len(a)
    return corr, l2, float(np.sum(a) * dphi), float(np.sum(b) * dphi)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--reference", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--title", default="")
    ap.add_argument("patterns", nargs="+")
    args = ap.parse_args()
    data, order = load(args.patterns)
    cases = sorted({(k[1], k[2], k[3]) for k in data if k[0] == args.reference})
    if not cases:
        sys.exit(f"no patterns of the reference {args.reference}")
    with open(args.out + "-metrics.csv", "w") as f:
        f.write("# merged by plugins/bem/tools/merge_compare.py from: " + " ".join(args.patterns) + "\n")
        f.write("method,reference,theta_i_deg,phi_i_deg,lambda_nm,pol,correlation,rel_l2,R_method,R_reference,dR\n")
        for m in order:
            for (th, ph, lam) in cases:
                for pol in ("1", "2", "mean"):
                    if (m, th, ph, lam, pol) not in data:
                        continue
                    a = data[(m, th, ph, lam, pol)][1]
                    b = data[(args.reference, th, ph, lam, pol)][1]
                    c, l2, r, rr = metrics(a, b)
                    f.write(f"{m},{args.reference},{th:g},{ph:g},{lam:g},{pol},{c:.6f},{l2:.6f},{r:.6f},{rr:.6f},{r - rr:.6f}\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    incidents = sorted({(c[0], c[1]) for c in cases}, key=lambda x: (x[0], -x[1]))
    lams = sorted({c[2] for c in cases})
    # One colour per method across panels, and one legend listing every method of any panel.
    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    colour = {m: cycle[i % len(cycle)] for i, m in enumerate(order)}
    for (th, ph) in incidents:
        handles = {}
        cols = min(len(lams), 4)  # wrap many wavelengths into rows of at most 4 panels
        nrows = (len(lams) + cols - 1) // cols
        fig, axes = plt.subplots(nrows, cols, figsize=(max(8.0, 5.2 * cols), 4.2 * nrows), squeeze=False)
        for ax in list(axes.flat)[len(lams):]:
            ax.axis("off")
        for ax, lam in zip(axes.flat, lams):
            for m in order:
                key = (m, th, ph, lam, "mean")
                if key not in data:
                    continue
                x, y = data[key]
                ref = m == args.reference or m.startswith("fullwave")
                (line,) = ax.plot(x, y, lw=1.6 if ref else 1.0, ls="-" if ref else "--", color=colour[m], label=m)
                handles.setdefault(m, line)
            ax.set_title(f"lambda = {lam:g} nm")
            ax.set_xlabel("outgoing azimuth phi_o (deg)")
            ax.set_xlim(-90, 90)
        for row in axes:
            row[0].set_ylabel("reflectance per rad (Eq. 10), unpolarised")
        axes[0][-1].legend([handles[m] for m in order if m in handles], [m for m in order if m in handles], fontsize=7)
        fig.suptitle(f"{args.title} theta_i = {th:g} deg, phi_i = {ph:g} deg", fontsize=10)
        fig.tight_layout()
        tag = f"theta{th:g}_phi{ph:g}".replace("-", "m").replace(".", "p")
        fig.savefig(f"{args.out}-patterns-{tag}.png", dpi=110)
        plt.close(fig)


if __name__ == "__main__":
    main()
