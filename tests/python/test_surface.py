"""surface/ from Python: roughness parameters on numpy arrays (thesis ch. 5-6)."""
import importlib.util
import math
import pathlib
import zipfile

import numpy as np
import pytest

import asperity

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"
EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "roughness"
um = 1e-6


def test_table_5_4_combined_column_and_psi():
    pzt = asperity.SpectralMoments.from_parameters(1.763 * um, 3.34e-4 / um**2, 40.76 * um)
    lc = asperity.SpectralMoments.from_parameters(2.015 * um, 2.51e-4 / um**2, 44.77 * um)
    comb = pzt + lc
    assert comb.sigma / um == pytest.approx(2.677, abs=5e-4)
    assert comb.R / um == pytest.approx(30.14, abs=5e-3)
    assert comb.eta * um**2 == pytest.approx(2.91e-4, abs=1e-6)
    steel = asperity.Material(E=200e9, nu=0.24, G=80.7e9, H=5.8e9)
    pair = asperity.ContactPair.combine(steel, steel, 1.0)
    assert asperity.plasticity_index(pair, comb) == pytest.approx(4.725, rel=0.01)
    assert comb.beta == pytest.approx(0.02036 * math.sqrt(comb.alpha), rel=1e-4)


def test_filter_transmission_and_moments_of_a_sinusoid():
    assert asperity.gaussian_transmission(0.8e-3, lc=0.8e-3, ls=None) == pytest.approx(0.5)
    t = asperity.gaussian_transmission(np.array([20e-6, 0.8e-3]), lc=0.8e-3, ls=20e-6)
    assert t.shape == (2,)
    dx, lam, a = 0.5 * um, 100 * um, 1 * um
    x = np.arange(0, 12e-3, dx)
    z = a * np.sin(2 * np.pi * x / lam) + 3e-3 * x
    m = asperity.profile_moments(z, dx)
    T = asperity.gaussian_transmission(lam)
    k = 2 * np.pi / lam
    assert m.m0 == pytest.approx(0.5 * a**2 * T**2, rel=0.01)
    assert m.m2 == pytest.approx(0.5 * a**2 * T**2 * k**2, rel=0.01)
    assert m.m4 == pytest.approx(0.5 * a**2 * T**2 * k**4, rel=0.01)
    r, x0 = asperity.filter_profile(z, dx)
    assert r.size == z.size - 2 * (1600 + 40)
    assert x0 == pytest.approx((1600 + 40) * dx)
    assert np.allclose(asperity.level_profile(3.0 + 2.0 * np.arange(5.0)), 0.0)


def test_equivalent_isotropic_rules():
    a = asperity.SpectralMoments(4e-12, 0.04, 8e8)
    b = asperity.SpectralMoments(2e-12, 0.01, 2e8)
    g = asperity.equivalent_isotropic(a, b)
    assert (g.m0, g.m2, g.m4) == pytest.approx((3e-12, 0.02, 4e8))
    ar = asperity.equivalent_isotropic(a, b, "arithmetic")
    assert (ar.m2, ar.m4) == pytest.approx((0.025, 5e8))
    with pytest.raises(asperity.InvalidInput):
        asperity.equivalent_isotropic(a, b, "harmonic")


def test_readers_and_x3p_round_trip(tmp_path):
    p = asperity.read_profile(str(DATA / "dektak-1.csv"))
    assert p["z"].size == 9600
    assert p["dx"] == pytest.approx(0.15625 * um, rel=1e-3)
    m = asperity.read_x3p(str(DATA / "mountainsmap-650x650.x3p"))
    assert m["z"].shape == (650, 650)
    assert asperity.rms_height_about_plane(m["z"]) == pytest.approx(7.7193e-8, rel=1e-4)
    z = np.random.default_rng(0).normal(size=(4, 7)) * 1e-6
    z[1, 2] = np.nan
    path = tmp_path / "map.x3p"
    asperity.write_x3p(str(path), z, 1e-6, 2e-6, type="F")
    back = asperity.read_x3p(str(path))
    assert back["invalid_points"] == 1
    assert np.allclose(back["z"], z, equal_nan=True, atol=1e-12)
    with pytest.raises(asperity.InvalidInput, match="MD5|zip"):
        bad = tmp_path / "bad.x3p"
        bad.write_bytes(b"PK\x03\x04" + b"\0" * 40)
        asperity.read_x3p(str(bad))


