"""Scenes and rendering from Python: the same EXR and PNG bytes as `plumage render`, the radiance
as an array, the renderer's settings as the command's flags, bad input as plumage.errors."""
import math

import numpy as np
import pytest

import plumage
from plumage import errors

# As tests/cli/test_render_cli.cpp: a plane of albedo 0.5 under a distant light along its normal.
PLANE = """\
scene: plane
render: {resolution: [24, 16]}
camera: {position_mm: [0, 0, 50], look_at_mm: [0, 0, 0], up: [0, 1, 0], fov_deg: 20}
lights: [{type: distant, toward_light: [0, 0, 1], irradiance: 2}]
renderer: {type: pathtracer, spp: 16, seed: 5}
materials: {paper: {type: diffuse, albedo: 0.5}}
objects: [{type: plane, material: paper, size_mm: 200}]
"""

# A barb-level feather with a material file (the small rockdove material of the fuzz corpus), two views.
FEATHER = """\
scene: feather
renderer: {spp: 2, seed: 9}
render: {resolution: [32, 32]}
camera: {position_mm: [0, -5, 30], look_at_mm: [0, 4, 0], up: [0, 1, 0], fov_deg: 30}
lights: [{type: distant, toward_light: [0, 0.3, 1], irradiance: 3}, {type: environment, radiance: 0.05}]
materials: {green: {type: feather, file: PLM}}
objects: [{type: feather, material: green, detail: barb_level, shape: {length_mm: 8, vane_width_mm: 4}}]
views: [{name: a}, {name: b, camera: {position_mm: [10, -5, 28]}}]
"""


@pytest.fixture
def plane(tmp_path):
    path = tmp_path / "plane.yaml"
    path.write_text(PLANE)
    return path


@pytest.fixture
def feather(tmp_path, source_dir):
    plm = source_dir / "fuzz" / "corpus" / "plm" / "rockdove-grid2.plm"
    assert plm.exists()
    path = tmp_path / "feather.yaml"
    path.write_text(FEATHER.replace("PLM", str(plm)))
    return path


def test_load_scene(feather):
    s = plumage.load_scene(feather)
    assert s.name == "feather" and [v["name"] for v in s.views] == ["a", "b"]
    assert s.views[1]["position_mm"] == [10, -5, 28] and s.views[0]["width"] == 32
    green = s.materials[0]
    assert green["name"] == "green" and green["kind"] == "feather" and green["species_config"] is None
    assert green["file"].name == "rockdove-grid2.plm" and green["fidelity"] == "preview"
    assert {"name": "default_shaft", "kind": "diffuse"} in s.materials
    assert s.objects[0]["kind"] == "feather" and s.objects[0]["material"] == "green"
    assert "2 spp" in s.renderer and "seed 9" in s.renderer
    assert s.summary == plumage.check_config(feather)["summary"]


def test_render_writes_the_commands_images(feather, tmp_path, plumage_cli):
    flags = dict(spp=2, seed=4, width=24, height=16, lod="instance", threads=1)
    plumage_cli("render", feather, "--spp", 2, "--seed", 4, "--width", 24, "--height", 16, "--lod", "instance",
                "--threads", 1, "--out", tmp_path / "cli")
    views = plumage.render(feather, out=tmp_path / "py", **flags)
    assert [v.name for v in views] == ["feather-a", "feather-b"]
    for v in views:
        for ext in ("exr", "png"):
            assert (tmp_path / "py" / f"{v.name}.{ext}").read_bytes() == (tmp_path / "cli" / f"{v.name}.{ext}").read_bytes()
        assert v.exr == tmp_path / "py" / f"{v.name}.exr"
        assert v.radiance.shape == (16, 24, 3) and v.radiance.dtype == np.float32
        assert not v.radiance.flags.writeable
        # The array is the renderer's buffer: the command's EXR pixels bit for bit.
        cli_radiance, attributes = plumage.read_exr(tmp_path / "cli" / f"{v.name}.exr")
        assert cli_radiance.tobytes() == v.radiance.tobytes()
        assert "plumage:warnings" not in attributes
        assert v.stats["camera_paths"] == 24 * 16 * 2
        assert v.warnings == []
    assert views[0].radiance[..., 1].max() > 0  # the feather is seen
    # Without `out`: nothing kept, the same pixels (deterministic), more threads the same image.
    only_b = plumage.render(feather, view="b", **{**flags, "threads": 2})
    assert len(only_b) == 1 and only_b[0].exr is None
    np.testing.assert_array_equal(only_b[0].radiance, views[1].radiance)


def test_plane_radiance_is_albedo_times_irradiance_over_pi(plane):
    (v,) = plumage.render(plane, spp=4)
    assert v.width == 24 and v.stats["camera_paths"] == 24 * 16 * 4
    assert float(v.radiance.mean()) == pytest.approx(0.5 * 2 / math.pi, rel=0.02)


def test_a_raising_progress_stops_the_render(plane, tmp_path):
    class Stop(Exception):
        pass

    def stop(done, total, what):
        raise Stop()

    with pytest.raises(Stop):
        plumage.render(plane, out=tmp_path / "out", progress=stop)
    assert not (tmp_path / "out" / "plane.exr").exists()


def test_bad_inputs_raise_the_documented_errors(plane, tmp_path, configs):
    bad = tmp_path / "bad.yaml"
    bad.write_text(PLANE.replace("fov_deg", "fov_dge"))
    with pytest.raises(errors.ConfigError) as e:
        plumage.load_scene(bad)
    assert e.value.field.endswith("fov_dge") and e.value.line == 3
    with pytest.raises(errors.ConfigError):
        plumage.render(bad)
    (tmp_path / "file").write_text("")
    with pytest.raises(errors.OutputPathError):
        plumage.render(plane, out=tmp_path / "file")
    (tmp_path / "out").mkdir()
    (tmp_path / "out" / "plane.exr").symlink_to(tmp_path / "elsewhere.exr")
    with pytest.raises(errors.OutputPathError):
        plumage.render(plane, out=tmp_path / "out")
    with pytest.raises(ValueError, match="together"):
        plumage.render(plane, width=8)
    with pytest.raises(ValueError, match="spp"):
        plumage.render(plane, spp=0)
    # A setting the renderer's own table refuses names the Python argument as its source.
    with pytest.raises(errors.ConfigError, match=r"plumage\.render\(spp=\.\.\.\).*renderer\.spp"):
        plumage.render(plane, spp=2**21)
    # A species material that is not cached, characterisation off: the message names the command.
    uncached = tmp_path / "uncached.yaml"
    species = configs / "species" / "starling.yaml"
    uncached.write_text(PLANE.replace("materials: {", f"materials: {{s: {{type: feather, species: {species}}}, ")
                        .replace("objects: [", "objects: [{type: feather, material: s, detail: barb_level}, "))
    with pytest.raises(errors.ConfigError, match="plumage characterize"):
        plumage.render(uncached, materials=tmp_path / "no-materials", allow_characterize=False, out=tmp_path / "o2")
    assert not (tmp_path / "o2").exists()
