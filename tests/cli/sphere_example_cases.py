#!/usr/bin/env python3
"""Runs the C++ example examples/sphere_example.cpp (Table 3.2 and the data of Fig. 3.2,
3.4, 3.6-3.8).

Usage: sphere_example_cases.py SPHERE_EXAMPLE_EXE {writes_csv|unwritable_dir}

Standard library only. Reference values: Table 3.2 mu (CFC, CEB, KE, BKE) at 35 N and
23 N and the section 3.5 stiffness 8 G* a = 16.17 / 14.06 N/um, printed by the example
to 3 decimals -> 1 % relative (KE's printed values are ~0.8 % below B.12, SEED_NOTES.md).
Row counts follow from the example's grids (400 interferences; 3 branches x 200 loop
points and 201 amplitudes per model).
"""
import csv
import os
import re
import subprocess
import sys
import tempfile

TABLE_3_2 = {"35.0": ({"cfc": 0.284, "ceb": 0.528, "ke": 0.858, "bke": 1.444}, 16.17),
             "23.0": ({"cfc": 0.284, "ceb": 0.626, "ke": 0.992, "bke": 1.639}, 14.06)}


def fail(message):
    print("FAIL:", message, file=sys.stderr)
    return 1


def rows(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


def writes_csv(exe):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "new", "dir")  # created by the example
        r = subprocess.run([exe, out], capture_output=True, text=True, timeout=120)
        if r.returncode != 0:
            return fail(f"exit {r.returncode}: {r.stderr}")
        if "P_c = 152.8 N" not in r.stdout or "Hertz's interference" not in r.stdout:
            return fail(f"stdout: {r.stdout!r}")
        for P, (mu, K_T) in TABLE_3_2.items():
            line = next((l for l in r.stdout.splitlines() if l.startswith(f"P = {P} N")), None)
            if line is None:
                return fail(f"no line for P = {P} N: {r.stdout!r}")
            k = float(re.search(r"8G\*a = ([0-9.]+) N/um", line).group(1))
            if abs(k - K_T) > 1e-2 * K_T:
                return fail(f"P = {P} N: 8 G* a = {k}, section 3.5: {K_T}")
            for name, ref in mu.items():
                value = float(re.search(rf" {name} ([0-9.]+)", line).group(1))
                if abs(value - ref) > 1e-2 * ref:
                    return fail(f"P = {P} N: {name} mu = {value}, Table 3.2: {ref}")
        expected = {"fig_3_2_3_4.csv": (9, 400), "fig_3_6_3_7.csv": (4, 4 * 3 * 200),
                    "fig_3_8.csv": (3, 4 * 201)}
        if sorted(os.listdir(out)) != sorted(expected):
            return fail(f"files: {sorted(os.listdir(out))}")
        for name, (columns, count) in expected.items():
            table = rows(os.path.join(out, name))
            if len(table) != count + 1 or any(len(row) != columns for row in table):
                return fail(f"{name}: {len(table)} rows, widths {set(map(len, table))}")
    return 0


def unwritable_dir(exe):
    """The output directory cannot be made (a regular file is in the way): the example
    must say so and exit non-zero, not exit 0 having written nothing."""
    with tempfile.TemporaryDirectory() as tmp:
        blocker = os.path.join(tmp, "a_file")
        with open(blocker, "w") as f:
            f.write("x")
        for out in (blocker, os.path.join(blocker, "sub")):
            r = subprocess.run([exe, out], capture_output=True, text=True, timeout=120)
            if r.returncode == 0:
                return fail(f"{out}: exit 0")
            if out not in r.stderr:
                return fail(f"{out}: the message does not name the directory: {r.stderr!r}")
        if os.listdir(tmp) != ["a_file"]:
            return fail(f"files left: {os.listdir(tmp)}")
    return 0


CASES = {"writes_csv": writes_csv, "unwritable_dir": unwritable_dir}

if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[2] not in CASES:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(CASES[sys.argv[2]](sys.argv[1]))
