"""asperity.fem.structure_fretting: the [fretting] apparatus of a structure case from Python.

The two-block example (examples/structures/two_blocks.toml, seconds) run once from Python and
once by `asperity structure --fretting --json` (ASPERITY_CLI, or the installed command): the
same C++ run, so the numbers agree to round-off (1e-9 relative: the element loops run in
parallel, so sums may be taken in another order; nothing else differs). The loops returned
obey what the apparatus and every hysteresis loop must:

- Q = k (Delta_0 sin theta - delta) at every sample (the drive spring, Fig. 5.7), to 1e-9 of
  k Delta_0 (one subtraction of numbers of that size);
- the loop's area (trapezoids over the N_t samples of the closed loop) equals W, the energy
  reported from the first harmonic (exact for the series drive), to 1e-3 (the samples of a
  degree-H trigonometric series at N_t >= 2 H + 2 points integrate it exactly up to the
  aliasing of the loop's higher harmonics, which the harmonic balance truncates: measured
  below 1e-6, asserted at 1e-3 as the CLI test does);
- W > 0 and growing with the tip amplitude, Q_0 and delta_0 growing, the secant Q_0/delta_0
  below the stuck joint's stiffness (a Masing backbone is concave);
- the bolts' preload carried by the interface and the grips together (equilibrium along the
  bolt), the interface carrying most of it.
"""
import json
import math
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

import asperity
import asperity.fem as fem

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "structures" / "two_blocks.toml"


def asperity_command() -> str:
    if os.environ.get("ASPERITY_CLI"):
        return os.environ["ASPERITY_CLI"]
    installed = pathlib.Path(sys.executable).parent / "asperity"
    if installed.is_file():
        return str(installed)
    found = shutil.which("asperity")
    if found:
        return found
    raise AssertionError("no asperity command: set ASPERITY_CLI or pip install the package")


@pytest.fixture(scope="module")
def python_run():
    return fem.structure_fretting(EXAMPLE)


def test_the_python_run_is_the_commands_run(python_run, tmp_path):
    p = subprocess.run([asperity_command(), "structure", str(EXAMPLE), "--fretting", "--out",
                        str(tmp_path / "out"), "--json"], capture_output=True, text=True,
                       timeout=600)
    assert p.returncode == 0, p.stderr
    j = json.loads(p.stdout)
    r = python_run
    assert r["mesh_nodes"] == j["mesh"]["nodes"]
    assert r["held_nodes"] == j["apparatus"]["held"]["nodes"]
    assert r["driven_nodes"] == j["apparatus"]["driven"]["nodes"]
    assert r["interface_elements"] == j["apparatus"]["interface_elements"]
    assert r["drive_stiffness"] == j["apparatus"]["drive_stiffness_N_per_m"]
    assert [c[0] for c in r["costs"]] == [c["step"] for c in j["costs"]]
    assert len(r["runs"]) == len(j["fretting"])
    for run, jr in zip(r["runs"], j["fretting"]):
        assert run["total_preload"] == jr["total_preload_N"]
        assert run["elements_in_contact"] == jr["elements_in_contact"]
        for key, jkey in [("interface_load", "interface_normal_force_N"),
                          ("real_contact_area", "real_contact_area_m2"),
                          ("stiffness", "stiffness_N_per_m")]:
            assert run[key] == pytest.approx(jr[jkey], rel=1e-9), key
        assert run["pressure"].max() == pytest.approx(jr["max_pressure_Pa"], rel=1e-9)
        assert len(run["cycles"]) == len(jr["cycles"])
        for c, jc in zip(run["cycles"], jr["cycles"]):
            assert c["tip_amplitude"] == jc["tip_amplitude_m"]
            for key, jkey in [("force_amplitude", "force_amplitude_N"),
                              ("displacement_amplitude", "displacement_amplitude_m"),
                              ("energy", "energy_J")]:
                assert c[key] == pytest.approx(jc[jkey], rel=1e-9), key
        exps = [jc["energy_force_exponent"] for jc in jr["cycles"][1:]]
        for e, je in zip(run["exponents"], exps):
            assert (je is None and math.isnan(e)) or e == pytest.approx(je, rel=1e-9)


def test_the_loops_obey_the_apparatus(python_run):
    k = python_run["drive_stiffness"]
    for run in python_run["runs"]:
        assert run["interface_load"] + run["preload_through_grips"] == pytest.approx(
            run["total_preload"], rel=1e-12)
        assert 0.9 * run["total_preload"] < run["interface_load"] <= run["total_preload"]
        assert run["pressure"].shape == (python_run["interface_elements"],)
        assert (run["pressure"] >= 0).all()
        assert len(run["exponents"]) == len(run["cycles"]) - 1
        previous = None
        for c in run["cycles"]:
            d0 = c["tip_amplitude"]
            delta, force = c["delta"], c["force"]
            theta = 2 * np.pi * np.arange(len(delta)) / len(delta)
            np.testing.assert_allclose(force, k * (d0 * np.sin(theta) - delta), rtol=0,
                                       atol=1e-9 * k * d0)
            d = np.append(delta, delta[0])
            q = np.append(force, force[0])
            area = float(np.sum(0.5 * (q[1:] + q[:-1]) * np.diff(d)))
            assert c["energy"] > 0
            assert area == pytest.approx(c["energy"], rel=1e-3)
            assert c["force_amplitude"] / c["displacement_amplitude"] <= run["stiffness"] * (
                1 + 1e-6)
            assert c["residual"] <= 1e-5
            if previous is not None:
                assert c["energy"] > previous["energy"]
                assert c["force_amplitude"] > previous["force_amplitude"]
                assert c["displacement_amplitude"] > previous["displacement_amplitude"]
            previous = c
    assert all(mib > 1 for _, _, mib in python_run["costs"])


def test_a_case_without_fretting_is_refused_by_name(tmp_path):
    text = EXAMPLE.read_text()
    case = tmp_path / "no_fretting.toml"
    case.write_text(text[:text.index("\n[fretting]\n")])
    with pytest.raises(asperity.InvalidInput, match=r"no \[fretting\] table"):
        fem.structure_fretting(case)
