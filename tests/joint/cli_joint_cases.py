"""CLI cases of asperity predict / analyze / synthesize / validate (issue 5).

Usage: cli_joint_cases.py ASPERITY CASE SOURCE_DIR. Exit 0 on success.
"""
import atexit
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

exe, case, src = sys.argv[1], sys.argv[2], sys.argv[3]
ex = os.path.join(src, "examples", "joints")
tmp = tempfile.mkdtemp(prefix="asperity-joint-")
atexit.register(shutil.rmtree, tmp, ignore_errors=True)  # no directory left per run


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


def expect_refused(args, out):
    """--out names a directory asperity did not write: exit 2, the directory intact."""
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "precious.txt"), "w") as f:
        f.write("not asperity's")
    before = sorted(os.listdir(tmp))
    p = run(*args, "--out", out, code=2)
    check("did not write" in p.stderr and "choose another --out" in p.stderr, p.stderr)
    check(os.listdir(out) == ["precious.txt"], f"foreign directory touched: {os.listdir(out)}")
    check(open(os.path.join(out, "precious.txt")).read() == "not asperity's", "file changed")
    check(sorted(os.listdir(tmp)) == before, f"stray files: {sorted(os.listdir(tmp))}")


if case == "predict_example":
    out = os.path.join(tmp, "out")
    p = run("predict", os.path.join(ex, "steel420_two_bolts.toml"), "--out", out)
    check("0.34" in p.stdout and "partial slip" in p.stdout and "gross slip" in p.stdout, p.stdout)
    files = ["summary.json", "loops.csv", "energy.csv", "backbones.csv", "loops.png", "energy_vs_force.png",
             "mu_vs_preload.png", "stiffness_vs_preload.png"]
    for f in files:
        check(os.path.getsize(os.path.join(out, f)) > 0, f"missing {f}")
    check(f"wrote {out}/ ({', '.join(files)})" in p.stdout, p.stdout)
    check(os.path.exists(os.path.join(out, ".asperity-output")), "no marker")
    check(sorted(os.listdir(tmp)) == ["out"], f"stray files: {os.listdir(tmp)}")
elif case == "out_dir_safety":
    # An unrelated existing directory is refused and left intact, by every command.
    expect_refused(["predict", os.path.join(ex, "steel420_two_bolts.toml")], os.path.join(tmp, "precious"))
    expect_refused(["validate"], os.path.join(tmp, "docs"))
    data = synth("d.csv", "--imposed", "6.75um", "--P", "526N")
    expect_refused(["analyze", data, "--P", "526N"], os.path.join(tmp, "mine"))
    # A previous asperity output is replaced as a whole (its old files go).
    out = os.path.join(tmp, "out")
    run("predict", os.path.join(ex, "steel420_two_bolts.toml"), "--out", out)
    check(os.path.exists(os.path.join(out, "loops.png")), "first run wrote no plots")
    run("predict", os.path.join(ex, "steel420_two_bolts.toml"), "--out", out, "--no-plots")
    check(sorted(os.listdir(out)) == [".asperity-output", "backbones.csv", "energy.csv", "loops.csv",
                                      "summary.json"],
          f"not replaced: {sorted(os.listdir(out))}")
    # A nonexistent directory is created; an empty one is taken.
    new = os.path.join(tmp, "new")
    run("predict", os.path.join(ex, "steel420_two_bolts.toml"), "--out", new, "--no-plots")
    check(os.path.exists(os.path.join(new, "summary.json")), "not created")
    empty = os.path.join(tmp, "empty")
    os.makedirs(empty)
    run("predict", os.path.join(ex, "steel420_two_bolts.toml"), "--out", empty + "/", "--no-plots")
    check(os.path.exists(os.path.join(empty, "summary.json")), "empty directory not used")
    check(not [f for f in os.listdir(tmp) if f.startswith(".")], f"temporaries left: {os.listdir(tmp)}")
elif case == "predict_without_excitation":
    text = BASE[:BASE.index("[excitation]")]
    out = os.path.join(tmp, "out")
    p = run("predict", write_case(text), "--out", out)
    check("no [excitation]" in p.stdout, p.stdout)
    written = sorted(f for f in os.listdir(out) if not f.startswith("."))
    check(written == ["backbones.csv", "mu_vs_preload.png", "stiffness_vs_preload.png",
                      "summary.json"], written)
    check(f"wrote {out}/ (summary.json, backbones.csv, mu_vs_preload.png, stiffness_vs_preload.png)"
          in p.stdout,
          p.stdout)
