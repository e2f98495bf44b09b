#!/usr/bin/env python3
"""Behaviour of `asperity roughness`: the shipped example (Table 5.4 from synthetic scans
of the two milled halves), the README command, --plot, ls = 5 dx, and bad input (exit
2, a message naming the file and the problem, nothing on stdout).

Usage: roughness_cases.py ASPERITY_EXE SOURCE_DIR CASE. Standard library only.
"""
import json
import os
import random
import struct
import zipfile
import subprocess
import sys
import tempfile

from summit_table import linear_moments


def run(exe, argv):
    return subprocess.run([exe, "roughness"] + argv, capture_output=True, text=True, timeout=120)


def fail(msg):
    print("FAIL:", msg, file=sys.stderr)
    return 1


def bad(exe, argv, must_contain):
    """Exit 2, nothing on stdout, and a message naming every fragment (the file and
    the problem)."""
    r = run(exe, argv)
    if r.returncode != 2:
        return fail(f"expected exit 2, got {r.returncode}: {r.stderr}")
    if r.stdout:
        return fail(f"stdout not empty: {r.stdout!r}")
    for text in ([must_contain] if isinstance(must_contain, str) else must_contain):
        if text.lower() not in r.stderr.lower():
            return fail(f"message does not mention {text!r}: {r.stderr}")
    return 0


def main():
    with tempfile.TemporaryDirectory() as tmp:
        return check(sys.argv[1], sys.argv[2], sys.argv[3], tmp)


