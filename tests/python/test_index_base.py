"""One index base (issue 21, item 7; the rule: docs/vibration_cases.md, "Numbering"):
positions in a case file count from 1 in every message, sweep key, summary field, default
name and file name; DOFs (rows of M and K) are numbered from 0, and messages about them
say so. The same second [[element]] is `element[2]` in the parser's error, in a sweep key
and in its default name; the second [[frequency_response]] is table 2."""
import pytest

import asperity
from asperity import vibration as vib
from asperity.sweep import spec

# Two Jenkins elements on two masses (the structure is only a carrier for the numbering).
CASE = """
[structure]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 2.0]]
damping = [[0.01, 0.0], [0.0, 0.01]]

[[element]]
type = "jenkins"
T = [[1.0, 0.0]]
k_t = 0.25
F_s = 0.2

[[element]]
type = "jenkins"
T = [[0.0, 1.0]]
k_t = 0.25
F_s = 0.2

[harmonic_balance]
max = 1
time_points = 16

[quasi_static_mode]
mode = 1
amplitude = { from = 0.1, to = 1.0 }
points = 3
"""


def test_the_parser_and_a_sweep_key_name_the_second_element_alike(tmp_path):
    case = spec.read_toml(_write(tmp_path, CASE))
    # The sweep key element[2] addresses the second [[element]] ...
    (loc,) = spec.expand(case, "element[2].T")
    spec.put(case, loc, [[1.0]])
    assert case["element"][1]["T"] == [[1.0]] and case["element"][0]["T"] == [[1.0, 0.0]]
    # ... which the parser's refusal of that value calls element[2].
    with pytest.raises(asperity.InvalidInput, match=r"element\[2\]\.T has 1 column"):
        vib.run_case_text(spec.to_toml(case))


def test_unnamed_elements_are_named_by_their_position():
    r = vib.run_case_text(CASE)
    assert [e["name"] for e in r.summary["elements"]] == ["element 1", "element 2"]


def test_a_table_is_numbered_from_1_in_messages_and_results():
    frf = """
[[frequency_response]]
force_cos = [[0.0, 0.0], [0.1, 0.0]]
omega = { from = 0.8, to = 1.0 }
"""
    bad = frf.replace("omega = { from = 0.8, to = 1.0 }", "omega = { from = 0.8 }")
    with pytest.raises(asperity.InvalidInput, match=r"frequency_response\[2\]\.omega needs to"):
        vib.run_case_text(CASE + frf + bad)
    r = vib.run_case_text(CASE + frf + frf)
    assert [c.table for c in r.frequency_response] == [1, 2]
    assert [c["table"] for c in r.summary["frequency_response"]] == [1, 2]


def test_dofs_are_numbered_from_0_and_the_message_says_so():
    text = CASE.replace("[structure]\n", "[structure]\noutput_dofs = [1, 2]\n")
    # The second entry (position 2) holds DOF 2, beyond the DOFs 0 .. 1.
    with pytest.raises(asperity.InvalidInput,
                       match=r"structure\.output_dofs\[2\]: DOFs are numbered 0 \.\. 1"):
        vib.run_case_text(text)


def _write(tmp_path, text):
    p = tmp_path / "case.toml"
    p.write_text(text)
    return str(p)
