"""Configs and plug-ins from Python: the same registry as the command, config errors as
exceptions carrying file, line, column and field."""
import textwrap

import pytest

import plumage


def test_registry_finds_the_shipped_plugins():
    registry = plumage.default_registry()
    types = {p["type"] for p in registry.plugins()}
    for expected in ("multilayer", "photonic_crystal", "bem", "fdtd_periodic", "pathtracer", "approximate"):
        assert expected in types
    assert registry.problems == []
    ml = registry.describe("multilayer")
    assert ml["kind"] == "local_reflection" and ml["library"] is not None
    assert all({"name", "type", "unit", "default", "range", "doc"} <= set(p) for p in ml["params"])


def test_describe_names_the_nearest_type():
    with pytest.raises(KeyError, match="did you mean 'multilayer'"):
        plumage.default_registry().describe("multilayr")


def test_plugin_path_argument_is_searched_first(tmp_path):
    registry = plumage.Registry(plugin_path=[tmp_path])
    assert registry.search_path[0] == tmp_path.resolve()


def test_plugin_path_problem_is_listed_not_raised(tmp_path):
    (tmp_path / "libplumage_broken.so").write_bytes(b"\x7fELF not really")
    registry = plumage.Registry(plugin_path=[tmp_path])
    assert any("libplumage_broken.so" in p for p in registry.problems)
    assert "multilayer" in {p["type"] for p in registry.plugins()}


def test_load_species(configs):
    rd = plumage.load_species(configs / "species" / "rockdove.yaml")
    assert rd.species == "rockdove" and rd.variant in rd.variants
    sim = rd.simulation
    assert sim["lambda_nm"].ndim == 1 and sim["lambda_nm"][0] >= 300
    preview = rd.simulation_at("preview")
    assert preview["instances"] <= sim["instances"]


def test_config_error_carries_file_line_column_field(tmp_path, configs):
    text = (configs / "species" / "rockdove.yaml").read_text()
    bad = tmp_path / "bad.yaml"
    # An unknown key in the structure section: the error names it and suggests the right one.
    assert "structure:" in text
    bad.write_text(text.replace("structure:\n", "structure:\n  generatr: x\n", 1))
    with pytest.raises(plumage.ConfigError) as info:
        plumage.load_species(bad)
    e = info.value
    assert e.file.endswith("bad.yaml")
    assert e.line > 0 and e.column > 0
    assert "generatr" in e.field or "generatr" in e.message
    assert str(e).startswith(f"{e.file}:{e.line}:{e.column}:")
    assert isinstance(e, plumage.Error) and isinstance(e, ValueError)


def test_missing_file_is_a_config_error(tmp_path):
    with pytest.raises(plumage.ConfigError):
        plumage.load_species(tmp_path / "none.yaml")


def test_unknown_variant(configs):
    with pytest.raises(plumage.ConfigError, match="variant"):
        plumage.load_species(configs / "species" / "rockdove.yaml", variant="nosuch")


def test_check_config_collects_errors(tmp_path, configs):
    ok = plumage.check_config(configs / "species" / "rockdove.yaml")
    assert ok["kind"] == "species" and ok["errors"] == []
    bad = tmp_path / "bad.yaml"
    bad.write_text(textwrap.dedent("""\
        species: x
        variant: a
        variants: {a: {}}
        simulation: {instances: -3}
    """))
    result = plumage.check_config(bad)
    assert result["errors"], result
    assert all(str(bad) in e for e in result["errors"])


def test_max_memory():
    with pytest.raises(ValueError):
        plumage.set_max_memory("lots")
    plumage.set_max_memory("64G")
    plumage.set_max_memory(None)