elif case == "predict_sweep_files":
    # Chapter 5 joint from scans: Table 5.4 within 0.3 % (JointCase.ProfilesGiveTable54), so
    # its mu at 526 N is the BKE value of section 5.3 (0.335) within the 5 %, and
    # equals the parameter case's within 0.5 %.
    ref = json.loads(run("predict", write_case(BASE.replace(
        'bolts = { count = 2, total_torques = ["1.2 lbf*in", "1.7 lbf*in", "2.7 lbf*in", "3.7 lbf*in"], nut_factor = 0.2, diameter = "2.9 mm" }',
        'preload = "526 N"')), "--json").stdout)
    out = os.path.join(tmp, "prof")
    run("predict", os.path.join(ex, "steel420_profiles.toml"), "--out", out, "--no-plots")
    s = json.load(open(os.path.join(out, "summary.json")))
    check(abs(s["mu"] - 0.335) / 0.335 < 0.05, f"mu {s['mu']} vs 0.335 (section 5.3)")
    for k in ["mu", "stiffness", "Q_max"]:
        check(abs(s[k] - ref[k]) / ref[k] < 5e-3, f"{k}: scans {s[k]} vs parameters {ref[k]}")
    # Chapter 6 joints: the same mu as validate's Table 6.4 rows (built-in copies of these
    # files), to the report's 5 digits.
    md = run("validate").stdout
    labels = {"aluminium_smooth": "smooth Al", "aluminium_rough": "rough Al",
              "steel_smooth": "smooth St", "steel_rough": "rough St"}
    for name, label in labels.items():
        out = os.path.join(tmp, name)
        run("predict", os.path.join(ex, name + ".toml"), "--out", out, "--no-plots")
        s = json.load(open(os.path.join(out, "summary.json")))
        for load in s["loads"]:
            row = [l for l in md.splitlines() if l.startswith(f"| {label} dry mu at ") and f"({load['preload']:.0f} N)" in l]
            check(len(row) == 1, f"{name}: no Table 6.4 row for {load['preload']}")
            ours = float(row[0].split("|")[3])
            check(abs(load["mu"] - ours) / ours < 1e-4, f"{name}: mu {load['mu']} vs validate {ours}")
            check(load["stiffness"] > 0 and load["gross_slip_amplitude"] > 0, load)
            imposed = [a for a in load["amplitudes"] if "imposed" in a]
            check(len(imposed) == 8 and len(load["amplitudes"]) == 12, f"{name}: amplitudes")
            # Fig. 5.7 in series: delta + c Q_peak = imposed.
            c = 1 / 38e6 + 1 / 1462e6
            for a in imposed:
                check(abs(a["delta_max"] + c * a["Q_peak"] - a["imposed"]) < 1e-12, a)
            # The small joint amplitudes are in partial slip (slope 2-3 part of Fig. 6.12).
            check(all(a["regime"] == "partial slip" for a in load["amplitudes"][:3]), name)
elif case == "predict_long_sweep":
    # 40 preloads: one colour scale instead of 40 legend entries (looked at by eye).
    P = ", ".join(f'"{200 + 15 * i} N"' for i in range(40))
    text = BASE.replace(
        'bolts = { count = 2, total_torques = ["1.2 lbf*in", "1.7 lbf*in", "2.7 lbf*in", "3.7 lbf*in"], nut_factor = 0.2, diameter = "2.9 mm" }',
        f"preloads = [{P}]").replace('amplitudes = ["0.05 um", "0.1 um", "0.25 um", "0.5 um", "1 um", "2 um", "4 um"]',
                                   'amplitudes = ["0.1 um", "1 um"]')
    out = os.path.join(tmp, "sweep")
    run("predict", write_case(text), "--out", out)
    s = json.load(open(os.path.join(out, "summary.json")))
    check(len(s["loads"]) == 40, len(s["loads"]))
    for f in ["loops.png", "energy_vs_force.png", "mu_vs_preload.png"]:
        check(os.path.getsize(os.path.join(out, f)) > 0, f"missing {f}")
