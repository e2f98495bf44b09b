"""The command line's conventions across commands (issue 13): one name per quantity,
--json everywhere, case-insensitive model names, the nearest command or option on a typo,
one error prefix, one style of defaults in --help, "-" for standard output, one "wrote"
line. Usage: interface_cases.py ASPERITY SOURCE_DIR CASE. Exit 0 on success.
"""
import atexit
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

exe, src, case = sys.argv[1], sys.argv[2], sys.argv[3]
tmp = tempfile.mkdtemp(prefix="asperity-cli-")
atexit.register(shutil.rmtree, tmp, ignore_errors=True)  # no directory left per run
COMMANDS = ["sphere", "flat", "roughness", "dynamics", "predict", "analyze", "synthesize", "validate"]
CASE = "examples/joints/steel420_two_bolts.toml"
SPHERE = ["sphere", "--E1", "207GPa", "--nu1", "0.3", "--E2", "207GPa", "--nu2", "0.3", "--H", "6.83GPa",
          "--R1", "2.5mm", "--mu-cfc", "0.284", "--delta-max", "1.5um"]
FLAT = ["flat", "--beta", "0.04", "--psi", "0.5", "--nu", "0.3", "--P-star", "1e-3", "--delta-star-max", "0.6"]


def run(*args, code=0):
    p = subprocess.run([exe, *args], capture_output=True, text=True, cwd=src, timeout=600)
    if p.returncode != code:
        sys.exit(f"{args}: exit {p.returncode}, expected {code}\nstdout:{p.stdout}\nstderr:{p.stderr}")
    return p


def check(cond, msg):
    if not cond:
        sys.exit(msg)


def error_line(p):
    check(p.stdout == "", f"stdout not empty on error: {p.stdout!r}")
    lines = p.stderr.splitlines()
    check(len(lines) == 1 and lines[0].startswith("asperity: error: "), f"not one prefixed line: {p.stderr!r}")
    return lines[0]


if case == "preload_alias":
    # --P is the name of the normal load in every command that takes one; --preload is its alias.
    a = json.loads(run(*SPHERE, "--P", "35N", "--json").stdout)
    b = json.loads(run(*SPHERE, "--preload", "35N", "--json").stdout)
    check(a == b, "sphere: --preload differs from --P")
    for cmd in ["sphere", "flat", "analyze", "synthesize"]:
        h = run(cmd, "--help").stdout
        check("--P,--preload" in h, f"{cmd} --help lacks --P,--preload:\n{h}")
    run("synthesize", CASE, "--imposed", "6.75um", "--P", "526N", "--out", os.path.join(tmp, "p.csv"))
    run("synthesize", CASE, "--imposed", "6.75um", "--preload", "526N", "--out", os.path.join(tmp, "q.csv"))
    check(open(os.path.join(tmp, "p.csv")).read() == open(os.path.join(tmp, "q.csv")).read(),
          "synthesize: --preload differs from --P")
    line = error_line(run("synthesize", CASE, "--imposed", "6.75um", "--P", "-1N", "--out", "x.csv", code=2))
    check("--P = -1N" in line, line)
elif case == "json_everywhere":
    for cmd in COMMANDS:
        check("--json" in run(cmd, "--help").stdout, f"{cmd} has no --json")
    j = json.loads(run("synthesize", CASE, "--imposed", "6.75um", "--out", os.path.join(tmp, "s.csv"), "--json").stdout)
    check(j["samples"] == 11001 and j["out"].endswith("s.csv"), j)
    j = json.loads(run("dynamics", "examples/dynamics/impulse_dankowicz.toml", "--json").stdout)
    check(j["friction_model"] == "dankowicz", j.get("friction_model"))
    p = run("validate", "--json")
    j = json.loads(p.stdout)
    check(j["failures"] == 0 and len(j["rows"]) > 50, (j["failures"], len(j["rows"])))
elif case == "validate_no_plots":
    out = os.path.join(tmp, "v")
    p = run("validate", "--out", out, "--no-plots")
    check(sorted(os.listdir(out)) == [".asperity-output", "validation.md"], os.listdir(out))
    check(f"wrote {out}/ (validation.md)" in p.stderr, p.stderr)
    # The message for a missing gnuplot names the way out: --no-plots.
    env = dict(os.environ, PATH="/nonexistent")
    q = subprocess.run([exe, "validate", "--out", os.path.join(tmp, "w")], capture_output=True, text=True,
                       cwd=src, env=env, timeout=600)
    check(q.returncode == 2 and "--no-plots" in q.stderr, (q.returncode, q.stderr))
elif case == "model_case_insensitive":
    for name in ["BKE", "Bke"]:
        a = json.loads(run(*FLAT, "--model", name, "--json").stdout)
        check(a["model"] == "bke", a["model"])
    a = json.loads(run(*SPHERE, "--P", "35N", "--model", "ALL", "--json").stdout)
    check(sorted(a["models"]) == ["bke", "ceb", "cfc", "ke"], a["models"])
    a = json.loads(run(*SPHERE, "--P", "35N", "--model", "Ke", "--interference", "OWN", "--json").stdout)
    check(list(a["models"]) == ["ke"] and a["interference"] == "own", a)
elif case == "typo_suggestions":
    line = error_line(run("flatt", code=2))
    check('unknown command "flatt"' in line and 'did you mean "flat"' in line, line)
    line = error_line(run("frobnicate", code=2))
    check('unknown command "frobnicate"' in line and "did you mean" not in line and "sphere" in line, line)
    line = error_line(run(code=2))
    check("a command is required" in line, line)
    line = error_line(run("flat", "--jsn", code=2))
    check("unknown option --jsn of asperity flat" in line and "did you mean --json?" in line, line)
    line = error_line(run(*SPHERE, "--delta-maxx", "1um", code=2))
    check("did you mean --delta-max?" in line, line)
    line = error_line(run("predict", CASE, "--no-plot", code=2))
    check("did you mean --no-plots?" in line, line)
