"""Joint layer from Python (issue 5): predict on the thesis's chapter 5 joint, the
fretting analysis on a synthetic experiment, Eq. 5.2, the validation report."""
import os

import numpy as np
import pytest

import asperity

EX = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "joints")


def test_predict_chapter5_mu_within_five_percent():
    # Section 5.3: BKE mu = 0.354/0.334/0.335/0.347 at 234/331/526/721 N.
    r = asperity.predict(os.path.join(EX, "steel420_two_bolts.toml"))
    np.testing.assert_allclose(r["preload"], [234, 331, 526, 721], rtol=2.5e-3)  # Table 5.5
    np.testing.assert_allclose(r["mu"], [0.354, 0.334, 0.335, 0.347], rtol=0.05)
    ld = r["loads"][2]
    assert ld["regime"][0] == "partial slip" and ld["regime"][-1] == "gross slip"
    # energy per cycle: Masing on the SI backbone of the same load case, to round-off
    for a, e in zip(ld["delta_max"], ld["energy"]):
        assert e == pytest.approx(ld["backbone"].energy_per_cycle(a), rel=1e-12)
    loop = ld["loops"][3]
    assert loop["Q"][0] == pytest.approx(ld["Q_peak"][3], rel=1e-12)


def test_bolt_preload_table_5_2():
    # #4-48 UNF, D = 2.845 mm, k = 0.2: 0.057 N m -> 99 N (Table 5.2, 0.5 lb-in).
    assert asperity.bolt_preload(0.5 * 0.112984829, 0.2, 2.845e-3) == pytest.approx(99, rel=5e-3)
    with pytest.raises(asperity.InvalidInput):
        asperity.bolt_preload(-1.0, 0.2, 2.9e-3)


def test_bad_case_names_key_and_line(tmp_path):
    text = open(os.path.join(EX, "steel420_two_bolts.toml")).read().replace('area = "170 mm^2"', 'area = "3 N"')
    with pytest.raises(asperity.InvalidInput, match=r"<string>:7: joint.area"):
        asperity.predict_case_text(text, EX)


def test_analyze_synthetic_experiment():
    # Table 5.6 conditions (526 N, PZT 6.75 um), noise 0.1 um / 1 N (section 5.2).
    d = asperity.synthetic_experiment(os.path.join(EX, "steel420_two_bolts.toml"), 526.0, 6.75e-6, seed=5)
    clean = asperity.synthetic_experiment(os.path.join(EX, "steel420_two_bolts.toml"), 526.0, 6.75e-6,
                                          noise_delta=0.0, noise_Q=0.0)
    a = asperity.analyze_fretting(d["t"], d["delta"], d["Q"], 526.0)
    steady = (clean["t"] >= 2) & (clean["t"] < 3)
    amp = 0.5 * np.ptp(clean["delta"][steady])
    q_amp = 0.5 * np.ptp(clean["Q"][steady])
    r = asperity.predict(os.path.join(EX, "steel420_two_bolts.toml"))
    bb = r["loads"][2]["backbone"]
    assert a["cycles"] == 9
    assert a["mean"]["energy"] == pytest.approx(bb.energy_per_cycle(amp), rel=0.02)
    assert a["mu"] == pytest.approx(q_amp / 526.0, rel=0.01)


def test_analyze_with_imposed_displacement_fits_the_apparatus():
    # With Delta, Delta = delta + c Q + const (Fig. 5.7: 38 and 1462 N/um in series); the
    # fit's standard error is about 0.03 %, 0.5 % is about 15 of them. The residual is
    # the 0.1 um displacement noise and c times the 1 N force noise in quadrature.
    d = asperity.synthetic_experiment(os.path.join(EX, "steel420_two_bolts.toml"), 526.0, 6.75e-6, seed=7)
    a = asperity.analyze_fretting(d["t"], d["delta"], d["Q"], 526.0, Delta=d["Delta"])
    c = 1 / 38e6 + 1 / 1462e6
    assert a["stiffness_from_imposed"]
    assert a["apparatus_compliance"] == pytest.approx(c, rel=5e-3)
    assert a["apparatus_residual_rms"] == pytest.approx(np.hypot(0.1e-6, c * 1.0), rel=0.05)
    b = asperity.analyze_fretting(d["t"], d["delta"], d["Q"], 526.0, Delta=d["Delta"],
                                  stiffness_from_imposed=False)
    assert not b["stiffness_from_imposed"] and "apparatus_compliance" not in b
    assert b["mu"] == a["mu"]  # only the stiffness method differs


def test_validation_report_has_no_failure():
    rows, md = asperity.validation_report()
    assert not [r for r in rows if r["verdict"] == "FAIL"]
    assert "Table 5.4" in md


def test_plot_helpers(tmp_path):
    import matplotlib  # a dependency (python/requirements.txt): a missing one must fail

    matplotlib.use("Agg")
    r = asperity.predict(os.path.join(EX, "steel420_two_bolts.toml"))
    ax = asperity.joints.plot_loops(r, load=2)
    assert len(ax.lines) == len(r["loads"][2]["delta_max"])
    ax = asperity.joints.plot_energy_vs_force(r)
    assert len(ax.lines) == len(r["loads"]) + 2
    ax.figure.savefig(tmp_path / "e.png")
    assert (tmp_path / "e.png").stat().st_size > 0
