#!/usr/bin/env python3
"""Behaviour of `asperity flat`: the JSON contract of the issue, the history mode, and
bad input (exit 2, a message naming what to change, nothing on stdout, no output file).

Usage: flat_cases.py ASPERITY_EXE CASE. Standard library only. Exit 0 = pass, 1 = fail.
"""
import atexit
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

NORMALIZED = ["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=1e-3", "--model=bke"]
STEEL = ["--E1=200GPa", "--nu1=0.24", "--G1=80.7GPa", "--E2=200GPa", "--nu2=0.24",
         "--G2=80.7GPa", "--H=5.8GPa"]
DIMENSIONAL = ["flat"] + STEEL + ["--sigma=2.677um", "--eta=2.91e-4um^-2", "--R=30.14um",
                                  "--area=170mm^2", "--P=526N", "--model=bke"]


def run(exe, argv):
    return subprocess.run([exe] + argv, capture_output=True, text=True, timeout=120)


def fail(msg):
    print("FAIL:", msg, file=sys.stderr)
    return 1


def check_json(exe, argv, keys):
    r = run(exe, argv + ["--json"])
    if r.returncode != 0:
        return fail(f"exit {r.returncode}: {r.stderr}")
    j = json.loads(r.stdout)
    missing = [k for k in keys if k not in j]
    if missing:
        return fail(f"missing keys {missing}")
    for k, v in j.items():
        if isinstance(v, float) and not math.isfinite(v):
            return fail(f"{k} is not finite")
    return j


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def bad(exe, argv, must_contain, tmp=None):
    r = run(exe, argv)
    if r.returncode != 2:
        return fail(f"expected exit 2, got {r.returncode}; stderr: {r.stderr}")
    if r.stdout:
        return fail(f"stdout not empty: {r.stdout!r}")
    if must_contain.lower() not in r.stderr.lower():
        return fail(f"message does not mention {must_contain!r}: {r.stderr}")
    if tmp and os.path.exists(os.path.join(tmp, "out.csv")):
        return fail("an output file was left behind")
    return 0


