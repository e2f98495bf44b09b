"""Scaling table of issue 14: time and peak memory of the command line from 1e3 to 1e7
samples, with fitted exponents, as docs/performance.md shows it.

For each size it writes a synthetic rough profile (x[mm],z[um], dx = 1 um) and a
displacement history (delta_star) into a temporary directory and runs, under
/usr/bin/time -v (wall time, maximum resident set size):

  roughness --surface P --end regression --json   the ISO filter (FFT) and moments
  roughness --surface P --filter none --json      the same without the filter (reading)
  flat ... --history H --out F                    forces along the history, written

then `dynamics` on the harmonic Coulomb example for 1e2 to 1e4 cycles (1e5 with
--long), summary only and with --out --decimate 10, and the two thread-parallel paths
(predict on the steel 420 joint, roughness of the 650 x 650 X3P map) with
ASPERITY_THREADS=1 and 2. Each run is repeated (--repeat, default 3) and the median
time and memory are reported: the machine may be shared, so single timings are noisy.
Exponents are least-squares slopes of log(time) and log(memory above the smallest run's)
against log(size) over the three largest sizes (below 1e5, process start-up dominates).

    .venv/bin/python bench/scaling.py [--asperity build/release/src/cli/asperity]
"""
import argparse
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent


def measure(cmd, repeat, env=None):
    """Median wall time [s] and median peak RSS [MB] of `cmd` over `repeat` runs."""
    times, rss = [], []
    for _ in range(repeat):
        start = time.perf_counter()
        r = subprocess.run(["/usr/bin/time", "-v", *map(str, cmd)], capture_output=True,
                           text=True, env={**os.environ, **(env or {})})
        times.append(time.perf_counter() - start)  # /usr/bin/time prints 10 ms steps
        if r.returncode != 0:
            sys.exit(f"failed ({r.returncode}): {' '.join(map(str, cmd))}\n{r.stderr[-2000:]}")
        rss.append(int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", r.stderr).group(1)) / 1024)
    return statistics.median(times), statistics.median(rss)


def slope(xs, ys):
    lx, ly = np.log(xs), np.log(ys)
    return float(np.polyfit(lx, ly, 1)[0])


def write_inputs(d, n, rng):
    profile = d / f"profile_{n}.csv"
    # Roughness correlated over ~20 points on a slow random waviness.
    kernel = 0.3 * 0.95 ** np.arange(100)
    a = np.convolve(rng.standard_normal(n + 99), kernel, "valid")[:n]
    a += np.cumsum(0.05 * rng.standard_normal(n)) * 0.03
    with open(profile, "w") as f:
        f.write("x[mm],z[um]\n")
        np.savetxt(f, np.c_[np.arange(n) * 1e-3, a], fmt=["%.4f", "%.6f"], delimiter=",")
    history = d / f"history_{n}.csv"
    t = np.arange(n)
    with open(history, "w") as f:
        f.write("delta_star\n")
        np.savetxt(f, 0.8 * np.sin(2 * np.pi * t / 1000) * (1 + 0.3 * np.sin(2 * np.pi * t / 37000)),
                   fmt="%.9f")
    return profile, history


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    default = ROOT / "build/release/src/cli/asperity"
    if not default.exists():
        default = ROOT / "build/ci/src/cli/asperity"
    ap.add_argument("--asperity", default=str(default))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--max-exponent", type=int, default=7)
    ap.add_argument("--long", action="store_true", help="also 1e5 dynamics cycles (~20 s a run)")
    ap.add_argument("--threads-only", action="store_true",
                    help="only the 1- and 2-thread table (seconds, not minutes)")
    args = ap.parse_args()
    A = args.asperity
    if args.threads_only:
        with tempfile.TemporaryDirectory(prefix="asperity_scaling_") as tmp:
            thread_table(A, Path(tmp), args.repeat)
        return
    rng = np.random.default_rng(14)
    sizes = [10 ** k for k in range(3, args.max_exponent + 1)]
    rows = {"roughness (filtered)": [], "roughness (--filter none)": [], "flat --history": []}
    flat = ["flat", "--beta", "0.04", "--psi", "0.5", "--nu", "0.3", "--P-star", "1e-3",
            "--model", "bke"]
    with tempfile.TemporaryDirectory(prefix="asperity_scaling_") as tmp:
        d = Path(tmp)
        for n in sizes:
            profile, history = write_inputs(d, n, rng)
            file_mb = profile.stat().st_size / 2 ** 20
            rows["roughness (filtered)"].append(
                (n, *measure([A, "roughness", "--surface", profile, "--end", "regression", "--json"],
                             args.repeat), file_mb))
            rows["roughness (--filter none)"].append(
                (n, *measure([A, "roughness", "--surface", profile, "--filter", "none", "--json"],
                             args.repeat), file_mb))
            rows["flat --history"].append(
                (n, *measure([A, *flat, "--history", history, "--out", d / "forces.csv"],
                             args.repeat), history.stat().st_size / 2 ** 20))
            profile.unlink()
            history.unlink()
            print(f"done n = {n:.0e}", file=sys.stderr)

        print("| command | samples | time [s] | peak memory [MB] | input file [MB] |")
        print("|---|---:|---:|---:|---:|")
        for name, r in rows.items():
            for n, t, m, f in r:
                print(f"| {name} | {n:.0e} | {t:.3g} | {m:.0f} | {f:.1f} |")
        print(f"\n(times: median of {args.repeat} runs; memory: peak resident set size)\n")
        print("| command | time exponent | memory exponent | bytes per sample at the largest size |")
        print("|---|---:|---:|---:|")
        for name, r in rows.items():
            fit = r[-3:]
            n = [x[0] for x in fit]
            t = [x[1] for x in fit]
            # Memory over the process's own floor (the smallest run): what the data costs.
            floor = r[0][2]
            m = [max(x[2] - floor, 1e-3) for x in fit]
            per = (r[-1][2] - floor) * 2 ** 20 / r[-1][0]
            print(f"| {name} | {slope(n, t):.2f} | {slope(n, m):.2f} "
                  f"| {per:.1f} |")

        print()
        case = (ROOT / "examples/dynamics/harmonic_coulomb.toml").read_text()
        cycles = [100, 1000, 10000] + ([100000] if args.long else [])
        print("| dynamics, harmonic Coulomb example | cycles | time [s] | peak memory [MB] |")
        print("|---|---:|---:|---:|")
        for c in cycles:
            f = d / f"harmonic_{c}.toml"
            f.write_text(case.replace("duration = 60", f"duration = {c}"))
            t, m = measure([A, "dynamics", f], args.repeat if c < 100000 else 1)
            print(f"| summary only (no --out) | {c:.0e} | {t:.3g} | {m:.0f} |")
            t, m = measure([A, "dynamics", f, "--out", d / "dyn", "--no-plots", "--decimate", "10"],
                           args.repeat if c < 100000 else 1)
            print(f"| --out --decimate 10 --no-plots | {c:.0e} | {t:.3g} | {m:.0f} |")

        print()
        thread_table(A, d, args.repeat)

# A vectorized call of the Python package on 4e6 points (core::parallel_for in chunks).
PYTHON_BATCH = (
    "import numpy as np, asperity\n"
    "flat = asperity.RoughFlat(model='bke', beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)\n"
    "b = flat.backbone(flat.separation_star(1e-3))\n"
    "x = np.linspace(0.0, 2.0, 4_000_000)\n"
    "for _ in range(25): b.force(x)\n")


def thread_table(A, d, repeat):
    """1 and 2 threads (ASPERITY_THREADS) on the thread-parallel paths."""
    print("| threads (ASPERITY_THREADS) | 1 thread [s] | 2 threads [s] | ratio |")
    print("|---|---:|---:|---:|")
    jobs = {
        "predict steel420_two_bolts (4 load cases, uniform pressure)":
            [A, "predict", ROOT / "examples/joints/steel420_two_bolts.toml", "--out", d / "pred",
             "--no-plots"],
        "predict steel420_bolt_field (4 load cases, bolt pressure field)":
            [A, "predict", ROOT / "examples/joints/steel420_bolt_field.toml", "--out",
             d / "pred_field", "--no-plots"],
        "roughness of the 650 x 650 X3P map (lc 20 um, ls 2.5 um)":
            [A, "roughness", "--surface", ROOT / "tests/data/mountainsmap-650x650.x3p",
             "--lc", "20um", "--ls", "2.5um", "--json"],
        "Python: RoughFlatBackbone.force on 4e6 points, 25 calls (incl. ~0.1 s start-up)":
            [sys.executable, "-c", PYTHON_BATCH],
    }
    for name, cmd in jobs.items():
        t1, _ = measure(cmd, repeat, {"ASPERITY_THREADS": "1"})
        t2, _ = measure(cmd, repeat, {"ASPERITY_THREADS": "2"})
        print(f"| {name} | {t1:.3g} | {t2:.3g} | {t2 / t1:.2f} |")


if __name__ == "__main__":
    main()
