#!/usr/bin/env python3
"""Behaviour of `asperity vibration`: the summary.json contract of issue 10, whole CSVs,
the shipped examples, bad input (exit 2, one line naming what to change, nothing on
stdout) and a continuation that stalls (exit 3, the points it has written whole).

Usage: vibration_cases.py ASPERITY_EXE CASE. Standard library only. Exit 0 = pass.
Registered in tests/cli/CMakeLists.txt, one CTest per case (cli.vibration.<case>).
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(HERE, "..", "..", "examples", "vibration")

# The Jenkins SDOF (m = 1, k = 1, c = 0.01, k_t = 0.25, F_s = 0.2).
JENKINS = """[structure]
mass = [[1.0]]
stiffness = [[1.0]]
damping = [[0.01]]
output_dofs = [0]
[[element]]
type = "jenkins"
T = [[1.0]]
k_t = 0.25
F_s = 0.2
[harmonic_balance]
max = 3
time_points = 256
"""
EPMC = """[nonlinear_mode]
log10_amplitude = { from = -2.0, to = 5.0 }
"""
FRF = """[[frequency_response]]
force_cos = [[0.0], [0.1]]
omega = { from = 0.7, to = 1.5 }
"""

NONLINEAR_MODE_KEYS = ["log10_amplitude", "amplitude", "omega_rad_s", "frequency_hz",
                       "damping_ratio", "output_amplitude"]
FRF_KEYS = ["force_scale", "omega_rad_s", "output_amplitude", "max_displacement",
            "harmonic_amplitude"]
QS_KEYS = ["amplitude", "omega_rad_s", "damping_ratio"]
SOLVER_KEYS = ["points", "newton_iterations", "residual_evaluations", "jacobian_evaluations",
               "rejected_steps", "turning_points", "wall_time_s", "complete", "stop_reason"]


def fail(msg):
    print("FAIL:", msg, file=sys.stderr)
    return 1


def run(exe, case_text, tmp, extra=("--no-plots",), name="case.toml"):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(case_text)
    out = os.path.join(tmp, "out")
    return subprocess.run([exe, "vibration", path, "--out", out, *extra],
                          capture_output=True, text=True, timeout=300), out


def bad(exe, case_text, must_contain, code=2):
    with tempfile.TemporaryDirectory() as tmp:
        r, out = run(exe, case_text, tmp)
        if os.path.exists(out):
            return fail(f"bad input wrote {out}")
    if r.returncode != code:
        return fail(f"expected exit {code}, got {r.returncode}; stderr: {r.stderr}")
    if r.stdout:
        return fail(f"stdout not empty: {r.stdout!r}")
    lines = [l for l in r.stderr.splitlines() if l.strip()]
    if len(lines) != 1:
        return fail(f"expected one line on stderr: {r.stderr!r}")
    for word in [must_contain] if isinstance(must_contain, str) else must_contain:
        if word.lower() not in r.stderr.lower():
            return fail(f"message does not mention {word!r}: {r.stderr}")
    return 0


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], rows[1:]
    for i, row in enumerate(data):
        if len(row) != len(header):
            raise ValueError(f"{path}: row {i} has {len(row)} fields, header {len(header)}")
        for v in row:
            if not math.isfinite(float(v)):
                raise ValueError(f"{path}: non-finite value {v} in row {i}")
    return header, [[float(v) for v in row] for row in data]


def check_summary(j, want_qs=True, want_frf=True, want_nm=True):
    """Returns a message for the first key the issue lists that is missing, else None."""
    for k in ["case", "structure", "elements", "harmonic_balance", "solver", "warnings"]:
        if k not in j:
            return f"missing {k}"
    for k in SOLVER_KEYS:
        if k not in j["solver"]:
            return f"missing solver.{k}"
    if want_nm:
        for k in NONLINEAR_MODE_KEYS:
            if k not in j["nonlinear_mode"]:
                return f"missing nonlinear_mode.{k}"
        n = len(j["nonlinear_mode"]["amplitude"])
        for k in NONLINEAR_MODE_KEYS:
            if len(j["nonlinear_mode"][k]) != n:
                return f"nonlinear_mode.{k} has {len(j['nonlinear_mode'][k])} points, not {n}"
    if want_frf:
        for c in j["frequency_response"]:
            for k in FRF_KEYS:
                if k not in c:
                    return f"missing frequency_response[].{k}"
            n = len(c["omega_rad_s"])
            if not (len(c["output_amplitude"]) == len(c["max_displacement"]) ==
                    len(c["harmonic_amplitude"]) == n):
                return "frequency_response arrays of different lengths"
            nh = len(j["harmonic_balance"]["harmonics"])
            if any(len(per_output) != nh for p in c["harmonic_amplitude"] for per_output in p):
                return "harmonic_amplitude: not one value per harmonic"
    if want_qs:
        for k in QS_KEYS:
            if k not in j["quasi_static_mode"]:
                return f"missing quasi_static_mode.{k}"
    return None


def summary_keys(exe):
    case = JENKINS + EPMC + FRF.replace("omega", "force_scales = [0.5, 1.0]\nomega") + """
