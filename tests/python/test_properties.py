"""Properties of the Cattaneo-Mindlin responses (B.14-B.20) and the normal laws,
checked against independent numerics (numpy), for all four models."""
import math

import numpy as np
import pytest

import asperity
from asperity import mindlin

OMEGA_STARS = [0.1, 0.374, 0.6, 0.95, 3.0]


def models(pair, params, omega_star):
    out = []
    for name in asperity.models:
        m = asperity.PartialSlipModel.from_interference_star(pair, name, omega_star, params)
        if m.mu > 0:  # CEB beyond w = 1 and KE beyond 6.2 carry no friction
            out.append(m)
    return out


def trapezoid_area(delta, Q):
    # Closed polygon area (shoelace), equal to the loop integral of Q d(delta).
    return 0.5 * abs(np.sum(delta * np.roll(Q, -1) - np.roll(delta, -1) * Q))


@pytest.mark.parametrize("omega_star", OMEGA_STARS)
@pytest.mark.parametrize("ratio", [0.05, 0.5, 0.99, 1.0, 2.5])
def test_loop_closes_and_stays_bounded(micro_pair, micro_params, omega_star, ratio):
    for m in models(micro_pair, micro_params, omega_star):
        c = m.contact
        delta_max = ratio * c.slip_displacement
        n = 401
        loop = c.loop(delta_max, n)
        d, Q = loop.delta, loop.Q
        # Loading ends where unloading starts, reloading ends there again (closure).
        for k in (n - 1, n, -1):
            assert d[k] == pytest.approx(delta_max, rel=1e-14)
        assert Q[-1] == pytest.approx(Q[n], rel=1e-12, abs=1e-12 * c.Q_max)
        assert Q[n - 1] == pytest.approx(Q[n], rel=1e-12)
        # Unloading reaches the mirror point (odd symmetry of the loop).
        assert Q[2 * n - 1] == pytest.approx(-Q[n], rel=1e-12)
        assert np.all(np.abs(Q) <= c.Q_max * (1 + 1e-12))
        # Monotone branches: loading and reloading increase, unloading decreases.
        assert np.all(np.diff(Q[:n]) >= -1e-12 * c.Q_max)
        assert np.all(np.diff(Q[n:2 * n]) <= 1e-12 * c.Q_max)


@pytest.mark.parametrize("omega_star", OMEGA_STARS)
def test_energy_equals_loop_area(micro_pair, micro_params, omega_star):
    for m in models(micro_pair, micro_params, omega_star):
        c = m.contact
        for ratio in (0.1, 0.6, 1.0, 3.0):
            delta_max = ratio * c.slip_displacement
            loop = c.loop(delta_max, 20001)
            n = 20001
            d = np.asarray(loop.delta[n:])
            Q = np.asarray(loop.Q[n:])
            area = trapezoid_area(d, Q)
            W = c.energy_per_cycle(delta_max)
            # Trapezoidal rule on 2e4 points of a curve with a (1 - x)^(3/2) end: 1e-6.
            assert W == pytest.approx(area, rel=1e-6), (m.model, ratio)


@pytest.mark.parametrize("omega_star", OMEGA_STARS)
def test_energy_non_negative_and_increasing(micro_pair, micro_params, omega_star):
    for m in models(micro_pair, micro_params, omega_star):
        d = np.linspace(0.0, 3.0, 301) * m.contact.slip_displacement
        W = m.energy_curve(d)
        assert W[0] == 0.0
        assert np.all(W >= 0.0)
        assert np.all(np.diff(W) > 0.0)
        # Gross slip: slope 4 mu P (the rectangle grows on both strokes).
        k = np.searchsorted(d, 1.5 * m.contact.slip_displacement)
        slope = (W[-1] - W[k]) / (d[-1] - d[k])
        assert slope == pytest.approx(4.0 * m.Q_max, rel=1e-9)


def test_b19_small_amplitude_limit():
    x = np.geomspace(1e-4, 0.2, 40)
    exact = mindlin.energy_tilde(x)
    small = mindlin.energy_tilde_small_amplitude(x)
    # B.20 drops O(x^5) of an O(x^3) quantity: relative error O(x^2).
    assert np.all(np.abs(small / exact - 1.0) < 0.5 * x ** 2)
    assert mindlin.energy_tilde(1.0) == pytest.approx(1.0 / 6.0, rel=1e-15)
    assert mindlin.energy_tilde_for_displacement(1.0) == pytest.approx(1.0 / 6.0)