def main():
    exe, case = sys.argv[1], sys.argv[2]
    tmp = tempfile.mkdtemp(prefix="asperity-flat-")
    atexit.register(shutil.rmtree, tmp, ignore_errors=True)  # no directory left per run
    norm_keys = ["beta", "psi", "sigma_a_over_sigma", "omega_c_star", "separation_star", "P_star",
                 "Q_max_star", "mu", "stiffness_star"]
    amp_keys = ["delta_max_star", "Q_at_delta_max_star", "energy_star"]
    if case == "normalized_json":
        j = check_json(exe, NORMALIZED + ["--delta-star-max=0.6"], norm_keys + amp_keys)
        if not isinstance(j, dict):
            return 1
        # Eq. 4.4 inverted: the load is the one asked for; BKE mu at psi = 0.5 above 1.
        if abs(j["P_star"] - 1e-3) > 1e-15 or not (j["mu"] > 1.0) or j["energy_star"] <= 0:
            return fail(str(j))
        return 0
    if case == "dimensional_json":
        j = check_json(exe, DIMENSIONAL + ["--delta-max=1um"],
                       norm_keys + amp_keys + ["separation", "P", "Q_max", "stiffness", "energy"])
        if not isinstance(j, dict):
            return 1
        # Chapter 5: BKE mu at 526 N printed as 0.335 (SEED_NOTES.md); within 5 %.
        if abs(j["mu"] - 0.335) / 0.335 > 0.05:
            return fail(f"mu = {j['mu']}")
        # SI consistency: Q_max = mu P.
        if abs(j["Q_max"] - j["mu"] * j["P"]) > 1e-9 * j["Q_max"]:
            return fail("Q_max != mu P")
        return 0
    if case in ("history_star", "history_si"):
        # A virgin ramp to the amplitude, then two full cycles, then the same negated: the
        # forces must equal the loading curve at the amplitude (the --json value of the
        # same table), close the loop, stay within Q_max, and be odd in the history.
        hist = os.path.join(tmp, "h.csv")
        out = os.path.join(tmp, "out.csv")
        amp = 0.6 if case == "history_star" else 1.0  # delta* or um
        ramp = [amp * k / 100 for k in range(1, 101)]
        cycle = [amp * math.cos(math.pi * k / 100) for k in range(1, 201)]
        xs = ramp + cycle + cycle
        if case == "history_star":
            base = NORMALIZED
            col, amp_flag, q_key, qmax_key = "delta_star", f"--delta-star-max={amp}", "Q_at_delta_max_star", "Q_max_star"
        else:
            base = DIMENSIONAL
            col, amp_flag, q_key, qmax_key = "delta[um]", f"--delta-max={amp}um", "Q_at_delta_max", "Q_max"
        j = check_json(exe, base + [amp_flag], [q_key, qmax_key])
        if not isinstance(j, dict):
            return 1
        results = []
        for sign in (1, -1):
            write(hist, col + "\n" + "\n".join(f"{sign * x:.17g}" for x in xs) + "\n")
            r = run(exe, base + ["--history", hist, "--out", out])
            if r.returncode != 0:
                return fail(r.stderr)
            with open(out) as f:
                rows = list(csv.reader(f))
            expected_header = ["delta_star", "Q_star"] if case == "history_star" else ["delta[m]", "Q[N]"]
            if rows[0] != expected_header or len(rows) != len(xs) + 1:
                return fail(f"header {rows[0]}, {len(rows)} rows")
            results.append([float(r[1]) for r in rows[1:]])
        Q, Qn = results
        tol = 2e-11 * j[qmax_key]  # one table for all runs; the CSV carries 12 digits
        if abs(Q[99] - j[q_key]) > tol:
            return fail(f"Q at the amplitude {Q[99]} != loading curve {j[q_key]}")
        if abs(Q[-1] - Q[99]) > tol or abs(Q[299] - Q[99]) > tol:
            return fail("the cycle does not close on the loading curve's end")
        if max(abs(q) for q in Q) > j[qmax_key] * (1 + 1e-12):
            return fail("|Q| exceeds Q_max")
        if any(abs(a + b) > tol for a, b in zip(Q, Qn)):
            return fail("the response is not odd")
        return 0
    if case == "loop_not_written_on_bad_history":
        hist = os.path.join(tmp, "h.csv")
        loop = os.path.join(tmp, "loop.csv")
        write(hist, "delta_star\n0.1\nnan\n")
        r = run(exe, NORMALIZED + ["--delta-star-max=0.6", "--loop", loop, "--history", hist,
                                   "--out", os.path.join(tmp, "out.csv")])
        if r.returncode != 2 or os.path.exists(loop) or os.path.exists(os.path.join(tmp, "out.csv")):
            return fail(f"exit {r.returncode}, files {os.listdir(tmp)}: {r.stderr}")
        return 0
    if case == "own_law_scaling":
        # Eq. 4.8 with each law's own a/P: the same outputs, finite (a NaN once aborted it).
        j = check_json(exe, NORMALIZED + ["--delta-star-max=0.6", "--slip-scaling=own-law"],
                       norm_keys + amp_keys)
        if not isinstance(j, dict):
            return 1
        if not (j["stiffness_star"] > 0 and j["energy_star"] > 0):
            return fail(str(j))
        return 0
    if case == "near_maximum_load":
        # CEB at 99.8 % of the largest load it can carry (the table build aborted here once).
        r = run(exe, ["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=0.646",
                      "--model=ceb", "--delta-star-max=0.01", "--json"])
        if r.returncode != 0:
            return fail(r.stderr)
        return 0
    if case == "loop_and_plot":
        loop = os.path.join(tmp, "loop.csv")
        png = os.path.join(tmp, "loop.png")
        r = run(exe, NORMALIZED + ["--delta-star-max=0.6", "--loop", loop, "--plot", png])
        if r.returncode != 0:
            return fail(r.stderr)
        with open(png, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                return fail("not a PNG")
        with open(loop) as f:
            rows = list(csv.reader(f))[1:]
        # The loop closes: the last point equals the end of the first loading.
        first_peak = next(r for r in rows if abs(float(r[0]) - 0.6) < 1e-12)
        if abs(float(rows[-1][1]) - float(first_peak[1])) > 1e-12:
            return fail("loop does not close")
        return 0
    if case == "odfalk_vingsbo":
        # Eq. 3.10 in series with Mindlin (Fig. 3.3): at amplitude delta_max the force
        # amplitude Q_m is Mindlin's at the elastic amplitude delta_max - (Q_m - Q_ty)/(2 k_p)
        # and the energy adds the parallelogram's (Q_m^2 - Q_ty^2)/k_p. Reference: the same
        # command with the default law at that amplitude (the same table: 1e-9 covers the
        # root's and the quadrature's rounding).
        Q_ty, k_p = 20.0, 50e6
        law = ["--tangential", "odfalk-vingsbo", "--fretting-yield-point", "20N",
               "--hardening-coefficient", "50N/um"]
        loop = os.path.join(tmp, "loop.csv")
        j = check_json(exe, DIMENSIONAL + law + ["--delta-max=2um", "--loop", loop], ["tangential"])
        if j == 1:
            return 1
        if j["tangential"]["law"] != "odfalk_vingsbo":
            return fail(f"tangential: {j['tangential']}")
        Q_m, W = j["Q_at_delta_max"], j["energy"]
        x_e = 2e-6 - (Q_m - Q_ty) / (2 * k_p)
        m = check_json(exe, DIMENSIONAL + [f"--delta-max={x_e * 1e6!r}um"], [])
        if m == 1:
            return 1
        if abs(m["Q_at_delta_max"] - Q_m) > 1e-9 * Q_m:
            return fail(f"Q_m {Q_m} against Mindlin's {m['Q_at_delta_max']} at {x_e}")
        W_ref = m["energy"] + (Q_m ** 2 - Q_ty ** 2) / k_p
        if abs(W - W_ref) > 1e-9 * W_ref:
            return fail(f"energy {W} against {W_ref}")
        # The loop written: symmetric, closing at (delta_max, Q_m), its area the energy (201
        # points per branch: the trapezoidal error of the kinks at -+Q_ty is below 1e-3).
        with open(loop) as f:
            rows = [(float(a), float(b)) for a, b in list(csv.reader(f))[1:]]
        if abs(rows[-1][1] - Q_m) > 1e-9 * Q_m or abs(rows[402][1] + Q_m) > 1e-9 * Q_m:
            return fail(f"loop ends {rows[-1]}, {rows[402]} against Q_m = {Q_m}")
        cyc = rows[201:]
        area = sum(0.5 * (cyc[i][1] + cyc[i + 1][1]) * (cyc[i + 1][0] - cyc[i][0])
                   for i in range(len(cyc) - 1))
        if abs(abs(area) - W) > 1e-3 * W:
            return fail(f"loop area {area} against energy {W}")
        return 0
    if case == "odfalk_vingsbo_case":
        # flat --case follows a history with the case's Odfalk-Vingsbo law (the history
        # operator); predict gives the same steady peak from the closed form (the root of
        # x_m = x_l(Q_m) + (Q_m - Q_ty)/(2 k_p)): 1e-9 covers both roots' rounding.
        src = os.path.join(os.path.dirname(os.path.abspath(__file__)), "../../examples/joints")
        with open(os.path.join(src, "steel_rough.toml")) as f:
            text = f.read()
        text = text.split("[excitation]")[0] + (
            '[excitation]\namplitudes = ["1 um"]\n[interface]\ntangential = "odfalk_vingsbo"\n'
            'fretting_yield_point = "20 N"\nhardening_coefficient = "50 N/um"\n')
        case_file = os.path.join(tmp, "ov.toml")
        write(case_file, text)
        r = run(exe, ["predict", case_file, "--json"])
        if r.returncode != 0:
            return fail(r.stderr)
        load = json.loads(r.stdout)["loads"][0]
        Q_peak, P = load["amplitudes"][0]["Q_peak"], load["preload"]
        hist = os.path.join(tmp, "h.csv")
        path = ([i / 100 for i in range(101)] + [1 - i / 50 for i in range(1, 101)]
                + [-1 + i / 50 for i in range(1, 101)])
        write(hist, "delta[um]\n" + "\n".join(f"{x!r}" for x in path) + "\n")
        out = os.path.join(tmp, "out.csv")
        r = run(exe, ["flat", "--case", case_file, "--history", hist, "--out", out, f"--P={P!r}N"])
        if r.returncode != 0:
            return fail(r.stderr)
        with open(out) as f:
            Q = [float(row[1]) for row in list(csv.reader(f))[1:]]
        for k, want in ((100, Q_peak), (200, -Q_peak), (300, Q_peak)):
            if abs(Q[k] - want) > 1e-9 * Q_peak:
                return fail(f"Q[{k}] = {Q[k]} against {want}")
        return 0
    hist = os.path.join(tmp, "h.csv")
    out = os.path.join(tmp, "out.csv")
    cases = {
        "bad_input.odfalk_vingsbo_without_parameters": (
            DIMENSIONAL + ["--tangential=odfalk-vingsbo", "--fretting-yield-point=20N"],
            "obtained experimentally"),
        "bad_input.odfalk_vingsbo_normalized": (
            NORMALIZED + ["--tangential=odfalk-vingsbo", "--fretting-yield-point=20N",
                          "--hardening-coefficient=5N/um"], "dimensional"),
        "bad_input.beta_too_small": (["flat", "--beta=0.019", "--psi=0.5", "--nu=0.3", "--P-star=1e-3"], "beta"),
        "bad_input.psi_zero": (["flat", "--beta=0.04", "--psi=0", "--nu=0.3", "--P-star=1e-3"], "--psi"),
        "bad_input.preload_too_large": (["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=1e3"], "preload"),
        "bad_input.negative_amplitude": (NORMALIZED + ["--delta-star-max=-0.1"], "--delta-star-max"),
        "bad_input.mixed_inputs": (NORMALIZED + ["--sigma=2um"], "mixing"),
        "bad_input.unknown_model": (["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=1e-3", "--model=xyz"], "xyz"),
        "bad_input.cfc_without_mu": (["flat", "--beta=0.04", "--psi=0.5", "--nu=0.3", "--P-star=1e-3", "--model=cfc"], "--mu-cfc"),
        "bad_input.contact_area_beyond_nominal": (["flat", "--beta=0.2", "--psi=8", "--nu=0.3", "--P-star=30", "--model=cfc", "--mu-cfc=0.3"], "real contact area"),
        "bad_input.same_output_file": (NORMALIZED + ["--delta-star-max=0.6", "--loop", "/tmp/x.csv", "--plot", "/tmp/x.csv"], "both name"),
        "bad_input.dimensional_amplitude_with_normalized": (NORMALIZED + ["--delta-max=1um"], "mixing"),
        "bad_input.output_directory_missing": (NORMALIZED + ["--delta-star-max=0.6", "--loop", "/tmp/asperity-no-such-dir/l.csv"], "does not exist"),
        "bad_input.G_over_E_too_large": (NORMALIZED + ["--G-over-E=5"], "G*/E*"),
    }
    history_cases = {
        "bad_input.history_not_a_number": ("delta_star\n0.1\nabc\n", "abc"),
        "bad_input.history_nan": ("delta_star\n0.1\nnan\n", "finite"),
        "bad_input.history_missing_column": ("x\n0.1\n", "delta_star"),
        "bad_input.history_wrong_unit": ("delta[N]\n0.1\n", "length"),
        "bad_input.history_two_columns": ("delta_star,delta[um]\n0.1,0.2\n", "both"),
    }
    if case in cases:
        argv, text = cases[case]
        return bad(exe, argv, text)
    if case in history_cases:
        content, text = history_cases[case]
        write(hist, content)
        argv = (DIMENSIONAL if case.endswith("wrong_unit") else NORMALIZED) + ["--history", hist, "--out", out]
        return bad(exe, argv, text, tmp)
    return fail(f"unknown case {case}")


if __name__ == "__main__":
    sys.exit(main())
