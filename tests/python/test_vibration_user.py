"""User-defined elements (asperity.vibration.UserElement, issue 23): a force law written in
Python runs through the same AFT harmonic balance as the built-in elements.

Reference: the built-in polynomial_stiffness and cubic_damping elements
(src/vibration/elements.cpp), which evaluate the same laws in C++. A Python law equal to
them must give the same residual, Jacobian and curves up to the round-off of evaluating
the law in another language (a few ulp per sample, summed over the samples by the DFT).
Also the [[backbone_rom]] curves of a case through the Python API (issue 23).
"""
from __future__ import annotations

import numpy as np
import pytest

import asperity.vibration as vib

K1, K2, K3 = 0.5, -0.3, 2.0
M2 = np.array([[1.0, 0.0], [0.0, 2.0]])
K2_STRUCT = np.array([[3.0, -1.0], [-1.0, 2.0]])
T = [1.0, -0.5]


def cubic_force(u, v):
    return u * (K1 + u * (K2 + u * K3))


def cubic_jacobian(u, v):
    return (K1 + u * (2.0 * K2 + 3.0 * u * K3))[:, :, None], None


def systems(user):
    s = vib.Structure(M2, K2_STRUCT, 0.02 * K2_STRUCT)
    ref = vib.HarmonicBalance(s, [vib.PolynomialStiffness(k1=K1, k2=K2, k3=K3, T=T)],
                              max_harmonic=3, time_points=64)
    mine = vib.HarmonicBalance(s, [user], max_harmonic=3, time_points=64)
    return ref, mine


@pytest.mark.parametrize("exact_jacobian", [True, False])
def test_python_cubic_spring_gives_the_built_in_residual_and_jacobian(exact_jacobian):
    user = vib.UserElement(cubic_force, cubic_jacobian if exact_jacobian else None, T=T)
    ref, mine = systems(user)
    assert user.core.type == "user"
    np.testing.assert_array_equal(user.core.initial_stiffness, [[K1]])
    rng = np.random.default_rng(23)
    for _ in range(3):
        U = rng.normal(size=ref.unknowns)
        R0, J0, W0 = ref.residual(U, 1.3)
        R1, J1, W1 = mine.residual(U, 1.3)
        # Round-off: the law evaluated in numpy instead of C++ (a few ulp per sample) summed
        # over 64 samples by the DFT: below 1e-13 of the largest coefficient.
        scale = np.abs(R0).max()
        np.testing.assert_allclose(R1, R0, rtol=0, atol=1e-13 * scale)
        np.testing.assert_allclose(W1, W0, rtol=0, atol=1e-13 * np.abs(W0).max())
        # The exact Jacobian: round-off as above. Central differences with steps of 1e-6
        # of the samples' magnitude: exact for the quadratic part, k3 h^2 for the cubic
        # (1e-12 relative) and round-off eps |f| / h ~ 1e-10 relative: 1e-8 of the largest
        # entry.
        tol = 1e-13 if exact_jacobian else 1e-8
        np.testing.assert_allclose(J1, J0, rtol=0, atol=tol * np.abs(J0).max())


def test_python_cubic_spring_gives_the_built_in_frequency_response_and_mode():
    user = vib.UserElement(cubic_force, cubic_jacobian, T=T)
    ref, mine = systems(user)
    F = ref.force(cos={1: [0.05, 0.0]})
    a = ref.frequency_response(F, omega=(0.6, 1.8), output_dofs=[0, 1])[0]
    b = mine.frequency_response(F, omega=(0.6, 1.8), output_dofs=[0, 1])[0]
    assert a.continuation["complete"] and b.continuation["complete"]
    # The same Newton path from residuals equal to round-off: every point to 1e-10 of the
    # largest amplitude (Newton stops at 1e-8 steps; the paths differ only by round-off).
    assert len(a.omega) == len(b.omega)
    np.testing.assert_allclose(b.omega, a.omega, rtol=1e-10)
    np.testing.assert_allclose(b.output_amplitude, a.output_amplitude, rtol=0,
                               atol=1e-10 * np.abs(a.output_amplitude).max())
    # Mode 2 stretches the spring: its backbone hardens from 1.95 to 4.8 rad/s.
    ma = ref.nonlinear_mode(mode=2, log10_amplitude=(-1.0, 0.5))
    mb = mine.nonlinear_mode(mode=2, log10_amplitude=(-1.0, 0.5))
    assert ma.continuation["complete"] and ma.omega[-1] > 2.0 * ma.omega[0]
    np.testing.assert_allclose(mb.omega, ma.omega, rtol=1e-10)
    np.testing.assert_allclose(mb.damping_ratio, ma.damping_ratio, rtol=1e-8, atol=1e-14)


