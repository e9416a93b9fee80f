#!/usr/bin/env python3
"""Approximate-solver error against the full-wave one, per barbule instance, next to the top
surface's roughness (docs/validation.md "Roughness on a species: starling").

  plot_species_roughness.py OUT.png STATS.txt SPECIES METRICS.csv [METRICS.csv ...]

STATS.txt is the output of `test_core "[stability-species]"` (one line per species and instance:
rough slope and its limit); each METRICS.csv one `plumage compare --instance N` run of that species
(the instance is read from the file's first line). Prints a markdown table (per instance: slope,
limit, warned, and per method the mean correlation and relative L2 of the unpolarised pattern
over incident directions and wavelengths, and the largest |dR|) and draws rel. L2 against
slope / limit.
"""
import csv
import re
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def stats_of(path, species):
    out = {}
    pat = re.compile(r"^(\S+)\s+instance (\d+): .*rough slope ([0-9.]+) rad \(limit ([0-9.]+)\)")
    for line in open(path):
        m = pat.match(line)
        if m and m.group(1) == species:
            out[int(m.group(2))] = (float(m.group(3)), float(m.group(4)))
    return out


def metrics_of(path):
    with open(path) as f:
        first = f.readline()
        m = re.search(r"instance (\d+),", first)
        if not m:
            sys.exit(f"{path}: first line names no instance")
        rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
    per = defaultdict(lambda: {"corr": [], "l2": [], "dr": []})
    for r in rows:
        if r["pol"] != "mean" or r["method"] == r["reference"]:
            continue
        p = per[r["method"]]
        p["corr"].append(float(r["correlation"]))
        p["l2"].append(float(r["rel_l2"]))
        p["dr"].append(abs(float(r["dR"])))
    return int(m.group(1)), per


def main():
    if len(sys.argv) < 5:
        sys.exit(__doc__)
    out, stats_path, species = sys.argv[1:4]
    stats = stats_of(stats_path, species)
    runs = sorted(metrics_of(p) for p in sys.argv[4:])
    methods = sorted({m for _, per in runs for m in per})
    print("| instance | rms slope (rad) | limit | warned | " + " | ".join(f"{m}: corr. / rel. L2 / max abs dR" for m in methods) + " |")
    print("|---" * (4 + len(methods)) + "|")
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    markers = ["o", "s", "^", "D"]
    for inst, per in runs:
        slope, limit = stats[inst]
        cells = []
        for k, m in enumerate(methods):
            p = per[m]
            corr = sum(p["corr"]) / len(p["corr"])
            l2 = sum(p["l2"]) / len(p["l2"])
            cells.append(f"{corr:.3f} / {l2:.3f} / {max(p['dr']):.4f}")
            warned = slope > limit
            ax.plot([slope / limit], [l2], markers[k % 4], color="tab:red" if warned else "tab:blue",
                    mfc="none" if k else None, ms=8, label=m if inst == runs[0][0] else None)
            ax.annotate(str(inst), (slope / limit, l2), textcoords="offset points", xytext=(6, 4), fontsize=8)
        print(f"| {inst} | {slope:.3f} | {limit:.3f} | {'yes' if slope > limit else 'no'} | " + " | ".join(cells) + " |")
    ax.axvline(1.0, color="grey", ls=":", lw=1)
    ax.axhline(0.15, color="grey", ls="--", lw=1)
    ax.text(1.01, ax.get_ylim()[0], " warning limit", color="grey", fontsize=8, va="bottom")
    ax.set_xlabel("top-surface rms slope / the solver's limit (approx.rough_surface above 1)")
    ax.set_ylabel("rel. L2 of U(phi_o) vs full-wave, mean over cases")
    ax.set_title(f"{species}: approximate vs full-wave per instance (red: warned)", fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
