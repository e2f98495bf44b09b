"""ISO 21920-2 / ISO 25178-2 parameters, the PSD and spike removal from Python, on the real
MountainsMap X3P of tests/data: against SurfaceTopography (ContactEngineering, an
independent implementation) where it computes the same quantity (Rq, Rdq, Sq, the rms
gradient) and against numpy where it does not (Ra, Rz, Rsk, Rku, Sa, Ssk, Sku, the PSD).

The heights given to both are the S-L surface asperity computes; SurfaceTopography
subtracts the mean before Rq and Sq while ISO 21920-2/25178-2 (and asperity) take the
ordinates about the reference (the mean line/plane the filter removed, z = 0), so the
comparisons use heights of zero mean. Round-off: sums over 1e5 points, 1e-12 relative.
"""
import os

import numpy as np
import pytest
from SurfaceTopography import Topography, UniformLineScan
from SurfaceTopography.Uniform.ScalarParameters import Rdq, Rq, Sq, rms_gradient

import asperity

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
X3P = os.path.join(ROOT, "tests", "data", "mountainsmap-650x650.x3p")
# A cut-off pair the refusal of the default filter names for this 83 x 204 um map.
LC, LS = 26.5e-6, 1.6e-6


@pytest.fixture(scope="module")
def surface():
    x = asperity.read_x3p(X3P)
    sl, _, _ = asperity.scale_limited_surface(x["z"], x["dx"], x["dy"], lc=LC, ls=LS)
    return sl - sl.mean(), x["dx"], x["dy"]


