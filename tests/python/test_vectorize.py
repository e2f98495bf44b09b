"""Vectorized functions: any shape in, same shape out; scalars in, float out."""
import math

import numpy as np
import pytest

import asperity
from asperity import mindlin


def test_scalar_in_float_out():
    for x in (0.5, 1, np.float64(0.5), np.float32(0.5), np.array(0.5), np.int64(2)):
        out = asperity.normal_load_star("hertz", x, 0.3)
        assert type(out) is float, type(x)
    assert asperity.normal_load_star("hertz", 4, 0.3) == 8.0


@pytest.mark.parametrize("shape", [(0,), (1,), (7,), (3, 4), (2, 3, 4), (2, 0, 3)])
def test_shape_preserved(shape):
    w = np.random.default_rng(1).uniform(0.05, 20.0, size=shape)
    for law in asperity.normal_laws:
        for f in (asperity.normal_load_star, asperity.contact_radius_star):
            out = f(law, w, 0.3)
            assert isinstance(out, np.ndarray)
            assert out.shape == shape and out.dtype == np.float64
    for law in asperity.friction_laws:
        assert asperity.friction_coefficient(law, w, 0.3).shape == shape


def test_values_match_scalar_calls():
    w = np.linspace(0.05, 12.0, 37).reshape(37, 1)
    for law in asperity.normal_laws:
        arr = asperity.normal_load_star(law, w, 0.3)
        for wi, pi in zip(w.ravel(), arr.ravel()):
            assert pi == asperity.normal_load_star(law, float(wi), 0.3)


def test_lists_tuples_ints_and_strided_views():
    assert asperity.hardness_factor([0.0, 0.3]).tolist() == pytest.approx([0.454, 0.577])
    assert asperity.hardness_factor((0, 0)).shape == (2,)
    w = np.arange(12, dtype=np.int32).reshape(3, 4)[:, ::2]  # non-contiguous ints
    out = asperity.normal_load_star("hertz", w, 0.3)
    np.testing.assert_allclose(out, w.astype(float) ** 1.5, rtol=1e-15)


def test_input_not_modified_and_output_fresh():
    w = np.array([0.2, 0.4])
    out = asperity.contact_radius_star("hertz", w, 0.3)
    out[0] = -1.0
    assert w.tolist() == [0.2, 0.4]
    assert asperity.contact_radius_star("hertz", 0.2, 0.3) == math.sqrt(0.2)


def test_broadcasting_of_several_arguments():
    w = np.linspace(0.1, 2.0, 5)
    nu = np.array([[0.2], [0.3], [0.4]])
    out = asperity.normal_load_star("bke", w, nu)
    assert out.shape == (3, 5)
    assert out[1, 2] == asperity.normal_load_star("bke", w[2], 0.3)
    d = np.linspace(-0.5, 0.5, 11)
    q = mindlin.unloading_force_tilde(d, 0.5)
    assert q.shape == (11,)
    with pytest.raises(ValueError):
        asperity.normal_load_star("hertz", np.ones(3), np.full(4, 0.3))


def test_mindlin_functions_vectorized():
    x = np.linspace(0.0, 1.0, 12).reshape(3, 4)
    for f in (mindlin.stick_displacement_tilde, mindlin.loading_displacement_tilde,
              mindlin.loading_force_tilde, mindlin.energy_tilde,
              mindlin.energy_tilde_small_amplitude, mindlin.energy_tilde_for_displacement):
        assert f(x).shape == (3, 4)
        assert type(f(0.5)) is float
    assert mindlin.unloading_displacement_tilde(x, 1.0).shape == (3, 4)
    assert mindlin.reloading_displacement_tilde(x, 1.0).shape == (3, 4)
    assert mindlin.reloading_force_tilde(x, 1.0).shape == (3, 4)


def test_model_methods_vectorized(micro_pair, micro_params):
    m = asperity.PartialSlipModel.from_load(micro_pair, "ke", 35.0, micro_params)
    d = np.linspace(0.0, 3e-6, 6).reshape(2, 3)
    assert m.energy_curve(d).shape == (2, 3)
    assert type(m.energy_curve(1e-6)) is float
    c = m.contact
    assert c.loading_force(d).shape == (2, 3)
    assert c.unloading_force(d - 1.5e-6, 3e-6).shape == (2, 3)
    assert c.energy_per_cycle(d).shape == (2, 3)
    Q = np.linspace(-c.Q_max, c.Q_max, 5)
    assert c.loading_displacement(Q).shape == (5,)
    laws = asperity.AsperityLaws("bke", 0.3)
    assert laws.mu([[0.3, 0.4]]).shape == (1, 2)
    assert laws.interference_star(laws.load_star(np.array([0.5, 2.0]))).shape == (2,)


