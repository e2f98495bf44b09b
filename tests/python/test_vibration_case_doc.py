"""docs/vibration_cases.md documents the vibration case file key by key (issue 21, item
4): every key the parser accepts (the allowed lists of its check_keys calls in
src/vibration/case_parse.cpp and case_elements.cpp) appears on the page, in backticks,
and docs/vibration.md links to the page. Source text only: no build needed."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[2]
PARSERS = [ROOT / "src/vibration/case_parse.cpp", ROOT / "src/vibration/case_elements.cpp"]
DOC = ROOT / "docs/vibration_cases.md"


def accepted_keys():
    """The string literals of every allowed-key list: check_keys(..., {"a", "b"}),
    keys({...}), with({...}) and the common sets of case_elements.cpp."""
    keys = set()
    pattern = re.compile(r"(?:check_keys\([^{;]*|keys\(|with\(|common)\s*\{([^}]*)\}", re.S)
    for path in PARSERS:
        for group in pattern.findall(path.read_text()):
            keys.update(re.findall(r'"([A-Za-z_0-9]+)"', group))
    return keys


def test_the_parser_lists_are_found():
    # The extraction itself: keys of each kind of table must be among those found.
    keys = accepted_keys()
    assert {"mass_file", "rayleigh", "output_dofs", "k_t", "F_S", "time_points",
            "force_per_omega2_sin", "residual_tolerance", "interface_element", "points",
            "asperity_model", "pressure", "type", "T"} <= keys


def test_every_accepted_key_is_documented():
    doc = DOC.read_text()
    documented = set(re.findall(r"`\[*([A-Za-z_0-9]+)", doc))
    missing = sorted(accepted_keys() - documented)
    assert not missing, f"keys the parser accepts that {DOC.name} does not document: {missing}"


def test_linked_from_vibration_md():
    assert "(vibration_cases.md)" in (ROOT / "docs/vibration.md").read_text()
