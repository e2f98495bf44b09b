"""Jenkins and four-parameter Iwan fits of fretting loops from Python
(asperity.vibration.fit_loops, the fit of `asperity analyze --fit`): recovery of known
parameters, and the round trip fit -> element -> loop on synthetic experiments of the
shipped joint case analysed as measurements."""
import os

import numpy as np
import pytest

import asperity
from asperity import vibration as vib

EX = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "joints")


def _loop(element, a, n=400):
    """The element's steady loop under u = a cos(2 pi i/n): the unloading half first."""
    u = (a * np.cos(2 * np.pi * np.arange(n) / n)).reshape(-1, 1)
    return u[:, 0], element.core.periodic_response(u, tangent=False)["f"][:, 0]


def test_known_iwan4_parameters_are_recovered():
    truth = dict(F_S=80.0, K_T=3e7, chi=-0.3, beta=0.5)
    el = vib.Iwan4(**truth)
    loops = [_loop(el, a) for a in (0.5e-6, 1.5e-6, 6e-6)]
    f = vib.fit_loops(loops, "iwan4")
    # Exact loops: the optimum is the truth; Levenberg-Marquardt stops at a relative change
    # of the cost of 1e-14, leaving the parameters within ~1e-7, checked at 1e-5.
    for k, v in truth.items():
        assert f.parameters[k]["value"] == pytest.approx(v, rel=1e-5)
    assert f.relative_residual < 1e-6
    assert isinstance(f.element, vib.Iwan4)
    assert 'type = "iwan4"' in f.element_toml


def test_round_trip_on_analysed_synthetic_experiments():
    # The shipped joint (the physics backbone, not an Iwan model) at three amplitudes,
    # noise-free sensors so that the averaged loops are monotone on each branch.
    runs = []
    for a in (2e-6, 4e-6, 8e-6):
        d = asperity.synthetic_experiment(os.path.join(EX, "steel420_two_bolts.toml"), 526.0, a,
                                          noise_delta=0.0, noise_Q=0.0)
        runs.append(asperity.analyze_fretting(d["t"], d["delta"], d["Q"], 526.0, Delta=d["Delta"]))
    for model in ("jenkins", "iwan4"):
        f = vib.fit_loops(runs, model)
        ss, n = 0.0, 0
        for k, r in enumerate(runs):
            x = np.asarray(r["loop_delta"])
            u = (x - 0.5 * (x.max() + x.min())).reshape(-1, 1)
            q = f.element.core.periodic_response(u, tangent=False)["f"][:, 0] + f.Q_offsets[k]
            # The element driven along the loop is the fitted loop (round-off of the branch
            # arithmetic: 1e-9 of the force).
            np.testing.assert_allclose(q, f.Q_model[k], rtol=0, atol=1e-9 * np.abs(q).max())
            ss += np.sum((q - np.asarray(r["loop_Q"])) ** 2)
            n += x.size
        # ... so its misfit to the measured loops is the fit's residual.
        assert np.sqrt(ss / n) == pytest.approx(f.residual_rms, rel=1e-9)
    # The physics loop is not a Jenkins loop (a corner instead of micro-slip): Iwan's four
    # parameters fit it better.
    assert vib.fit_loops(runs, "iwan4").residual_rms < vib.fit_loops(runs, "jenkins").residual_rms


def test_bad_model_is_refused():
    with pytest.raises(asperity.InvalidInput, match="jenkins or iwan4"):
        vib.fit_loops([(np.linspace(1, -1, 10), np.linspace(1, -1, 10))], "iwan")