def test_profile_parameters_against_surfacetopography_and_numpy(surface):
    sl, dx, _ = surface
    for row in sl[:: sl.shape[0] // 7]:
        row = row - row.mean()
        p = asperity.texture_parameters(row, dx, section_length=LC)
        line = UniformLineScan(row, physical_sizes=dx * row.size, periodic=False)
        assert p["Rq"] == pytest.approx(Rq(line), rel=1e-12)
        # Both take forward differences over the n - 1 neighbouring pairs.
        assert p["Rdq"] == pytest.approx(Rdq(line), rel=1e-12)
        q = np.sqrt(np.mean(row**2))
        assert p["Ra"] == pytest.approx(np.mean(np.abs(row)), rel=1e-12)
        assert p["Rsk"] == pytest.approx(np.mean(row**3) / q**3, rel=1e-12)
        assert p["Rku"] == pytest.approx(np.mean(row**4) / q**4, rel=1e-12)
        per = round(LC / dx)
        sections = [row[k * per:(k + 1) * per] for k in range(row.size // per)]
        assert p["sections"] == len(sections)
        assert p["Rz"] == pytest.approx(np.mean([s.max() - s.min() for s in sections]), rel=1e-12)


def test_areal_parameters_against_surfacetopography_and_numpy(surface):
    sl, dx, dy = surface
    ny, nx = sl.shape
    a = asperity.areal_parameters(sl, dx, dy, level="none", lc=None, ls=None)
    topo = Topography(sl.T.copy(), physical_sizes=(dx * nx, dy * ny), periodic=False)
    assert a["Sq"] == pytest.approx(Sq(topo), rel=1e-12)
    q = np.sqrt(np.mean(sl**2))
    assert a["Sa"] == pytest.approx(np.mean(np.abs(sl)), rel=1e-12)
    assert a["Ssk"] == pytest.approx(np.mean(sl**3) / q**3, rel=1e-12)
    assert a["Sku"] == pytest.approx(np.mean(sl**4) / q**4, rel=1e-12)
    # Sdq: asperity averages all (nx-1) ny x-differences and all nx (ny-1) y-differences;
    # SurfaceTopography adds the two squares on the (nx-1)(ny-1) cells both exist on.
    gx, gy = np.diff(sl, axis=1) / dx, np.diff(sl, axis=0) / dy
    assert a["Sdq"] == pytest.approx(np.sqrt(np.mean(gx**2) + np.mean(gy**2)), rel=1e-12)
    assert rms_gradient(topo) == pytest.approx(
        np.sqrt(np.mean(gx[:-1, :] ** 2 + gy[:, :-1] ** 2)), rel=1e-12)
    # The two differ by the one row/column of differences SurfaceTopography leaves out: a
    # share of at most 1/(n-1) of each mean.
    assert a["Sdq"] == pytest.approx(rms_gradient(topo), rel=1.0 / (min(nx, ny) - 1))


def test_psd_normalisation_and_numpy(surface):
    sl, dx, dy = surface
    row = sl[100]
    s = asperity.profile_power_spectrum(row, dx)
    # Parseval: sum psd * df = mean z^2 (one-sided, no window).
    assert np.sum(s["psd"]) * s["df"] == pytest.approx(np.mean(row**2), rel=1e-12)
    # numpy's rfft: psd = c |Z|^2 dx / n with c = 2 except at f = 0 and Nyquist.
    n = row.size
    Z = np.fft.rfft(row)
    c = np.full(Z.size, 2.0)
    c[0] = 1.0
    if n % 2 == 0:
        c[-1] = 1.0
    np.testing.assert_allclose(s["psd"], c * np.abs(Z) ** 2 * dx / n, rtol=1e-9,
                               atol=1e-12 * s["psd"].max())
    np.testing.assert_allclose(s["f"], np.fft.rfftfreq(n, dx), rtol=1e-12)
    for axis, lines in (("x", sl), ("y", sl.T)):
        a = asperity.areal_power_spectrum(sl, dx, dy, axis=axis)
        assert a["profiles"] == lines.shape[0]
        assert np.sum(a["psd"]) * a["df"] == pytest.approx(np.mean(sl**2), rel=1e-12)


def test_isotropic_surface_reports_the_areal_parameters_and_psd():
    r = asperity.equivalent_isotropic_surface([X3P], lc=LC, ls=LS, psd=True)
    a = r["areal_parameters"]
    x = asperity.read_x3p(X3P)
    direct = asperity.areal_parameters(x["z"], x["dx"], x["dy"], lc=LC, ls=LS)
    for k in ("Sa", "Sq", "Ssk", "Sku", "Sdq"):
        assert a[k] == pytest.approx(direct[k], rel=1e-12)
    assert [s["direction"] for s in r["psd"]] == ["x (rows)", "y (columns)"]
    assert all(s["parameters"] is None for s in r["scans"])  # areal axes


def test_areal_parameters_refuse_invalid_points_and_say_why(tmp_path):
    rng = np.random.default_rng(4)
    z = rng.normal(0.0, 1e-7, (64, 64))
    z[10, 10] = np.nan
    with pytest.raises(asperity.InvalidInput, match="1 of its 64 x 64 points are invalid"):
        asperity.areal_parameters(z, 1e-6, 1e-6, lc=None, ls=None)
    path = str(tmp_path / "masked.x3p")
    asperity.write_x3p(path, z, 1e-6, 1e-6)
    r = asperity.equivalent_isotropic_surface([path], lc=None, ls=None)
    assert r["areal_parameters"] is None
    assert "invalid" in r["areal_parameters_note"]


def test_spike_removal_from_python():
    x = np.linspace(0, 1e-3, 2001)
    z = 1e-6 * np.sin(2 * np.pi * x / 1e-4)
    spiky = z.copy()
    spiky[[500, 1200]] += 30e-6
    fixed, n = asperity.remove_spikes(spiky, 5.0)
    assert n == 2
    # The chord of the neighbours of a point of a sine: within A (k dx)^2/2 = 2e-9 m.
    np.testing.assert_allclose(fixed, z, atol=2.5e-9)
    p = asperity.profile_parameters(spiky, x[1], lc=None, ls=None, spikes=5.0)
    q = asperity.profile_parameters(z, x[1], lc=None, ls=None)
    assert p["Rq"] == pytest.approx(q["Rq"], rel=1e-3)
    with pytest.raises(asperity.InvalidInput, match="spikes.threshold"):
        asperity.remove_spikes(z, 1.0)
