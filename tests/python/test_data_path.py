"""The examples and JSON Schemas shipped in the package (issue 21, item 4):
asperity.data_path("examples") holds the source's examples/ file for file (the build
files CMakeLists.txt aside), data_path("schema") each docs/schema/*.schema.json byte for
byte, and a shipped sweep file still finds its case by its relative path."""
import pathlib

import pytest

import asperity

ROOT = pathlib.Path(__file__).resolve().parents[2]


def _files(root: pathlib.Path) -> dict:
    # pip byte-compiles the examples' .py files when it installs the wheel (__pycache__):
    # an artifact of the installation, not shipped content.
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in root.rglob("*")
            if p.is_file() and p.name != "CMakeLists.txt" and "__pycache__" not in p.parts}


def test_examples_are_the_sources():
    shipped = asperity.data_path("examples")
    assert shipped.parent == asperity.data_path()
    want = _files(ROOT / "examples")
    got = _files(shipped)
    assert sorted(got) == sorted(want)
    assert all(got[k] == want[k] for k in want)


def test_schemas_are_the_sources():
    want = {p.name: p.read_bytes() for p in (ROOT / "docs" / "schema").glob("*.schema.json")}
    got = {p.name: p.read_bytes() for p in asperity.data_path("schema").glob("*.json")}
    assert len(want) >= 10 and got == want


def test_a_shipped_sweep_file_finds_its_case():
    from asperity import sweep

    s = sweep.load(str(asperity.data_path("examples") / "sweeps" / "steel420_bolt_load.toml"))
    assert s.size == 2048  # the file's `samples`


def test_unknown_kind_is_refused_naming_the_choices():
    with pytest.raises(asperity.InvalidInput, match=r"'nope'.*'examples', 'schema'"):
        asperity.data_path("nope")