[quasi_static_mode]
amplitude = { from = 1e-2, to = 1e4 }
points = 30
"""
    with tempfile.TemporaryDirectory() as tmp:
        r, out = run(exe, case, tmp, extra=())
        if r.returncode != 0:
            return fail(f"exit {r.returncode}: {r.stderr}")
        j = json.load(open(os.path.join(out, "summary.json")))
        msg = check_summary(j)
        if msg:
            return fail(msg)
        if not j["solver"]["complete"]:
            return fail(f"incomplete: {j['solver']['stop_reason']}")
        files = sorted(os.listdir(out))
        want = ["frequency_response.png", "frequency_response_1.csv", "frequency_response_2.csv",
                "modal_damping.png", "modal_frequency.png", "nonlinear_mode.csv",
                "quasi_static_mode.csv", "summary.json"]
        if [f for f in files if not f.startswith(".")] != want:
            return fail(f"files {files}")
        # CSVs whole: one row per point of the summary, the same numbers.
        h, rows = read_csv(os.path.join(out, "nonlinear_mode.csv"))
        nm = j["nonlinear_mode"]
        if len(rows) != len(nm["amplitude"]) or len(rows) != j["nonlinear_mode"]["solver"]["points"]:
            return fail("nonlinear_mode.csv rows != points")
        for i, row in enumerate(rows):
            # 12 significant digits in the CSV.
            if abs(row[h.index("frequency_hz")] - nm["frequency_hz"][i]) > 1e-11 * nm["frequency_hz"][i]:
                return fail(f"nonlinear_mode.csv row {i} differs from summary.json")
        for k, c in enumerate(j["frequency_response"]):
            h, rows = read_csv(os.path.join(out, f"frequency_response_{k + 1}.csv"))
            if len(rows) != len(c["omega_rad_s"]):
                return fail(f"frequency_response_{k + 1}.csv rows")
            if "harmonic3_dof0_m" not in h or "max_displacement_dof0_m" not in h:
                return fail(f"header {h}")
        h, rows = read_csv(os.path.join(out, "quasi_static_mode.csv"))
        if len(rows) != 30:
            return fail("quasi_static_mode.csv rows")
        # --json prints the same summary (wall times aside).
        r2 = subprocess.run([exe, "vibration", os.path.join(tmp, "case.toml"), "--json"],
                            capture_output=True, text=True, timeout=300)
        if r2.returncode != 0:
            return fail(f"--json exit {r2.returncode}")
        j2 = json.loads(r2.stdout)
        if j2["nonlinear_mode"]["frequency_hz"] != nm["frequency_hz"]:
            return fail("--json differs from summary.json")
    # Physics of the Jenkins SDOF: stuck omega = sqrt(k + k_t) = sqrt(1.25) at small a;
    # slipped omega -> sqrt(k) = 1 at a = 1e5 (the slider adds ~F_s/a = 2e-6); damping
    # zeta -> c/(2 m omega) = 0.005 (friction adds ~4 F_s/(2 pi a) ~ 1e-6).
    f = nm["omega_rad_s"]
    if abs(f[0] - math.sqrt(1.25)) > 1e-6 * math.sqrt(1.25):
        return fail(f"omega at a = 0.01: {f[0]}")
    if abs(f[-1] - 1.0) > 1e-4:
        return fail(f"omega at a = 1e5: {f[-1]}")
    if abs(nm["damping_ratio"][-1] - 0.005) > 0.005 * 1e-2:
        return fail(f"zeta at a = 1e5: {nm['damping_ratio'][-1]}")
    return 0


def examples(exe):
    for name in ["jenkins_sdof", "steel420_sdof", "steel420_2dof"]:
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "out")
            r = subprocess.run([exe, "vibration", os.path.join(EXAMPLES, name + ".toml"),
                                "--out", out], capture_output=True, text=True, timeout=300)
            if r.returncode != 0:
                return fail(f"{name}: exit {r.returncode}: {r.stderr}")
            j = json.load(open(os.path.join(out, "summary.json")))
            msg = check_summary(j)
            if msg:
                return fail(f"{name}: {msg}")
            if not j["solver"]["complete"] or j["warnings"]:
                return fail(f"{name}: {j['solver']['stop_reason']} {j['warnings']}")
            if name.startswith("steel420"):
                # Table 5.5: 2.7 lbf*in total on the two bolts gives 526 N (docs/joints.md).
                if abs(j["joint"]["preload_N"] - 526.0) > 1.0:
                    return fail(f"{name}: preload {j['joint']['preload_N']}")
                # With the joint stuck its stiffness k_t adds to the structure's.
                kt = j["elements"][0]["k_t_N_per_m"]
                if name == "steel420_sdof":
                    f0 = math.sqrt(1e8 + kt) / (2 * math.pi)
                    got = j["structure"]["linear_frequencies_hz_elements_stuck"][0]
                    if abs(got - f0) > 1e-9 * f0:
                        return fail(f"{name}: stuck frequency {got}, expected {f0}")
                # The mode softens from stuck to slipped.
                fh = j["nonlinear_mode"]["frequency_hz"]
                slipped = j["structure"]["linear_frequencies_hz_without_elements"]
                mode = j["nonlinear_mode"]["mode"]
                if not (fh[0] > fh[-1] and abs(fh[-1] - slipped[mode - 1]) < 0.01 * slipped[mode - 1]):
                    return fail(f"{name}: frequency {fh[0]} -> {fh[-1]}, slipped {slipped}")
    return 0


def stall(exe):
    # A genuine stall: Newton may take 2 iterations per point and the step may not fall
    # below 0.25 (in log10 a). The stuck branch is linear (1 iteration per point); at the
    # onset of slip (a = F_s/k_t = 0.8) the corrector needs more than 2 iterations on
    # every step >= 0.25, so the continuation stops there.
    case = JENKINS + """[nonlinear_mode]
log10_amplitude = { from = -2.0, to = 5.0 }
continuation = { step = 0.5, min_step = 0.25, max_step = 0.5, max_iterations = 2, target_iterations = 1 }
"""
    with tempfile.TemporaryDirectory() as tmp:
        r, out = run(exe, case, tmp)
        if r.returncode != 3:
            return fail(f"expected exit 3, got {r.returncode}: {r.stderr}")
        if "stalled" not in r.stderr or "kept" not in r.stderr or "time_points" not in r.stderr:
            return fail(f"message: {r.stderr}")
        j = json.load(open(os.path.join(out, "summary.json")))
        msg = check_summary(j, want_qs=False, want_frf=False)
        if msg:
            return fail(msg)
        if j["solver"]["complete"] is not False or "stalled" not in j["solver"]["stop_reason"]:
            return fail(f"solver {j['solver']}")
        n = len(j["nonlinear_mode"]["amplitude"])
        if n < 2 or j["nonlinear_mode"]["log10_amplitude"][-1] >= 5.0:
            return fail(f"points {j['nonlinear_mode']['log10_amplitude']}")
        _, rows = read_csv(os.path.join(out, "nonlinear_mode.csv"))
        if len(rows) != n:
            return fail(f"nonlinear_mode.csv has {len(rows)} rows, summary {n} points")
        if not any("stalled" in w for w in j["warnings"]):
            return fail(f"warnings {j['warnings']}")
    return 0


def partial_results(exe):
    # Issue 23: a table that cannot start (Newton allowed one iteration from the linear
    # guess of a slipping joint) does not cost the others: they run and are written, the
    # failed one is named with its reason in summary.json `failed` and on stderr, exit 3.
    case = JENKINS + FRF + """[[frequency_response]]
