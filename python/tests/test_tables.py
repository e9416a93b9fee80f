"""Crystal cells and reflection tables from Python: the table file the same bytes as `plumage table
build`, queries the same numbers as `plumage table query`, bad input as plumage.errors."""
import json
import math
import os
import signal
import threading
import time

import numpy as np
import pytest

import plumage
from plumage import errors

# The smallest build of tests/cli/test_table_cli.cpp: one wavelength, one cos theta, two cos phi.
GRID = dict(fidelity="preview", n_lambda=1, lambda_min_nm=550, lambda_max_nm=550, n_theta=1, n_phi=2)
GRID_FLAGS = ["--fidelity", "preview", "--n-lambda", "1", "--lambda-min", "550", "--lambda-max", "550",
              "--n-theta", "1", "--n-phi", "2"]


@pytest.fixture
def tiny_crystal(configs, tmp_path):
    """mallard-green with a single row of rods: the cheapest real crystal cell."""
    text = (configs / "crystals" / "mallard-green.yaml").read_text()
    assert "rows: 6" in text
    path = tmp_path / "tiny-crystal.yaml"
    path.write_text(text.replace("rows: 6", "rows: 1"))
    return path


@pytest.fixture
def tiny_table(tiny_crystal, tmp_path, plumage_cli):
    out = tmp_path / "cli.plt"
    plumage_cli("table", "build", tiny_crystal, *GRID_FLAGS, "--out", out)
    return out


def test_load_crystal(tiny_crystal):
    c = plumage.load_crystal(tiny_crystal)
    assert c.name == "mallard-green" and c.rows == 1 and c.lattice == "hexagonal"
    assert c.summary == plumage.check_config(tiny_crystal)["summary"]
    assert c.depth_nm > c.cortex_nm > 0 and c.a_x_nm > 0
    assert c.materials["rod"] == "melanin"


def test_build_table_writes_the_commands_bytes(tiny_crystal, tiny_table, tmp_path):
    calls = []
    out = tmp_path / "py.plt"
    result = plumage.build_table(tiny_crystal, out, progress=lambda d, t, w: calls.append((d, t, w)), **GRID)
    assert out.read_bytes() == tiny_table.read_bytes()
    assert (result["crystal"], result["n_lambda"], result["n_theta"], result["n_phi"]) == ("mallard-green", 1, 1, 2)
    assert "fdtd runs" in result["notes"]
    assert calls and calls[-1][0] == calls[-1][1]  # the last call reports the work finished


def test_read_table_views_and_query_as_the_command(tiny_table, plumage_cli):
    t = plumage.read_table(tiny_table)
    assert t.crystal == "mallard-green"
    np.testing.assert_array_equal(t.lambda_nm, [550.0])
    np.testing.assert_array_equal(t.cos_phi, [0.5, 1.0])
    assert t.jones.shape == (1, 1, 2, 2, 2) and t.jones.dtype == np.complex128
    assert not t.jones.flags.writeable and not t.lambda_nm.flags.writeable
    assert t.jones.base is not None  # a view of the table's memory, not a copy
    # The mirror rule: ss, pp unchanged, sp, ps negated (reflection_table.hpp).
    j = t.query(550, 30, [10, -10])
    assert j.shape == (2, 2, 2)
    assert j[0, 0, 0] == j[1, 0, 0] and j[0, 1, 0] == -j[1, 1, 0]
    cli = json.loads(plumage_cli("table", "query", tiny_table, "--lambda-nm", "550", "--theta-deg", "30",
                                 "--phi-deg", "10", "--format", "json").stdout)
    for name, (row, col) in {"ss": (0, 0), "sp": (0, 1), "ps": (1, 0), "pp": (1, 1)}.items():
        re, im = cli["jones"][name]
        assert j[0, row, col] == pytest.approx(complex(re, im), rel=1e-8, abs=1e-12)  # %.9g in the JSON
    R = t.reflectance([550, 550], 30, 10)
    assert R.shape == (2, 2)
    assert R[0, 0] == pytest.approx(cli["R_s"], rel=1e-5) and R[0, 1] == pytest.approx(cli["R_p"], rel=1e-5)
    # Grazing incidence is exactly diag(-1, -1).
    np.testing.assert_array_equal(t.query(550, 90, 0)[0], [[-1, 0], [0, -1]])


def test_query_arguments(tiny_table):
    t = plumage.read_table(tiny_table)
    with pytest.raises(ValueError, match="equal lengths"):
        t.query([500, 550], [0, 10, 20], 0)
    with pytest.raises(ValueError, match="finite"):
        t.query(math.nan, 0, 0)
    with pytest.raises(TypeError):
        t.query(np.zeros((2, 2)), 0, 0)


def test_a_raising_progress_stops_the_build_and_the_rerun_resumes(tiny_crystal, tmp_path):
    class Stop(Exception):
        pass

    def stop(done, total, what):
        raise Stop()

    out = tmp_path / "stopped.plt"
    with pytest.raises(Stop):
        plumage.build_table(tiny_crystal, out, progress=stop, **GRID)
    assert not out.exists() and out.with_name(out.name + ".partial").exists()
    result = plumage.build_table(tiny_crystal, out, **GRID)
    assert "resumed from a checkpoint" in result["notes"]
    assert plumage.read_table(out).notes == result["notes"]


def test_ctrl_c_stops_the_build(tiny_crystal, tmp_path):
    # SIGINT while the builder runs without the GIL: the next progress report raises it.
    out = tmp_path / "interrupted.plt"
    timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            plumage.build_table(tiny_crystal, out, **GRID)
            time.sleep(5)  # a build faster than the timer: the interrupt still arrives here
    finally:
        timer.cancel()
    assert out.exists() or out.with_name(out.name + ".partial").exists()


def test_bad_inputs_raise_the_documented_errors(tiny_crystal, tmp_path):
    bad = tmp_path / "bad-crystal.yaml"
    bad.write_text(tiny_crystal.read_text().replace("rows: 1", "rows: 1\n  rowz: 2"))
    with pytest.raises(errors.ConfigError) as e:
        plumage.load_crystal(bad)
    assert e.value.field.endswith("rowz") and e.value.line > 0
    with pytest.raises(errors.ConfigError):
        plumage.build_table(bad, tmp_path / "x.plt", **GRID)
    with pytest.raises(errors.ConfigError, match="resolution_nm"):
        plumage.build_table(tiny_crystal, tmp_path / "x.plt", resolution_nm=-3, **GRID)
    (tmp_path / "folder.plt").mkdir()
    with pytest.raises(errors.OutputPathError):
        plumage.build_table(tiny_crystal, tmp_path / "folder.plt", **GRID)
    (tmp_path / "link.plt").symlink_to(tmp_path / "elsewhere.plt")
    with pytest.raises(errors.OutputPathError):
        plumage.build_table(tiny_crystal, tmp_path / "link.plt", **GRID)
    with pytest.raises(errors.OutputPathError):
        plumage.build_table(tiny_crystal, tiny_crystal, **GRID)  # the output would overwrite the input
    with pytest.raises(ValueError, match="fidelity"):
        plumage.build_table(tiny_crystal, tmp_path / "x.plt", **{**GRID, "fidelity": "draft"})
    with pytest.raises(errors.Error):
        plumage.read_table(tmp_path / "missing.plt")
    assert not (tmp_path / "x.plt").exists()