def test_shipped_example_reproduces_table_5_4():
    def half(name):
        mx = asperity.profile_moments(asperity.read_profile(str(EXAMPLES / f"{name}_max.csv"))["z"], 1 * um)
        mn = asperity.profile_moments(asperity.read_profile(str(EXAMPLES / f"{name}_min.csv"))["z"], 1 * um)
        return asperity.equivalent_isotropic(mx, mn)

    pzt, lc = half("pzt"), half("lc")
    assert (pzt.sigma / um, pzt.eta * um**2, pzt.R / um) == pytest.approx((1.763, 3.34e-4, 40.76), rel=1e-4)
    assert (lc.sigma / um, lc.eta * um**2, lc.R / um) == pytest.approx((2.015, 2.51e-4, 44.77), rel=1e-4)


def test_x3p_fixtures_built_independently(tmp_path):
    # tests/data/x3p/make_fixtures.py writes the archives with zipfile/struct/hashlib (not
    # our writer); regenerating them gives the committed members byte for byte.
    spec = importlib.util.spec_from_file_location("make_fixtures", DATA / "x3p" / "make_fixtures.py")
    fx = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(fx)
    for name, build in fx.FIXTURES.items():
        fx.write_archive(tmp_path / name, build())
        with zipfile.ZipFile(DATA / "x3p" / name) as a, zipfile.ZipFile(tmp_path / name) as b:
            assert a.namelist() == b.namelist()
            for member in a.namelist():
                assert a.read(member) == b.read(member), (name, member)
    # z = CZ Offset + CZ Increment x value (ISO 5436-2); the values are fx's.
    p = asperity.read_x3p(str(DATA / "x3p" / "prf_int16_offset.x3p"))
    assert p["z"].shape == (1, 7)
    assert p["z"][0] == pytest.approx([2.5e-6 + 1e-9 * v for v in fx.PRF_INT16_VALUES], rel=1e-14)
    assert (p["dx"], p["x0"]) == (0.5e-6, 1e-3)
    # The mask: bit k % 8 of byte k // 8, least significant first, 1 = valid (openGPS
    # ISO5436_2_XML valid_buffer.cxx, ValidBuffer::IsValid).
    s = asperity.read_x3p(str(DATA / "x3p" / "sur_int32_mask.x3p"))
    assert s["z"].shape == (3, 5)
    flat = s["z"].ravel()
    assert sorted(np.flatnonzero(np.isnan(flat))) == sorted(fx.SUR_INVALID)
    valid = [k for k in range(15) if k not in fx.SUR_INVALID]
    assert flat[valid] == pytest.approx([1e-10 * fx.SUR_INT32_VALUES[k] for k in valid], rel=1e-14)
    d = asperity.read_x3p(str(DATA / "x3p" / "prf_datalist_empty.x3p"))
    assert d["invalid_points"] == 1
    np.testing.assert_array_equal(d["z"][0], [1.5e-6, -2.25e-6, np.nan, 3.0e-6, 4e-7, 0.0])


def test_text_reader_refuses_a_break_inside_the_data(tmp_path):
    rows = [f"{i},{0.1 * (i % 7):.1f}" for i in range(6000)]
    path = tmp_path / "lifted.csv"
    path.write_text("\n".join(["x[um],z[um]"] + rows[:5000] + ["ERROR: stylus lifted"] + rows[5000:]) + "\n")
    with pytest.raises(asperity.InvalidInput, match="line 5002: not a number inside the data"):
        asperity.read_profile(str(path))
    # The header's names decide the column order.
    swapped = tmp_path / "zx.csv"
    swapped.write_text("z[um],x[mm]\n5,0\n6,0.001\n7,0.002\n")
    p = asperity.read_profile(str(swapped))
    assert p["dx"] == 1e-6
    np.testing.assert_allclose(p["z"], [5e-6, 6e-6, 7e-6], rtol=1e-15)


def test_a_profile_flat_after_levelling_is_refused():
    # A straight line levelled leaves only round-off (m0 ~ 1e-45 m^2, which gave
    # R = 4.6e17 um): refused, not turned into parameters.
    line = np.arange(5000.0) * 1e-9
    with pytest.raises(asperity.InvalidInput, match=r"flat after levelling \(line\) and filtering.*round-off"):
        asperity.profile_moments(line, 1e-6)  # 5 mm at 1 um: the default filter fits
    with pytest.raises(asperity.InvalidInput, match=r"flat after levelling \(line\):.*round-off"):
        asperity.profile_moments(line, 1e-6, lc=None, ls=None)
    # 1 nm of roughness on the same tilt is kept: a 20 um sine of amplitude 1 nm has
    # sigma = 1 nm / sqrt(2) less the levelling line's share (250 periods: 5e-6).
    x = np.arange(5000.0) * 1e-6
    m = asperity.profile_moments(line + 1e-9 * np.sin(2 * np.pi * x / 20e-6), 1e-6, lc=None, ls=None)
    assert m.sigma == pytest.approx(1e-9 / math.sqrt(2), rel=1e-4)
