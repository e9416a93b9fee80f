#!/usr/bin/env python3
"""Paper Fig. 10, first row: projected-hemisphere plots of the rock dove barbule's mean BRDF and
of a synthesized BRDF instance, at the incident directions (θ_i, φ_i) = (0°, 0°), (0°, −45°),
(45°, 0°).

Each point of a plot is an outgoing direction ω_o of the upper hemisphere projected onto the unit
disk (ω_o,x across the barbule, ω_o,y along it); its colour is the spectral BRDF times cos θ_o
over the material's wavelengths turned into sRGB under D65 by the library's colour functions
(Material.hemisphere_panels, the same pixels as `plumage brdf plot`). The mean plots are smooth;
the instance is 1D-like, varying along one direction (paper §7.1).

    python3 fig10_hemispheres.py --out fig10.png                 # characterises a preview material
    python3 fig10_hemispheres.py --material rockdove.plm --out fig10.png

Without --material, the rock dove's preview material is characterised first (about 15–30 s on
one core) into a temporary folder (or --keep-material PATH).
"""
import argparse
import pathlib
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import plumage  # noqa: E402

INCIDENTS = [(0.0, 0.0), (0.0, -45.0), (45.0, 0.0)]  # (θ_i, φ_i) in degrees, as in Fig. 10
SOURCE_DIR = pathlib.Path(__file__).resolve().parents[2]


def material_for(args):
    """The material to plot: the one given, or a preview characterisation of the rock dove."""
    if args.material:
        return plumage.load_material(args.material)
    species = plumage.load_species(SOURCE_DIR / "configs" / "species" / "rockdove.yaml")
    out = pathlib.Path(args.keep_material) if args.keep_material else pathlib.Path(tempfile.mkdtemp()) / "rockdove.plm"
    print(f"characterising {species.species}/{species.variant} (preview) into {out} ...", file=sys.stderr)
    result = plumage.characterize(species, out, "preview")
    print(f"  {result['plan']['groups']} groups in {result['wall_s']:.1f} s", file=sys.stderr)
    return result["material"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="fig10_hemispheres.png", help="PNG to write")
    parser.add_argument("--material", help="feather material (.plm); default: characterise a preview one")
    parser.add_argument("--keep-material", help="where to keep the characterised material")
    parser.add_argument("--instance", type=int, default=0, help="BRDF instance to show beside the mean")
    parser.add_argument("--size", type=int, default=160, help="pixels per plot side")
    args = parser.parse_args()

    material = material_for(args)
    # Mean and instances 0 … k; the exposure maps the 99.5th percentile of the mean plots'
    # luminance to 1 (the command's automatic exposure), the same for every plot.
    panels = material.hemisphere_panels(incidents=INCIDENTS, instances=args.instance + 1, size=args.size)
    rgb = panels["srgb8"]

    fig, axes = plt.subplots(2, len(INCIDENTS), figsize=(3.0 * len(INCIDENTS), 6.2), squeeze=False)
    for col, (theta, phi) in enumerate(INCIDENTS):
        for row, (column, name) in enumerate([(0, r"mean $\bar f_r$"), (1 + args.instance, f"instance $f_r^{{({args.instance})}}$")]):
            ax = axes[row][col]
            ax.imshow(rgb[col, column], extent=(-1, 1, -1, 1), origin="upper", interpolation="nearest")
            ax.add_patch(plt.Circle((0, 0), 1.0, fill=False, color="0.5", lw=0.8))
            ax.set_title(f"{name}\n$(\\theta_i, \\phi_i) = ({theta:g}°, {phi:g}°)$", fontsize=9)
            ax.set_xticks([])
            ax.set_yticks([])
    axes[1][0].set_xlabel(r"$\omega_{o,x}$ (across the barbule)")
    axes[1][0].set_ylabel(r"$\omega_{o,y}$ (along the barbule)")
    fig.suptitle(f"{material.label} ({material.fidelity}): BRDF · cos θo, D65, exposure ×{panels['exposure']:.3g}",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=100)
    print(f"wrote {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
