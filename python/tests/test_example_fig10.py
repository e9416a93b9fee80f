"""examples/python/fig10_hemispheres.py (paper Fig. 10) runs as documented — characterising the
rock dove's preview material itself — and writes a PNG of the 2 × 3 hemisphere plots."""
import subprocess
import sys
import time

import matplotlib.image
import numpy as np


def test_fig10_example_writes_the_figure(source_dir, tmp_path):
    script = source_dir / "examples" / "python" / "fig10_hemispheres.py"
    png, plm = tmp_path / "fig10.png", tmp_path / "rockdove.plm"
    t0 = time.perf_counter()
    done = subprocess.run([sys.executable, str(script), "--out", str(png), "--keep-material", str(plm), "--size", "96"],
                          capture_output=True, text=True)
    elapsed = time.perf_counter() - t0
    assert done.returncode == 0, done.stderr
    assert elapsed < 90, f"the example took {elapsed:.0f} s"
    assert plm.exists() and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    image = matplotlib.image.imread(png)
    assert image.shape[0] > 400 and image.shape[1] > 600
    rgb = image[..., :3]
    # Coloured lobes on black: bright pixels, and not all grey.
    assert rgb.max() > 0.9 and np.mean(rgb.max(axis=2) - rgb.min(axis=2)) > 0.005
