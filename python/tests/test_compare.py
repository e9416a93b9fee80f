"""The accuracy comparison from Python: the same metrics and patterns CSV bytes as `plumage
compare`, metrics and patterns as arrays, selections, and selections the config does not have."""
import numpy as np
import pytest

import plumage


@pytest.fixture
def tiny(source_dir):
    return source_dir / "tests" / "cli" / "data" / "compare-tiny.yaml"


def test_tables_are_the_command_s(tiny, tmp_path, plumage_cli):
    plumage_cli("compare", tiny, "--out", tmp_path / "cli", "--no-pictures")
    run = plumage.load_comparison(tiny).run()
    files = run.write(tmp_path / "py", pictures=False)
    for kind in ("metrics", "patterns"):  # -times.csv holds wall times
        assert files[kind].read_bytes() == (tmp_path / "cli" / f"tiny-{kind}.csv").read_bytes()
    assert files["times"].exists() and files["figures"] == []
    assert run.metrics_csv() == files["metrics"].read_text()


def test_metrics_and_patterns_as_arrays(tiny):
    comparison = plumage.load_comparison(tiny)
    assert comparison.name == "tiny" and comparison.reference == "reflected"
    assert [m["name"] for m in comparison.methods][:2] == ["reflected", "reflected_again"]
    run = comparison.run()
    m = run.metrics
    rows = len(run.methods) * 2 * 3 * 3  # methods x incidents x wavelengths x (pol 0, 1, unpolarised)
    assert all(v.shape == (rows,) for v in m.values())
    again = m["method"] == 1
    # The same method twice: identical patterns, correlation 1, no difference.
    np.testing.assert_array_equal(m["rel_l2"][again], 0.0)
    np.testing.assert_allclose(m["correlation"][again], 1.0)
    u = run.pattern("reflected", incident=1, pol=2)
    assert u.shape == (3, 90) and run.phi_o_rad.shape == (90,)
    np.testing.assert_array_equal(u, run.pattern(1, incident=1))
    assert not np.array_equal(u, run.pattern("incident_and_reflected", incident=1))
    assert run.field("reflected", 0, 2).shape == (2, 90, 3)
    s = run.summary["incident_and_reflected"]
    assert s["rel_l2_max"] > 0 and s["solve_s"] >= 0 and s["solve_s_per_lambda"].shape == (3,)


def test_selection(tiny):
    comparison = plumage.load_comparison(tiny)
    run = comparison.run(only=["incident_and_reflected"], reference="reflected_again", wavelengths_nm=[550], instance=2)
    assert {m["name"] for m in run.methods} == {"reflected_again", "incident_and_reflected"}
    assert run.reference == "reflected_again" and list(run.lambda_nm) == [550.0] and run.instance == 2
    assert len(comparison.methods) == 4 and list(comparison.lambda_nm) == [450, 550, 650], "the loaded one is unchanged"


@pytest.mark.parametrize("selection, flag", [(dict(only=["nosuch"]), "--only"), (dict(reference="nosuch"), "--reference"),
                                             (dict(wavelengths_nm=[500]), "--wavelengths"), (dict(instance=-1), "--instance")])
def test_selection_the_config_does_not_have(tiny, selection, flag):
    with pytest.raises(plumage.ConfigError) as info:
        plumage.load_comparison(tiny).run(**selection)
    assert info.value.file == flag


def test_bad_config_and_stopping(tiny, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(tiny.read_text().replace("reference: reflected", "reference: nosuch").replace(
        "../../../configs", str(tiny.parents[3] / "configs")))
    with pytest.raises(plumage.ConfigError) as info:
        plumage.load_comparison(bad)
    assert info.value.file.endswith("bad.yaml") and info.value.line > 0

    def stop(done, total, what):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        plumage.load_comparison(tiny).run(progress=stop)
