"""examples/python/barbule_patterns.py runs (about 15 s: a 3 um BEM segment) and writes a PNG."""
import os
import struct
import subprocess

import conftest


def test_barbule_patterns_example(tmp_path):
    png = tmp_path / "patterns.png"
    env = dict(os.environ, PYTHONPATH=str(conftest.BINARY_DIR / "python"), MPLBACKEND="Agg")
    result = subprocess.run(["/usr/bin/python3", str(conftest.SOURCE_DIR / "examples" / "python" / "barbule_patterns.py"),
                             str(png)], capture_output=True, text=True, env=env, timeout=300)
    assert result.returncode == 0, result.stderr
    assert f"wrote {png}" in result.stdout.splitlines()
    header = png.read_bytes()[:24]
    assert header[:8] == b"\x89PNG\r\n\x1a\n" and header[12:16] == b"IHDR"
    width, height = struct.unpack(">II", header[16:24])
    assert 400 <= width <= 2000 and 300 <= height <= 2000