elif case == "predict_json_keys":
    p = run("predict", write_case(BASE.replace(
        'bolts = { count = 2, total_torques = ["1.2 lbf*in", "1.7 lbf*in", "2.7 lbf*in", "3.7 lbf*in"], nut_factor = 0.2, diameter = "2.9 mm" }',
        'preload = "526 N"')), "--json")
    s = json.loads(p.stdout)
    for k in ["preload", "mu", "stiffness", "Q_max", "separation", "amplitudes", "loads", "gross_slip_amplitude"]:
        check(k in s, f"summary lacks {k}")
    check(abs(s["preload"] - 526) < 1e-9, s["preload"])
    check(abs(s["mu"] - 0.335) / 0.335 < 0.05, f"mu {s['mu']} vs thesis 0.335")
    for a in s["amplitudes"]:
        check(set(["delta_max", "Q_peak", "energy", "regime"]) <= set(a), a)
        check((a["regime"] == "gross slip") == (a["delta_max"] >= s["gross_slip_amplitude"]), a)
    check(s["amplitudes"][0]["delta_max"] == 0.05e-6, s["amplitudes"][0])
elif case == "analyze_synthetic":
    # Seed 1, the default. Measured with the noise of core/random.hpp (issue 13) over seeds
    # 1-20: (k - k_model)/se has rms 1.36, not 1 (the standard error understates the
    # seed-to-seed spread by about a third), and seed 11, used here before the generator
    # changed, gives 3.09 > 3; seeds 10, 13, 18 give 2.2-2.6 (docs/joints.md).
    data = synth("d.csv", "--imposed", "6.75um", "--P", "526N", "--seed", "1")
    out = os.path.join(tmp, "an")
    p = run("analyze", data, "--P", "526N", "--model", os.path.join(ex, "steel420_two_bolts.toml"), "--json",
            "--out", out)
    j = json.loads(p.stdout)
    check(j["cycles"] == 9 and len(j["per_cycle"]) == 9, j["cycles"])
    for k in ["energy", "Q_max", "delta_max", "stiffness"]:
        check(k in j["mean"] and all(k in c for c in j["per_cycle"]), k)
    check(abs(j["mu"] - 0.3427) < 0.01 * 0.3427, f"mu {j['mu']}")  # model mu at 526 N: 0.3427
    check(abs(j["model"]["relative_difference"]["mu"]) < 0.01, j["model"])
    # The stiffness with its standard error; the mean is the harmonic mean of the cycles'.
    k, se = j["mean"]["stiffness"], j["standard_error"]["stiffness"]
    check(abs(k - j["model"]["stiffness"]) < 3 * se, f"k {k} +- {se} vs {j['model']['stiffness']}")
    ks = [c["stiffness"] for c in j["per_cycle"]]
    check(abs(k - len(ks) / sum(1 / x for x in ks)) < 1e-9 * k, "mean is not the harmonic mean")
    check(j["energy_resolved"] and isinstance(j["warnings"], list), j["warnings"])
    for f in ["analysis.json", "cycles.csv", "cycle_traces.csv", "averaged_loop.csv", "loops.png"]:
        check(os.path.getsize(os.path.join(out, f)) > 0, f"missing {f}")
    traces = open(os.path.join(out, "cycle_traces.csv")).read().splitlines()
    check(traces[0] == "run,cycle,t[s],delta[um],Q[N],Delta[um]", traces[0])
    check(len(traces) > 9 * 1000, f"{len(traces)} trace lines")
    # Text output: the standard errors are printed.
    p = run("analyze", data, "--P", "526N")
    check("+-" in p.stdout and "stiffness" in p.stdout, p.stdout)