def check(exe, src, case, tmp):
    ex = os.path.join(src, "examples", "roughness")

    def write(name, text):
        p = os.path.join(tmp, name)
        with open(p, "w") as f:
            f.write(text)
        return p

    def write_bytes(name, data):
        p = os.path.join(tmp, name)
        with open(p, "wb") as f:
            f.write(data)
        return p

    if case == "table_5_4_example":
        r = run(exe, ["--surface", f"{ex}/pzt_max.csv,{ex}/pzt_min.csv",
                      "--surface", f"{ex}/lc_max.csv,{ex}/lc_min.csv",
                      "--E", "200GPa", "--nu", "0.24", "--H", "5.8GPa", "--json"])
        if r.returncode != 0:
            return fail(r.stderr)
        j = json.loads(r.stdout)
        c = j["combined"]
        # Table 5.4 combined column (before experiments): 2.677 um, 2.91e-4 um^-2, 30.14 um;
        # psi 4.725 (section 5.3). Printed to 3-4 digits: 0.5 % on sigma and R, one unit
        # of the last digit on eta, 1 % on psi (the tolerance).
        checks = [(c["sigma"], 2.677e-6, 5e-3), (c["R"], 30.14e-6, 5e-3),
                  (c["eta"], 2.91e8, 0.01 / 2.91 + 1e-3), (c["psi"], 4.725, 0.01)]
        for got, want, tol in checks:
            if abs(got - want) / want > tol:
                return fail(f"{got} vs {want}")
        for key in ("sigma", "eta", "R", "beta", "alpha", "m0", "m2", "m4", "filter"):
            if key not in c:
                return fail(f"combined lacks {key}")
        return 0
    x3p = os.path.join(src, "tests", "data", "x3p")
    sys.path.insert(0, x3p)
    import make_fixtures as fx  # builds X3P files with zipfile, struct, hashlib

    def x3p_file(name, members):
        p = os.path.join(tmp, name)
        fx.write_archive(p, members, zipfile.ZIP_DEFLATED)
        return p

    def tampered(name, change):
        members = dict(fx.prf_int16_offset())
        change(members)
        return x3p_file(name, list(members.items()))

    def grid(n, first=0):
        return "".join(f"{i},{0.1 * (i % 7):.1f}\n" for i in range(first, first + n))

    # case: (file, fragments the message must name besides the file)
    cases = {
        "empty_file": (lambda: write("empty.csv", ""), ["empty"]),
        "single_point": (lambda: write("one.csv", "x[um],z[um]\n0,1\n"), ["only 1 data point", "at least 2"]),
        "nan_height": (lambda: write("nan.csv", "x[um],z[um]\n" + "".join(f"{i},{'nan' if i == 5 else 0.1}\n" for i in range(3000))), ["line 7", "not a finite number"]),
        "unknown_unit": (lambda: write("unit.csv", "x[um],z[furlong]\n" + "".join(f"{i},0.1\n" for i in range(3000))), ["no known length unit"]),
        "decreasing_x": (lambda: write("dec.csv", "x[um],z[um]\n" + "".join(f"{3000 - i},0.1\n" for i in range(3000))), ["line 3", "does not increase"]),
        # 1500 points at 1 um, then 2 um: the first x off the grid is on line 1503.
        "non_uniform_x": (lambda: write("nonuni.csv", "x[um],z[um]\n" + "".join(f"{i if i < 1500 else 1500 + 2 * (i - 1500)},{0.1 * (i % 7):.1f}\n" for i in range(3000))), ["line 1503", "not uniformly spaced"]),
        # An instrument message between two blocks: refused, not half the data dropped.
        "data_break": (lambda: write("lifted.csv", "x[um],z[um]\n" + grid(5000) + "ERROR: stylus lifted\n" + grid(1000, 5000)), ["line 5002", "not a number inside the data", "stylus lifted"]),
        "too_short_for_filter": (lambda: write("short.csv", "x[um],z[um]\n" + "".join(f"{i},{(i % 7) * 0.1}\n" for i in range(200))), ["shorter than the filter needs"]),
        "corrupt_x3p": (lambda: write("bad.x3p", "PK\x03\x04 not really a zip"), ["zip"]),
        "wrong_md5": (lambda: tampered("md5.x3p", lambda m: m.update({"bindata/data.bin": b"\x01" + m["bindata/data.bin"][1:]})), ["bindata/data.bin", "MD5 checksum mismatch"]),
        "missing_entry": (lambda: tampered("missing.x3p", lambda m: m.pop("bindata/data.bin")), ["bindata/data.bin", "missing from the archive"]),
        "absurd_size": (lambda: tampered("absurd.x3p", lambda m: m.update({"main.xml": m["main.xml"].replace(b"<SizeX>7</SizeX>", b"<SizeX>1000000000</SizeX>")})), ["SizeX", "1000000000", "is not a size between 1 and"]),
        "huge_main_xml": (lambda: tampered("huge.x3p", lambda m: m.update({"main.xml": m["main.xml"] + b" " * (65 << 20)})), ["main.xml", "more than the 64 MiB allowed"]),
        "inline_not_integer": (lambda: x3p_file("inline.x3p", [("main.xml", fx.prf_datalist_empty()[0][1].replace(b"<DataType>D</DataType><Increment>1</Increment>", b"<DataType>L</DataType><Increment>1</Increment>"))]), ["DataList Datum 1", "is not an integer"]),
        "random_bytes": (lambda: write_bytes("random.dat", random.Random(7).randbytes(4096)), ["not a text profile"]),
        "random_zip_bytes": (lambda: write_bytes("random.x3p", b"PK\x03\x04" + random.Random(8).randbytes(4096)), ["zip archive"]),
    }
    if case in cases:
        make, fragments = cases[case]
        path = make()
        return bad(exe, ["--surface", path], [path] + fragments)
    if case == "ls_5um":
        # ls = 5 dx exactly on the shipped 1 um scan: accepted, dx reported as 1e-06.
        r = run(exe, ["--surface", f"{ex}/pzt_min.csv", "--ls", "5um", "--json"])
        if r.returncode != 0:
            return fail(r.stderr)
        scan = json.loads(r.stdout)["surfaces"][0]["scans"][0]
        if scan["dx"] != 1e-6:
            return fail(f"dx = {scan['dx']!r}, expected 1e-06")
        return 0
    if case in ("plot_dektak", "plot_example"):
        png = os.path.join(tmp, "out.png")
        argv = (["--surface", os.path.join(src, "tests", "data", "dektak-1.csv"), "--lc", "0.25mm", "--ls", "2.5um"]
                if case == "plot_dektak" else
                ["--surface", f"{ex}/pzt_max.csv,{ex}/pzt_min.csv", "--surface", f"{ex}/lc_max.csv,{ex}/lc_min.csv"])
        r = run(exe, argv + ["--plot", png])
        if r.returncode != 0:
            return fail(r.stderr)
        with open(png, "rb") as f:
            head = f.read(24)
        # PNG signature, then the IHDR chunk: width and height (the four panels).
        if head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
            return fail("not a PNG")
        if struct.unpack(">II", head[16:24]) != (1400, 1000):
            return fail(f"size {struct.unpack('>II', head[16:24])}")
        return 0
    if case == "readme_command":
        # The roughness command of README.md, run as written (from the source tree).
        r = subprocess.run([exe, "roughness", "--surface", "examples/roughness/pzt_max.csv,examples/roughness/pzt_min.csv",
                            "--surface", "examples/roughness/lc_max.csv,examples/roughness/lc_min.csv", "--json"],
                           capture_output=True, text=True, timeout=120, cwd=src)
        if r.returncode != 0:
            return fail(r.stderr)
        c = json.loads(r.stdout)["combined"]
        # Table 5.4 combined sigma and R (printed to 4 digits: 0.5 %).
        for got, want in ((c["sigma"], 2.677e-6), (c["R"], 30.14e-6)):
            if abs(got - want) / want > 5e-3:
                return fail(f"{got} vs {want}")
        return 0
    if case == "bad_params":
        return bad(exe, ["--params", "sigma=1um,eta=abc,R=40um"], "eta")
    if case == "negative_params":
        # The flag occurrence and the user's own text, not "sigma = -1e-06".
        return bad(exe, ["--params", "sigma=1um,eta=3e-4um^-2,R=40um",
                         "--params", "sigma=-1um,eta=3e-4um^-2,R=40um"],
                   ["--params #2", 'sigma = "-1um"', "must be > 0"])
    if case == "plot_overwrites_input":
        # An output naming an input (plain, through "..", or with a @max tag) is refused
        # before anything is written: the input is left as it was.
        with open(f"{ex}/pzt_min.csv", "rb") as f:
            original = f.read()
        inp = write_bytes("pm.csv", original)
        os.mkdir(os.path.join(tmp, "sub"))
        for surfaces, plot, label in (
                (["--surface", inp], inp, "--surface #1"),
                (["--surface", f"{ex}/pzt_max.csv", "--surface", inp],
                 os.path.join(tmp, "sub", "..", "pm.csv"), "--surface #2"),
                (["--surface", f"{ex}/pzt_max.csv@max,{inp}@min"], inp, "--surface #1")):
            if bad(exe, surfaces + ["--plot", plot], [label, "--plot", "would overwrite an input file"]):
                return 1
            with open(inp, "rb") as f:
                if f.read() != original:
                    return fail("the input file was changed")
        return 0
    if case == "plot_is_directory":
        return bad(exe, ["--surface", f"{ex}/pzt_min.csv", "--plot", tmp],
                   ["--plot", tmp, "is a directory"])
    if case == "flat_profile":
        # z = 0.001 x exactly (the heights are x scaled by 1e-3: x in mm, z in um): only
        # round-off is left after levelling; it used to give R = 4.6e17 um.
        path = write("line.csv", "x[mm],z[um]\n" + "".join(f"{i * 0.0003:.4f},{i * 0.0003:.4f}\n" for i in range(5000)))
        for extra, step in ((["--filter", "none"], "flat after levelling (line)"),
                            (["--lc", "0.25mm"], "flat after levelling (line) and filtering")):
            if bad(exe, ["--surface", path] + extra, [path, step, "round-off"]):
                return 1
        return 0
    if case == "dektak_default_filter":
        # 1.5 mm is too short for lc = 0.8 mm; the message names the longest lc that fits
        # (9600 points of 0.15625 um, ls = 20 um: 0.486 mm, see roughness_test.cpp) and the
        # documented command works.
        dektak = os.path.join(src, "tests", "data", "dektak-1.csv")
        if bad(exe, ["--surface", dektak], [dektak, "shorter than the filter needs",
                                            "a shorter lc (--lc): this profile allows up to 0.486 mm",
                                            "0.25 mm"]):
            return 1
        for argv in (["--lc", "0.486mm"], ["--lc", "0.25mm", "--ls", "2.5um"]):
            r = run(exe, ["--surface", dektak, "--json"] + argv)
            if r.returncode != 0:
                return fail(f"{argv}: {r.stderr}")
        return 0
    if case == "x3p_no_valid_points":
        # Every point masked: said as such, also without a filter (it used to ask for a
        # shorter --lc).
        def all_masked(m):
            m["bindata/valid.bin"] = b"\0\0"
            m["main.xml"] = m["main.xml"].replace(fx.md5(fx.mask_bytes(15, fx.SUR_INVALID)).encode(),
                                                  fx.md5(b"\0\0").encode())
        members = dict(fx.sur_int32_mask())
        all_masked(members)
        path = x3p_file("masked.x3p", list(members.items()))
        for extra in ([], ["--filter", "none"]):
            if bad(exe, ["--surface", path] + extra, [path, "holds no valid points", "all 5 x 3 are invalid"]):
                return 1
            r = run(exe, ["--surface", path] + extra)
            if "--lc" in r.stderr:
                return fail(f"asks for a shorter --lc: {r.stderr}")
        return 0
    if case == "json_cutoffs_as_typed":
        # The cut-offs are echoed as the decimals given (20um is 2e-05 m, not
        # 1.9999999999999998e-05 m).
        for argv, lc, ls in (([], 0.0008, 2e-05), (["--lc", "0.25mm", "--ls", "8um"], 0.00025, 8e-06),
                             (["--lc", "800um", "--ls", "0.02mm"], 0.0008, 2e-05)):
            r = run(exe, ["--surface", f"{ex}/pzt_min.csv", "--json"] + argv)
            if r.returncode != 0:
                return fail(r.stderr)
            f = json.loads(r.stdout)["surfaces"][0]["filter"]
            if repr(f["lc"]) != repr(lc) or repr(f["ls"]) != repr(ls):
                return fail(f"{argv}: lc = {f['lc']!r}, ls = {f['ls']!r}")
        return 0
    if case == "x3p_refusal_names_pair":
        # The default filter does not fit the 83 x 204 um X3P; the refusal names a cut-off
        # pair, and that pair gives the moments and the ISO 25178-2 parameters.
        x3p = os.path.join(src, "tests", "data", "mountainsmap-650x650.x3p")
        if bad(exe, ["--surface", x3p], [x3p, "a cut-off pair that fits: --lc"]):
            return 1
        words = run(exe, ["--surface", x3p]).stderr.split("a cut-off pair that fits: ")[1].split()
        lc, ls = words[1], words[3]
        r = run(exe, ["--surface", x3p, "--lc", lc, "--ls", ls, "--json"])
        if r.returncode != 0:
            return fail(f"the named pair {lc}, {ls} is refused: {r.stderr}")
        a = json.loads(r.stdout)["surfaces"][0]["areal_parameters"]
        if a is None or not a["Sq"] > 0:
            return fail(f"no areal parameters: {r.stdout}")
        return 0
    if case == "psd_outputs":
        # The PSD CSV integrates to each scan's m0 (Parseval; the CSV's 12 digits allow
        # 1e-9), the plot is a PNG.
        csv_path, png_path = os.path.join(tmp, "psd.csv"), os.path.join(tmp, "psd.png")
        r = run(exe, ["--surface", f"{ex}/pzt_max.csv,{ex}/pzt_min.csv", "--json",
                      "--psd", csv_path, "--psd-plot", png_path])
        if r.returncode != 0:
            return fail(r.stderr)
        scans = json.loads(r.stdout)["surfaces"][0]["scans"]
        spectra = {}
        with open(csv_path) as f:
            if f.readline().strip() != "surface,spectrum,profiles,f[1/m],psd[m^3]":
                return fail("PSD header")
            for line in f:
                label = line.split('"')[1]
                fr, p = map(float, line.strip().split(",")[-2:])
                spectra.setdefault(label, []).append((fr, p))
        if len(spectra) != 2:
            return fail(f"spectra: {list(spectra)}")
        for sc in scans:
            rows = [v for k, v in spectra.items() if k.endswith(os.path.basename(sc["file"]))][0]
            total = sum(p for _, p in rows) * (rows[1][0] - rows[0][0])  # sum psd * df
            if abs(total / sc["m0"] - 1) > 1e-9:
                return fail(f"{sc['file']}: sum psd df = {total}, m0 = {sc['m0']}")
        with open(png_path, "rb") as f:
            if f.read(8) != b"\x89PNG\r\n\x1a\n":
                return fail("psd.png is not a PNG")
        return 0
    if case == "spikes":
        # Three 40 um spikes in the 1.76 um rms scan: --spikes 6 replaces exactly them and
        # gives back the clean scan's Rq to 0.1 % (the replaced points follow the chord of
        # their neighbours; 1e-5 measured); without it Rq is more than 2 % high (4.6 %
        # measured: the ls filter spreads each spike). Off by default.
        lines = open(f"{ex}/pzt_max.csv").read().splitlines()
        for i in (1500, 2000, 2001):
            x, z = lines[i].split(",")
            lines[i] = f"{x},{float(z) + 40.0:.5f}"
        spiky = write("spiky.csv", "\n".join(lines) + "\n")
        def rq(path, extra):
            r = run(exe, ["--surface", path, "--json"] + extra)
            if r.returncode != 0:
                raise RuntimeError(r.stderr)
            s = json.loads(r.stdout)["surfaces"][0]
            return s["scans"][0]["parameters"]["Rq"], s["spikes_removed"]
        clean, n0 = rq(f"{ex}/pzt_max.csv", ["--spikes", "6"])
        fixed, n1 = rq(spiky, ["--spikes", "6"])
        raw, n2 = rq(spiky, [])
        if n0 != 0 or n1 != 3 or n2 != 0:
            return fail(f"spikes removed: clean {n0}, spiky {n1}, off {n2}")
        if abs(fixed / clean - 1) > 1e-3 or raw / clean - 1 < 0.02:
            return fail(f"Rq clean {clean}, with --spikes {fixed}, without {raw}")
        if bad(exe, ["--surface", spiky, "--spikes", "1"], ["--spikes", "spikes.threshold"]):
            return 1
        return 0
    if case == "table_alignment":
        # Huge and tiny parameters keep the columns: every row as long as the header, and
        # each column's values end where its title does.
        r = run(exe, ["--params", "sigma=1e9um,eta=1e-20um^-2,R=1e12um",
                      "--params", "sigma=1e-9um,eta=1e20um^-2,R=1e-12um",
                      "--E", "200GPa", "--nu", "0.3", "--H", "1GPa"])
        if r.returncode != 0:
            return fail(r.stderr)
        lines = r.stdout.splitlines()
        header = lines[0]
        ends = [header.index(t) + len(t) for t in header.split()[1:]]
        for line in lines[1:4]:
            if len(line) != len(header):
                return fail(f"row {line!r} is not as long as the header {header!r}")
            for e in ends:
                if line[e - 1] == " " or (e < len(line) and line[e] != " "):
                    return fail(f"row {line!r} does not end a value at column {e}")
            if " 0.0000 " in line + " ":
                return fail(f"a non-zero value printed as 0: {line!r}")
        return 0
    if case == "summits_table":
        return summits_table(exe, src, tmp)
    if case == "summits_bad_input":
        x3p = os.path.join(src, "tests", "data", "mountainsmap-650x650.x3p")
        filt = ["--lc", "26.5um", "--ls", "1.6um"]
        out = os.path.join(tmp, "s.csv")
        for argv, fragments in (
                (["--surface", f"{ex}/pzt_max.csv", "--summits", out],
                 ["--summits: summits are found on the S-L surface of areal maps",
                  "here surface 1 is profile scans"]),
                (["--surface", x3p, "--params", "sigma=1um,eta=1e-3um^-2,R=10um", "--summits",
                  out] + filt,
                 ["surface 1 is an areal map, surface 2 is given by --params"]),
                (["--surface", x3p, "--summit-bins", "4"] + filt,
                 ["--summit-bins = 4: allowed are 1 to 10000 with --summits"]),
                (["--surface", x3p, "--summits", out, "--summit-bins", "10001"] + filt,
                 ["--summit-bins = 10001: allowed are 1 to 10000"]),
                (["--surface", x3p, "--summits", "-", "--json"] + filt,
                 ["--summits - and --json both write to standard output"]),
                (["--surface", x3p, "--summits", "-", "--psd", "-"] + filt,
                 ["--psd - and --summits - both write to standard output"]),
                (["--surface", x3p, "--summits", x3p] + filt, ["would overwrite an input file"]),
                (["--surface", x3p, "--summits", tmp] + filt, ["is a directory"])):
            if bad(exe, argv, fragments):
                return 1
            if os.path.exists(out):
                return fail(f"{argv}: {out} written on bad input")
        return 0
    return fail(f"unknown case {case}")


