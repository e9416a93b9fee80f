"""Measured spectra from Python: the reader and comparison of `plumage spectra --measured`."""
import numpy as np
import pytest

import plumage


def test_reads_a_semicolon_percent_export_with_angles(source_dir):
    s = plumage.read_measured_spectrum(source_dir / "fuzz" / "corpus" / "measured" / "semicolon-percent-angles.csv")
    assert [c["theta_deg"] for c in s["curves"]] == [0.0, 30.0]
    first = s["curves"][0]
    np.testing.assert_allclose(first["lambda_nm"], [400, 450.5, 500, 550.5, 600])
    np.testing.assert_allclose(first["reflectance"], [0.051, 0.123, 0.31, 0.224, 0.082])
    assert any("percent" in n for n in s["notes"])


def test_bad_file_names_its_line(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("wavelength,R\n400,0.1\n450,0.2\n440,0.3\n500,0.1\n")
    with pytest.raises(plumage.InputFileError, match=r"bad\.csv:4"):
        plumage.read_measured_spectrum(bad)


def test_compare_a_shifted_gaussian():
    lam = np.arange(400.0, 700.0, 2.0)
    gauss = lambda centre: 0.3 * np.exp(-0.5 * ((lam - centre) / 20.0) ** 2)
    measured = {"lambda_nm": lam, "reflectance": gauss(557.3)}
    c = plumage.compare_spectra(lam, gauss(550.3), measured)
    assert c["peak_difference_nm"] == pytest.approx(7.0, abs=0.1)
    assert c["points"] == lam.size
    assert 0 < c["rms_error"] < 0.1 and 0.8 < c["correlation"] < 1.0


def test_compare_refuses_unequal_lengths():
    with pytest.raises(ValueError):
        plumage.compare_spectra([400, 500, 600], [0.1, 0.2], {"lambda_nm": [400, 500, 600], "reflectance": [0, 1, 0]})


def test_same_numbers_as_the_command(configs, source_dir, plumage_cli):
    import re
    file = source_dir / "fuzz" / "corpus" / "measured" / "comma-fraction.csv"
    printed = plumage_cli("spectra", configs / "species" / "rockdove.yaml", "--measured", file,
                          "--lambda-nm", "400:700:5").stderr
    match = re.search(r"peak predicted ([0-9.]+) nm, measured ([0-9.]+) nm.*RMS error ([0-9.]+), correlation (-?[0-9.]+)", printed)
    assert match, printed
    lam = np.arange(400, 701, 5)
    R = plumage.spectra(plumage.load_species(configs / "species" / "rockdove.yaml"), lam, theta_deg=[0])[0]
    c = plumage.compare_spectra(lam, 0.5 * (R["R_s"][0] + R["R_p"][0]),
                                plumage.read_measured_spectrum(file)["curves"][0])
    assert f"{c['predicted_peak_nm']:.1f}" == match[1] and f"{c['measured_peak_nm']:.1f}" == match[2]
    assert f"{c['rms_error']:.4f}" == match[3] and f"{c['correlation']:.3f}" == match[4]