elif case == "analyze_runs_power_law":
    # Noise-free runs: the exponent equals the Masing exponent of the model over the same
    # runs (the model's Q_peak and energy at each run's measured delta_max) to 1e-3: the
    # measured energies are all 0.11 % low (moving average), which cancels in the slope.
    files = [synth(f"r{i}.csv", "--imposed", a, "--P", "721N", "--noise-delta", "0um", "--noise-Q", "0N")
             for i, a in enumerate(["1um", "1.5um", "2um"])]
    j = json.loads(run("analyze", *files, "--P", "721N", "--json", "--model",
                       os.path.join(ex, "steel420_two_bolts.toml")).stdout)
    q = [math.log(r["model"]["Q_peak"]) for r in j["runs"]]
    e = [math.log(r["model"]["energy"]) for r in j["runs"]]
    qm, em = sum(q) / 3, sum(e) / 3
    n_model = sum((a - qm) * (b - em) for a, b in zip(q, e)) / sum((a - qm) ** 2 for a in q)
    check(len(j["runs"]) == 3 and abs(j["power_law_exponent"] - n_model) < 1e-3 * n_model,
          f"{j.get('power_law_exponent')} vs Masing {n_model}")
    check(j["power_law"]["runs_excluded"] == [], j["power_law"])
    # With the noise (0.1 um, 1 N) at 526 N: the thin loops of 0.5 and 1 um imposed
    # are below their noise floor and left out; the exponent of the others has an interval
    # that holds the model's.
    files = [synth(f"n{i}.csv", "--imposed", a, "--P", "526N", "--seed", str(i + 3))
             for i, a in enumerate(["0.5um", "1um", "2um", "3um", "4um"])]
    p = run("analyze", *files, "--P", "526N", "--json", "--model", os.path.join(ex, "steel420_two_bolts.toml"))
    j = json.loads(p.stdout)
    law = j["power_law"]
    check(law["runs_excluded"] == files[:2] and law["runs_used"] == files[2:], law)
    check("left out" in p.stderr, p.stderr)
    used = [r for r in j["runs"] if r["file"] in law["runs_used"]]
    q = [math.log(r["model"]["Q_peak"]) for r in used]
    e = [math.log(r["model"]["energy"]) for r in used]
    qm, em = sum(q) / len(q), sum(e) / len(e)
    n_model = sum((a - qm) * (b - em) for a, b in zip(q, e)) / sum((a - qm) ** 2 for a in q)
    check(law["ci95"][0] < n_model < law["ci95"][1], f"{law} vs Masing {n_model}")
    out = os.path.join(tmp, "pl")
    run("analyze", *files, "--P", "526N", "--out", out)
    check(os.path.getsize(os.path.join(out, "energy_vs_force.png")) > 0, "no energy plot")
elif case == "outputs_apart_from_inputs":
    # An output never names an input (nor holds one): exit 2, the input untouched.
    import shutil
    case_file = os.path.join(tmp, "c.toml")
    shutil.copy(os.path.join(ex, "steel420_two_bolts.toml"), case_file)
    original = open(case_file).read()

    def refused(args, needle):
        p = run(*args, code=2)
        check(needle in p.stderr, f"{args}: stderr lacks {needle!r}: {p.stderr}")
        check(p.stdout == "", p.stdout)
        check(open(case_file).read() == original, f"{args}: the case file was changed")

    refused(["synthesize", case_file, "--imposed", "6.75um", "--out", case_file],
            "the case file and --out both name")
    # The same file through another spelling of its path.
    refused(["synthesize", case_file, "--imposed", "6.75um", "--out",
             os.path.join(tmp, "sub", "..", "c.toml")], "both name")
    refused(["predict", case_file, "--out", case_file], 'names the case file')
    data = os.path.join(tmp, "d.csv")
    run("synthesize", case_file, "--imposed", "6.75um", "--out", data)
    data_text = open(data).read()
    refused(["analyze", data, "--P", "234N", "--out", data], "names the data file")
    refused(["analyze", data, "--P", "234N", "--model", case_file, "--out", case_file],
            "names the --model case file")
    check(open(data).read() == data_text, "the data file was changed")
    # An earlier asperity output that holds an input would be replaced as a whole.
    out = os.path.join(tmp, "out")
    run("predict", case_file, "--out", out, "--no-plots")
    inner = os.path.join(out, "c.toml")
    shutil.copy(case_file, inner)
    p = run("predict", inner, "--out", out, "--no-plots", code=2)
    check("holds the case file" in p.stderr and os.path.exists(inner), p.stderr)
    shutil.copy(data, os.path.join(out, "d.csv"))
    p = run("analyze", os.path.join(out, "d.csv"), "--P", "234N", "--out", out, code=2)
    check("holds the data file" in p.stderr and os.path.exists(os.path.join(out, "d.csv")), p.stderr)
    # A scan the case reads is an input too.
    scans = os.path.join(tmp, "scans")
    os.makedirs(scans)
    for f in ["pzt_max.csv", "pzt_min.csv", "lc_max.csv", "lc_min.csv"]:
        shutil.copy(os.path.join(src, "examples", "roughness", f), scans)
    prof = write_case(open(os.path.join(ex, "steel420_profiles.toml")).read().replace(
        "../roughness/", "scans/"), "prof.toml")
    scan = os.path.join(scans, "pzt_max.csv")
    scan_text = open(scan).read()
    p = run("synthesize", prof, "--imposed", "6.75um", "--out", scan, code=2)
    check("a profile of half 1 of the case and --out both name" in p.stderr, p.stderr)
    run("predict", prof, "--out", scans, code=2)
    check(open(scan).read() == scan_text, "a scan was changed")
