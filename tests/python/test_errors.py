"""C++ errors arrive as asperity.InvalidInput (a ValueError) or asperity.NumericalError
(a RuntimeError), with the field, its value and what is allowed in the message."""
import math

import numpy as np
import pytest

import asperity
from asperity import mindlin


def test_hierarchy():
    assert issubclass(asperity.InvalidInput, ValueError)
    assert issubclass(asperity.InvalidInput, asperity.Error)
    assert issubclass(asperity.NumericalError, RuntimeError)
    assert issubclass(asperity.NumericalError, asperity.Error)
    assert not issubclass(asperity.InvalidInput, RuntimeError)
    assert asperity.InvalidInput.__module__ == "asperity"


@pytest.mark.parametrize("nu", [0.5, 0.7, -0.1, math.nan])
def test_bad_poisson_ratio(nu):
    with pytest.raises(asperity.InvalidInput, match=r"nu = .* \[0, 0\.5\)"):
        asperity.Material(E=207e9, nu=nu)


@pytest.mark.parametrize("E", [-1.0, 0.0, math.inf])
def test_bad_young_modulus(E):
    with pytest.raises(asperity.InvalidInput, match=r"material\.E = .*> 0"):
        asperity.Material(E=E, nu=0.3)


def test_combine_names_the_body(micro_pair):
    ball = asperity.Material(E=207e9, nu=0.3, H=6.83e9)
    bad = asperity.Material(E=207e9, nu=0.3)
    bad.nu = 0.6  # fields are writable; combine validates again
    with pytest.raises(asperity.InvalidInput, match=r"body2\.nu = 0\.6"):
        asperity.ContactPair.combine(ball, bad, 2.5e-3)
    with pytest.raises(asperity.InvalidInput, match="R1"):
        asperity.ContactPair.combine(ball, ball, -1.0)
    with pytest.raises(asperity.InvalidInput, match="hardness"):
        asperity.ContactPair.combine(asperity.Material(E=1e9, nu=0.3),
                                     asperity.Material(E=1e9, nu=0.3), 1e-3)
    with pytest.raises(asperity.InvalidInput, match="H = "):
        asperity.ContactPair(E_star=1e11, G_star=1e10, R=1e-3, H=-1.0, nu=0.3)


def test_unknown_names(micro_pair):
    with pytest.raises(asperity.InvalidInput, match=r'model "coulomb" is unknown.*cfc, ceb, ke, bke'):
        asperity.PartialSlipModel.from_load(micro_pair, "coulomb", 35.0)
    with pytest.raises(asperity.InvalidInput, match=r'normal law "cfc" is unknown.*hertz'):
        asperity.normal_load_star("cfc", 1.0, 0.3)
    with pytest.raises(asperity.InvalidInput, match=r'friction law "hertz" is unknown'):
        asperity.friction_coefficient("hertz", 1.0, 0.3)
    with pytest.raises(asperity.InvalidInput, match="model"):
        asperity.AsperityLaws("BKE", 0.3)  # names are lower case


def test_bad_loads_and_parameters(micro_pair):
    with pytest.raises(asperity.InvalidInput, match=r"^P = -1 "):
        asperity.PartialSlipModel.from_load(micro_pair, "cfc", -1.0)
    with pytest.raises(asperity.InvalidInput, match="omega_star"):
        asperity.PartialSlipModel.from_interference_star(micro_pair, "ke", 0.0)
    with pytest.raises(asperity.InvalidInput, match="mu_cfc"):
        asperity.FrictionParameters(mu_cfc=0.0)
    with pytest.raises(asperity.InvalidInput, match="P/P_c"):
        asperity.interference_star("ke", -1.0, 0.3)
    with pytest.raises(asperity.InvalidInput, match="BKE fits"):
        asperity.BkeConstants.for_poisson(0.05)
    with pytest.raises(asperity.InvalidInput, match="G_star"):
        asperity.MindlinContact(0.3, 10.0, 0.0, 1e-4)


def test_error_inside_an_array_names_the_value():
    w = np.array([0.5, 0.0, 1.0])
    with pytest.raises(asperity.InvalidInput, match=r"w = omega/omega_c = 0 .*ke"):
        asperity.friction_coefficient("ke", w, 0.3)
    with pytest.raises(asperity.InvalidInput, match=r"Q~ = Q/\(mu P\) = 1\.5"):
        mindlin.loading_displacement_tilde([0.5, 1.5])


def test_gross_slip_is_not_an_error(micro_pair, micro_params):
    m = asperity.PartialSlipModel.from_load(micro_pair, "cfc", 23.0, micro_params)
    c = m.contact
    assert c.regime_for_displacement(10e-6) == "gross_slip"
    assert c.regime_for_displacement(0.1e-6) == "partial_slip"
    assert math.isfinite(c.energy_per_cycle(10e-6))
    assert c.loading_force(10e-6) == pytest.approx(c.Q_max, rel=1e-15)
    # Under force control beyond mu P the displacement is unbounded: that is an error.
    with pytest.raises(asperity.InvalidInput, match="exceeds"):
        c.loading_displacement(1.01 * c.Q_max)
    with pytest.raises(asperity.InvalidInput, match="gross slip"):
        c.energy_per_cycle_for_force(1.01 * c.Q_max)


def test_units():
    assert asperity.parse_quantity("207 GPa").value == pytest.approx(207e9)
    assert str(asperity.parse_quantity("1.7 lbf*in").dimension).startswith("energy")
    for bad in ("207 GPaa", "abc", ""):
        with pytest.raises(asperity.InvalidInput, match="E1"):
            asperity.parse_quantity(bad, "E1")


def test_wrong_python_types_raise_type_error():
    with pytest.raises(TypeError):
        asperity.normal_load_star(3, 1.0, 0.3)
    with pytest.raises(TypeError):
        asperity.Material(E="207 GPa", nu=0.3)


@pytest.mark.parametrize("f", [mindlin.stick_displacement_tilde,
                               mindlin.energy_tilde_small_amplitude, mindlin.energy_tilde,
                               mindlin.loading_displacement_tilde])
@pytest.mark.parametrize("q", [math.nan, -0.1, 5.0])
def test_mindlin_force_helpers_check_their_range(f, q):
    # Q~ = Q/(mu P) lies in [0, 1]: outside (NaN included) an error naming Q~ and the
    # range, never a NaN or a displacement outside [0, 1].
    with pytest.raises(asperity.InvalidInput, match=r"Q~.*\[0, 1\]"):
        f(q)


def test_mindlin_loading_force_rejects_nan():
    with pytest.raises(asperity.InvalidInput, match="delta~"):
        mindlin.loading_force_tilde(math.nan)
    with pytest.raises(asperity.InvalidInput, match="delta~"):
        mindlin.loading_force_tilde(np.array([0.5, math.nan]))


def test_backbone_tolerance_named_as_the_argument():
    # Issue 21: the message named a "table tolerance", not the argument the caller gave.
    flat = asperity.RoughFlat(model="bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)
    d_star = flat.separation_star(1e-3)
    for bad in (0.0, 0.1):
        with pytest.raises(asperity.InvalidInput,
                           match=r"^rel_tol = .* is not allowed: it must lie in \[1e-12, 1e-3\]"):
            flat.backbone(d_star, rel_tol=bad)
