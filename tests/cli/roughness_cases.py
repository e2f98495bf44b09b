#!/usr/bin/env python3
"""Behaviour of `asperity roughness`: the shipped example (Table 5.4 from synthetic scans
of the two milled halves) and bad input (exit 2, a message naming the file or flag,
nothing on stdout).

Usage: roughness_cases.py ASPERITY_EXE SOURCE_DIR CASE. Standard library only.
"""
import json
import os
import subprocess
import sys
import tempfile


def run(exe, argv):
    return subprocess.run([exe, "roughness"] + argv, capture_output=True, text=True, timeout=120)


def fail(msg):
    print("FAIL:", msg, file=sys.stderr)
    return 1


def bad(exe, argv, must_contain):
    r = run(exe, argv)
    if r.returncode != 2:
        return fail(f"expected exit 2, got {r.returncode}: {r.stderr}")
    if r.stdout:
        return fail(f"stdout not empty: {r.stdout!r}")
    if must_contain.lower() not in r.stderr.lower():
        return fail(f"message does not mention {must_contain!r}: {r.stderr}")
    return 0


def main():
    exe, src, case = sys.argv[1], sys.argv[2], sys.argv[3]
    ex = os.path.join(src, "examples", "roughness")
    tmp = tempfile.mkdtemp()

    def write(name, text):
        p = os.path.join(tmp, name)
        with open(p, "w") as f:
            f.write(text)
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
    cases = {
        "empty_file": (write("empty.csv", ""), "empty"),
        "single_point": (write("one.csv", "x[um],z[um]\n0,1\n"), "one.csv"),
        "nan_height": (write("nan.csv", "x[um],z[um]\n" + "".join(f"{i},{'nan' if i == 5 else 0.1}\n" for i in range(3000))), "nan.csv"),
        "unknown_unit": (write("unit.csv", "x[um],z[furlong]\n" + "".join(f"{i},0.1\n" for i in range(3000))), "no known length unit"),
        "decreasing_x": (write("dec.csv", "x[um],z[um]\n" + "".join(f"{3000 - i},0.1\n" for i in range(3000))), "dec.csv"),
        "too_short_for_filter": (write("short.csv", "x[um],z[um]\n" + "".join(f"{i},{(i % 7) * 0.1}\n" for i in range(200))), "short.csv"),
        "corrupt_x3p": (write("bad.x3p", "PK\x03\x04 not really a zip"), "bad.x3p"),
    }
    if case in cases:
        path, text = cases[case]
        return bad(exe, ["--surface", path], text)
    if case == "bad_params":
        return bad(exe, ["--params", "sigma=1um,eta=abc,R=40um"], "eta")
    return fail(f"unknown case {case}")


if __name__ == "__main__":
    sys.exit(main())
