"""Far fields from Python: simulate() writes the same .ffs bytes as `plumage simulate`, its arrays
are views of the set, progress reaches a callable that can stop the run, and bad requests raise
ConfigError at the command's flag."""
import os
import signal

import numpy as np
import pytest

import plumage

REQUEST = dict(lambda_nm=[450.0, 550.0], instances=2)


@pytest.fixture
def rockdove(configs):
    return plumage.load_species(configs / "species" / "rockdove.yaml")


def test_ffs_and_csv_are_byte_identical_to_the_command(rockdove, configs, tmp_path, plumage_cli):
    plumage_cli("simulate", configs / "species" / "rockdove.yaml", "--lambda-nm", "450,550", "--instances", 2,
                "--out", tmp_path / "cli.ffs", "--csv", tmp_path / "cli.csv")
    result = plumage.simulate(rockdove, **REQUEST)
    result.write(tmp_path / "py.ffs")
    result.write_pattern_csv(tmp_path / "py.csv")
    assert (tmp_path / "py.ffs").read_bytes() == (tmp_path / "cli.ffs").read_bytes()
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()


def test_arrays_of_a_unit(rockdove):
    result = plumage.simulate(rockdove, **REQUEST)
    assert len(result) == 2 and result.metadata["species"] == "rockdove"
    unit = result.units[1]
    assert unit.lambda_nm == 550.0 and unit.instances == 2 and unit.theta_rad == 0.0
    assert unit.pattern_count == 400 == unit.pattern_phi_o_rad.size
    n = unit.phi_o_rad.size
    assert unit.projected_phi_o_rad.size == n - 400
    np.testing.assert_array_equal(unit.phi_o_rad[:400], unit.pattern_phi_o_rad)
    fields = unit.fields
    assert fields.shape == (2, 2, n, 3) and fields.dtype == np.complex128
    view = unit.field(1, 0)
    np.testing.assert_array_equal(view, fields[1, 0])
    assert not view.flags.writeable and not unit.phi_o_rad.flags.writeable
    assert unit.incident_power.shape == (2, 2) and (unit.incident_power > 0).all()
    jitter = unit.incident_rad[:, 1]
    assert jitter[0] != jitter[1], "instances see φ_i + δ_n"
    density = unit.mean_reflectance_density(-1)
    np.testing.assert_allclose(density, 0.5 * (unit.mean_reflectance_density(0) + unit.mean_reflectance_density(1)))
    assert density.shape == (n,) and (density >= 0).all() and density.max() > 0


def test_views_outlive_the_set(rockdove):
    view = plumage.simulate(rockdove, lambda_nm=[550.0], instances=1).units[0].field(0, 1)
    assert np.isfinite(view).all()


def test_read_back(rockdove, tmp_path):
    result = plumage.simulate(rockdove, **REQUEST)
    result.write(tmp_path / "a.ffs")
    back = plumage.read_far_field_set(tmp_path / "a.ffs")
    assert back.metadata == result.metadata
    # The file stores fields in single precision (docs/formats.md).
    np.testing.assert_array_equal(back.units[0].fields, result.units[0].fields.astype(np.complex64))
    (tmp_path / "bad.ffs").write_bytes((tmp_path / "a.ffs").read_bytes()[:100])
    with pytest.raises(plumage.Error, match="bad.ffs"):
        plumage.read_far_field_set(tmp_path / "bad.ffs")


def test_warnings_are_in_the_metadata_of_their_run_only(rockdove, configs):
    starling = plumage.simulate(plumage.load_species(configs / "species" / "starling.yaml"), lambda_nm=[550.0], instances=2)
    assert "approx.rough_surface" in starling.warnings == starling.metadata["warnings"]
    assert "warnings" not in plumage.simulate(rockdove, lambda_nm=[550.0], instances=1).metadata


def test_progress_and_stopping(rockdove):
    calls = []
    plumage.simulate(rockdove, **REQUEST, progress=lambda done, total, what: calls.append((done, total, what)))
    assert calls[0] == (0, 2, "work units") and calls[-1] == (2, 2, "work units")

    class Stop(Exception):
        pass

    def stop(done, total, what):
        if done >= 1:
            raise Stop()

    with pytest.raises(Stop):
        plumage.simulate(rockdove, **REQUEST, progress=stop)


def test_ctrl_c_stops_the_run(rockdove):
    def ctrl_c(done, total, what):
        if done == 1:
            os.kill(os.getpid(), signal.SIGINT)  # as a Ctrl-C arriving during the run

    with pytest.raises(KeyboardInterrupt):
        plumage.simulate(rockdove, **REQUEST, progress=ctrl_c)


def test_cone_colours_picture(rockdove, tmp_path):
    plumage.simulate(rockdove, **REQUEST).draw_cone_colours(tmp_path / "p.png", "rock dove")
    assert (tmp_path / "p.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("request_, flag", [(dict(theta_deg=90.0), "--theta-deg"), (dict(phi_deg=[0, 95]), "--phi-deg"),
                                            (dict(lambda_nm=[50.0]), "--lambda-nm"), (dict(instances=-1), "--instances")])
def test_out_of_range_requests(rockdove, request_, flag):
    with pytest.raises(plumage.ConfigError) as info:
        plumage.simulate(rockdove, **request_)
    assert info.value.file == flag


def test_bad_arguments(rockdove):
    with pytest.raises(ValueError, match="directions"):
        plumage.simulate(rockdove, directions="sideways")
    with pytest.raises(ValueError, match="tables"):
        plumage.simulate(rockdove, tables="sometimes")
    with pytest.raises(plumage.ConfigError, match="full-wave"):
        plumage.simulate(rockdove, lambda_nm=[550.0], instances=1, directions="full")
