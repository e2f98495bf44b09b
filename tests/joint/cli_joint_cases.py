"""CLI cases of asperity predict / analyze / synthesize / validate (issue 5).

Usage: cli_joint_cases.py ASPERITY CASE SOURCE_DIR. Exit 0 on success.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

exe, case, src = sys.argv[1], sys.argv[2], sys.argv[3]
ex = os.path.join(src, "examples", "joints")
tmp = tempfile.mkdtemp(prefix="asperity-joint-")


def run(*args, code=0):
    p = subprocess.run([exe, *args], capture_output=True, text=True)
    if p.returncode != code:
        sys.exit(f"{args}: exit {p.returncode}, expected {code}\nstdout:{p.stdout}\nstderr:{p.stderr}")
    return p


def check(cond, msg):
    if not cond:
        sys.exit(msg)


BASE = open(os.path.join(ex, "steel420_two_bolts.toml")).read()


def write_case(text, name="case.toml"):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def bad_case(text, *needles):
    p = run("predict", write_case(text), "--out", os.path.join(tmp, "out"), code=2)
    for n in needles:
        check(n in p.stderr, f"stderr lacks {n!r}: {p.stderr}")
    check(p.stdout == "", "stdout not empty on error")
    check(not os.path.exists(os.path.join(tmp, "out")), "an output directory was left behind")
    check(len(os.listdir(tmp)) == 1, f"temporary files left: {os.listdir(tmp)}")


def synth(name, *extra):
    path = os.path.join(tmp, name)
    run("synthesize", os.path.join(ex, "steel420_two_bolts.toml"), "--out", path, *extra)
    return path


if case == "predict_example":
    out = os.path.join(tmp, "out")
    p = run("predict", os.path.join(ex, "steel420_two_bolts.toml"), "--out", out)
    check("0.34" in p.stdout and "partial slip" in p.stdout and "gross slip" in p.stdout, p.stdout)
    for f in ["summary.json", "loops.csv", "energy.csv", "loops.png", "energy_vs_force.png",
              "mu_vs_preload.png", "stiffness_vs_preload.png"]:
        check(os.path.getsize(os.path.join(out, f)) > 0, f"missing {f}")
    check(sorted(os.listdir(tmp)) == ["out"], f"stray files: {os.listdir(tmp)}")
elif case == "predict_sweep_files":
    for name in ["aluminium_smooth", "aluminium_rough", "steel_smooth", "steel_rough", "steel420_profiles"]:
        out = os.path.join(tmp, name)
        run("predict", os.path.join(ex, name + ".toml"), "--out", out, "--no-plots")
        s = json.load(open(os.path.join(out, "summary.json")))
        for load in s["loads"]:
            check(0.05 < load["mu"] < 2 and load["stiffness"] > 0, f"{name}: {load}")
elif case == "predict_json_keys":
    p = run("predict", write_case(BASE.replace(
        'bolts = { count = 2, total_torques = ["1.2 lbf*in", "1.7 lbf*in", "2.7 lbf*in", "3.7 lbf*in"], nut_factor = 0.2, diameter = "2.9 mm" }',
        'preload = "526 N"')), "--json")
    s = json.loads(p.stdout)
    for k in ["preload", "mu", "stiffness", "Q_max", "separation", "amplitudes", "loads"]:
        check(k in s, f"summary lacks {k}")
    check(abs(s["preload"] - 526) < 1e-9, s["preload"])
    check(abs(s["mu"] - 0.335) / 0.335 < 0.05, f"mu {s['mu']} vs thesis 0.335")
    for a in s["amplitudes"]:
        check(set(["delta_max", "Q_peak", "energy", "regime"]) <= set(a), a)
    check(s["amplitudes"][0]["delta_max"] == 0.05e-6, s["amplitudes"][0])
elif case == "analyze_synthetic":
    data = synth("d.csv", "--imposed", "6.75um", "--preload", "526N", "--seed", "11")
    out = os.path.join(tmp, "an")
    p = run("analyze", data, "--P", "526N", "--model", os.path.join(ex, "steel420_two_bolts.toml"), "--json",
            "--out", out)
    j = json.loads(p.stdout)
    check(j["cycles"] == 9 and len(j["per_cycle"]) == 9, j["cycles"])
    for k in ["energy", "Q_max", "delta_max", "stiffness"]:
        check(k in j["mean"] and all(k in c for c in j["per_cycle"]), k)
    check(abs(j["mu"] - 0.3427) < 0.01 * 0.3427, f"mu {j['mu']}")  # model mu at 526 N: 0.3427
    check(abs(j["model"]["relative_difference"]["mu"]) < 0.01, j["model"])
    for f in ["analysis.json", "cycles.csv", "averaged_loop.csv", "loops.png"]:
        check(os.path.getsize(os.path.join(out, f)) > 0, f"missing {f}")
elif case == "analyze_runs_power_law":
    files = [synth(f"r{i}.csv", "--imposed", a, "--preload", "721N", "--noise-delta", "0um", "--noise-Q", "0N")
             for i, a in enumerate(["1um", "1.5um", "2um"])]
    j = json.loads(run("analyze", *files, "--P", "721N", "--json").stdout)
    check(len(j["runs"]) == 3 and 1.5 < j["power_law_exponent"] < 4, j.get("power_law_exponent"))
elif case == "validate_report":
    out = os.path.join(tmp, "val")
    p = run("validate", "--out", out)
    md = open(os.path.join(out, "validation.md")).read()
    check("FAIL" not in md and "| mu at 526 N | 0.335 |" in md, "report incomplete")
    check(p.stdout == md, "stdout differs from the file")
    for f in ["ch5_loops.png", "ch5_energy_vs_force.png", "ch5_mu_vs_preload.png", "ch5_stiffness_vs_preload.png"]:
        check(os.path.getsize(os.path.join(out, f)) > 0, f"missing {f}")
elif case == "validate_docs_current":
    p = run("validate")
    doc = open(os.path.join(src, "docs", "validation.md")).read()
    check(p.stdout == doc, "docs/validation.md is out of date: regenerate it with "
          "`asperity validate > docs/validation.md`")
elif case == "bad.unknown_key":
    bad_case(BASE.replace('model = "bke"', 'modle = "bke"'), "joint.modle", "unknown key", "case.toml:8:")
elif case == "bad.wrong_unit":
    bad_case(BASE.replace('area = "170 mm^2"', 'area = "3 N"'), "joint.area", "case.toml:7:")
elif case == "bad.missing_half":
    i = BASE.index("[[joint.half]]", BASE.index("[[joint.half]]") + 1)
    bad_case(BASE[:i] + BASE[BASE.index("[load]"):], "joint.half", "two")
elif case == "bad.negative_torque":
    bad_case(BASE.replace('"1.2 lbf*in"', '"-1.2 lbf*in"'), "load.bolts.total_torques[1]", "> 0")
elif case == "bad.no_partial_output":
    # Fails after the case is read: the preload is beyond the model's range.
    bad_case(BASE.replace('"3.7 lbf*in"', '"3e6 lbf*in"'), "preload")
elif case.startswith("bad.data"):
    rows = [(i * 0.01, 1e-6 * math.sin(2 * math.pi * i * 0.01), 100 * math.sin(2 * math.pi * i * 0.01))
            for i in range(500)]
    header = "t[s],delta[m],Q[N]"
    needle = ""
    if case == "bad.data_gap":
        rows = rows[:200] + rows[260:]
        needle = "gap"
    elif case == "bad.data_time_backwards":
        rows[100] = (rows[98][0],) + rows[100][1:]
        needle = "data row 101"
    elif case == "bad.data_missing_column":
        header = "t[s],delta[m],F[N]"
        needle = 'column "Q" is missing'
    elif case == "bad.data_less_than_a_cycle":
        rows = rows[:80]
        needle = "fewer than one complete"
    path = os.path.join(tmp, "data.csv")
    with open(path, "w") as f:
        f.write(header + "\n" + "".join(f"{a},{b},{c}\n" for a, b, c in rows))
    p = run("analyze", path, "--P", "100N", "--out", os.path.join(tmp, "o"), code=2)
    check(needle in p.stderr and "data.csv" in p.stderr, p.stderr)
    check(not os.path.exists(os.path.join(tmp, "o")), "output directory left behind")
else:
    sys.exit(f"unknown case {case}")
print("ok")