force_cos = [[0.0], [3.3]]
omega = { from = 0.2, to = 0.4 }
continuation = { max_iterations = 1, target_iterations = 1 }
""" + FRF.replace("0.1]]", "0.2]]")
    with tempfile.TemporaryDirectory() as tmp:
        r, out = run(exe, case, tmp)
        if r.returncode != 3:
            return fail(f"expected exit 3, got {r.returncode}: {r.stderr}")
        if "could not start" not in r.stderr or "frequency_response[2]" not in r.stderr:
            return fail(f"message: {r.stderr}")
        j = json.load(open(os.path.join(out, "summary.json")))
        failed = j.get("failed")
        if not failed or len(failed) != 1 or failed[0]["table"] != 2 or "cannot start" not in failed[0]["reason"]:
            return fail(f"failed: {failed}")
        tables = [c["table"] for c in j["frequency_response"]]
        # Tables counted from 1, as the files frequency_response_<k>.csv and the messages.
        if tables != [1, 3]:
            return fail(f"curves of tables {tables}, expected [1, 3]")
        for c in j["frequency_response"]:
            if not c["solver"]["complete"]:
                return fail(f"curve of table {c['table']} incomplete: {c['solver']}")
        if j["solver"]["complete"] is not False:
            return fail(f"solver {j['solver']}")
        for k in (1, 2):
            _, rows = read_csv(os.path.join(out, f"frequency_response_{k}.csv"))
            if len(rows) != len(j["frequency_response"][k - 1]["omega_rad_s"]):
                return fail(f"frequency_response_{k}.csv rows")
    return 0


def matrix_market(exe):
    # The same structure from .mtx files (relative to the case file) gives the same curve.
    with tempfile.TemporaryDirectory() as tmp:
        os.mkdir(os.path.join(tmp, "m"))
        with open(os.path.join(tmp, "m", "M.mtx"), "w") as f:
            f.write("%%MatrixMarket matrix array real general\n1 1\n1.0\n")
        with open(os.path.join(tmp, "m", "K.mtx"), "w") as f:
            f.write("%%MatrixMarket matrix coordinate real symmetric\n1 1 1\n1 1 1.0\n")
        inline, _ = run(exe, JENKINS + EPMC, tmp, extra=("--no-plots", "--json"))
        files = JENKINS.replace("mass = [[1.0]]", 'mass_file = "m/M.mtx"').replace(
            "stiffness = [[1.0]]", 'stiffness_file = "m/K.mtx"')
        os.mkdir(os.path.join(tmp, "sub"))
        with open(os.path.join(tmp, "sub2.toml"), "w") as f:
            f.write(files + EPMC)
        r = subprocess.run([exe, "vibration", os.path.join(tmp, "sub2.toml"), "--json"],
                           capture_output=True, text=True, timeout=300)
    if inline.returncode != 0 or r.returncode != 0:
        return fail(f"exit {inline.returncode} {r.returncode}: {inline.stderr} {r.stderr}")
    a, b = json.loads(inline.stdout), json.loads(r.stdout)
    if a["nonlinear_mode"]["frequency_hz"] != b["nonlinear_mode"]["frequency_hz"]:
        return fail("mtx and inline structures differ")
    return 0


def omega_in_hz(exe):
    # "0.15 Hz" is 2 pi 0.15 rad/s; missing force rows are zero.
    a_case = JENKINS + FRF.replace("omega = { from = 0.7", 'omega = { from = "0.12 Hz"')
    b_case = JENKINS + FRF.replace("omega = { from = 0.7", f"omega = {{ from = {2 * math.pi * 0.12!r}").replace(
        "[[0.0], [0.1]]", "[[0.0], [0.1], [0.0], [0.0]]")
    with tempfile.TemporaryDirectory() as tmp:
        a, _ = run(exe, a_case, tmp, extra=("--no-plots", "--json"), name="a.toml")
        b, _ = run(exe, b_case, tmp, extra=("--no-plots", "--json"), name="b.toml")
    if a.returncode != 0 or b.returncode != 0:
        return fail(f"exit {a.returncode} {b.returncode}: {a.stderr} {b.stderr}")
    ja, jb = json.loads(a.stdout), json.loads(b.stdout)
    wa = ja["frequency_response"][0]["omega_rad_s"]
    if abs(wa[0] - 2 * math.pi * 0.12) > 1e-12 * wa[0]:
        return fail(f"omega from {wa[0]}")
    if wa != jb["frequency_response"][0]["omega_rad_s"]:
        return fail("Hz and rad/s cases differ")
    return 0


def without_out_prints_the_summary(exe):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "case.toml")
        with open(path, "w") as f:
            f.write(JENKINS + EPMC)
        r = subprocess.run([exe, "vibration", path], capture_output=True, text=True, timeout=300)
        if r.returncode != 0 or "nonlinear mode 1" not in r.stdout or "no files written" not in r.stdout:
            return fail(f"exit {r.returncode}: {r.stdout} {r.stderr}")
        if sorted(os.listdir(tmp)) != ["case.toml"]:
            return fail(f"wrote {os.listdir(tmp)}")
        # Repeated element types are counted, not listed one by one (a finite-element
        # interface has hundreds): two Jenkins joints read "jenkins x 2".
        with open(path, "w") as f:
            f.write((JENKINS + EPMC).replace("[harmonic_balance]", """[[element]]
type = "jenkins"
T = [[1.0]]
k_t = 0.1
F_s = 0.3
[harmonic_balance]"""))
        r = subprocess.run([exe, "vibration", path], capture_output=True, text=True, timeout=300)
        if r.returncode != 0 or "2 element(s) (jenkins x 2)" not in r.stdout:
            return fail(f"exit {r.returncode}: {r.stdout} {r.stderr}")
    return 0


def force_in_newton(exe):
    # Issue 21, item 6: a forced-response curve is named by its force amplitude in N: the
    # scale times the norm of the table's force (0.1 N on one DOF and harmonic; scales
    # 0.5 and 2), as the plots' legends.
    case = JENKINS + FRF.replace("omega = { from = 0.7", "force_scales = [0.5, 2.0]\n"
                                 "omega = { from = 0.7")
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "case.toml")
        with open(path, "w") as f:
            f.write(case)
        r = subprocess.run([exe, "vibration", path], capture_output=True, text=True, timeout=300)
    if r.returncode != 0:
        return fail(f"exit {r.returncode}: {r.stderr}")
    for want in ("frequency response 1 (F = 0.05 N, force scale 0.5)",
                 "frequency response 2 (F = 0.2 N, force scale 2)"):
        if want not in r.stdout:
            return fail(f"no {want!r} in: {r.stdout}")
    return 0


TWO_DOF = """[structure]
mass = [[1.0, 0.0], [0.0, 1.0]]
stiffness = [[2.0, -1.0], [-1.0, 2.0]]
rayleigh = { alpha = 0.01 }
[harmonic_balance]
max = 3
time_points = 256
[nonlinear_mode]
log10_amplitude = { from = -2.0, to = 1.0 }
"""


def element_types(exe):
    # Every element type of the issue parses and runs; parameters with units convert.
    elements = {
        "iwan4": 'type = "iwan4"\nT = [1.0, 0.0]\nF_S = "0.2 N"\nK_T = 0.25\nchi = -0.5\nbeta = 0.1',
        "coulomb": 'type = "coulomb"\nT = [1.0, 0.0]\nF_s = 0.05\nk_tan = "100 s/m"',
        "elastic_dry_friction_2d": 'type = "elastic_dry_friction_2d"\nT = [[1.0, 0.0], [0.0, 1.0]]\n'
                                   'k_t = "0.25 N/m"\nk_n = 1.0\nmu = 0.3\nN0 = 0.5',
        "jenkins": 'type = "jenkins"\nname = "left"\nT = [[1.0, -1.0]]\nk_t = 0.25\nF_s = 0.2',
    }
    for name, text in elements.items():
        with tempfile.TemporaryDirectory() as tmp:
            r, out = run(exe, TWO_DOF + "[[element]]\n" + text + "\n", tmp)
            if r.returncode != 0:
                return fail(f"{name}: exit {r.returncode}: {r.stderr}")
            j = json.load(open(os.path.join(out, "summary.json")))
            e = j["elements"][0]
            if e["type"] != name or not j["solver"]["complete"]:
                return fail(f"{name}: {e} {j['solver']}")
            if name == "jenkins" and (e["name"] != "left" or e["T"] != [[1.0, -1.0]]):
                return fail(f"element echo {e}")
            # Parameters echoed in SI: "0.2 N" and "100 s/m" as given.
            if name == "iwan4" and (e["F_S_N"] != 0.2 or e["chi"] != -0.5):
                return fail(f"iwan4 echo {e}")
            if name == "coulomb" and e["k_tan_s_per_m"] != 100.0:
                return fail(f"coulomb echo {e}")
    return 0


def rough_flat_forms(exe):
    # The same rough flat written dimensionally and normalized (beta = sigma R eta, psi on
    # sigma_a = sigma sqrt(1 - 3.717e-4/beta^2), K = 0.454 + 0.41 nu, force scale K H A0,
    # P* = P/(K H A0); rough_flat.hpp) gives the same Q_max and k_t to round-off.
    E, G, H, nu, sig, R, eta, A0, P = 106e9, 22.9e9, 5.8e9, 0.3, 2.7e-6, 30.1e-6, 2.9e8, 1e-4, 500.0
    K = 0.454 + 0.41 * nu
    beta = sig * R * eta
    sig_a = sig * math.sqrt(1 - 3.717e-4 / beta ** 2)
    psi = 2 * E / (math.pi * K * H) * math.sqrt(sig_a / R)
    fs = K * H * A0
    base = """[structure]
