"""The contact layer's Python API: materials, pairs, laws and models (SI units)."""
import math

import numpy as np
import pytest

import asperity


def test_material_and_combination():
    steel = asperity.Material(E=200e9, nu=0.25)  # G derived: E/(2(1+nu))
    assert steel.shear_modulus() == pytest.approx(80e9)
    assert steel.G == 0.0 and steel.H == 0.0
    soft = asperity.Material(E=100e9, nu=0.35, G=37e9, H=1e9)
    pair = asperity.ContactPair.combine(steel, soft, 1e-3, 3e-3)
    assert pair.E_star == pytest.approx(1 / ((1 - 0.25**2) / 200e9 + (1 - 0.35**2) / 100e9))
    assert pair.G_star == pytest.approx(1 / ((2 - 0.25) / 80e9 + (2 - 0.35) / 37e9))
    assert pair.R == pytest.approx(0.75e-3)
    assert (pair.H, pair.nu) == (1e9, 0.35)  # the softer body's (steel has no H)
    assert pair.K == pytest.approx(asperity.hardness_factor(0.35))
    assert "Material(E=2e+11" in repr(steel)
    # A flat: R2 = inf by default.
    assert asperity.ContactPair.combine(steel, soft, 2e-3).R == 2e-3


def test_critical_values_eq_3_5(micro_pair):
    c = micro_pair.critical
    K, H, R, E = micro_pair.K, micro_pair.H, micro_pair.R, micro_pair.E_star
    assert c.a_c == pytest.approx(math.pi * K * H * R / (2 * E), rel=1e-14)
    assert c.omega_c == pytest.approx((math.pi * K * H / (2 * E)) ** 2 * R, rel=1e-14)
    assert c.P_c == pytest.approx(2 / 3 * K * H * math.pi * c.a_c**2, rel=1e-14)


def test_law_names_and_model_pairs():
    assert asperity.models == ("cfc", "ceb", "ke", "bke")
    assert asperity.normal_laws == ("hertz", "ceb", "ke", "bke")
    assert [asperity.normal_law_of(m) for m in asperity.models] == ["hertz", "ceb", "ke", "bke"]
    assert [asperity.friction_law_of(m) for m in asperity.models] == list(asperity.models)


def test_asperity_laws_match_free_functions():
    w = np.geomspace(0.01, 50.0, 40)
    for model in asperity.models:
        laws = asperity.AsperityLaws(model, 0.3, asperity.FrictionParameters(mu_cfc=0.2))
        law = asperity.normal_law_of(model)
        np.testing.assert_array_equal(laws.load_star(w), asperity.normal_load_star(law, w, 0.3))
        np.testing.assert_array_equal(laws.radius_star(w),
                                      asperity.contact_radius_star(law, w, 0.3))
        np.testing.assert_array_equal(
            laws.mu(w), asperity.friction_coefficient(model, w, 0.3,
                                                      asperity.FrictionParameters(mu_cfc=0.2)))
        assert laws.model == model and laws.nu == 0.3
        assert laws.friction_parameters.mu_cfc == 0.2
    assert asperity.AsperityLaws("bke", 0.3).break_points().tolist() == [
        pytest.approx(asperity.BkeConstants.for_poisson(0.3).delta_c)]


def test_friction_law_limits():
    assert asperity.friction_coefficient("ceb", [1.0, 2.0], 0.3).tolist() == [0.0, 0.0]
    assert asperity.friction_coefficient("ke", [6.3, 100.0], 0.3).tolist() == [0.0, 0.0]
    assert asperity.friction_coefficient("bke", 1e6, 0.3) == pytest.approx(0.26, rel=1e-3)
    assert asperity.friction_coefficient("cfc", 0.0, 0.3,
                                         asperity.FrictionParameters(mu_cfc=0.284)) == 0.284
    assert asperity.cfc_coefficient(186e6, 655e6) == pytest.approx(0.284, abs=5e-4)  # Eq. 3.13
    # Static friction force mu P/P_c stays finite at w -> 0 where mu diverges.
    w = np.array([0.0, 1e-8, 0.5])
    P = asperity.normal_load_star("bke", w, 0.3)
    F = asperity.static_friction_star("bke", w, 0.3, P)
    assert F[0] == 0.0 and F[1] < 1e-8
    assert F[2] == pytest.approx(asperity.friction_coefficient("bke", 0.5, 0.3) * P[2])


