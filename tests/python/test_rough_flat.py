"""The rough flat (thesis ch. 4) and the Masing engine through the Python face.

Reference values: Fig. 4.4 conditions (beta = 0.04, psi = 0.5, nu = 0.3, P* = 1e-3,
identical materials so G*/E* = (1 - nu)/(2 (2 - nu))); CFC's Q*_max = 0.3 P* (section
4.3); Jenkins energy per cycle 4 F (x - F/k) (closed form)."""
import numpy as np
import pytest

import asperity

G_OVER_E = 0.7 / 3.4


def fig44(model):
    return asperity.RoughFlat(model, beta=0.04, psi=0.5, nu=0.3, G_over_E=G_OVER_E, mu_cfc=0.3)


def test_cfc_static_friction_is_mu_times_load():
    flat = fig44("cfc")
    d = flat.separation_star(1e-3)
    assert flat.normal_load_star(d) == pytest.approx(1e-3, rel=1e-12)
    assert flat.static_friction_star(d) == pytest.approx(0.3e-3, rel=1e-10)


def test_vectorized_shapes():
    flat = fig44("bke")
    d = flat.separation_star(1e-3)
    x = np.linspace(0.0, 1.0, 12).reshape(3, 4)
    q = flat.loading_force_star(x, d)
    assert q.shape == (3, 4)
    b = flat.backbone(d)
    # The table equals the quadrature to its verified bound (1e-8 is the target).
    np.testing.assert_allclose(b.force(x[x > 0]), q[x > 0], rtol=1e-8)
    assert isinstance(flat.separation_star(1e-3), float)


def test_table_energy_equals_sum_of_asperity_loops():
    flat = fig44("ke")
    d = flat.separation_star(1e-3)
    b = flat.backbone(d)
    amps = np.array([0.05, 0.3, 0.6, 2.0])
    # Eq. 4.14 by the per-asperity closed form against 8 Int Q_l - 4 x Q_l on the table.
    np.testing.assert_allclose(b.energy_per_cycle(amps), flat.energy_star(amps, d), rtol=1e-7)


def test_hysteresis_history_is_odd_bounded_and_matches_update():
    flat = fig44("bke")
    b = flat.backbone(flat.separation_star(1e-3))
    rng = np.random.default_rng(3)
    turns = rng.uniform(-1.5, 1.5, 20)
    x = np.concatenate([np.linspace(a, c, 30, endpoint=False) for a, c in zip(np.r_[0, turns[:-1]], turns)])
    h = asperity.Hysteresis(b)
    q = h.forces(x)
    assert np.all(np.abs(q) <= b.limit * (1 + 1e-12))
    np.testing.assert_array_equal(h.forces(-x), -q)
    h2 = asperity.Hysteresis(b)
    np.testing.assert_array_equal([h2.update(v) for v in x], q)
    # The inverse recovers the displacements where the force stays below the limit.
    back = asperity.Hysteresis(b).displacements(q)
    np.testing.assert_allclose(back[np.abs(q) < 0.99 * b.limit], x[np.abs(q) < 0.99 * b.limit],
                               rtol=1e-7, atol=1e-10)


def test_jenkins_energy_closed_form():
    k, F = 2e6, 3.0
    b = asperity.JenkinsBackbone(k, F)
    x = 5.0 * F / k
    assert b.energy_per_cycle(x) == pytest.approx(4 * F * (x - F / k), rel=1e-14)


def test_reset_rule_is_available():
    b = asperity.JenkinsBackbone(1.0, 1.0)
    h = asperity.Hysteresis(b, memory="reset_at_reversal")
    assert h.update(0.5) == pytest.approx(0.5)
    with pytest.raises(asperity.InvalidInput, match="memory rule"):
        asperity.Hysteresis(b, memory="nonsense")


def test_dimensional_chapter5_mu():
    steel = asperity.Material(E=200e9, nu=0.24, G=80.7e9, H=5.8e9)
    flat = asperity.RoughFlat.from_dimensional(steel, steel, sigma=2.677e-6, eta=2.91e8,
                                               R=30.14e-6, A0=170e-6, model="bke")
    P_star = 526.0 / flat.scales.force
    d = flat.separation_star(P_star)
    # Chapter 5, BKE at 526 N: 0.335 printed (SEED_NOTES.md); the issue allows 5 %.
    assert flat.static_friction_star(d) / P_star == pytest.approx(0.335, rel=0.05)


@pytest.mark.parametrize("kwargs, field", [
    (dict(beta=0.019), "beta"),
    (dict(psi=0.0), "psi"),
    (dict(nu=0.5), "nu"),
])
def test_bad_input_names_the_field(kwargs, field):
    args = dict(beta=0.04, psi=0.5, nu=0.3, G_over_E=0.2)
    args.update(kwargs)
    with pytest.raises(asperity.InvalidInput, match=field):
        asperity.RoughFlat("bke", **args)


def test_preload_beyond_the_model_is_an_error():
    flat = fig44("bke")
    with pytest.raises(asperity.InvalidInput, match="preload"):
        flat.separation_star(10.0 * flat.max_load_star)