mass = [[1.0]]
stiffness = [[1e8]]
damping = [[20.0]]
[harmonic_balance]
max = 1
time_points = 64
[quasi_static_mode]
amplitude = { from = 1e-9, to = 1e-7 }
points = 4
[[element]]
type = "rough_flat"
T = [[1.0]]
"""
    dim = (f'E_star = "106 GPa"\nG_star = "22.9 GPa"\nH = "5.8 GPa"\nnu = 0.3\nsigma = "2.7 um"\n'
           f'R = "30.1 um"\neta = "2.9e8 m^-2"\nA0 = "1 cm^2"\nP = "500 N"\n')
    nrm = (f"beta = {beta!r}\npsi = {psi!r}\nnu = 0.3\nG_over_E = {G / E!r}\nP_star = {P / fs!r}\n"
           f"sigma = {sig!r}\nforce_scale = {fs!r}\n")
    got = []
    for text in [dim, nrm]:
        with tempfile.TemporaryDirectory() as tmp:
            r, out = run(exe, base + text, tmp)
            if r.returncode != 0:
                return fail(f"exit {r.returncode}: {r.stderr}")
            got.append(json.load(open(os.path.join(out, "summary.json")))["elements"][0])
    for k in ["Q_max_N", "k_t_N_per_m"]:
        a, b = got[0][k], got[1][k]
        if not (a > 0 and abs(a - b) < 1e-9 * a):
            return fail(f"{k}: dimensional {a}, normalized {b}")
    if got[0]["backbone"] != "dimensional" or got[1]["backbone"] != "normalized":
        return fail(f"backbones {got[0]['backbone']} {got[1]['backbone']}")
    return 0


def masing_table_from_predict(exe):
    # The backbone `asperity predict --out` exports (backbones.csv, 401 points to the slip
    # displacement) as a masing_table element in the rig of examples/vibration/
    # steel420_sdof.toml, against that case's rough_flat element (the same joint and
    # preload): Q_max to the file's 12 digits; quasi-static frequency to 1e-5 and damping
    # to 1 % from 10 nm up. The table's intervals are x_s/400 = 6 nm wide, so at 10 nm a
    # loop spans a few of them and the cubic's curvature error shows in the damping
    # (0.65 %; 4e-4 at 32 nm, falling as h^3 once a loop spans many intervals).
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    sdof = open(os.path.join(root, "examples", "vibration", "steel420_sdof.toml")).read()
    head = sdof.split("[harmonic_balance]")[0]
    qs = """[harmonic_balance]
harmonics = [0, 1, 2, 3]
time_points = 256

[quasi_static_mode]
mode = 1
amplitude = { from = 1e-8, to = 1e-5 }
points = 7
"""
    with tempfile.TemporaryDirectory() as tmp:
        pr = subprocess.run([exe, "predict", os.path.join(root, "examples", "joints",
                                                          "steel420_two_bolts.toml"),
                             "--out", os.path.join(tmp, "pr"), "--no-plots"],
                            capture_output=True, text=True, timeout=300)
        if pr.returncode != 0:
            return fail(pr.stderr)
        r, out = run(exe, head + qs, tmp, name="physics.toml")
        if r.returncode != 0:
            return fail(r.stderr)
        a = json.load(open(os.path.join(out, "summary.json")))
        P = a["joint"]["preload_N"]
        struct = head[head.index("[structure]"):head.index("[[element]]")]
        table = (f'[[element]]\ntype = "masing_table"\nT = [[1.0]]\ntable = "pr/backbones.csv"\n'
                 f'preload = "{P!r} N"\n')
        r, out = run(exe, struct + table + qs, tmp, name="table.toml")
        if r.returncode != 0:
            return fail(r.stderr)
        b = json.load(open(os.path.join(out, "summary.json")))
        ea, eb = a["elements"][0], b["elements"][0]
        if eb["type"] != "masing_table" or abs(eb["Q_max_N"] / ea["Q_max_N"] - 1) > 1e-11:
            return fail(f"elements {ea} {eb}")
        qa, qb = a["quasi_static_mode"], b["quasi_static_mode"]
        for wa, wb, za, zb in zip(qa["omega_rad_s"], qb["omega_rad_s"], qa["damping_ratio"],
                                  qb["damping_ratio"]):
            if abs(wb / wa - 1) > 1e-5 or abs(zb / za - 1) > 0.01:
                return fail(f"omega {wa} vs {wb}, damping {za} vs {zb}")
        # Without `preload`, a file of several preloads is refused naming them.
        r, out = run(exe, struct + table.replace(f'preload = "{P!r} N"\n', "") + qs, tmp,
                     name="noP.toml")
        if r.returncode != 2 or "preload" not in r.stderr or "525.964 N" not in r.stderr:
            return fail(f"several preloads: exit {r.returncode}: {r.stderr}")
    return 0


def masing_table_from_flat(exe):
    # `asperity flat --backbone` (dimensional inputs) writes the rough flat's virgin curve in
    # SI; as a masing_table element its slip force is flat's Q_max (to the 12 digits of the
    # file) and its stiffness at rest, the first interval's secant, is within 1 % of flat's
    # (the backbone bends over the first of 400 intervals by about half its curvature times
    # the interval, 0.6 % here). Normalized inputs are refused.
    flat = ["flat", "--E1", "200GPa", "--nu1", "0.24", "--G1", "80.7GPa", "--E2", "200GPa",
            "--nu2", "0.24", "--G2", "80.7GPa", "--H", "5.8GPa", "--sigma", "2.677um",
            "--eta", "2.91e-4um^-2", "--R", "30.14um", "--area", "170mm^2", "--P", "526N"]
    with tempfile.TemporaryDirectory() as tmp:
        f = subprocess.run([exe, *flat, "--backbone", os.path.join(tmp, "fb.csv"), "--json"],
                           capture_output=True, text=True, timeout=300)
        if f.returncode != 0:
            return fail(f.stderr)
        fj = json.loads(f.stdout)
        r, out = run(exe, """[structure]
mass = [[1.0]]
stiffness = [[1e8]]
damping = [[20.0]]
[[element]]
type = "masing_table"
T = [[1.0]]
table = "fb.csv"
[harmonic_balance]
max = 3
time_points = 128
[quasi_static_mode]
amplitude = { from = 1e-8, to = 1e-6 }
points = 3
""", tmp)
        if r.returncode != 0:
            return fail(r.stderr)
        e = json.load(open(os.path.join(out, "summary.json")))["elements"][0]
        if abs(e["Q_max_N"] / fj["Q_max"] - 1) > 1e-11:
            return fail(f"Q_max {e['Q_max_N']} vs flat's {fj['Q_max']}")
        if abs(e["stiffness_N_per_m"] / fj["stiffness"] - 1) > 0.01:
            return fail(f"stiffness {e['stiffness_N_per_m']} vs flat's {fj['stiffness']}")
        n = subprocess.run([exe, "flat", "--beta", "0.04", "--psi", "0.5", "--nu", "0.3",
                            "--P-star", "1e-3", "--backbone", os.path.join(tmp, "n.csv")],
                           capture_output=True, text=True, timeout=60)
        if n.returncode != 2 or "dimensional" not in n.stderr or os.path.exists(os.path.join(tmp, "n.csv")):
            return fail(f"normalized --backbone: exit {n.returncode}: {n.stderr}")
    return 0


def base_excitation(exe):
    # A linear SDOF (m = 1, k = 1, c = 0.1) on a base moving as y = Y sin(omega t),
    # Y = 0.01: force_sin = k Y, force_per_omega_cos = c Y. Closed form (transmissibility):
    # |X| = Y sqrt(k^2 + (c omega)^2) / sqrt((k - m omega^2)^2 + (c omega)^2).
    case = """[structure]
