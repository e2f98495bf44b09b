"""The Odfalk-Vingsbo law (thesis Eq. 3.10) from Python: the vibration element, a joint
case carrying the law into vibration, and predict's loops under the law."""
import math
import pathlib

import numpy as np
import pytest

import asperity
from asperity import vibration as vib

ROOT = pathlib.Path(__file__).resolve().parents[2]


def ov_case(tmp_path, Q_ty="20 N", k_p="50 N/um"):
    # The rough steel joint of chapter 6 at its first preload, with the law in [interface].
    text = (ROOT / "examples" / "joints" / "steel_rough.toml").read_text()
    text = text.split("[excitation]")[0] + (
        '[excitation]\namplitudes = ["0.1 um", "1 um"]\n[interface]\n'
        f'tangential = "odfalk_vingsbo"\nfretting_yield_point = "{Q_ty}"\n'
        f'hardening_coefficient = "{k_p}"\n')
    path = tmp_path / "ov.toml"
    path.write_text(text)
    return path


def test_predict_loops_follow_the_law(tmp_path):
    # Each loop's peak is the amplitude row's Q_peak, the law's (the root of
    # x_m = x_l(Q_m) + (Q_m - Q_ty)/(2 k_p)), not Masing's on the elastic backbone
    # (which is larger once Q_m > Q_ty); both to 1e-9 (the two roots' rounding).
    L = asperity.predict(str(ov_case(tmp_path)))["loads"][0]
    assert L["odfalk_vingsbo"] == {"fretting_yield_point": 20.0, "hardening_coefficient": 50e6}
    for Q_peak, loop, x_m in zip(L["Q_peak"], L["loops"], L["delta_max"]):
        assert np.max(loop["Q"]) == pytest.approx(Q_peak, rel=1e-9)
        if Q_peak > 20.0:
            assert L["backbone"].force(x_m) > Q_peak * (1 + 1e-6)


def test_joint_case_element_is_the_law(tmp_path):
    # RoughFlat.from_joint_case returns the law's element for such a case; driven along
    # x_m cos(t) its force amplitude is the predicted Q_peak (Eq. 3.10 at delta_max): 1e-9.
    path = ov_case(tmp_path)
    L = asperity.predict(str(path))["loads"][0]
    e = vib.RoughFlat.from_joint_case(path)
    assert isinstance(e, vib.OdfalkVingsbo) and e.type == "rough_flat"
    d = e.describe()
    assert d["tangential"] == "odfalk_vingsbo" and d["fretting_yield_point_N"] == 20.0
    t = 2 * math.pi * np.arange(64) / 64
    for Q_peak, x_m in zip(L["Q_peak"], L["delta_max"]):
        r = e.core.periodic_response((x_m * np.cos(t))[:, None], np.zeros((0, 0)), False)
        assert r["f"][0, 0] == pytest.approx(Q_peak, rel=1e-9)
        assert r["f"][32, 0] == pytest.approx(-Q_peak, rel=1e-9)


def test_below_the_yield_point_it_is_the_rough_flat():
    # Q_ty above the gross-slip force: no plastic slip, the RoughFlat element's backbone
    # (EPMC of a 1-DOF oscillator) to 1e-10 (the same steps on the same residuals).
    bb = asperity.JenkinsBackbone(2e8, 50.0)
    s = vib.Structure([[1.0]], [[1e8]], [[20.0]])
    a, b = (vib.nonlinear_mode(vib.HarmonicBalance(s, [e], max_harmonic=3, time_points=64),
                               log10_amplitude=(-8.0, -5.0))
            for e in (vib.RoughFlat(bb), vib.OdfalkVingsbo(bb, 100.0, 1e8)))
    assert len(a.omega) == len(b.omega) > 10
    np.testing.assert_allclose(b.omega, a.omega, rtol=1e-10)
    np.testing.assert_allclose(b.damping_ratio, a.damping_ratio, rtol=1e-10)


def test_bad_parameters_are_refused():
    bb = asperity.JenkinsBackbone(2e8, 50.0)
    with pytest.raises(ValueError, match="fretting_yield_point"):
        vib.OdfalkVingsbo(bb, 0.0, 1e8)
    with pytest.raises(ValueError, match="hardening_coefficient"):
        vib.OdfalkVingsbo(bb, 10.0, float("nan"))