elif case == "synthesize_limits":
    cf = os.path.join(ex, "steel420_two_bolts.toml")
    out = os.path.join(tmp, "s.csv")
    # 1e15 samples: refused at once with the flags and the limit named (was: bad_alloc, 134).
    p = run("synthesize", cf, "--imposed", "6.75um", "--rate", "1e9Hz", "--cycles", "1000000",
            "--out", out, code=2)
    check("--rate = 1e9Hz" in p.stderr and "--cycles = 1000000" in p.stderr and
          "limit of 1e+07" in p.stderr, p.stderr)
    # 1 sample per period (was: 12 samples written): at least 50 per period.
    p = run("synthesize", cf, "--imposed", "6.75um", "--rate", "1Hz", "--out", out, code=2)
    check("--rate = 1Hz gives 1 samples per period at --frequency = 1Hz" in p.stderr and
          "--rate >= 50 Hz" in p.stderr, p.stderr)
    run("synthesize", cf, "--imposed", "6.75um", "--rate", "49Hz", "--out", out, code=2)
    check(not os.path.exists(out), "a file was written on error")
    # The bound itself: 50 Hz at 1 Hz, 11 s -> 551 samples, which analyze can read.
    p = run("synthesize", cf, "--imposed", "6.75um", "--rate", "50Hz", "--out", out)
    check("551 samples" in p.stdout, p.stdout)
    run("analyze", out, "--P", "234N")
    for flag, value in [("--frequency", "0Hz"), ("--P", "-1N"), ("--imposed", "0um"),
                        ("--cycles", "0")]:
        p = run("synthesize", cf, "--imposed", "6.75um", flag, value, "--out", out, code=2)
        check(flag in p.stderr, p.stderr)
elif case == "out_of_memory":
    # Memory exhausted (address space limited to 200 MB; 9e6 samples need 4 x 72 MB):
    # a message and exit 2 (README), not an abort; nothing written.
    import resource

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (200 << 20, 200 << 20))

    out = os.path.join(tmp, "big.csv")
    p = subprocess.run([exe, "synthesize", os.path.join(ex, "steel420_two_bolts.toml"),
                        "--imposed", "6.75um", "--rate", "818kHz", "--out", out],
                       capture_output=True, text=True, preexec_fn=limit)
    check(p.returncode == 2 and "out of memory" in p.stderr,
          f"exit {p.returncode}: {p.stderr}")
    check(not os.path.exists(out) and os.listdir(tmp) == [], os.listdir(tmp))
elif case == "analyze_power_law_note":
    # Noise-free runs at 526 N, all in partial slip by the model (Q/Q_s 0.59-1.0): the
    # exponent is above 3 as the model's is near saturation; no run is called gross slip.
    cf = os.path.join(ex, "steel420_two_bolts.toml")
    files = [synth(f"q{a}.csv", "--imposed", f"{a}um", "--P", "526N", "--noise-delta",
                   "0um", "--noise-Q", "0N") for a in (3, 5, 8, 12)]
    p = run("analyze", *files[:3], "--P", "526N", "--model", cf, "--json")
    j = json.loads(p.stdout)
    check(all(r["model"]["regime"] == "partial slip" for r in j["runs"]), j["runs"])
    law = j["power_law"]
    check(law["exponent"] > 3 and "at or above 3" in law["note"] and "Q_s" in law["note"], law)
    check(j["warnings"] == [] and "gross slip" not in p.stderr, (j["warnings"], p.stderr))
    p = run("analyze", *files[:3], "--P", "526N")
    check("note: n = " in p.stdout and "warning" not in p.stdout, p.stdout)
    # With a run the model puts in gross slip (12 um imposed): a warning naming it.
    p = run("analyze", *files[1:], "--P", "526N", "--model", cf, "--json")
    j = json.loads(p.stdout)
    check(any(files[3] in w and "gross slip" in w for w in j["warnings"]), j["warnings"])
    check(files[3] in p.stderr, p.stderr)