mass = [[1.0]]
stiffness = [[1.0]]
damping = [[0.1]]
[harmonic_balance]
max = 1
time_points = 16
[[frequency_response]]
force_sin = [[0.0], [0.01]]
force_per_omega_cos = [[0.0], [0.001]]
omega = { from = 0.5, to = 2.0 }
"""
    with tempfile.TemporaryDirectory() as tmp:
        r, out = run(exe, case, tmp)
        if r.returncode != 0:
            return fail(f"exit {r.returncode}: {r.stderr}")
        c = json.load(open(os.path.join(out, "summary.json")))["frequency_response"][0]
    Y, k, m, cc = 0.01, 1.0, 1.0, 0.1
    for w, x in zip(c["omega_rad_s"], c["output_amplitude"]):
        exact = Y * math.hypot(k, cc * w) / math.hypot(k - m * w * w, cc * w)
        # A linear system: harmonic balance is exact up to the Newton tolerance (1e-9).
        if abs(x[0] - exact) > 1e-7 * exact:
            return fail(f"omega {w}: {x[0]} vs {exact}")
    if len(c["omega_rad_s"]) < 10:
        return fail(f"only {len(c['omega_rad_s'])} points")
    return 0


def out_refuses_a_foreign_directory(exe):
    # An existing directory asperity did not write is refused before any work (exit 2),
    # and left as it was.
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        os.mkdir(out)
        with open(os.path.join(out, "mine.txt"), "w") as f:
            f.write("keep")
        r, _ = run(exe, JENKINS + EPMC, tmp)
        if r.returncode != 2 or r.stdout:
            return fail(f"exit {r.returncode}: {r.stdout} {r.stderr}")
        if os.listdir(out) != ["mine.txt"]:
            return fail(f"directory changed: {os.listdir(out)}")
        # A directory asperity wrote is replaced whole.
        os.remove(os.path.join(out, "mine.txt"))
        os.rmdir(out)
        for _ in range(2):
            r, _ = run(exe, JENKINS + EPMC, tmp)
            if r.returncode != 0:
                return fail(f"rewrite: exit {r.returncode}: {r.stderr}")
    return 0


def stability(exe):
    # The shipped forced Duffing case with stability = true (docs/vibration.md, Stability):
    # the points where omega falls along the curve (between its folds) are unstable by
    # a real multiplier beyond +1, those where it rises are stable; the same flags in
    # summary.json and in the curve's CSV; --stability asks for it on a case without the
    # key (the linear base-excitation SDOF: every point stable, exponents -c/2 +- i w_d).
    with tempfile.TemporaryDirectory() as tmp:
        case = open(os.path.join(EXAMPLES, "duffing_stability.toml")).read()
        r, out = run(exe, case, tmp)
        if r.returncode != 0:
            return fail(f"exit {r.returncode}: {r.stderr}")
        c = json.load(open(os.path.join(out, "summary.json")))["frequency_response"][0]
        header, rows = read_csv(os.path.join(out, "frequency_response_1.csv"))
        if "unstable point(s) (Hill)" not in r.stdout:
            return fail(f"text summary without the unstable count: {r.stdout}")
    st = c.get("stability")
    if st is None:
        return fail("no frequency_response[1].stability")
    w = c["omega_rad_s"]
    if len(st["stable"]) != len(w) or len(st["floquet_exponents_per_s"]) != len(w):
        return fail("stability arrays not parallel to omega_rad_s")
    falling = rising = 0
    for i in range(1, len(w) - 1):
        if w[i - 1] > w[i] > w[i + 1]:
            falling += 1
            if st["stable"][i] or st["instability"][i] != "fold":
                return fail(f"omega {w[i]} on the middle branch: {st['stable'][i]}, "
                            f"{st['instability'][i]!r}")
        elif w[i - 1] < w[i] < w[i + 1]:
            rising += 1
            if not st["stable"][i]:
                return fail(f"omega {w[i]} on an outer branch called unstable")
    if falling < 3 or rising < 10:
        return fail(f"{falling} falling and {rising} rising points")
    if len(c["folds"]) != 2:
        return fail(f"{len(c['folds'])} folds, expected 2")
    for f in c["folds"]:
        re, im = f["smallest_floquet_exponent_per_s"]
        # The fold located to ~1e-8 of a chord: the exponent at it below 1e-6 omega, real.
        if math.hypot(re, im) > 1e-6 * f["omega_rad_s"] or im != 0.0:
            return fail(f"fold at {f['omega_rad_s']}: exponent {re} + {im} i")
    col = header.index("stable")
    if [bool(row[col]) for row in rows] != list(st["stable"]):
        return fail("CSV stable column differs from summary.json")
    base = """[structure]