def test_b19_matches_independent_quadrature():
    # Delta W~ = 10/9 * (area of the loop in Q~, (3/16) delta~ units) computed with
    # numpy from B.16/B.17 (displacement for a force) by the trapezoidal rule.
    for Qm in (0.05, 0.3, 0.7, 0.999):
        Q = np.linspace(-Qm, Qm, 200001)
        d_un = mindlin.unloading_displacement_tilde(Q, Qm)
        d_re = mindlin.reloading_displacement_tilde(Q, Qm)
        area_tilde = np.trapezoid(d_un - d_re, Q) if hasattr(np, "trapezoid") else np.trapz(
            d_un - d_re, Q)
        # delta = (3 mu P/(16 G* a)) delta~, Q = mu P Q~, W~ = 10 G* a W/(9 (mu P)^2)
        W_tilde = area_tilde * 3.0 / 16.0 * 10.0 / 9.0
        assert mindlin.energy_tilde(Qm) == pytest.approx(W_tilde, rel=1e-8)


def test_mindlin_branches_invert_each_other():
    dm = 0.7
    d = np.linspace(-dm, dm, 101)
    Qm = mindlin.loading_force_tilde(dm)
    Q = mindlin.unloading_force_tilde(d, dm)
    np.testing.assert_allclose(mindlin.unloading_displacement_tilde(Q, Qm), d, atol=1e-12)
    Q = mindlin.reloading_force_tilde(d, dm)
    np.testing.assert_allclose(mindlin.reloading_displacement_tilde(Q, Qm), d, atol=1e-12)
    q = np.linspace(0.0, 0.999, 50)
    np.testing.assert_allclose(mindlin.loading_force_tilde(mindlin.loading_displacement_tilde(q)),
                               q, atol=1e-12)
    # Initial slope of B.15 equals full stick B.14 (stiffness 8 G* a).
    eps = 1e-7
    assert mindlin.loading_displacement_tilde(eps) / eps == pytest.approx(
        mindlin.stick_displacement_tilde(1.0), rel=1e-6)


def test_stiffness_is_8_G_a(micro_pair, micro_params):
    for m in models(micro_pair, micro_params, 0.374):
        c = m.contact
        h = 1e-6 * c.slip_displacement
        assert c.loading_force(h) / h == pytest.approx(c.stiffness, rel=1e-5)
        assert c.stiffness == pytest.approx(8.0 * micro_pair.G_star * m.a, rel=1e-15)


@pytest.mark.parametrize("law", ["hertz", "ceb", "ke", "bke"])
def test_inverse_normal_laws(law):
    # Away from the jumps of CEB (w = 1) and KE (1, 6, 110) the inverse is exact.
    w = np.concatenate([np.geomspace(1e-3, 0.99, 30), np.geomspace(1.01, 5.9, 20),
                        np.geomspace(6.1, 109.0, 20), np.geomspace(111.0, 1e3, 10)])
    back = asperity.interference_star(law, asperity.normal_load_star(law, w, 0.3), 0.3)
    np.testing.assert_allclose(back, w, rtol=1e-12)


def test_from_load_recovers_the_load(micro_pair, micro_params):
    for name in asperity.models:
        for P in (1.0, 35.0, 500.0, 5e4):
            m = asperity.PartialSlipModel.from_load(micro_pair, name, P, micro_params)
            assert m.P == P
            if not (name in ("ceb", "ke") and m.omega_star in (1.0, 6.0, 110.0)):
                P_law = micro_pair.critical.P_c * asperity.normal_load_star(
                    asperity.normal_law_of(name), m.omega_star, micro_pair.nu)
                assert P_law == pytest.approx(P, rel=1e-12)


def test_fig_3_statements(micro_pair, micro_params):
    """What section 3.4 says about Fig. 3.6-3.8 at omega* = 0.6."""
    ms = {m.model: m for m in models(micro_pair, micro_params, 0.6)}
    mu = [ms[n].mu for n in asperity.models]
    assert mu == sorted(mu)  # CFC < CEB < KE < BKE
    # Fig. 3.6: sliding inception lowest for CFC, highest for BKE; same initial stiffness
    # (Hertz radius for CFC/CEB/KE; BKE's radius law is 6 % larger at omega* = 0.6).
    slips = [ms[n].contact.slip_displacement for n in asperity.models]
    assert slips == sorted(slips)
    assert ms["cfc"].K_T == ms["ceb"].K_T == ms["ke"].K_T
    assert ms["bke"].K_T / ms["cfc"].K_T == pytest.approx(1.06, abs=0.01)
    # Fig. 3.7: one amplitude where only CFC slides grossly.
    d = 0.2 * ms["cfc"].delta_scale
    regimes = {n: m.contact.regime_for_displacement(d) for n, m in ms.items()}
    assert regimes == {"cfc": "gross_slip", "ceb": "partial_slip", "ke": "partial_slip",
                       "bke": "partial_slip"}
    # Fig. 3.8: energy falls with mu at small amplitude, rises with mu in gross slip.
    small = [ms[n].energy_curve(0.02 * ms[n].delta_scale) for n in asperity.models]
    large = [ms[n].energy_curve(2.0 * ms[n].delta_scale) for n in asperity.models]
    assert small == sorted(small, reverse=True)
    assert large == sorted(large)