def read_summit_csv(path):
    """(comment lines, header, heights, densities) of a --summits table."""
    comments, rows = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                comments.append(line)
            else:
                rows.append(line.strip())
    return comments, rows[0], [float(r.split(",")[0]) for r in rows[1:]], \
        [float(r.split(",")[1]) for r in rows[1:]]


def summits_table(exe, src, tmp):
    """--summits on the MountainsMap scan: the report's statistics are those of the table
    written (the CSV's 12 significant digits allow 1e-10), the table is a frequency polygon
    (zero rows at both ends, equal bins, Rice's ceil(2 n^(1/3)) of them, unit integral), and
    the sum surface of the scan with itself is the scan doubled: the same summits, heights and
    spread twice, the radius halved (closed forms, 1e-12)."""
    import math
    x3p = os.path.join(src, "tests", "data", "mountainsmap-650x650.x3p")
    filt = ["--lc", "26.5um", "--ls", "1.6um"]
    one, two = os.path.join(tmp, "one.csv"), os.path.join(tmp, "two.csv")
    r = run(exe, ["--surface", x3p, "--summits", one, "--json"] + filt)
    if r.returncode != 0:
        return fail(r.stderr)
    s = json.loads(r.stdout)["summits"]
    if s["surface"] != "1" or s["file"] != one or s["count"] < 100:
        return fail(f"summits {s}")
    if abs(s["eta"] / (s["count"] / s["area"]) - 1) > 1e-14:
        return fail(f"eta {s['eta']} is not count/area")
    comments, header, z, p = read_summit_csv(one)
    if header != "height[m],density[1/m]" or len(comments) != 3:
        return fail(f"header {header!r}, comments {comments}")
    if len(z) != s["bins"] + 2 or s["bins"] != math.ceil(2 * s["count"] ** (1 / 3)):
        return fail(f"{len(z)} rows for {s['bins']} bins of {s['count']} summits")
    if p[0] != 0 or p[-1] != 0 or min(p) < 0:
        return fail(f"densities {p}")
    for a, b in zip(z, z[1:]):
        if abs((b - a) / s["bin_width"] - 1) > 1e-9:
            return fail(f"bin {a}..{b}, width {s['bin_width']}")
    I, mean, var = linear_moments(z, p)
    if abs(I - 1) > 1e-10 or abs(math.sqrt(var) / s["table_sigma"] - 1) > 1e-10:
        return fail(f"table: integral {I}, sd {math.sqrt(var)} vs {s['table_sigma']}")
    # Wider than the summits' own spread by the bins (h^2/6 and the binning): within 5 %.
    if not s["sigma"] < s["table_sigma"] < 1.05 * s["sigma"]:
        return fail(f"table sd {s['table_sigma']}, summits {s['sigma']}")
    for key in ("eta", "sigma_a", "R"):
        if not s["spectral"][key] > 0:
            return fail(f"spectral {s['spectral']}")
    r = run(exe, ["--surface", x3p, "--surface", x3p, "--summits", two, "--json"] + filt)
    if r.returncode != 0:
        return fail(r.stderr)
    d = json.loads(r.stdout)
    s2 = d["summits"]
    if s2["surface"] != "1+2" or s2["count"] != s["count"] or s2["bins"] != s["bins"]:
        return fail(f"sum surface {s2}")
    for key, factor in (("sigma", 2), ("mean_height", 2), ("R", 0.5), ("eta", 1),
                        ("table_sigma", 2)):
        if abs(s2[key] / (factor * s[key]) - 1) > 1e-12:
            return fail(f"{key}: {s2[key]} for the doubled scan, {s[key]} for the scan")
    if abs(s2["spectral"]["eta"] / d["combined"]["eta"] - 1) > 1e-14:
        return fail("the sum surface's spectral eta is not the combined surfaces'")
    r = run(exe, ["--surface", x3p, "--summits", "-", "--summit-bins", "20"] + filt)
    if r.returncode != 0 or "\nheight[m],density[1/m]\n" not in r.stdout:
        return fail(f"--summits -: {r.returncode} {r.stderr}")
    if len([l for l in r.stdout.split("height[m],density[1/m]\n")[1].splitlines() if l]) != 22:
        return fail("--summit-bins 20 gives 22 rows")
    return 0


if __name__ == "__main__":
    sys.exit(main())
