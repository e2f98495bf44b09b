"""Cost of small calls into the Python package against a plain Python function call.

Issue 14, item 6: Hysteresis.forces on a scalar or a small array within 3 times a
Python function call. Timed with timeit (best of 7 repeats of 200000 calls, the
minimum being the least disturbed by other load); the reference is a Python function
of one argument that returns it, called with the same argument in the same run.

Two states: `h` has just turned (x = -0.2 after 0.5), so 0.3 is a reversal (the
slow path of Hysteresis::peek); `hc` is moving up from -0.2 at 0.1, so 0.3 continues
its branch (the inline path). `out=` writes into a preallocated array instead of
making a new one (a build without it prints "n/a" on those lines). Last, the cost
against the history's length, fitted as a fixed cost a call plus a cost a point.

    PYTHONPATH=build/ci/python .venv/bin/python bench/python_call_overhead.py
"""
import os
import timeit

import numpy as np

import asperity


def main():
    flat = asperity.RoughFlat(model="bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)
    load_before = os.getloadavg()
    backbone = flat.backbone(flat.separation_star(1e-3))
    h = asperity.Hysteresis(backbone)
    h.update(0.5)
    h.update(-0.2)  # two reversals on the stack; 0.3 turns the motion again
    hc = asperity.Hysteresis(backbone)
    for x in (0.5, -0.2, 0.1):
        hc.update(x)  # moving up from -0.2: 0.3 continues the branch (closes at 0.5)

    def python_function(x):
        return x

    a1 = np.array([0.3])
    a8 = np.linspace(-0.3, 0.3, 8)
    c8 = np.linspace(0.3, 0.45, 8)  # continues hc's branch: no reversal, no state copy
    o1 = np.empty(1)
    o8 = np.empty(8)
    try:
        h.forces(a1, out=o1)
        has_out = True
    except TypeError:
        has_out = False
    cases = {
        "python_function(0.3)": lambda: python_function(0.3),
        "python_function(a1)": lambda: python_function(a1),
        "h.force(0.3)": lambda: h.force(0.3),
        "h.forces(0.3)  [reversal]": lambda: h.forces(0.3),
        "hc.forces(0.3)  [continuing]": lambda: hc.forces(0.3),
        "h.forces(a1)  [1-element float64 array]": lambda: h.forces(a1),
        "hc.forces(a1)  [continuing]": lambda: hc.forces(a1),
        "h.forces(a1, out=o1)": (lambda: h.forces(a1, out=o1)) if has_out else None,
        "hc.forces(a1, out=o1)  [continuing]": (lambda: hc.forces(a1, out=o1)) if has_out else None,
        "h.forces(a8)  [8-element float64 array]": lambda: h.forces(a8),
        "h.forces(a8, out=o8)": (lambda: h.forces(a8, out=o8)) if has_out else None,
        "hc.forces(c8)  [8 points continuing]": lambda: hc.forces(c8),
        "hc.forces(c8, out=o8)  [continuing]": (lambda: hc.forces(c8, out=o8)) if has_out else None,
        "h.forces([0.3])  [list, via numpy.asarray]": lambda: h.forces([0.3]),
    }
    number = 200_000
    best = {}
    for name, f in cases.items():
        best[name] = min(timeit.repeat(f, number=number, repeat=7)) / number if f else None
    # Cost against length (with out=, from h; one reversal at the second point, so the
    # rest runs on a copy of the state): least squares t = a + b n over n = 2..64 splits a call
    # into its fixed part a (the call, argument checks, the state copy) and b, the
    # engine's own cost a point (compare BM_RoughFlatForceStrided in asperity_bench).
    lengths = [2, 4, 8, 16, 32, 64]
    by_length = []
    for n in lengths:
        xs = np.linspace(-0.3, 0.3, n)
        buf = np.empty(n)
        t = min(timeit.repeat(lambda: h.forces(xs, out=buf), number=number // 2, repeat=7))
        by_length.append(t / (number // 2))
    fit_b, fit_a = np.polyfit(lengths, by_length, 1) if has_out else (None, None)
    ref = best["python_function(0.3)"]
    print(f"load average (1, 5, 15 min) before: {load_before}, after: {os.getloadavg()}")
    print(f"{'call':45s} {'ns':>8s} {'/ Python call':>14s}")
    for name, t in best.items():
        if t is None:
            print(f"{name:45s} {'n/a':>8s} {'n/a':>14s}")
        else:
            print(f"{name:45s} {t * 1e9:8.1f} {t / ref:14.2f}")
    print("(the lambda wrapper's own call is in every line, the reference included)")
    if has_out:
        print(f"\nh.forces(linspace(-0.3, 0.3, n), out=buf), by length n:")
        for n, t in zip(lengths, by_length):
            print(f"  n = {n:3d}: {t * 1e9:7.1f} ns  {t / ref:6.2f} Python calls")
        print(f"  least squares over n = {lengths[0]}..{lengths[-1]}: {fit_a * 1e9:.1f} ns "
              f"({fit_a / ref:.2f} Python calls) a call + {fit_b * 1e9:.2f} ns a point")


if __name__ == "__main__":
    main()