def test_regime_for_displacement_vectorized(micro_pair, micro_params):
    # Like its siblings: a float gives a str, an array the names in the same shape,
    # each equal to the scalar call.
    c = asperity.PartialSlipModel.from_load(micro_pair, "ke", 35.0, micro_params).contact
    s = c.slip_displacement
    d = np.array([[0.0, 0.5 * s], [s, 3.0 * s]])
    names = c.regime_for_displacement(d)
    assert names.shape == (2, 2)
    assert names.tolist() == [["partial_slip", "partial_slip"], ["gross_slip", "gross_slip"]]
    assert [c.regime_for_displacement(float(x)) for x in d.ravel()] == names.ravel().tolist()
    assert type(c.regime_for_displacement(0.5 * s)) is str
    assert c.regime_for_displacement([0.5 * s]).tolist() == ["partial_slip"]
    with pytest.raises(asperity.InvalidInput, match="delta_max"):
        c.regime_for_displacement(np.array([s, -1.0]))


def test_loop_arrays(micro_pair, micro_params):
    m = asperity.PartialSlipModel.from_load(micro_pair, "bke", 35.0, micro_params)
    loop = m.loop(1.5e-6, 50)
    assert len(loop) == 150
    for a in (loop.delta, loop.Q, loop.branch):
        assert isinstance(a, np.ndarray) and a.shape == (150,)
        assert not a.flags.writeable
    assert loop.branch.tolist() == [0] * 50 + [1] * 50 + [2] * 50
    delta, Q, branch = asperity.loop_arrays(loop)
    delta[0] = 1.0  # copies are writeable and independent
    assert loop.delta[0] == 0.0
    del m, loop  # the views keep their owner alive
    assert Q.shape == (150,)


def test_views_keep_their_owners_alive(micro_pair):
    import gc

    def make():
        m = asperity.PartialSlipModel.from_load(micro_pair, "bke", 35.0)
        return m.loop(1e-6, 100).Q, m.contact, m.pair, m.Q_max

    Q, contact, pair, Q_max = make()
    gc.collect()
    _ = [list(range(50)) for _ in range(2000)]  # reuse freed memory, if any
    assert Q[-1] == pytest.approx(contact.loading_force(1e-6))
    assert contact.Q_max == Q_max
    assert pair.R == 2.5e-3


def test_large_arrays_in_parallel_blocks_equal_scalar_calls_and_raise_the_first_error():
    # Arrays above one block (8192 elements) are evaluated in blocks over the cores
    # (core::parallel_for): each element must equal its scalar call exactly, the shape
    # is kept, and a bad element raises the error of the first bad index.
    w = np.random.default_rng(4).uniform(0.05, 20.0, size=(3, 9000))
    out = asperity.normal_load_star("bke", w, 0.3)
    assert out.shape == w.shape
    ref = np.array([asperity.normal_load_star("bke", float(v), 0.3) for v in w.ravel()])
    np.testing.assert_array_equal(out.ravel(), ref)
    bad = w.ravel().copy()
    bad[20000] = -1.0
    bad[25000] = float("nan")
    with pytest.raises(asperity.InvalidInput) as first:
        asperity.normal_load_star("bke", bad, 0.3)
    with pytest.raises(asperity.InvalidInput) as alone:
        asperity.normal_load_star("bke", -1.0, 0.3)
    assert str(first.value) == str(alone.value)
    # One thread (set_thread_count) gives the same numbers bit for bit.
    before = asperity.thread_count()
    try:
        asperity.set_thread_count(1)
        assert asperity.thread_count() == 1
        np.testing.assert_array_equal(asperity.normal_load_star("bke", w, 0.3), out)
    finally:
        asperity.set_thread_count(before)
    for n in (0, -3, 257):
        with pytest.raises(asperity.InvalidInput, match=f"thread count {n} is not allowed"):
            asperity.set_thread_count(n)
    assert asperity.thread_count() == before