elif case == "predict_energy_csv_imposed":
    # Amplitudes given directly have no imposed value: an empty field, not 0; the JSON
    # leaves the key out.
    out = os.path.join(tmp, "ss")
    run("predict", os.path.join(ex, "steel_smooth.toml"), "--out", out, "--no-plots")
    rows = open(os.path.join(out, "energy.csv")).read().splitlines()
    check(rows[0].endswith(",imposed[um]"), rows[0])
    cells = [r.split(",") for r in rows[1:]]
    check(all(len(c) == 7 for c in cells), rows)
    direct = [c for c in cells if c[6] == ""]
    imposed = [c for c in cells if c[6] != ""]
    check(len(direct) == 3 * 4 and len(imposed) == 3 * 8, (len(direct), len(imposed)))
    check(all(float(c[6]) > 0 for c in imposed), imposed)
    s = json.load(open(os.path.join(out, "summary.json")))
    amps = s["loads"][0]["amplitudes"]
    check(sum("imposed" in a for a in amps) == 8, amps)
elif case == "predict_profile_provenance":
    # summary.json of a case from scans records the files, the processing and each half's
    # parameters; the halves' m0 add to the combined one (Eq. 5.1).
    out = os.path.join(tmp, "prof")
    p = run("predict", os.path.join(ex, "steel420_profiles.toml"), "--out", out, "--no-plots")
    check("half 1: sigma = 1.763 um" in p.stdout and "pzt_max.csv" in p.stdout, p.stdout)
    r = json.load(open(os.path.join(out, "summary.json")))["roughness"]
    h = r["halves"]
    check([x["source"] for x in h] == ["profiles", "profiles"], h)
    check([os.path.basename(f["file"]) for f in h[0]["profiles"]] == ["pzt_max.csv", "pzt_min.csv"]
          and [os.path.basename(f["file"]) for f in h[1]["profiles"]] == ["lc_max.csv", "lc_min.csv"], h)
    check({f["direction"] for f in h[0]["profiles"]} == {"max_slope", "min_slope"}, h)
    proc = r["processing"]
    check(proc["level"] == "line" and proc["rule"] == "geometric" and proc["end"] == "discard"
          and abs(proc["lc"] - 0.8e-3) < 1e-12 and abs(proc["ls"] - 20e-6) < 1e-12, proc)
    # Table 5.4: PZT half 1.763 um, load-cell half 2.015 um (the scans reproduce it to 0.3 %).
    check(abs(h[0]["sigma"] - 1.763e-6) < 3e-3 * 1.763e-6 and
          abs(h[1]["sigma"] - 2.015e-6) < 3e-3 * 2.015e-6, h)
    for m in ["m0", "m2", "m4"]:  # Eq. 5.1: moments add (round-off only)
        check(abs(h[0][m] + h[1][m] - r[m]) < 1e-12 * r[m], (m, r))
    # A case from parameters says so and has no processing block.
    s = json.loads(run("predict", os.path.join(ex, "steel420_two_bolts.toml"), "--json").stdout)
    check([x["source"] for x in s["roughness"]["halves"]] == ["parameters"] * 2 and
          "processing" not in s["roughness"], s["roughness"])
elif case == "validate_report":
    out = os.path.join(tmp, "val")
    p = run("validate", "--out", out)
    md = open(os.path.join(out, "validation.md")).read()
    check("| FAIL |" not in md and "| mu at 526 N | 0.335 |" in md, "report incomplete")
    check(p.stdout == md, "stdout differs from the file")
    for f in ["ch5_loops.png", "ch5_energy_vs_force.png", "ch5_mu_vs_preload.png", "ch5_stiffness_vs_preload.png",
              "ch5_stiffness_variants.png", "ch6_stiffness_variants.png", "ch6_exponent_vs_preload.png"]:
        check(os.path.getsize(os.path.join(out, f)) > 0, f"missing {f}")
elif case == "validate_docs_current":
    p = run("validate")
    doc = open(os.path.join(src, "docs", "validation.md")).read()
    check(p.stdout == doc, "docs/validation.md is out of date: regenerate it with "
          "`asperity validate > docs/validation.md`")
elif case == "bad.unknown_key":
    bad_case(BASE.replace('model = "bke"', 'modle = "bke"'), "joint.modle", "unknown key", "case.toml:8:")
elif case == "bad.reference_count":
    # [reference] (published mu drawn on mu_vs_preload.png): one mu per preload.
    bad_case(BASE.replace("mu = [0.354, 0.334, 0.335, 0.347]", "mu = [0.354, 0.334]"),
             "reference.mu", "2 values for 4 preloads")
elif case == "bad.wrong_unit":
    bad_case(BASE.replace('area = "170 mm^2"', 'area = "3 N"'), "joint.area", "case.toml:7:")