mass = [[1.0]]
stiffness = [[1.0]]
damping = [[0.1]]
[harmonic_balance]
max = 3
time_points = 16
[[frequency_response]]
force_cos = [[0.0], [0.01]]
omega = { from = 0.5, to = 2.0 }
"""
    with tempfile.TemporaryDirectory() as tmp:
        r, out = run(exe, base, tmp, extra=("--no-plots", "--stability"))
        if r.returncode != 0:
            return fail(f"exit {r.returncode}: {r.stderr}")
        c = json.load(open(os.path.join(out, "summary.json")))["frequency_response"][0]
    wd = math.sqrt(1.0 - 0.05 ** 2)
    for e in c["stability"]["floquet_exponents_per_s"]:
        for re, im in e:
            # Round-off of a 14 x 14 eigenvalue problem: 1e-10.
            if abs(re + 0.05) > 1e-10 or abs(abs(im) - wd) > 1e-10:
                return fail(f"exponent {re} + {im} i, expected -0.05 +- {wd} i")
    if not all(c["stability"]["stable"]):
        return fail("a linear damped response called unstable")
    return 0


def backbone_rom(exe):
    """[[backbone_rom]] of examples/vibration/jenkins_backbone_rom.toml against the full
    harmonic balance of the same forces in the same run: the peak amplitudes and where
    they lie, the CSV and the plot."""
    with tempfile.TemporaryDirectory() as tmp:
        case = open(os.path.join(EXAMPLES, "jenkins_backbone_rom.toml")).read()
        r, out = run(exe, case, tmp, extra=())
        if r.returncode != 0:
            return fail(f"exit {r.returncode}: {r.stderr}")
        j = json.load(open(os.path.join(out, "summary.json")))
        header, rows = read_csv(os.path.join(out, "backbone_rom_2.csv"))
        if not os.path.getsize(os.path.join(out, "backbone_rom.png")) > 0:
            return fail("backbone_rom.png empty")
        if "backbone ROM 2 (force scale 1)" not in r.stdout:
            return fail(f"text summary without the ROM: {r.stdout}")
    nm, roms, full = j["nonlinear_mode"], j["backbone_rom"], j["frequency_response"]
    if len(roms) != 2 or [c["force_scale"] for c in roms] != [0.5, 1.0]:
        return fail(f"backbone_rom curves: {[c.get('force_scale') for c in roms]}")
    if j["warnings"] or not j["solver"]["complete"]:
        return fail(f"{j['warnings']} {j['solver']['stop_reason']}")
    if len(rows) != len(roms[1]["omega_rad_s"]) or header[:4] != [
            "omega_rad_s", "frequency_hz", "modal_amplitude", "side"]:
        return fail(f"backbone_rom_2.csv: {header}, {len(rows)} rows")
    a = nm["amplitude"]
    grid = max(a[i + 1] / a[i] for i in range(len(a) - 1)) ** (1.0 / 64) - 1.0
    zeta = max(nm["damping_ratio"])
    # Tolerance of the peak amplitude: the model's peak is the last point of its amplitude
    # grid the force can drive, up to one grid step below its own peak (grid = (largest
    # ratio of successive backbone amplitudes)^(1/64) - 1 = 7.2e-4 here); single nonlinear
    # mode theory takes the damping at the backbone frequency and drops the forced
    # response's deviation from the mode shape, errors of the order of zeta^2 near
    # resonance (zeta <= 0.040 on this backbone: 1.6e-3). Measured: 4.5e-5 and 2.1e-4.
    tol_a = grid + zeta ** 2
    # The peak's frequency is flat to second order: an amplitude error eps moves it by
    # about zeta omega sqrt(2 eps) (a resonance |X| ~ 1 / ((w0^2 - w^2)^2 + (2 zeta w0 w)^2)
    # ^(1/2) near its peak). Measured: 6.4e-4 and 1.6e-3 of omega.
    tol_w = zeta * math.sqrt(2.0 * tol_a)
    for rom, hb in zip(roms, full):
        if rom["force_scale"] != hb["force_scale"] or len(hb["peaks"]) != 1:
            return fail(f"curves out of step: {rom['force_scale']} {hb['force_scale']}")
        p, q = rom["peaks"][0], hb["peaks"][0]
        if abs(p["amplitude"] / q["amplitude_m"] - 1.0) > tol_a:
            return fail(f"scale {rom['force_scale']}: ROM peak {p['amplitude']} m, harmonic "
                        f"balance {q['amplitude_m']} m (tolerance {tol_a:.3g})")
        if abs(p["omega_rad_s"] / q["omega_rad_s"] - 1.0) > tol_w:
            return fail(f"scale {rom['force_scale']}: ROM peak at {p['omega_rad_s']} rad/s, "
                        f"harmonic balance {q['omega_rad_s']} (tolerance {tol_w:.3g})")
        # Below the backbone first, then above it, meeting at the peak.
        n = rom["low_side_points"]
        w = rom["omega_rad_s"]
        if not (10 < n < len(w) - 10 and max(w[:n]) < p["omega_rad_s"] * (1 + 1e-12)
                and rom["peak_modal_amplitude"] == max(rom["modal_amplitude"])):
            return fail(f"scale {rom['force_scale']}: sides {n} of {len(w)}")
    return 0


def plots_of_controlled_analyses(exe):
    """The shipped force-sweep and phase-resonance examples write one PNG per analysis
    (gnuplot), listed in the text summary; --no-plots writes none."""
    want = {"duffing_force_sweep": ["force_response.png"],
            "duffing_phase_resonance": ["amplitude_control.png", "phase_resonance.png"],
            "duffing_superharmonic": ["superharmonic_resonance.png"]}
    for name, pngs in want.items():
        case = open(os.path.join(EXAMPLES, name + ".toml")).read()
        for extra in [(), ("--no-plots",)]:
            with tempfile.TemporaryDirectory() as tmp:
                r, out = run(exe, case, tmp, extra=extra)
                if r.returncode != 0:
                    return fail(f"{name}: exit {r.returncode}: {r.stderr}")
                for png in pngs:
                    path = os.path.join(out, png)
                    if extra:
                        if os.path.exists(path):
                            return fail(f"{name}: {png} written with --no-plots")
                        continue
                    with open(path, "rb") as f:
                        if f.read(8) != b"\x89PNG\r\n\x1a\n":
                            return fail(f"{name}: {png} is not a PNG")
                    if png not in r.stdout:
                        return fail(f"{name}: {png} not listed: {r.stdout}")
    return 0


def rough_contact_case(old, new):
    with open(os.path.join(EXAMPLES, "rough_contact_3d.toml")) as f:
        text = f.read()
    assert old in text
    return text.replace(old, new)


BAD = {
    "rough_contact_summit_heights_and_sigma": (
        rough_contact_case('sigma = "2.7 um"\n', 'sigma = "2.7 um"\nsummit_heights = "s.csv"\n'),
        ["element[1]: give sigma or summit_heights", "(line 14)"]),
    "rough_contact_summit_heights_missing": (
        rough_contact_case('sigma = "2.7 um"\n', 'summit_heights = "missing.csv"\n'),
        ["element[1].summit_heights", "missing.csv"]),
    "singular_mass": (JENKINS.replace("mass = [[1.0]]", "mass = [[0.0]]") + EPMC, "mass"),
    "singular_mass_2dof": (
        JENKINS.replace("mass = [[1.0]]", "mass = [[1.0, 1.0], [1.0, 1.0]]").replace(
            "stiffness = [[1.0]]", "stiffness = [[1.0, 0.0], [0.0, 1.0]]").replace(
            "damping = [[0.01]]", "").replace("T = [[1.0]]", "T = [[1.0, 0.0]]") + EPMC,
        "mass"),
    "nonsymmetric_mass": (
        JENKINS.replace("mass = [[1.0]]", "mass = [[1.0, 0.5], [0.0, 1.0]]").replace(
            "stiffness = [[1.0]]", "stiffness = [[1.0, 0.0], [0.0, 1.0]]").replace(
            "damping = [[0.01]]", "").replace("T = [[1.0]]", "T = [[1.0, 0.0]]") + EPMC,
        ["mass", "symmetric"]),
    "mismatched_sizes": (
        JENKINS.replace("mass = [[1.0]]", "mass = [[1.0, 0.0], [0.0, 1.0]]") + EPMC, "stiffness"),
    "ragged_matrix": (JENKINS.replace("stiffness = [[1.0]]", "stiffness = [[1.0], [1.0, 2.0]]") + EPMC,
                      ["structure.stiffness", "row 1"]),
    "T_wrong_columns": (JENKINS.replace("T = [[1.0]]", "T = [[1.0, -1.0]]") + EPMC,
                        ["element[1].T", "2 column", "1 DOFs"]),
    "T_wrong_rows": (JENKINS.replace("T = [[1.0]]", "T = [[1.0], [1.0]]") + EPMC,
                     ["element[1].T", "2 row"]),
    "no_harmonic_1": (JENKINS.replace("max = 3", "harmonics = [0, 2, 3]") + EPMC,
                      ["harmonic 1", "add 1"]),
    # A Duffing mode at amplitude 1e3 is 1e6 times stiffer than its linear start: two
    # Newton iterations cannot reach it.
    "cannot_start": (JENKINS.replace('type = "jenkins"', 'type = "polynomial_stiffness"').replace(
        "k_t = 0.25\nF_s = 0.2\n", "k3 = 1.0\n") + """[nonlinear_mode]
