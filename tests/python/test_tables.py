"""Tables 3.1-3.4 of the thesis (Eriten 2012, chapter 3) reproduced through Python.

Sources: Table 3.1 (materials, "Combined" row), the text of section 3.5 (critical values
7.41 um / 0.136 mm / 152.8 N, penetrations 2.77 um and 2.1 um, stiffnesses 8 G* a =
16.17 and 14.06 N/um; nano-scale 12.67 nm / 0.14 um / 105.9 uN), Table 3.2 and 3.4
(omega* and mu of CFC, CEB, KE, BKE). Tolerances follow the printed digits: a value
printed to 3-4 significant digits is matched to 0.5 % (the rounding alone can be
0.4 %, e.g. a_c = 0.136 mm); mu printed to 3 decimals to 0.2 % except KE (see below).
"""
import math

import pytest

import asperity


def rel(a, b):
    return abs(a - b) / abs(b)


def test_table_3_1_combined_properties(micro_pair):
    # Table 3.1 "Combined": E* = 113.8 GPa, G* = 24.3 GPa, nu and H of the softer (ball).
    assert rel(micro_pair.E_star, 113.8e9) < 5e-3
    assert rel(micro_pair.G_star, 24.3e9) < 5e-3
    assert micro_pair.R == 2.5e-3
    assert micro_pair.H == 6.83e9
    assert micro_pair.nu == 0.3
    assert math.isclose(micro_pair.K, 0.454 + 0.41 * 0.3)


def test_critical_values_within_half_percent(micro_pair):
    c = micro_pair.critical  # Eq. 3.5; section 3.5: 7.41 um, 0.136 mm, 152.8 N
    assert rel(c.omega_c, 7.41e-6) < 5e-3
    assert rel(c.a_c, 0.136e-3) < 5e-3
    assert rel(c.P_c, 152.8) < 5e-3


TABLE_3_2 = [
    # P [N], omega*, penetration [m] (section 3.5 text), mu (CFC, CEB, KE, BKE), 8G*a [N/m]
    (35.0, 0.374, 2.77e-6, (0.284, 0.528, 0.858, 1.444), 16.17e6),
    (23.0, 0.283, 2.10e-6, (0.284, 0.626, 0.992, 1.639), 14.06e6),
]

# Relative tolerance on mu per model. CFC is an input (s/H = 0.284). CEB and BKE agree
# with B.11/B.13 to the printed digits (half a unit of 0.001 is <= 0.1 %). The thesis's
# KE values are 0.6-0.8 % below what B.12 gives at the printed omega* (SEED_NOTES.md),
# so KE gets 1 %, the tolerance the issue asks of every model.
MU_TOL = {"cfc": 1e-12, "ceb": 2e-3, "ke": 1e-2, "bke": 2e-3}


@pytest.mark.parametrize("P, omega_star, omega, mu, stiffness", TABLE_3_2,
                         ids=["exp1_35N", "exp2_23N"])
def test_table_3_2(micro_pair, micro_params, P, omega_star, omega, mu, stiffness):
    hertz = asperity.PartialSlipModel.from_load(micro_pair, "cfc", P, micro_params)
    assert rel(hertz.omega_star, omega_star) < 5e-3
    assert rel(hertz.omega, omega) < 1e-2  # printed to 2-3 digits
    assert rel(hertz.K_T, stiffness) < 1e-2
    assert rel(hertz.P, P) < 1e-12
    # Table 3.2 evaluates every model at the Hertzian omega* of the load.
    for name, expected in zip(asperity.models, mu):
        m = asperity.PartialSlipModel.from_interference_star(micro_pair, name, hertz.omega_star,
                                                             micro_params)
        assert rel(m.mu, expected) < MU_TOL[name], (name, m.mu, expected)
    # The vectorized laws give the same numbers in one call per law.
    w = hertz.omega_star
    assert rel(asperity.friction_coefficient("bke", [w], 0.3)[0], mu[3]) < MU_TOL["bke"]


@pytest.mark.parametrize("P, omega_star, omega, mu, stiffness", TABLE_3_2,
                         ids=["exp1_35N", "exp2_23N"])
def test_table_3_2_hertz_reading(micro_pair, micro_params, P, omega_star, omega, mu,
                                 stiffness):
    # interference="hertz" (the CLI's default): the load as given, Hertz's omega and a
    # for every model, so section 3.5's 8 G* a (16.17 / 14.06 N/um) holds for all four.
    for name, expected in zip(asperity.models, mu):
        m = asperity.PartialSlipModel.from_load(micro_pair, name, P, micro_params,
                                                interference="hertz")
        assert m.interference == "hertz"
        assert m.P == P
        assert rel(m.omega, omega) < 1e-2
        assert rel(m.K_T, stiffness) < 1e-2, name
        assert rel(m.mu, expected) < MU_TOL[name], (name, m.mu, expected)
    assert asperity.PartialSlipModel.from_load(micro_pair, "bke", P,
                                               micro_params).interference == "own"
    with pytest.raises(asperity.InvalidInput, match="hertz, own"):
        asperity.PartialSlipModel.from_load(micro_pair, "bke", P, micro_params,
                                            interference="Hertz")