elif case == "bad.missing_half":
    i = BASE.index("[[joint.half]]", BASE.index("[[joint.half]]") + 1)
    bad_case(BASE[:i] + BASE[BASE.index("[load]"):], "joint.half", "two")
elif case == "bad.negative_torque":
    # The value as the user typed it, with file, line and key.
    bad_case(BASE.replace('"1.2 lbf*in"', '"-1.2 lbf*in"'),
             'case.toml:24: load.bolts.total_torques[1] = "-1.2 lbf*in": must be > 0')
elif case == "bad.no_partial_output":
    # Fails after the case is read: the preload is beyond the model's range; the error
    # names where that load case came from.
    bad_case(BASE.replace('"3.7 lbf*in"', '"3e6 lbf*in"'),
             'case.toml:24: load.bolts.total_torques[4] = "3e6 lbf*in": preload = ')
elif case == "bad.nu_string":
    bad_case(BASE.replace("nu = 0.24, G", 'nu = "0.24", G', 1),
             'case.toml:12: joint.half[1].material.nu = "0.24": a dimensionless value is a bare number')
elif case == "bad.nu_with_unit":
    # A unit on a dimensionless value: drop it (not "write nu = 0.24 GPa").
    bad_case(BASE.replace("nu = 0.24, G", 'nu = "0.24 GPa", G', 1),
             'joint.half[1].material.nu = "0.24 GPa": nu is dimensionless and takes no unit: '
             'write nu = 0.24 (no quotes, no "GPa")')
elif case == "bad.profile_too_short":
    # The hint names the case file's key, not `asperity roughness`'s --end flag.
    rows = open(os.path.join(src, "examples", "roughness", "pzt_max.csv")).read().splitlines()[:1200]
    with open(os.path.join(tmp, "short.csv"), "w") as f:
        f.write("\n".join(rows) + "\n")
    text = open(os.path.join(ex, "steel420_profiles.toml")).read().replace(
        '"../roughness/pzt_max.csv", "../roughness/pzt_min.csv"', '"short.csv"').replace(
        "../roughness/", os.path.join(src, "examples", "roughness") + "/")
    p = run("predict", write_case(text), code=2)
    check('end = "regression" in [profiles]' in p.stderr and "--end" not in p.stderr, p.stderr)
    s = json.loads(run("predict", write_case(text.replace('rule = "geometric"',
                                                          'rule = "geometric"\nend = "regression"')),
                       "--json").stdout)
    check(s["roughness"]["processing"]["end"] == "regression", s["roughness"])
elif case.startswith("bad.data"):
    rows = [(i * 0.01, 1e-6 * math.sin(2 * math.pi * i * 0.01), 100 * math.sin(2 * math.pi * i * 0.01))
            for i in range(500)]
    header = "t[s],delta[m],Q[N]"
    needle = ""
    if case == "bad.data_gap":
        rows = rows[:200] + rows[260:]
        needle = "data.csv:202: a gap in time (1.99 s to 2.6 s, a step of 0.61 s where the median step is 0.01 s)"
    elif case == "bad.data_time_backwards":
        rows[100] = (rows[98][0],) + rows[100][1:]
        needle = "data.csv:102: time t = 0.98 s does not increase"  # header on line 1
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
elif case == "predict_bolt_field":
    # Issue 11: the ch. 5 joint under its two bolts' pressure cones, in 170 patches.
    out = os.path.join(tmp, "bf")
    p = run("predict", os.path.join(ex, "steel420_bolt_field.toml"), "--out", out)
    check("slip[%]" in p.stdout and "loaded patches" in p.stdout, p.stdout)
    s = json.load(open(os.path.join(out, "summary.json")))
    check(s["interface"]["pressure"] == "bolted" and s["interface"]["patches"] == [17, 10], s["interface"])
    for load in s["loads"]:
        forces = sum(q["force"] for q in load["patches"])
        check(abs(forces - load["preload"]) < 1e-9 * load["preload"], (forces, load["preload"]))
        for a in load["amplitudes"]:
            check(len(a["patch_gross_slip"]) == len(load["patches"]), "slip map size")
            check((a["exponent"] is None) == (a["regime"] == "gross slip") or a["exponent"] is not None,
                  a)
    for f in ["patches.csv", "pressure_map.png", "slip_map.png"]:
        check(os.path.getsize(os.path.join(out, f)) > 0, f"missing {f}")
    # A case without [interface] writes none of them and no patch keys (today's output).
    u = os.path.join(tmp, "u")
    run("predict", os.path.join(ex, "steel420_two_bolts.toml"), "--out", u, "--no-plots")
    check(not os.path.exists(os.path.join(u, "patches.csv")), "patches.csv for a uniform case")
    check("patches" not in json.load(open(os.path.join(u, "summary.json")))["loads"][0], "patch keys")