log10_amplitude = { from = 3.0, to = 5.0 }
continuation = { max_iterations = 2, target_iterations = 1 }
""", ["cannot start", "nonlinear_mode"]),
    # Issue 20: a range that starts in gross slip. The stuck mode (omega^2 = 1.25) at
    # amplitude 10 moves the Jenkins slider 10 > F_s / k_t = 0.8: it slides; the stuck
    # force k_t a reaches F_s at a = 0.8 (log10 -0.10).
    "starts_in_gross_slip": (JENKINS + """[nonlinear_mode]
log10_amplitude = { from = 1.0, to = 2.0 }
""", ["nonlinear_mode", "log10_amplitude starts at 1 in gross slip", "element 1 (jenkins)",
      "near log10 amplitude -0.10"]),
    # A cubic spring makes no even harmonics: nothing drives a 2:1 superharmonic.
    "superharmonic_not_driven": (JENKINS.replace('type = "jenkins"', 'type = "polynomial_stiffness"').replace(
        "k_t = 0.25\nF_s = 0.2\n", "k3 = 1.0\n").replace("max = 3", "harmonics = [1, 2, 3]") + """[[superharmonic_resonance]]
force_cos = [[1.0]]
harmonic = 2
log10_force = { from = -2.0, to = 0.0 }
""", ["superharmonic_resonance[1]", "no harmonic 2 from the lower harmonics", "symmetric"]),
    "unknown_key": (JENKINS.replace("k_t = 0.25", "k_t = 0.25\nkt = 0.3") + EPMC,
                    ['"kt"', "line 10", "element[1]"]),
    "unknown_table": (JENKINS + EPMC + "[solver]\nx = 1\n", ['"solver"', "line"]),
    "unknown_element_type": (JENKINS.replace('"jenkins"', '"jenkin"') + EPMC, ["jenkin", "use"]),
    "masing_table_not_monotone": (
        JENKINS.replace('type = "jenkins"', 'type = "masing_table"').replace(
            "k_t = 0.25\nF_s = 0.2\n", "displacement = [0.0, 1.0, 2.0]\nforce = [0.0, 0.2, 0.1]\n")
        + EPMC, ["element[1]", "monotone", "point 3"]),
    "masing_table_not_through_origin": (
        JENKINS.replace('type = "jenkins"', 'type = "masing_table"').replace(
            "k_t = 0.25\nF_s = 0.2\n", "displacement = [0.5, 1.0]\nforce = [0.0, 0.2]\n")
        + EPMC, ["element[1]", "origin"]),
    "masing_table_without_backbone": (
        JENKINS.replace('type = "jenkins"', 'type = "masing_table"').replace(
            "k_t = 0.25\nF_s = 0.2\n", "") + EPMC, ["masing_table", "table ="]),
    "missing_parameter": (JENKINS.replace("F_s = 0.2\n", "") + EPMC, "F_s"),
    "wrong_units": (JENKINS.replace("k_t = 0.25", 'k_t = "0.25 N"') + EPMC, "k_t"),
    "omega_ambiguous_units": (JENKINS + FRF.replace("from = 0.7", 'from = "0.7 s^-1"'), ["Hz", "rad/s"]),
    "force_wrong_columns": (JENKINS + FRF.replace("[[0.0], [0.1]]", "[[0.0, 0.0], [0.1, 0.0]]"),
                            ["force_cos", "column"]),
    "force_at_point_without_model": (
        JENKINS + FRF.replace("[[0.0], [0.1]]",
                              '{ point = "tip", direction = [0, 0, 1], force = [0, "1 N"] }'),
        ["frequency_response[1].force_cos", "a force at a point needs a reduced model"]),
    "force_sine_of_harmonic_0": (JENKINS + FRF.replace("omega", "force_sin = [[1.0]]\nomega"),
                                 ["harmonic 0", "sine"]),
    "nothing_to_run": (JENKINS, "nothing to run"),
    "no_structure": ("[harmonic_balance]\nmax = 1\n", "[structure]"),
    "rough_flat_without_parameters": (JENKINS.replace('"jenkins"', '"rough_flat"').replace(
        "k_t = 0.25\nF_s = 0.2\n", "") + EPMC, ["rough_flat", "joint"]),
    "mtx_missing": (JENKINS.replace("mass = [[1.0]]", 'mass_file = "nope.mtx"') + EPMC, "nope.mtx"),
    "stability_not_boolean": (JENKINS + FRF + "stability = 1\n",
                              "frequency_response[1].stability"),
    "backbone_rom_without_mode": (JENKINS + FRF + "[[backbone_rom]]\nforce_cos = [[0.0], [0.1]]\n",
                                  ["backbone_rom[1]", "[nonlinear_mode]"]),
    "backbone_rom_without_first_harmonic": (
        JENKINS + EPMC + "[[backbone_rom]]\nforce_cos = [[0.5]]\n",
        ["backbone_rom[1]", "first harmonic"]),
    "backbone_rom_negative_scale": (
        JENKINS + EPMC + "[[backbone_rom]]\nforce_cos = [[0.0], [0.1]]\nforce_scales = [-1.0]\n",
        "backbone_rom[1].force_scales[1]"),
    "mode_out_of_range": (JENKINS + EPMC.replace("[nonlinear_mode]", "[nonlinear_mode]\nmode = 2"),
                          "nonlinear_mode.mode"),
    # Eq. 3.10's parameters are measured: refused without them, naming the key and why.
    "odfalk_vingsbo_without_parameters": (
        JENKINS.replace('"jenkins"', '"rough_flat"').replace(
            "k_t = 0.25\nF_s = 0.2\n",
            'backbone = "normalized"\nbeta = 0.04\npsi = 0.5\nnu = 0.3\nG_over_E = 0.2\n'
            'P_star = 1e-3\nsigma = 1e-6\nforce_scale = 1e4\ntangential = "odfalk_vingsbo"\n'
            'fretting_yield_point = "2 N"\n') + EPMC,
        ["element[1]", "hardening_coefficient", "measured"]),
    # The quasi-static estimate builds loops by Masing's rules from the static push: not the
    # Odfalk-Vingsbo law's (refused before any work, pointing to [nonlinear_mode]).
    "odfalk_vingsbo_quasi_static": (
        JENKINS.replace('"jenkins"', '"rough_flat"').replace(
            "k_t = 0.25\nF_s = 0.2\n",
            'backbone = "normalized"\nbeta = 0.04\npsi = 0.5\nnu = 0.3\nG_over_E = 0.2\n'
            'P_star = 1e-3\nsigma = 1e-6\nforce_scale = 1e4\ntangential = "odfalk_vingsbo"\n'
            'fretting_yield_point = "2 N"\nhardening_coefficient = "1 N/um"\n')
        + "[quasi_static_mode]\namplitude = { from = 1e-9, to = 1e-7 }\n",
        ["quasi_static_mode", "Masing", "[nonlinear_mode]"]),
    "odfalk_vingsbo_unknown_law": (
        JENKINS.replace('"jenkins"', '"rough_flat"').replace(
            "k_t = 0.25\nF_s = 0.2\n",
            'backbone = "normalized"\nbeta = 0.04\npsi = 0.5\nnu = 0.3\nG_over_E = 0.2\n'
            'P_star = 1e-3\nsigma = 1e-6\nforce_scale = 1e4\ntangential = "plastic"\n') + EPMC,
        ["element[1].tangential", "plastic", "odfalk_vingsbo"]),
}


def rough_contact_equals_rough_flat(exe):
    """The 3-D rough_contact element of examples/vibration/rough_contact_3d.toml moved along
    t1 at constant normal load is the rough_flat element at the same preload (the same
    table, the same Masing memory): the mode-1 backbones agree point by point to 1e-10
    (round-off of two continuations along the same path)."""
    with open(os.path.join(EXAMPLES, "rough_contact_3d.toml")) as f:
        text = f.read()
    one_d = "\n".join([
        "[structure]", "mass = [[1.0]]", "stiffness = [[1e8]]", "damping = [[20.0]]",
        "output_dofs = [0]", "[[element]]", 'type = "rough_flat"', 'backbone = "dimensional"',
        'E_star = "106 GPa"', 'G_star = "22.9 GPa"', 'H = "5.8 GPa"', "nu = 0.3",
        'sigma = "2.7 um"', 'R = "30.1 um"', 'eta = "2.9e8 m^-2"', 'A0 = "170 mm^2"',
        'P = "525.98 N"', 'asperity_model = "bke"', "T = [[1.0]]", "[harmonic_balance]",
        "max = 3", "time_points = 128", "[nonlinear_mode]", "mode = 1",
        "log10_amplitude = { from = -9.0, to = -5.0 }", ""])
    got = {}
    for name, case in [("3d", text), ("1d", one_d)]:
        with tempfile.TemporaryDirectory() as tmp:
            r, out = run(exe, case, tmp)
            if r.returncode != 0:
                return fail(f"{name}: exit {r.returncode}: {r.stderr}")
            with open(os.path.join(out, "summary.json")) as f:
                got[name] = json.load(f)["nonlinear_mode"]
    a, b = got["3d"], got["1d"]
    if len(a["frequency_hz"]) != len(b["frequency_hz"]) or len(a["frequency_hz"]) < 20:
        return fail(f"points: {len(a['frequency_hz'])} against {len(b['frequency_hz'])}")
    for key in ["frequency_hz", "damping_ratio", "amplitude"]:
        for x, y in zip(a[key], b[key]):
            if abs(x - y) > 1e-10 * abs(y):
                return fail(f"{key}: {x} against the rough flat's {y}")
    # Microslip softens and damps: the backbone falls from the stuck 5 kHz towards the
    # flexure alone (1.6 kHz) as the damping ratio rises.
    f, z = a["frequency_hz"], a["damping_ratio"]
    if not (f[0] > 4900 and f[-1] < 0.5 * f[0] and z[-1] > 10 * z[0]):
        return fail(f"backbone {f[0]} -> {f[-1]} Hz, damping {z[0]} -> {z[-1]}")
    return 0


def odfalk_vingsbo(exe):
    """tangential = "odfalk_vingsbo" (Eq. 3.10) on a rough_flat element: where the joint's
    force stays below Q_ty the mode-1 backbone is the Cattaneo-Mindlin element's, point by
    point to 1e-10 (the same steps on the same residuals); once the force passes Q_ty the
    backbone departs from it. The summary names the law and its inputs."""
    base = "\n".join([
        "[structure]", "mass = [[1.0]]", "stiffness = [[1e8]]", "damping = [[20.0]]",
        "output_dofs = [0]", "[[element]]", 'type = "rough_flat"', 'backbone = "dimensional"',
        'E_star = "106 GPa"', 'G_star = "22.9 GPa"', 'H = "5.8 GPa"', "nu = 0.3",
        'sigma = "2.7 um"', 'R = "30.1 um"', 'eta = "2.9e8 m^-2"', 'A0 = "170 mm^2"',
        'P = "525.98 N"', "T = [[1.0]]", "{law}", "[harmonic_balance]", "max = 3",
        "time_points = 128", "[nonlinear_mode]", "mode = 1",
        "log10_amplitude = {{ from = -9.0, to = -5.5 }}", ""])
    law = ('tangential = "odfalk_vingsbo"\nfretting_yield_point = "60 N"\n'
           'hardening_coefficient = "200 N/um"')
    got = {}
    for name, text in [("mindlin", base.format(law="")), ("ov", base.format(law=law))]:
        with tempfile.TemporaryDirectory() as tmp:
            r, out = run(exe, text, tmp)
            if r.returncode != 0:
                return fail(f"{name}: exit {r.returncode}: {r.stderr}")
            with open(os.path.join(out, "summary.json")) as f:
                got[name] = json.load(f)
    el = got["ov"]["elements"][0]
    if (el.get("tangential") != "odfalk_vingsbo" or el.get("fretting_yield_point_N") != 60.0
            or el.get("hardening_coefficient_N_per_m") != 2e8 or el["type"] != "rough_flat"):
        return fail(f"element summary: {el}")
    m, o = got["mindlin"]["nonlinear_mode"], got["ov"]["nonlinear_mode"]
    # Below Q_ty: x k_t < Q_ty/4 for a <= 1e-8 (k_t ~ 9e8 N/m, Q_ty = 60 N).
    same = 0
    for i, a in enumerate(o["amplitude"]):
        if a > 1e-8 or i >= len(m["amplitude"]):
            break
        for key in ["amplitude", "frequency_hz", "damping_ratio"]:
            if abs(o[key][i] - m[key][i]) > 1e-10 * abs(m[key][i]):
                return fail(f"{key}[{i}] (a = {a}): {o[key][i]} against Mindlin's {m[key][i]}")
        same += 1
    if same < 3:
        return fail(f"only {same} points below Q_ty")
    # Beyond Q_ty the law acts: the loops differ (Eq. 3.10's parallelogram shifts the
    # elastic amplitude and adds its area; whether the damping ratio rises or falls depends
    # on the regime: in gross slip the Masing part loses more than the parallelogram adds,
    # tests/vibration/odfalk_vingsbo_element_test.cpp checks the loop itself), and the
    # damping stays positive.
    a_end = min(m["amplitude"][-1], o["amplitude"][-1])
    def at(d, key):
        return next(v for a, v in zip(d["amplitude"], d[key]) if a >= a_end * (1 - 1e-9))
    for key in ["damping_ratio", "frequency_hz"]:
        if not abs(at(o, key) - at(m, key)) > 1e-3 * abs(at(m, key)):
            return fail(f"{key} at a = {a_end}: {at(o, key)}, Mindlin's {at(m, key)}")
    if not all(z > 0 for z in o["damping_ratio"]):
        return fail(f"damping ratios {o['damping_ratio']}")
    return 0


def main():
    exe, case = sys.argv[1], sys.argv[2]
    if case.startswith("bad_input."):
        text, words = BAD[case.split(".", 1)[1]]
        return bad(exe, text, words)
    return {
        "summary_keys": summary_keys,
        "examples": examples,
        "stall": stall,
        "partial_results": partial_results,
        "matrix_market": matrix_market,
        "omega_in_hz": omega_in_hz,
        "without_out_prints_the_summary": without_out_prints_the_summary,
        "element_types": element_types,
        "base_excitation": base_excitation,
        "out_refuses_a_foreign_directory": out_refuses_a_foreign_directory,
        "rough_flat_forms": rough_flat_forms,
        "masing_table_from_predict": masing_table_from_predict,
        "masing_table_from_flat": masing_table_from_flat,
        "rough_contact_equals_rough_flat": rough_contact_equals_rough_flat,
        "stability": stability,
        "odfalk_vingsbo": odfalk_vingsbo,
        "backbone_rom": backbone_rom,
        "plots_of_controlled_analyses": plots_of_controlled_analyses,
        "force_in_newton": force_in_newton,
    }[case](exe)


if __name__ == "__main__":
    sys.exit(main())
