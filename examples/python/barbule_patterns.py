#!/usr/bin/env python3
"""Approximate against full-wave (BEM) reflection patterns of one barbule segment (paper §6.1).

Runs the comparison examples/python/barbule_patterns.yaml (a 3 um rock-dove segment at 550 nm,
normal incidence) through plumage.load_comparison(...).run(), and plots the unpolarised
reflectance density U(phi_o) (Eq. 10) of both methods with matplotlib:

    PYTHONPATH=build/python python3 examples/python/barbule_patterns.py [out.png]
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import plumage  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("png", nargs="?", default="barbule_patterns.png", help="picture to write")
    parser.add_argument("--config", default=str(HERE / "barbule_patterns.yaml"), help="comparison config")
    args = parser.parse_args()

    comparison = plumage.load_comparison(args.config)
    run = comparison.run()
    phi_o_deg = np.degrees(run.phi_o_rad)
    incident = run.incidents

    fig, ax = plt.subplots(figsize=(7, 4), dpi=100)
    for method in run.methods:
        u = run.pattern(method["name"], incident=0, pol=2)  # (n_lambda, n_directions)
        seconds = run.summary[method["name"]]["solve_s"]
        label = f"{method['name']} ({method['solver_type']}, {seconds:.2f} s)"
        for k, lam in enumerate(run.lambda_nm):
            ax.plot(phi_o_deg, u[k], label=f"{label}, {lam:g} nm")
    approx = run.summary["approximate"]
    ax.set_title(f"{comparison.species.common_name} barbule, {comparison.segment_um:g} um segment, "
                 f"theta_i = {incident['theta_deg'][0]:g} deg, phi_i = {incident['phi_deg'][0]:g} deg\n"
                 f"approximate vs BEM: correlation {approx['correlation_mean']:.3f}, "
                 f"relative L2 {approx['rel_l2_mean']:.3f}", fontsize=9)
    ax.set_xlabel("outgoing azimuth phi_o (deg)")
    ax.set_ylabel("reflectance density per rad (Eq. 10)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.png)
    print(f"wrote {args.png}")


if __name__ == "__main__":
    main()