elif case == "error_prefix":
    # CLI11's own errors carry our prefix and point at --help.
    line = error_line(run("flat", "--points", "x", code=2))
    check("--points" in line and "asperity flat --help" in line, line)
    line = error_line(run("predict", code=2))
    check("asperity predict --help" in line, line)
elif case == "defaults_style":
    # One style: "(default: X)" in the description; no CLI11 "TEXT=X".
    for cmd in COMMANDS:
        h = run(cmd, "--help").stdout
        check(not re.search(r"(TEXT|INT|UINT|FLOAT)=\S", h), f"{cmd}: CLI11 default style:\n{h}")
        for m in re.finditer(r"default[^:]", h):
            ctx = h[max(0, m.start() - 1):m.end() + 10]
            check(False, f"{cmd}: default not written as '(default: X)': {ctx!r}")
elif case == "standard_output":
    # "-" is standard output for text outputs; the data alone is printed.
    p = run(*FLAT, "--loop", "-")
    check(p.stdout.startswith("delta_star,Q_star\n") and "rough flat" not in p.stdout, p.stdout[:200])
    p = run(*SPHERE, "--P", "35N", "--energy-curve", "-")
    check(p.stdout.startswith("model,delta_max[m],energy[J]\n"), p.stdout[:200])
    p = run("synthesize", CASE, "--imposed", "6.75um", "--out", "-")
    check(p.stdout.startswith("t[s],delta[um],Q[N],Delta[um]\n") and len(p.stdout.splitlines()) == 11002,
          p.stdout[:200])
    j = json.loads(run("predict", CASE, "--out", "-").stdout)
    check(len(j["loads"]) == 4, j.keys())
    # --out naming a .json file writes that file.
    f = os.path.join(tmp, "summary.json")
    p = run("predict", CASE, "--out", f)
    check(json.load(open(f))["loads"] == j["loads"] and f"wrote {f}" in p.stdout, p.stdout[-300:])
    f = os.path.join(tmp, "dyn.json")
    run("dynamics", "examples/dynamics/impulse_dankowicz.toml", "--out", f)
    check(json.load(open(f))["friction_model"] == "dankowicz", "dynamics --out FILE.json")
    # Two uses of stdout at once are refused.
    line = error_line(run(*FLAT, "--loop", "-", "--json", code=2))
    check("--json and --loop -" in line, line)
    line = error_line(run(*SPHERE, "--P", "35N", "--loop", "-", "--energy-curve", "-", code=2))
    check("standard output" in line, line)
    line = error_line(run(*SPHERE, "--P", "35N", "--plot", "-", code=2))
    check("--plot -" in line, line)
elif case == "wrote_line":
    # Every command that writes files says so with one "wrote ..." line.
    loop = os.path.join(tmp, "loop.csv")
    check(f"wrote {loop}\n" in run(*SPHERE, "--P", "35N", "--loop", loop).stdout, "sphere")
    hist, forces = os.path.join(tmp, "h.csv"), os.path.join(tmp, "q.csv")
    with open(hist, "w") as f:
        f.write("delta_star\n0\n0.3\n-0.3\n0.3\n")
    p = run(*FLAT[:-2], "--history", hist, "--out", forces)
    check(p.stdout.endswith(f"wrote {forces}\n"), p.stdout)
    p = run(*FLAT, "--loop", loop)
    check(f"wrote {loop}\n" in p.stdout, p.stdout)
    png = os.path.join(tmp, "r.png")
    p = run("roughness", "--surface", "examples/roughness/pzt_max.csv", "--plot", png)
    check(p.stdout.endswith(f"wrote {png}\n"), p.stdout)
    p = run("roughness", "--surface", "examples/roughness/pzt_max.csv", "--plot", png, "--json")
    json.loads(p.stdout)
    check(f"wrote {png}" in p.stderr, p.stderr)
    data = os.path.join(tmp, "d.csv")
    check(f"wrote {data} (" in run("synthesize", CASE, "--imposed", "6.75um", "--out", data).stdout, "synthesize")
    out = os.path.join(tmp, "an")
    p = run("analyze", data, "--P", "526N", "--out", out, "--no-plots")
    check(p.stdout.endswith(f"wrote {out}/ (analysis.json, cycles.csv, cycle_traces.csv, averaged_loop.csv)\n"),
          p.stdout[-300:])
    out = os.path.join(tmp, "dy")
    p = run("dynamics", "examples/dynamics/impulse_dankowicz.toml", "--out", out, "--no-plots")
    check(p.stdout.endswith(f"wrote {out}/ (summary.json, timeseries.csv, spectrum.csv)\n"), p.stdout[-300:])
elif case == "energy_unit_per_output":
    # predict: table, energy.csv and plot in uJ (JSON in J, SI).
    out = os.path.join(tmp, "p")
    p = run("predict", CASE, "--out", out, "--no-plots")
    rows = open(os.path.join(out, "energy.csv")).read().splitlines()
    check(rows[0].split(",")[3] == "energy[uJ]", rows[0])
    s = json.load(open(os.path.join(out, "summary.json")))
    e_json = s["loads"][0]["amplitudes"][0]["energy"]
    e_csv = float(rows[1].split(",")[3])
    # 12 significant digits in the CSV: equal to 1e-10 relative.
    check(abs(e_csv - e_json * 1e6) <= 1e-10 * abs(e_json * 1e6), (e_csv, e_json))
    check("energy[uJ]" in p.stdout, "table unit")
else:
    sys.exit(f"unknown case {case}")
