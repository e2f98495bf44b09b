"""RoughFlat.backbone_at_preload: the dimensional backbone of a rough flat in one call."""
import numpy as np
import pytest

import asperity

STEEL = asperity.Material(E=200e9, nu=0.24, G=80.7e9, H=5.8e9)


def chapter5_flat():
    # The two-bolt steel 420 joint of chapter 5 (Table 5.4 combined roughness, 170 mm^2).
    return asperity.RoughFlat.from_dimensional(STEEL, STEEL, sigma=2.677e-6, eta=2.91e8,
                                               R=30.14e-6, A0=170e-6, model="bke")


def test_is_the_scaled_table_at_the_preload_separation():
    flat = chapter5_flat()
    s = flat.scales
    P = 526.0
    d = flat.separation_star(P / s.force)
    table = flat.backbone(d)
    si = flat.backbone_at_preload(P)
    delta = np.array([0.01e-6, 0.1e-6, 0.25e-6, 1e-6, 4e-6])
    # Q(delta) = K H A0 Q*(delta/sigma_s): the same table, scaled (round-off only).
    expected = np.array([table.force(x / s.sigma) for x in delta]) * s.force
    assert np.array([si.force(x) for x in delta]) == pytest.approx(expected, rel=1e-14)
    # Static friction Q_max = mu P with mu from Eq. 4.7 at the same separation; its
    # initial slope the tangential stiffness (Q* per delta*, times K H A0/sigma_s).
    assert si.limit == pytest.approx(flat.static_friction_star(d) * s.force, rel=1e-9)
    assert si.initial_stiffness == pytest.approx(flat.stiffness_star(d) * s.force / s.sigma,
                                                 rel=1e-6)
    # As `asperity flat ... --P 526N --json` prints for this joint: mu = 0.34247.
    assert si.limit / P == pytest.approx(0.34247, rel=1e-4)


def test_follows_a_history_with_masing_memory():
    si = chapter5_flat().backbone_at_preload(526.0)
    h = asperity.Hysteresis(si)
    x = np.concatenate([np.linspace(0, 0.25e-6, 50), np.linspace(0.25e-6, -0.25e-6, 100),
                        np.linspace(-0.25e-6, 0.25e-6, 100)])
    Q = h.forces(x)
    # Masing: the loop closes at the first reversal, on the virgin curve (Q_l(0.25 um)).
    assert Q[-1] == pytest.approx(si.force(0.25e-6), rel=1e-12)
    assert Q[149] == pytest.approx(-si.force(0.25e-6), rel=1e-12)


def test_bad_input_names_what_to_change():
    normalized = asperity.RoughFlat("bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.2)
    with pytest.raises(asperity.InvalidInput, match="from_dimensional"):
        normalized.backbone_at_preload(526.0)
    for bad in (-1.0, 0.0, float("nan"), float("inf")):
        with pytest.raises(asperity.InvalidInput, match="P = "):
            chapter5_flat().backbone_at_preload(bad)
