"""Hill's stability of forced responses from Python (docs/vibration.md, "Stability"):
the case key, the run_case switch, the HarmonicBalance API and the plot, on the forced
Duffing oscillator whose unstable branch lies between its two folds (one-harmonic closed
form in tests/vibration/stability_test.cpp)."""

from __future__ import annotations

import numpy as np
import pytest

import asperity
import asperity.vibration as vib

CASE = """
[structure]
mass = [[1.0]]
stiffness = [[1.0]]
damping = [[0.05]]
[[element]]
type = "polynomial_stiffness"
T = [[1.0]]
k3 = 1.0
[harmonic_balance]
max = 3
time_points = 32
[[frequency_response]]
force_cos = [[0.0], [0.3]]
omega = { from = 0.5, to = 2.5 }
"""


def _falling_and_rising(omega):
    w = np.asarray(omega)
    falling = np.zeros(len(w), bool)
    rising = np.zeros(len(w), bool)
    falling[1:-1] = (w[:-2] > w[1:-1]) & (w[1:-1] > w[2:])
    rising[1:-1] = (w[:-2] < w[1:-1]) & (w[1:-1] < w[2:])
    return falling, rising


def test_case_switch_marks_the_branch_between_the_folds_unstable():
    plain = vib.run_case_text(CASE)
    assert "stability" not in plain.frequency_response[0]  # off unless asked
    r = vib.run_case_text(CASE, stability=True)
    c = r.frequency_response[0]
    st = c.stability
    n = len(c.omega)
    assert st.stable.dtype == bool and st.stable.shape == (n,)
    assert st.exponents.shape == (n, 2)  # 2 n exponents for n = 1 DOF
    assert np.iscomplexobj(st.exponents)
    falling, rising = _falling_and_rising(c.omega)
    assert falling.sum() > 3 and rising.sum() > 10
    assert not st.stable[falling].any()
    assert st.stable[rising].all()
    assert set(np.asarray(st.instability)[falling]) == {"fold"}
    # |mu| = exp(max Re lambda 2 pi / omega), to round-off.
    np.testing.assert_allclose(st.max_multiplier_modulus,
                               np.exp(st.max_real_exponent * 2 * np.pi / c.omega), rtol=1e-12)
    # The same through the case key, and in summary.json's layout.
    keyed = vib.run_case_text(CASE + "stability = true\n")
    js = keyed.summary["frequency_response"][0]["stability"]
    assert js["method"] == "hill"
    assert list(js["stable"]) == list(st.stable)


def test_api_switch_and_plot(tmp_path):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    s = vib.Structure(M=[[1.0]], K=[[1.0]], C=[[0.05]])
    hb = vib.HarmonicBalance(s, [vib.PolynomialStiffness(k3=1.0, T=[[1.0]])], max_harmonic=3,
                             time_points=32)
    curves = hb.frequency_response(hb.force(cos={1: [0.3]}), (0.5, 2.5), output_dofs=[0],
                                   stability=True)
    st = curves[0].stability
    assert (~st.stable).sum() > 3
    ax = vib.plot_response(curves)
    labels = [line.get_label() for line in ax.get_lines()]
    assert "unstable (Hill)" in labels
    ax.figure.savefig(tmp_path / "fr.png")


def test_bad_stability_key_is_refused():
    with pytest.raises(asperity.InvalidInput,
                       match=r"frequency_response\[1\]\.stability must be true or false"):
        vib.run_case_text(CASE + "stability = 1\n")