def test_bke_constants():
    c = asperity.BkeConstants.for_poisson(0.3)
    assert c.l_c == pytest.approx(8.88 * 0.3 - 10.13 * (0.09 + 0.089))
    assert c.delta_c == pytest.approx(6.82 * 0.3 - 7.83 * (0.09 + 0.0586))
    assert c.alpha == pytest.approx(0.174 + 0.08 * 0.3)
    assert c.gamma == pytest.approx(0.25 + 0.125 * 0.3)


def test_partial_slip_model(micro_pair, micro_params):
    m = asperity.PartialSlipModel.from_load(micro_pair, "ke", 35.0, micro_params)
    assert m.model == "ke"
    assert m.omega == pytest.approx(m.omega_star * micro_pair.critical.omega_c)
    assert m.Q_max == pytest.approx(m.mu * m.P)
    assert m.K_T == pytest.approx(8 * micro_pair.G_star * m.a)
    assert m.contact.stiffness == m.K_T
    assert m.delta_scale == pytest.approx(3 * m.critical.P_c / (16 * micro_pair.G_star *
                                                                m.critical.a_c))
    assert m.energy_scale == pytest.approx(m.critical.P_c**2 / (micro_pair.G_star *
                                                                m.critical.a_c))
    assert "PartialSlipModel(model='ke'" in repr(m)
    # A CEB load inside the jump at w = 1 gives the branch point and keeps P.
    P_c = micro_pair.critical.P_c
    ceb = asperity.PartialSlipModel.from_load(micro_pair, "ceb", 1.2 * P_c)
    assert ceb.omega_star == 1.0 and ceb.P == pytest.approx(1.2 * P_c) and ceb.mu == 0.0


def test_mindlin_contact_dimensional():
    c = asperity.MindlinContact(mu=0.5, P=10.0, G_star=20e9, a=1e-4)
    assert c.Q_max == 5.0
    assert c.stiffness == pytest.approx(8 * 20e9 * 1e-4)
    assert c.slip_displacement == pytest.approx(3 * 5.0 / (16 * 20e9 * 1e-4))
    s = c.slip_displacement
    # B.15 in dimensional form (Eq. 3.7).
    assert c.loading_displacement(2.5) == pytest.approx(s * (1 - 0.5 ** (2 / 3)))
    assert c.loading_force(-s) == -5.0
    # Eq. 3.12 for a force amplitude equals the displacement form.
    Qm = 3.0
    dm = c.loading_displacement(Qm)
    assert c.energy_per_cycle_for_force(Qm) == pytest.approx(c.energy_per_cycle(dm), rel=1e-12)
    x = Qm / 5.0
    eq_3_12 = 9 * 25 / (10 * 20e9 * 1e-4) * (1 - (1 - x) ** (5 / 3)
                                              - 5 * x / 6 * (1 + (1 - x) ** (2 / 3)))
    assert c.energy_per_cycle_for_force(Qm) == pytest.approx(eq_3_12, rel=1e-12)
    # Unloading/reloading displacement (Eq. 3.8/3.9) invert the force forms.
    d = np.linspace(-dm, dm, 21)
    np.testing.assert_allclose(c.unloading_displacement(c.unloading_force(d, dm), Qm), d,
                               atol=1e-12 * s)
    np.testing.assert_allclose(c.reloading_displacement(c.reloading_force(d, dm), Qm), d,
                               atol=1e-12 * s)
