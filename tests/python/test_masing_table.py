"""The masing_table element from Python (asperity.vibration.MasingTable): a two-point
table is the Jenkins element; a table of the shipped joint's predicted backbone, written
as predict's backbones.csv and read back, gives the rough-flat element's loop within three
times the table's interpolation error (a Masing branch moves the backbone's error at most
three times: B(a) and 2 B)."""
import os

import numpy as np
import pytest

import asperity
from asperity import vibration as vib

EX = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "joints")
CASE = os.path.join(EX, "steel420_two_bolts.toml")


def _response(element, a, n=256):
    u = (a * np.cos(2 * np.pi * np.arange(n) / n)).reshape(-1, 1)
    return element.core.periodic_response(u, tangent=False)["f"][:, 0]


def test_two_point_table_is_jenkins():
    k, F = 2e7, 50.0
    table = vib.MasingTable([0.0, F / k], [0.0, F])
    jenkins = vib.Jenkins(k, F)
    for a in (1e-6, 8e-6):
        np.testing.assert_allclose(_response(table, a), _response(jenkins, a), rtol=0,
                                   atol=1e-12 * F)


def test_predicted_backbone_through_a_csv(tmp_path):
    r = asperity.predict(CASE)
    loads = r["loads"]
    bb = loads[2]["backbone"]
    # As predict --out writes backbones.csv: 401 points to where the force is within 1e-9
    # of Q_max, one on the plateau; two preloads so that `preload` must choose.
    lines = ["preload[N],delta[um],Q[N]"]
    for ld in (loads[1], loads[2]):
        b = ld["backbone"]
        xs = b.displacement((1 - 1e-9) * b.limit)
        for x in list(np.linspace(0.0, xs, 401)) + [1.25 * xs]:
            q = b.force(x) if x <= xs else b.limit
            lines.append(f"{ld['preload']:.12g},{x * 1e6:.12g},{q:.12g}")
    path = tmp_path / "backbones.csv"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(asperity.InvalidInput, match="preload"):
        vib.MasingTable.from_csv(path)
    table = vib.MasingTable.from_csv(path, preload=loads[2]["preload"])
    physics = vib.RoughFlat.from_joint_case(CASE, load=2)
    xs = bb.displacement((1 - 1e-9) * bb.limit)
    grid = np.linspace(0.0, 1.3 * xs, 20001)
    # The table's error, found from the element's own virgin curve (static response).
    err = max(abs(table.core.static_response(np.array([x]))[0][0] - bb.force(x)) for x in grid)
    assert err < 1e-3 * bb.limit
    for f in (0.05, 0.5, 2.0):
        d = np.abs(_response(table, f * xs) - _response(physics, f * xs)).max()
        assert d <= 3 * err * (1 + 1e-9)
    assert table.describe()["Q_max_N"] == pytest.approx(bb.limit, rel=1e-11)


def test_bad_tables_are_refused():
    with pytest.raises(asperity.InvalidInput, match="monotone"):
        vib.MasingTable([0.0, 1e-6, 2e-6], [0.0, 2.0, 1.0])
    with pytest.raises(asperity.InvalidInput, match="origin"):
        vib.MasingTable([1e-6, 2e-6], [0.0, 1.0])
