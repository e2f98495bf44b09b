#!/usr/bin/env python3
"""Issue 21's reliability cases: inputs that the equations accept but no contact of the
thesis resembles are warned with their physical reason, impossible ones refused (exit 2)
naming the value and the limit, and wrong names in case files named with file, line and key.

Usage: plausibility_cases.py ASPERITY_EXE SOURCE_DIR CASE. Standard library only.
Exit 0 = pass, 1 = fail.
"""
import math
import os
import sys

from case_runner import check, main  # tests/cli/case_runner.py
from reliability_cases import expect_exit2, json_of, run

SPHERE = ["sphere", "--E1=207GPa", "--nu1=0.3", "--E2=207GPa", "--nu2=0.3", "--H=6.83GPa",
          "--R1=2.5mm", "--P=35N"]  # Table 3.1-3.2, experiment 1
STEEL420 = "examples/joints/steel420_two_bolts.toml"


def warnings_of(exe, argv, tmp):
    j, err = json_of(exe, argv, tmp)
    return j["warnings"], err


def case_sphere_mu_cfc_above_blau(exe, src, tmp):
    w, err = warnings_of(exe, SPHERE + ["--model=cfc", "--mu-cfc=50"], tmp)
    check(any("--mu-cfc = 50 is above 1.5" in x and "Blau" in x for x in w), w)
    check("warning: --mu-cfc = 50" in err, err)
    # Table 3.2's own value: no warning (the list can be non-empty: see above).
    w, err = warnings_of(exe, SPHERE + ["--model=cfc", "--mu-cfc=0.284"], tmp)
    check(w == [] and "warning" not in err, f"{w} {err}")


def case_sphere_radius_of_a_kilometre(exe, src, tmp):
    argv = [a for a in SPHERE if not a.startswith("--R1")] + ["--model=ke", "--R1=1km"]
    w, _ = warnings_of(exe, argv, tmp)
    check(any("--R1 = 1000 m is a sphere larger than 1 m" in x and "check the unit" in x
              for x in w), w)
    w, _ = warnings_of(exe, SPHERE + ["--model=ke", "--R2=2m"], tmp)
    check(any("--R2 = 2 m is a sphere larger than 1 m" in x for x in w), w)


def case_sphere_zeta_far_from_first_yield(exe, src, tmp):
    w, _ = warnings_of(exe, SPHERE + ["--model=ceb", "--zeta=2"], tmp)

    def c1(zeta):  # B.11
        return -1 + 1.5 * zeta * math.atan(1 / zeta) - zeta**2 / (2 * (1 + zeta**2))

    ratio = c1(0.48) / c1(2)  # 31.45: -0.28487 / -0.0090572
    check(any("--zeta = 2" in x and f"{1 / ratio:.3g} times" in x
              and f"{ratio:.3g} times as large" in x for x in w), w)
    w, err = warnings_of(exe, SPHERE + ["--model=ceb", "--zeta=0.48"], tmp)
    check(w == [] and "warning" not in err, f"{w} {err}")


def case_flat_psi_above_the_thesis(exe, src, tmp):
    argv = ["flat", "--beta=0.04", "--psi=1000", "--nu=0.3", "--P-star=1e-3", "--model=ke"]
    w, err = warnings_of(exe, argv, tmp)
    check(any("plasticity index psi = 1000 is above 4.7" in x for x in w), w)
    check("warning: plasticity index psi = 1000" in err, err)
    w, _ = warnings_of(exe, [a.replace("1000", "4.7") for a in argv], tmp)
    check(not any("plasticity index" in x for x in w), w)


def modified_case(src, tmp, old, new):
    with open(os.path.join(src, STEEL420)) as f:
        text = f.read()
    check(text.count(old) >= 1, f"the example changed: no {old!r}")
    path = os.path.join(tmp, "case.toml")
    with open(path, "w") as f:
        f.write(text.replace(old, new, 1))
    return path


def case_predict_hardness_above_young_modulus(exe, src, tmp):
    path = modified_case(src, tmp, 'H = "5.8 GPa"', 'H = "300 GPa"')
    r = run(exe, ["predict", path, "--out", "o"], tmp)
    expect_exit2(r, "joint.half[1].material.H", "300 GPa",
                 "must be below the Young's modulus E = 2e+11 Pa")
    check(not os.path.exists(os.path.join(tmp, "o")), "an output was written")


def case_predict_nut_factor_of_five(exe, src, tmp):
    path = modified_case(src, tmp, "nut_factor = 0.2", "nut_factor = 5")
    r = run(exe, ["predict", path, "--out", "o"], tmp)
    expect_exit2(r, "load.bolts.nut_factor = 5", "must lie in (0, 1]")


def case_synthesize_negative_seed(exe, src, tmp):
    r = run(exe, ["synthesize", os.path.join(src, STEEL420), "--imposed=6.75um", "--out=s.csv",
                  "--seed=-1"], tmp)
    expect_exit2(r, "--seed", "-1 is not allowed: it must be a whole number in [0, ")
    check("18446744073709551615" not in r.stderr.split("[0, ")[0], r.stderr)
    check(not os.path.exists(os.path.join(tmp, "s.csv")), "an output was written")


def case_unknown_asperity_model_names_file_line_key(exe, src, tmp):
    with open(os.path.join(src, "examples/dynamics/harmonic_physics_rough.toml")) as f:
        lines = f.read().split("\n")
    line = next(i for i, s in enumerate(lines, 1) if s.startswith('asperity_model = "bke"'))
    lines[line - 1] = 'asperity_model = "xyz"'
    path = os.path.join(tmp, "xyz.toml")
    with open(path, "w") as f:
        f.write("\n".join(lines))
    r = run(exe, ["dynamics", path, "--out", "o", "--no-plots"], tmp)
    expect_exit2(r, f"xyz.toml:{line}: dynamics.friction.asperity_model = \"xyz\"",
                 "allowed are cfc, ceb, ke, bke")


