"""Cross sections from Python: instance n of a species as arrays, its files byte-identical to
`plumage geometry`, the --stats report, and bad inputs."""
import numpy as np
import pytest

import plumage


@pytest.fixture
def rockdove(configs):
    return plumage.load_species(configs / "species" / "rockdove.yaml")


def test_arrays_of_an_instance(rockdove):
    cs = plumage.cross_section(rockdove, 1)
    assert cs.valid and cs.problems == [] and cs.instance == 1
    top = cs.top_nm
    assert top.ndim == 2 and top.shape[1] == 2 and top.shape[0] > 10
    assert np.all(np.diff(top[:, 0]) > 0), "the top surface runs left to right"
    assert cs.width_nm == pytest.approx(top[-1, 0] - top[0, 0])
    with pytest.raises(ValueError):
        top[0, 0] = 1.0  # a read-only view of the C++ section
    body = cs.regions[0]
    assert body["role"] == "body" and body["parent"] == -1 and body["material"] == "keratin"
    assert body["outline_nm"].shape[1] == 2
    assert all(0 <= r["parent"] < i for i, r in enumerate(cs.regions) if i > 0)


def test_views_keep_the_section_alive(rockdove):
    top = plumage.cross_section(rockdove, 0).top_nm  # the CrossSection itself is dropped
    assert np.isfinite(top).all() and top.base is not None


def test_layer_profile_under_the_centre(rockdove):
    cs = plumage.cross_section(rockdove, 0)
    assert cs.has_layered_model and cs.crystal is None
    profile = cs.layer_profile(len(cs.top_nm) // 2)
    assert isinstance(profile, plumage.LayerProfile)
    assert len(profile.materials) == len(profile.thickness_nm) >= 2
    assert (profile.thickness_nm > 0).all()
    assert profile.total_thickness_nm == pytest.approx(profile.thickness_nm.sum())
    assert len(cs.layer_profiles()) == len(cs.top_nm)
    with pytest.raises(IndexError):
        cs.layer_profile(len(cs.top_nm))


def test_files_are_those_of_the_command(rockdove, configs, tmp_path, plumage_cli):
    plumage_cli("geometry", configs / "species" / "rockdove.yaml", "--first", 2, "--out", tmp_path / "cli", "--no-png")
    cs = plumage.cross_section(rockdove, 2)
    cs.write(tmp_path / "py" / "rd", png=False)
    stem = f"rockdove-{rockdove.variant}-2"
    for ext in (".xsec", ".svg"):
        assert (tmp_path / "py" / f"rd{ext}").read_bytes() == (tmp_path / "cli" / f"{stem}{ext}").read_bytes()
    assert not (tmp_path / "py" / "rd.png").exists()


def test_statistics_report_is_the_command_s(rockdove, configs, plumage_cli):
    cli = plumage_cli("geometry", configs / "species" / "rockdove.yaml", "--instances", 2, "--stats").stdout
    sections = [plumage.cross_section(rockdove, n) for n in range(2)]
    assert plumage.geometry_statistics(sections, f"rockdove-{rockdove.variant}") == cli


def test_bad_inputs(rockdove):
    with pytest.raises(plumage.ConfigError) as info:
        plumage.cross_section(rockdove, -1)
    assert info.value.file == "--first"
    with pytest.raises(TypeError):
        plumage.cross_section("rockdove.yaml", 0)
