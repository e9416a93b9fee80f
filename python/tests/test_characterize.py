"""`plumage characterize` / `plumage merge` from Python: the same .plm bytes as the command, a
cancelled run (an exception from the progress callable, or Ctrl-C) leaves the journal and no
material, and the next call resumes it to the same bytes."""
import os
import signal

import pytest

import plumage

# The smallest preview runs of tests/cli/test_characterize_cli.cpp.
TINY = dict(grid=3, lambda_nm=[400, 500], instances=3, noise_functions=8)
TINY_FLAGS = ["--grid", "3", "--lambda-nm", "400,500", "--instances", "3", "--noise-functions", "8"]
RESUME = dict(grid=4, lambda_nm=[400, 450, 500], instances=3, noise_functions=8)
RESUME_FLAGS = ["--grid", "4", "--lambda-nm", "400,450,500", "--instances", "3", "--noise-functions", "8"]


@pytest.fixture(scope="module")
def rockdove():
    from conftest import SOURCE_DIR
    return plumage.load_species(SOURCE_DIR / "configs" / "species" / "rockdove.yaml")


def cli_material(plumage_cli, rockdove, flags, out):
    plumage_cli("characterize", rockdove.file, "--fidelity", "preview", *flags, "--out", out)
    return out.read_bytes()


def test_material_equals_the_commands(rockdove, tmp_path, plumage_cli, monkeypatch):
    expected = cli_material(plumage_cli, rockdove, TINY_FLAGS, tmp_path / "cli.plm")
    monkeypatch.chdir(tmp_path)  # nothing but the material may appear here (no diagnostics asked)
    seen, plans = [], []
    r = plumage.characterize(rockdove, tmp_path / "py.plm", "preview", **TINY,
                             progress=lambda done, total, what: seen.append((done, total, what)),
                             on_plan=plans.append)
    assert (tmp_path / "py.plm").read_bytes() == expected
    assert not (tmp_path / "py.plm.journal").exists()
    assert r["plan"]["groups"] == 6 and r["plan"]["todo"] == 6 and r["plan"]["resumed"] == 0
    assert plans and plans[0]["groups"] == 6
    assert seen[0] == (0, 18, "work units") and seen[-1] == (18, 18, "work units")
    assert r["settings"]["grid"] == 3 and list(r["settings"]["lambda_nm"]) == [400.0, 500.0]
    m = r["material"]
    assert m.label == "rockdove/forest" and m.key == r["settings"]["key"] and m.fidelity == "preview"
    assert r["wall_s"] > 0 and "fit" in r["fit_summary"].lower()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cli.plm", "py.plm"]
    # Diagnostics only where asked, and the same material bytes.
    plumage.characterize(rockdove, tmp_path / "d.plm", **TINY, diagnostics=tmp_path / "diag")
    assert (tmp_path / "diag" / "fit-summary.txt").exists() and (tmp_path / "d.plm").read_bytes() == expected


class Stop(Exception):
    pass


def stop_after_first_group(done, total, what):
    if done > 0:
        raise Stop()


def interrupt_after_first_group(done, total, what):
    if done > 0:
        os.kill(os.getpid(), signal.SIGINT)  # Ctrl-C, as a user would


@pytest.mark.parametrize("progress, raised", [(stop_after_first_group, Stop),
                                              (interrupt_after_first_group, KeyboardInterrupt)])
def test_cancelled_run_resumes_to_the_same_bytes(rockdove, tmp_path, plumage_cli, progress, raised):
    expected = cli_material(plumage_cli, rockdove, RESUME_FLAGS, tmp_path / "cli.plm")
    out = tmp_path / "py.plm"
    with pytest.raises(raised):
        plumage.characterize(rockdove, out, **RESUME, progress=progress)
    assert not out.exists()
    assert (tmp_path / "py.plm.journal").exists()
    r = plumage.characterize(rockdove, out, **RESUME)
    assert r["plan"]["resumed"] > 0 and r["plan"]["resumed"] + r["plan"]["todo"] == r["plan"]["groups"] == 12
    assert out.read_bytes() == expected
    assert not (tmp_path / "py.plm.journal").exists()


def test_shards_merged_equal_a_single_run(rockdove, tmp_path, plumage_cli):
    expected = cli_material(plumage_cli, rockdove, TINY_FLAGS, tmp_path / "cli.plm")
    shards = [tmp_path / "s2.shard", tmp_path / "s1.shard"]
    for i, shard in ((2, shards[0]), (1, shards[1])):
        r = plumage.characterize(rockdove, shard, **TINY, shard=(i, 2))
        assert r["shard_written"] and r["material"] is None and r["shard_groups"] == 3
    m = plumage.merge_shards(shards, tmp_path / "merged.plm")
    assert (tmp_path / "merged.plm").read_bytes() == expected
    assert m["material"].key == m["settings"]["key"]
    with pytest.raises(plumage.Error):
        plumage.merge_shards(shards[:1], tmp_path / "half.plm")
    assert not (tmp_path / "half.plm").exists()
    with pytest.raises(plumage.OutputPathError):
        plumage.merge_shards(shards, shards[0])


def test_bad_settings_raise_and_write_nothing(rockdove, tmp_path):
    with pytest.raises(plumage.ConfigError) as e:
        plumage.characterize(rockdove, tmp_path / "x.plm", grid=1, lambda_nm=[400], instances=3)
    assert e.value.field
    with pytest.raises(plumage.ConfigError):
        plumage.characterize(rockdove, tmp_path / "x.plm", **dict(TINY, lambda_nm=[500, 400]))
    with pytest.raises(ValueError):
        plumage.characterize(rockdove, tmp_path / "x.plm", **TINY, shard=(3, 2))
    with pytest.raises(plumage.Error, match="no fidelity preset 'nosuch'"):
        plumage.characterize(rockdove, tmp_path / "x.plm", "nosuch", **TINY)
    with pytest.raises(plumage.OutputPathError):
        plumage.characterize(rockdove, rockdove.file, **TINY)
    assert not any(tmp_path.iterdir())