@pytest.mark.parametrize("P, omega_star, omega, mu, stiffness", TABLE_3_2,
                         ids=["exp1_35N", "exp2_23N"])
def test_table_3_2_with_own_normal_law(micro_pair, micro_params, P, omega_star, omega, mu,
                                       stiffness):
    # Each model with its own normal law: the interference differs slightly (BKE's
    # elastic branch is 2.6 % stiffer than Hertz), which moves mu by < 1.5 %.
    for name, expected in zip(asperity.models, mu):
        m = asperity.PartialSlipModel.from_load(micro_pair, name, P, micro_params)
        assert rel(m.mu, expected) < 1.5e-2, name
        assert rel(m.P, P) < 1e-9


def test_nano_scale_critical_values(nano_pair):
    # Section 3.5: 12.67 nm, 0.14 um, 105.9 uN. The thesis's combined row (E* = 44.7
    # GPa) is reproduced to ~1 % only, hence 5 %.
    c = nano_pair.critical
    assert rel(c.omega_c, 12.67e-9) < 5e-2
    assert rel(c.a_c, 0.14e-6) < 5e-2
    assert rel(c.P_c, 105.9e-6) < 5e-2


@pytest.mark.parametrize("P, omega_star, mu", [
    (1.1e-6, 0.048, (0.259, 1.769, 2.498, 3.077)),
    (1.2e-6, 0.051, (0.259, 1.714, 2.424, 2.996)),
], ids=["nano1", "nano2"])
def test_table_3_4(nano_pair, P, omega_star, mu):
    # Table 3.4; omega* within 5 % (critical values differ ~1-3 % from the thesis's),
    # mu evaluated at the printed omega* within 5 %.
    params = asperity.thesis.nano_params()
    hertz = asperity.PartialSlipModel.from_load(nano_pair, "cfc", P, params)
    assert rel(hertz.omega_star, omega_star) < 5e-2
    for name, expected in zip(asperity.models, mu):
        m = asperity.PartialSlipModel.from_interference_star(nano_pair, name, omega_star, params)
        assert rel(m.mu, expected) < 5e-2, (name, m.mu, expected)


def test_thesis_normalization(micro_pair, micro_params):
    # Eq. 3.17: for CFC (Hertz) the slip displacement is delta* = mu omega*.
    m = asperity.PartialSlipModel.from_interference_star(micro_pair, "cfc", 0.6, micro_params)
    s = asperity.thesis_normalization(m)
    assert math.isclose(m.contact.slip_displacement / s["delta"], 0.284 * 0.6, rel_tol=1e-12)
    assert s["Q"] == m.critical.P_c
    assert math.isclose(s["energy"], m.critical.P_c ** 2 / (micro_pair.G_star * m.critical.a_c))


def test_table_3_4_follows_from_nu_0_2(nano_pair):
    """The thesis's nano-scale numbers follow from nu = 0.2 (0.19 rounded) for K and the
    BKE constants: then omega_c, a_c, P_c match the text to 0.2 %, and CEB and BKE match
    Table 3.4 to the printed digits at the unrounded Hertzian omega*. KE (independent of
    nu) stays 1.7-1.8 % below the table, like the 0.6-0.8 % of Table 3.2: the thesis's
    KE values do not follow from B.12 exactly."""
    pair = asperity.ContactPair(E_star=nano_pair.E_star, G_star=nano_pair.G_star,
                                R=nano_pair.R, H=nano_pair.H, nu=0.2)
    c = pair.critical
    assert rel(c.omega_c, 12.67e-9) < 2e-3
    assert rel(c.a_c, 0.14e-6) < 2e-3
    assert rel(c.P_c, 105.9e-6) < 2e-3
    params = asperity.thesis.nano_params()
    tol = {"cfc": 1e-12, "ceb": 2e-3, "ke": 2.5e-2, "bke": 2e-3}
    for P, mu, K_T in [(1.1e-6, (0.259, 1.769, 2.498, 3.077), 2356.0),
                       (1.2e-6, (0.259, 1.714, 2.424, 2.996), 2426.0)]:
        hertz = asperity.PartialSlipModel.from_load(pair, "cfc", P, params)
        assert rel(hertz.K_T, K_T) < 1e-3  # section 3.5: "2356-2426 N/m"
        for name, expected in zip(asperity.models, mu):
            m = asperity.PartialSlipModel.from_interference_star(pair, name, hertz.omega_star,
                                                                 params)
            assert rel(m.mu, expected) < tol[name], (name, m.mu, expected)
