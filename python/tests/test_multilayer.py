"""Planar stacks from Python: `plumage multilayer` and `plumage spectra` over arrays of λ and θ,
the same numbers as the commands, and bad inputs."""
import numpy as np
import pytest

import plumage

STACK = "air | keratin 300 | {melanin 90 | keratin 100}*3 | air"
LAMBDA_NM = [400.0, 455.5, 600.0, 700.0]
THETA_DEG = [0.0, 30.0, 60.0]


def g12(v):
    """A number as the command prints it (std::setprecision(12))."""
    return f"{v:.12g}"


def test_reflection_is_the_command_s(plumage_cli):
    r = plumage.multilayer(STACK, LAMBDA_NM, THETA_DEG)
    assert r["R_s"].shape == r["r_p"].shape == (len(THETA_DEG), len(LAMBDA_NM))
    assert r["r_s"].dtype == np.complex128
    np.testing.assert_allclose(r["R_s"], np.abs(r["r_s"]) ** 2, rtol=1e-14)  # std::norm may fuse (FMA)
    assert not r["r_sp"].any() and not r["r_ps"].any(), "a multilayer does not couple s and p"
    out = plumage_cli("multilayer", "--stack", STACK, "--lambda-nm", ",".join(map(g12, LAMBDA_NM)),
                      "--theta-deg", ",".join(map(g12, THETA_DEG))).stdout.splitlines()
    assert out[0] == "# stack: " + r["stack"]
    rows = out[3:]
    assert len(rows) == r["R_s"].size
    for i, row in enumerate(rows):
        t, k = divmod(i, len(LAMBDA_NM))
        rs, rp = r["r_s"][t, k], r["r_p"][t, k]
        mine = [LAMBDA_NM[k], THETA_DEG[t], rs.real, rs.imag, rp.real, rp.imag, r["R_s"][t, k], r["R_p"][t, k]]
        assert row == ",".join(map(g12, mine))


def test_stack_from_arrays_equals_the_text():
    arrays = plumage.LayerProfile(materials=["keratin"] + ["melanin", "keratin"] * 3,
                                  thickness_nm=np.array([300] + [90, 100] * 3), ambient="air", substrate="air")
    text = plumage.LayerProfile(STACK)
    assert str(arrays) == str(text) and len(text) == 7
    assert text.materials[:2] == ["keratin", "melanin"] and text.thickness_nm[1] == 90
    a, b = plumage.multilayer(arrays, LAMBDA_NM, 20.0), plumage.multilayer(STACK, LAMBDA_NM, 20.0)
    np.testing.assert_array_equal(a["r_s"], b["r_s"])
    np.testing.assert_array_equal(a["r_p"], b["r_p"])


def test_species_spectra_csv_is_the_command_s(configs, tmp_path, plumage_cli):
    species = configs / "species" / "rockdove.yaml"
    plumage_cli("spectra", species, "--lambda-nm", "400,500,600", "--theta-deg", "0,45", "--csv", tmp_path / "cli.csv")
    spectra = plumage.spectra(plumage.load_species(species), [400, 500, 600], [0, 45], csv=tmp_path / "py.csv")
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    (s,) = spectra
    assert s["species"] == "rockdove" and s["R_s"].shape == (2, 3)
    assert ((s["R_s"] >= 0) & (s["R_s"] <= 1)).all()


def test_bad_inputs():
    with pytest.raises(plumage.ConfigError) as info:
        plumage.multilayer(STACK, LAMBDA_NM, [95.0])
    assert info.value.file == "--theta-deg"
    with pytest.raises(plumage.ConfigError) as info:
        plumage.multilayer("air | keratin x | air", LAMBDA_NM)
    assert info.value.file == "--stack" and "keratin x" in info.value.message
    with pytest.raises(ValueError, match="differ in length"):
        plumage.LayerProfile(materials=["keratin"], thickness_nm=[1, 2])
    with pytest.raises(ValueError, match="materials\\[0\\]"):
        plumage.LayerProfile(materials=["unobtainium"], thickness_nm=[1])
    with pytest.raises(ValueError, match="finite"):
        plumage.multilayer(STACK, [np.nan])
    with pytest.raises(plumage.PluginError):
        plumage.multilayer(STACK, LAMBDA_NM, model="nosuch")