def test_python_cubic_damper_gives_the_built_in_residual():
    c3 = 0.7
    user = vib.UserElement(lambda u, v: c3 * v ** 3, T=T, velocity_dependent=True)
    s = vib.Structure(M2, K2_STRUCT, 0.02 * K2_STRUCT)
    ref = vib.HarmonicBalance(s, [vib.CubicDamping(c3, T=T)], max_harmonic=3, time_points=64)
    mine = vib.HarmonicBalance(s, [user], max_harmonic=3, time_points=64)
    U = np.random.default_rng(5).normal(size=ref.unknowns)
    R0, J0, _ = ref.residual(U, 1.3)
    R1, J1, _ = mine.residual(U, 1.3)
    # Tolerances as for the spring above (central differences in the velocity).
    np.testing.assert_allclose(R1, R0, rtol=0, atol=1e-13 * np.abs(R0).max())
    np.testing.assert_allclose(J1, J0, rtol=0, atol=1e-8 * np.abs(J0).max())


def test_two_direction_law_and_bad_laws():
    # A 2-direction law coupling its directions, f = K u with K non-diagonal, against the
    # built-in linear stiffness of the same K added to the structure.
    Ke = np.array([[1.0, 0.4], [0.4, 2.0]])
    user = vib.UserElement(lambda u, v: u @ Ke.T, T=np.eye(2))
    np.testing.assert_allclose(user.core.initial_stiffness, Ke, rtol=1e-9)
    s = vib.Structure(M2, K2_STRUCT, 0.02 * K2_STRUCT)
    lin = vib.HarmonicBalance(vib.Structure(M2, K2_STRUCT + Ke, 0.02 * K2_STRUCT), [],
                              max_harmonic=2, time_points=16)
    mine = vib.HarmonicBalance(s, [user], max_harmonic=2, time_points=16)
    U = np.random.default_rng(7).normal(size=lin.unknowns)
    R0, J0, _ = lin.residual(U, 0.9)
    R1, J1, _ = mine.residual(U, 0.9)
    np.testing.assert_allclose(R1, R0, rtol=0, atol=1e-13 * np.abs(R0).max())
    np.testing.assert_allclose(J1, J0, rtol=0, atol=1e-8 * np.abs(J0).max())
    # A law of the wrong shape, a NaN, an exception inside the law.
    with pytest.raises(ValueError, match="shape"):
        vib.UserElement(lambda u, v: np.zeros(3), T=T)
    bad = vib.UserElement(lambda u, v: np.where(np.abs(u) > 0.5, np.nan, u), T=T)
    hb = vib.HarmonicBalance(s, [bad], max_harmonic=1, time_points=8)
    with pytest.raises(ValueError, match="NaN"):
        hb.residual(np.ones(hb.unknowns), 1.0)

    def boom(u, v):
        if np.abs(u).max() > 0.5:
            raise ZeroDivisionError("inside the law")
        return u

    hb = vib.HarmonicBalance(s, [vib.UserElement(boom, T=T)], max_harmonic=1, time_points=8)
    with pytest.raises(ZeroDivisionError, match="inside the law"):
        hb.residual(np.ones(hb.unknowns), 1.0)
    with pytest.raises(ValueError, match="callable"):
        vib.UserElement(3.0, T=T)
    # The C++ element holds the law weakly: without its UserElement it says so.
    core = vib.UserElement(cubic_force, T=T).core
    with pytest.raises(ValueError, match="released"):
        core.static_response(np.array([0.1]))


def test_backbone_rom_of_a_case_is_the_mode_rom_of_its_backbone():
    # [[backbone_rom]] (examples/vibration/jenkins_backbone_rom.toml without its full
    # forced responses) against HarmonicBalance.mode_rom on the run's own backbone: the
    # same C++ function on the same numbers, so the same arrays exactly.
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "examples" / "vibration" /
            "jenkins_backbone_rom.toml").read_text()
    text = (text[:text.index("\n[[frequency_response]]")]
            + text[text.index("\n[[backbone_rom]]"):])
    r = vib.run_case_text(text)
    assert r.frequency_response == [] and len(r.backbone_rom) == 2
    assert [c.force_scale for c in r.backbone_rom] == [0.5, 1.0]
    hb = r.system
    mode = dict(r.nonlinear_mode)
    for c in r.backbone_rom:
        F = hb.force(cos={1: [0.1 * c.force_scale]})
        m = hb.mode_rom(mode, F, output_dofs=[0], subdivisions=64)
        np.testing.assert_array_equal(c.omega, m.omega)
        np.testing.assert_array_equal(c.output_amplitude, m.output_amplitude)
        assert c.low_side_points == m.low_side_points and c.peak_amplitude == m.peak_amplitude
