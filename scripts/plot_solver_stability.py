#!/usr/bin/env python3
"""Charts of the approximate solver's stability study against the BEM (issue 9).

Reads the CSVs that `ctest -R solver_stability_bem` (label `validation`, `make validate`) writes
into build/tests and draws one PNG of four panels:
  (a, b) relative L2 error of the reflectance pattern against the measured rms slope of the top
         (roughness), one curve per correlation length / curvature, at 550 and 650 nm (mean over
         phi_i = 0 and -30 deg);
  (c)    the same against the radius of curvature in wavelengths (curved films, melanin cylinders);
  (d)    toward grazing incidence: error against the horizon-spill ratio of the window's lobe.
The limits of core/src/solver/surface_validity.hpp are drawn as dotted lines.

    python3 scripts/plot_solver_stability.py build/tests/solver_stability_roughness.csv \
        build/tests/solver_stability_grazing.csv --out docs/img/solver-stability.png
"""
import argparse
import csv
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# Mirrors core/src/solver/surface_validity.hpp and the study's bound (tests/test_solver_stability_study.cpp).
MAX_ROUGH_SLOPE = 0.12
MAX_ROUGH_SLOPE_CURVED = 0.05  # at a curvature spread of 0.1 rad under the window (the 4 µm arc)
MIN_RADIUS_WAVELENGTHS = 2.0
MAX_HORIZON_SPILL = 0.5
HOLD_BOUND = 0.15


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("roughness_csv")
    ap.add_argument("grazing_csv")
    ap.add_argument("--out", required=True)
    args = ap.parse_args()

    rows = read(args.roughness_csv)
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))

    # (a, b): rough films, per wavelength; one point per body (mean over the two incident azimuths).
    for ax, lam in zip(axes[0], ("550", "650")):
        groups = defaultdict(dict)
        for r in rows:
            if r["body"] != "keratin_film" or float(r["lambda_nm"]) != float(lam):
                continue
            if float(r["rms_slope_nominal"]) == 0 and float(r["radius_um"]) not in (0.0, 4.0):
                continue
            radius = float(r["radius_um"])
            smooth = float(r["rms_slope_nominal"]) == 0
            taus = [0.25, 0.5, 1.0] if (smooth and radius == 0) else ([0.5] if smooth else [float(r["correlation_um"])])
            for tau in taus:
                label = f"τ = {tau:g} µm" + (f", arc R = {radius:g} µm" if radius > 0 else ", flat")
                key = (r["rms_slope_nominal"], r["seed"])
                body = groups[label].setdefault(key, [float(r["rough_slope_rad"]), []])
                body[1].append(float(r["rel_l2"]))
        for label, bodies in sorted(groups.items()):
            pts = sorted((v[0], sum(v[1]) / len(v[1])) for v in bodies.values())
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=4, label=label)
        ax.axvline(MAX_ROUGH_SLOPE, ls=":", c="k")
        ax.axvline(MAX_ROUGH_SLOPE_CURVED, ls=":", c="tab:orange")
        ax.axhline(HOLD_BOUND, ls="--", c="grey", lw=0.8)
        ax.set_xlabel("rms slope of the top about its mean arc, under the window (rad, measured)")
        ax.set_ylabel("relative L2 of U(φ_o) vs BEM")
        ax.set_title(f"({'a' if lam == '550' else 'b'}) roughness, λ = {lam} nm (mean of φ_i = 0°, −30°)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)

    # (c): curvature, radius in wavelengths.
    ax = axes[1][0]
    curves = defaultdict(list)
    for r in rows:
        if float(r["rms_slope_nominal"]) != 0:
            continue
        radius = float(r["radius_um"])
        if radius <= 0:
            continue
        label = ("film arc" if r["body"] == "keratin_film" else "melanin cylinder") + f", {float(r['lambda_nm']):g} nm"
        curves[label].append((radius * 1000 / float(r["lambda_nm"]), float(r["phi_i_deg"]), float(r["rel_l2"])))
    for label, pts in sorted(curves.items()):
        by_radius = defaultdict(list)
        for x, _, e in pts:
            by_radius[x].append(e)
        xs = sorted(by_radius)
        ax.plot(xs, [sum(by_radius[x]) / len(by_radius[x]) for x in xs], "o-", ms=4, label=label)
    ax.axvline(MIN_RADIUS_WAVELENGTHS, ls=":", c="k")
    ax.axhline(HOLD_BOUND, ls="--", c="grey", lw=0.8)
    ax.set_xscale("log")
    ax.set_xlabel("radius of curvature / λ")
    ax.set_ylabel("relative L2 of U(φ_o) vs BEM")
    ax.set_title("(c) curvature (mean of φ_i = 0°, −30°)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")

    # (d): grazing.
    ax = axes[1][1]
    curves = defaultdict(list)
    for r in read(args.grazing_csv):
        kind = "flat" if float(r["rms_slope_nominal"]) == 0 else f"rough {float(r['rms_slope_nominal']):g}"
        label = f"W = {float(r['width_um']):g} µm, {kind}"
        q = float(r["spill"])
        curves[label].append((min(q, 20.0), float(r["rel_l2"])))
    for label, pts in sorted(curves.items()):
        pts.sort()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o", ms=4, label=label)
    ax.axvline(MAX_HORIZON_SPILL, ls=":", c="k")
    ax.axhline(HOLD_BOUND, ls="--", c="grey", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("horizon spill: lobe half-width / distance to φ_o = ±90° (capped at 20)")
    ax.set_ylabel("relative L2 of U(φ_o) vs BEM")
    ax.set_title("(d) toward grazing, 650 nm, θ_i 0–84°, φ_i 0 to −84°")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")

    fig.suptitle("Approximate solver vs full-wave BEM (window s = W/5)\ndotted: warning limits (orange: roughness limit "
                 "at a window bend of 0.1 rad, the 4 µm arc); dashed: the 0.15 bound")
    fig.tight_layout()
    tmp = args.out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, args.out)


if __name__ == "__main__":
    main()
