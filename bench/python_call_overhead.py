"""Cost of small calls into the Python package against a plain Python function call.

Issue 14, item 6: Hysteresis.forces on a scalar or a small array within 3 times a
Python function call. Timed with timeit (best of 7 repeats of 200000 calls, the
minimum being the least disturbed by other load); the reference is a Python function
of one argument that returns it, called with the same argument in the same run.

    PYTHONPATH=build/ci/python .venv/bin/python bench/python_call_overhead.py
"""
import timeit

import numpy as np

import asperity


def main():
    flat = asperity.RoughFlat(model="bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)
    h = asperity.Hysteresis(flat.backbone(flat.separation_star(1e-3)))
    h.update(0.5)
    h.update(-0.2)  # two reversals on the stack: the copy made per call is not trivial

    def python_function(x):
        return x

    a1 = np.array([0.3])
    a8 = np.linspace(-0.3, 0.3, 8)
    cases = {
        "python_function(0.3)": lambda: python_function(0.3),
        "python_function(a1)": lambda: python_function(a1),
        "h.force(0.3)": lambda: h.force(0.3),
        "h.forces(0.3)": lambda: h.forces(0.3),
        "h.forces(a1)  [1-element float64 array]": lambda: h.forces(a1),
        "h.forces(a8)  [8-element float64 array]": lambda: h.forces(a8),
        "h.forces([0.3])  [list, via numpy.asarray]": lambda: h.forces([0.3]),
    }
    number = 200_000
    best = {}
    for name, f in cases.items():
        best[name] = min(timeit.repeat(f, number=number, repeat=7)) / number
    ref = best["python_function(0.3)"]
    print(f"{'call':45s} {'ns':>8s} {'/ Python call':>14s}")
    for name, t in best.items():
        print(f"{name:45s} {t * 1e9:8.1f} {t / ref:14.2f}")
    print("(the lambda wrapper's own call is in every line, the reference included)")


if __name__ == "__main__":
    main()
