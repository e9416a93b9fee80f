#!/usr/bin/env python3
"""Cost of the Python package over the C++ library, measured in one run on one machine:

(a) BSDF evaluation of 1e6 (ω_o, λ) samples from numpy (Bsdf.eval, one incident direction) against
    the C++ throughput of the same evaluation (`plumage bench bsdf`, same material, same ω_i,
    same sample distribution); CPU time of the evaluating thread, best of 3. Target: ≥ 80 %.
(b) Python overhead per work unit of simulate: plumage.simulate(...) + write against
    `plumage simulate ... --out` on the same request, at two request sizes, so that the
    per-unit slope excludes the command's start-up (process, plug-ins, config).

Prints a markdown table (the lead records it in docs/benchmarks.md).

    PYTHONPATH=build/python python3 python/bench/bench_python.py [--material x.plm] [--build build]
"""
import argparse
import os
import pathlib
import re
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

import plumage

SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]
THETA_DEG, PHI_DEG = 30.0, -20.0  # the C++ benchmark's defaults


def samples(material, n, seed=7):
    """n directions uniform over the upper hemisphere and n wavelengths uniform over the bins."""
    rng = np.random.default_rng(seed)
    z, a = rng.random(n), 2 * np.pi * rng.random(n)
    r = np.sqrt(1 - z * z)
    lo = material.lambda_nm[0]
    span = material.lambda_nm[-1] + material.bin_width_nm - lo
    return np.stack([r * np.cos(a), r * np.sin(a), z], axis=1), lo + span * rng.random(n)


def python_bsdf(material, n):
    """Best-of-3 thread CPU seconds of Bsdf.eval on n samples: mean, then instance 0."""
    bsdf = material.bsdf()
    wo, lam = samples(material, n)
    t, p = np.radians(THETA_DEG), np.radians(PHI_DEG)
    wi = np.array([np.cos(t) * np.sin(p), np.sin(t), np.cos(t) * np.cos(p)])  # direction_from_angles
    out = {}
    for name, instance in (("mean BRDF", None), ("instance 0", 0)):
        best = float("inf")
        for _ in range(3):
            c0 = time.thread_time()
            bsdf.eval(wi, wo, lam, instance=instance)
            best = min(best, time.thread_time() - c0)
        out[name] = best
    return out


def cpp_bsdf(plumage_exe, material_file, n):
    """CPU seconds per row of `plumage bench bsdf` (its markdown table)."""
    text = subprocess.run([str(plumage_exe), "-q", "bench", "bsdf", "--material", str(material_file), "--samples", str(n)],
                          capture_output=True, text=True, check=True).stdout
    out = {}
    for line in text.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 8 and cells[3] in ("mean BRDF", "instance 0"):
            out[cells[3]] = float(cells[5])
    return out


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def process_cpu():
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def simulate_request(units):
    """A rock dove request of `units` work units: wavelengths × four incident θ_i, 2 instances."""
    lam = list(np.linspace(400, 700, units // 4))
    return dict(lambda_nm=lam, theta_deg=[0.0, 20.0, 40.0, 60.0], instances=2)


def time_simulate(plumage_exe, species, request, folder):
    """(CLI wall, CLI CPU, Python wall, Python CPU) seconds of one request, best of 3 each."""
    flags = ["--lambda-nm", ",".join(repr(float(v)) for v in request["lambda_nm"]),
             "--theta-deg", ",".join(f"{v:g}" for v in request["theta_deg"]), "--instances", str(request["instances"])]
    best = [float("inf")] * 4
    for _ in range(3):
        c0, t0 = children_cpu(), time.perf_counter()
        subprocess.run([str(plumage_exe), "-q", "simulate", str(species.file), *flags, "--out", str(folder / "cli.ffs")],
                       check=True)
        best[0] = min(best[0], time.perf_counter() - t0)
        best[1] = min(best[1], children_cpu() - c0)
        c0, t0 = process_cpu(), time.perf_counter()
        plumage.simulate(species, lambda_nm=[float(v) for v in request["lambda_nm"]], theta_deg=request["theta_deg"],
                         instances=request["instances"]).write(folder / "py.ffs")
        best[2] = min(best[2], time.perf_counter() - t0)
        best[3] = min(best[3], process_cpu() - c0)
    same = (folder / "cli.ffs").read_bytes() == (folder / "py.ffs").read_bytes()
    return best, same


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--material", help="feather material (.plm); default: a preview rock dove characterised first")
    parser.add_argument("--build", default=os.environ.get("PLUMAGE_BINARY_DIR", SOURCE_DIR / "build"))
    parser.add_argument("--samples", type=int, default=1_000_000)
    args = parser.parse_args()
    exe = pathlib.Path(args.build) / "bin" / "plumage"
    folder = pathlib.Path(tempfile.mkdtemp(prefix="plumage-bench-python-"))
    plumage.set_warning_echo(False)
    species = plumage.load_species(SOURCE_DIR / "configs" / "species" / "rockdove.yaml")
    material_file = pathlib.Path(args.material) if args.material else folder / "rockdove.plm"
    if not args.material:
        plumage.characterize(species, material_file, "preview")
    material = plumage.load_material(material_file)
    with open("/proc/loadavg") as f:
        load = f.read().split()[0]

    py = python_bsdf(material, args.samples)
    cpp = cpp_bsdf(exe, material_file, args.samples)
    print(f"machine: {os.cpu_count()} cores, load {load}; material {material.label} ({material.fidelity}); "
          f"plumage {plumage.__version__}\n")
    print(f"| BSDF, {args.samples} (ω_o, λ) samples, one ω_i | C++ CPU s | Python CPU s | C++ Ms/s | Python Ms/s "
          "| Python / C++ |")
    print("|---|---|---|---|---|---|")
    for name in ("mean BRDF", "instance 0"):
        n = args.samples
        print(f"| {name} | {cpp[name]:.3f} | {py[name]:.3f} | {n / cpp[name] * 1e-6:.2f} | {n / py[name] * 1e-6:.2f} "
              f"| {cpp[name] / py[name] * 100:.0f} % |")

    small, large = 4, 40
    (s_cli_w, s_cli_c, s_py_w, s_py_c), same_s = time_simulate(exe, species, simulate_request(small), folder)
    (l_cli_w, l_cli_c, l_py_w, l_py_c), same_l = time_simulate(exe, species, simulate_request(large), folder)
    per = lambda a, b: (b - a) / (large - small) * 1e3  # ms per unit, the slope between the sizes
    print(f"\n| simulate (rock dove, 2 instances, + .ffs write) | {small} units s | {large} units s | ms per unit |")
    print("|---|---|---|---|")
    print(f"| `plumage simulate` wall | {s_cli_w:.3f} | {l_cli_w:.3f} | {per(s_cli_w, l_cli_w):.2f} |")
    print(f"| plumage.simulate wall | {s_py_w:.3f} | {l_py_w:.3f} | {per(s_py_w, l_py_w):.2f} |")
    print(f"| `plumage simulate` CPU | {s_cli_c:.3f} | {l_cli_c:.3f} | {per(s_cli_c, l_cli_c):.2f} |")
    print(f"| plumage.simulate CPU | {s_py_c:.3f} | {l_py_c:.3f} | {per(s_py_c, l_py_c):.2f} |")
    print(f"| Python overhead per unit (CPU) | | | {per(s_py_c, l_py_c) - per(s_cli_c, l_cli_c):+.2f} |")
    print(f"\n.ffs bytes identical to the command's: {same_s and same_l}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