def case_synthesize_imposed_of_a_metre(exe, src, tmp):
    r = run(exe, ["synthesize", os.path.join(src, STEEL420), "--imposed=1m", "--out=s.csv"], tmp)
    expect_exit2(r, "--imposed = 1m is not allowed: at most 1 mm", "check the unit")
    check(not os.path.exists(os.path.join(tmp, "s.csv")), "an output was written")


def case_analyze_preload_of_one_newton(exe, src, tmp):
    # A synthetic record at 526 N analysed with --P 1N gave mu = 180 silently.
    r = run(exe, ["synthesize", os.path.join(src, STEEL420), "--imposed=6.75um", "--P=526N",
                  "--cycles=4", "--out=s.csv"], tmp)
    check(r.returncode == 0, r.stderr)
    j, err = json_of(exe, ["analyze", "s.csv", "--P=1N"], tmp)
    check("is above 3 with the preload P = 1 N" in err and "check the preload" in err, err)
    check("check the preload" in str(j), "not in the JSON's warnings")
    _, err = json_of(exe, ["analyze", "s.csv", "--P=526N"], tmp)
    check("is above 3" not in err, err)


def case_flat_history_value_of_1e300(exe, src, tmp):
    with open(os.path.join(tmp, "h.csv"), "w") as f:
        f.write("delta[um]\n0.1\n1e300\n")
    argv = ["flat", "--E1=200GPa", "--nu1=0.24", "--E2=200GPa", "--nu2=0.24", "--H=5.8GPa",
            "--sigma=2.677um", "--eta=2.91e-4um^-2", "--R=30.14um", "--area=170mm^2", "--P=526N",
            "--history=h.csv", "--out=o.csv"]
    expect_exit2(run(exe, argv, tmp), "row 2 of column delta [m]", "at most 1 m")
    check(not os.path.exists(os.path.join(tmp, "o.csv")), "an output was written")


def case_vibration_negative_stiffness_is_not_a_rigid_body_mode(exe, src, tmp):
    with open(os.path.join(src, "examples/vibration/jenkins_sdof.toml")) as f:
        text = f.read()
    check("stiffness = [[1.0]]" in text, "the example changed")
    path = os.path.join(tmp, "neg.toml")
    with open(path, "w") as f:
        f.write(text.replace("stiffness = [[1.0]]", "stiffness = [[-1.0]]", 1))
    r = run(exe, ["vibration", path, "--out", "o", "--no-plots"], tmp)
    expect_exit2(r, "negative eigenvalue omega^2 = -0.75", "not positive semi-definite")
    check("rigid-body" not in r.stderr, r.stderr)


def case_dynamics_frequency_of_a_million_says_its_cost(exe, src, tmp):
    with open(os.path.join(src, "examples/dynamics/harmonic_physics_smooth.toml")) as f:
        text = f.read()
    check("\nfrequency = 1\n" in text, "the example changed")
    for f_, expect_refusal in (("1e6", True), ("1e4", False)):
        path = os.path.join(tmp, f"f{f_}.toml")
        with open(path, "w") as f:
            f.write(text.replace("\nfrequency = 1\n", f"\nfrequency = {f_}\n", 1))
        if expect_refusal:
            # 6e7 periods over duration 60: refused before any work, naming max_steps.
            r = run(exe, ["dynamics", path, "--out", "o", "--no-plots"], tmp, timeout=20)
            expect_exit2(r, "dynamics.harmonic.frequency = 1e+06", "above the integrator's max_steps")
        else:
            # 6e5 periods: the warning comes at once, before the integration (stopped here).
            import subprocess
            import time
            p = subprocess.Popen([exe, "dynamics", path, "--out", "o2", "--no-plots"], cwd=tmp,
                                 stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            try:
                line = p.stderr.readline()
            finally:
                p.kill()
                p.wait()
            check("expect about 1.8e+07 integration steps" in line, line)


def case_x3p_every_third_point_invalid_names_the_gaps(exe, src, tmp):
    # A 3 mm profile with every third point missing was refused as "the profile (2 points)
    # is shorter than the filter needs", as if the scan were short.
    sys.path.insert(0, os.path.join(src, "tests/data/x3p"))
    import make_fixtures as m  # the fixtures' X3P writer
    n = 3000
    vals = [None if k % 3 == 2 else f"{1e-6 * math.sin(0.05 * k):.6e}" for k in range(n)]
    datums = "".join("\n      <Datum/>" if t is None else f"\n      <Datum>{t}</Datum>"
                     for t in vals)
    xml = (m.HEADER + m.record1("PRF", ("1.0e-6", "0"), ("1.0e-6", "0"), ("D", "1", "0"))
           + m.RECORD2 + "  <Record3>\n" + m.dimension(n, 1)
           + f"    <DataList>{datums}\n    </DataList>\n  </Record3>\n" + m.RECORD4).encode()
    m.write_archive(os.path.join(tmp, "gaps.x3p"), [("main.xml", xml)])
    r = run(exe, ["roughness", "--surface", "gaps.x3p"], tmp)
    expect_exit2(r, "gaps.x3p: 1000 of the file's 3000 points are invalid",
                 "longest run of consecutive valid points", "has 2 points", "fill the gaps")
    check(r.stderr.index("invalid") < r.stderr.index("shorter than the filter"), r.stderr)


if __name__ == "__main__":
    sys.exit(main(globals()))