elif case == "flat_case_history":
    # flat --case: Masing on the case's backbone (with its [interface]); on the virgin curve
    # the force is predict's Q_peak at the same amplitude (the same table: 1e-12).
    hist = os.path.join(src, "examples", "flat", "history.csv")
    x1 = float(open(hist).read().split()[2]) * 1e-6  # the first step, delta[um]
    for name in ["steel420_two_bolts.toml", "steel420_bolt_field.toml"]:
        text = open(os.path.join(ex, name)).read()
        text = text.replace('amplitudes = ["0.05 um"', f'amplitudes = ["{x1 * 1e6!r} um", "0.05 um"')
        s = json.loads(run("predict", write_case(text), "--json").stdout)
        ld = s["loads"][2]  # 526 N (Table 5.5's 2.7 lbf in)
        out = os.path.join(tmp, "f.csv")
        run("flat", "--case", os.path.join(ex, name), "--P", f"{ld['preload']!r}N", "--history", hist,
            "--out", out)
        rows = [l.split(",") for l in open(out).read().split()[1:]]
        check(abs(float(rows[1][0]) - x1) < 1e-18, (rows[1], x1))
        q1 = float(rows[1][1])
        a = [a for a in ld["amplitudes"] if abs(a["delta_max"] - x1) < 1e-15][0]
        check(abs(a["Q_peak"] - q1) < 1e-12 * q1, (name, a["Q_peak"], q1))
        qmax = max(abs(float(r[1])) for r in rows)
        check(qmax <= ld["Q_max"] * (1 + 1e-12), (name, qmax, ld["Q_max"]))
    # a sweep needs --P; flat's own inputs do not mix with --case
    p = run("flat", "--case", os.path.join(ex, "steel420_two_bolts.toml"), "--history", hist,
            "--out", os.path.join(tmp, "g.csv"), code=2)
    check("choose one with --P" in p.stderr, p.stderr)
    p = run("flat", "--case", os.path.join(ex, "steel420_two_bolts.toml"), "--P", "526N", "--beta", "0.04",
            "--history", hist, "--out", os.path.join(tmp, "g.csv"), code=2)
    check("--case takes the joint from the case file" in p.stderr, p.stderr)
elif case.startswith("bad.interface_"):
    bolted = open(os.path.join(ex, "steel420_bolt_field.toml")).read()
    if case == "bad.interface_bolt_outside":
        bad_case(bolted.replace('["12.75 mm", "5 mm"]', '["16.5 mm", "5 mm"]'),
                 "interface.bolts.positions[2]", "must lie inside the outline")
    elif case == "bad.interface_patches_too_small":
        bad_case(bolted.replace("patches = [17, 10]", "patches = [170, 100]"),
                 "holds fewer than 100 asperities")
    elif case == "bad.interface_map_not_covering":
        m_dir = tempfile.mkdtemp(prefix="asperity-map-")  # apart from tmp
        atexit.register(shutil.rmtree, m_dir, ignore_errors=True)
        m = os.path.join(m_dir, "map.csv")
        with open(m, "w") as f:
            f.write("x[mm],y[mm],p[MPa]\n0,0,1\n12,0,1\n0,10,1\n12,10,1\n")
        text = BASE + f'\n[interface]\npressure = "map"\nsize = ["17 mm", "10 mm"]\npatches = [4, 2]\nmap = "{m}"\n'
        bad_case(text, "does not cover the interface", "[0, 17] x [0, 10] mm")
    elif case == "bad.interface_map_negative":
        m = write_case("x[mm],y[mm],p[MPa]\n0,0,1\n17,0,-1\n0,10,1\n17,10,1\n", "map.csv")
        text = BASE + '\n[interface]\npressure = "map"\nsize = ["17 mm", "10 mm"]\npatches = [4, 2]\nmap = "map.csv"\n'
        p = run("predict", write_case(text), "--out", os.path.join(tmp, "out"), code=2)
        check("must be >= 0" in p.stderr and "map.csv" in p.stderr, p.stderr)
        check(not os.path.exists(os.path.join(tmp, "out")), "an output directory was left behind")
    else:
        sys.exit(f"unknown case {case}")
else:
    sys.exit(f"unknown case {case}")
print("ok")
