"""Issue 13: one function turns scans into the equivalent isotropic surface; Python, the
case files and the CLI give the same numbers for the same files."""
import json
import os
import subprocess

import numpy as np
import pytest

import asperity

ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
EX = os.path.join(ROOT, "examples", "roughness")
PZT_MAX, PZT_MIN = os.path.join(EX, "pzt_max.csv"), os.path.join(EX, "pzt_min.csv")


def test_untagged_pair_is_ordered_by_m2_and_combined_by_eq_5_1():
    a = asperity.equivalent_isotropic_surface([PZT_MIN, PZT_MAX])
    b = asperity.equivalent_isotropic_surface([PZT_MAX, PZT_MIN])
    assert a["moments"].m0 == b["moments"].m0 and a["moments"].m4 == b["moments"].m4
    mx = asperity.profile_moments(asperity.read_profile(PZT_MAX)["z"],
                                  asperity.read_profile(PZT_MAX)["dx"])
    mn = asperity.profile_moments(asperity.read_profile(PZT_MIN)["z"],
                                  asperity.read_profile(PZT_MIN)["dx"])
    expected = asperity.equivalent_isotropic(mx, mn, "geometric")
    # Same functions on the same data: equal to round-off (1e-12 relative).
    assert b["moments"].m2 == pytest.approx(expected.m2, rel=1e-12)
    assert [s["direction"] for s in b["scans"]] == ["max_slope", "min_slope"]


def test_tags_agree_with_the_untagged_pair_and_mixed_tags_are_refused():
    tagged = asperity.equivalent_isotropic_surface([PZT_MAX + "@max", PZT_MIN + "@min"])
    plain = asperity.equivalent_isotropic_surface([PZT_MAX, PZT_MIN])
    assert tagged["moments"].m2 == pytest.approx(plain["moments"].m2, rel=1e-12)
    with pytest.raises(asperity.InvalidInput, match="tag every scan"):
        asperity.equivalent_isotropic_surface([PZT_MAX + "@max", PZT_MIN])
    with pytest.raises(asperity.InvalidInput, match='unknown tag "@diagonal"'):
        asperity.equivalent_isotropic_surface([PZT_MAX + "@diagonal"])


def test_case_file_and_python_agree_on_tagged_scans():
    text = f"""
[joint]
area = "170 mm^2"
model = "bke"
[[joint.half]]
material = {{ E = "200 GPa", nu = 0.24, G = "80.7 GPa", H = "5.8 GPa" }}
profiles = ["{PZT_MIN}@min", "{PZT_MAX}@max"]
[[joint.half]]
material = {{ E = "200 GPa", nu = 0.24, G = "80.7 GPa", H = "5.8 GPa" }}
roughness = {{ sigma = "2.015 um", eta = "2.51e-4 um^-2", R = "44.77 um" }}
[load]
preloads = ["526 N"]
"""
    r = asperity.predict_case_text(text)
    half = r["roughness"]["halves"][0]
    m = asperity.equivalent_isotropic_surface([PZT_MIN + "@min", PZT_MAX + "@max"])["moments"]
    assert half["sigma"] == pytest.approx(m.sigma, rel=1e-12)
    assert half["eta"] == pytest.approx(m.eta, rel=1e-12)
    assert half["R"] == pytest.approx(m.R, rel=1e-12)
    assert half["directions"] == ["min_slope", "max_slope"]


def test_profile_cut_by_invalid_points_says_so(tmp_path):
    # Issue 21: a profile X3P with every third point NaN was refused as "the profile (2
    # points) is shorter than the filter needs", without a word of the invalid points that
    # made it so short.
    z = asperity.read_profile(PZT_MAX)["z"].copy()
    dx = asperity.read_profile(PZT_MAX)["dx"]
    z[::3] = np.nan
    path = str(tmp_path / "holes.x3p")
    asperity.write_x3p(path, z.reshape(1, -1), dx, dx)
    n = z.size
    with pytest.raises(asperity.InvalidInput,
                       match=(rf"{len(z[::3])} of the file's {n} points are invalid \(NaN or "
                              r"masked\) and scattered: the longest run of consecutive valid "
                              r"points, which is what gets processed, has 2 points; fill the gaps"
                              r".*shorter than the filter needs")):
        asperity.equivalent_isotropic_surface([path])
    # The same file without holes: the moments of the whole profile.
    asperity.write_x3p(path, asperity.read_profile(PZT_MAX)["z"].reshape(1, -1), dx, dx)
    assert asperity.equivalent_isotropic_surface([path])["scans"][0]["points"] > 2
