"""nanobind's nb::ndarray against numpy's C API for the array in and out of a small call.

Issue 21 item 9: would nb::ndarray keep Hysteresis.forces's speed (python/src/hysteresis.cpp
reads and makes its arrays with numpy's C API)? ndbench.cpp has the same raw
METH_FASTCALL function (tanh of each point, a new array back) both ways, plus the input
and the output alone. timeit, best of 7 x 200000 calls, as bench/python_call_overhead.py.
A standalone module, not part of the project's build:

    cmake -S bench/nb_ndarray -B /tmp/ndbench -DPython_EXECUTABLE=.venv/bin/python \
          -Dnanobind_DIR=$(.venv/bin/python -m nanobind --cmake_dir)
    cmake --build /tmp/ndbench && PYTHONPATH=/tmp/ndbench .venv/bin/python bench/nb_ndarray/bench.py
"""
import os
import timeit

import numpy as np

import ndbench as m


def main():
    a1 = np.array([0.3])
    a8 = np.linspace(-0.3, 0.3, 8)
    s8 = np.linspace(-0.3, 0.3, 16)[::2]  # strided
    for x in (a1, a8, s8):
        assert np.array_equal(m.capi(x), m.ndarr(x))
        assert np.array_equal(m.capi(x), m.ndarr_dispatch(x))

    def python_function(x):
        return x

    cases = {
        "python_function(a1)": lambda: python_function(a1),
        "capi(a1)": lambda: m.capi(a1),
        "ndarr(a1)": lambda: m.ndarr(a1),
        "ndarr_dispatch(a1)  [nanobind method]": lambda: m.ndarr_dispatch(a1),
        "capi(a8)": lambda: m.capi(a8),
        "ndarr(a8)": lambda: m.ndarr(a8),
        "capi(s8)  [strided]": lambda: m.capi(s8),
        "ndarr(s8)  [strided]": lambda: m.ndarr(s8),
        "capi_in(a1)  [input only]": lambda: m.capi_in(a1),
        "ndarr_in(a1)  [input only]": lambda: m.ndarr_in(a1),
        "capi_out(0.3)  [output only]": lambda: m.capi_out(0.3),
        "ndarr_out(0.3)  [output only]": lambda: m.ndarr_out(0.3),
    }
    print("load average before", os.getloadavg())
    for name, f in cases.items():
        t = min(timeit.repeat(f, number=200000, repeat=7)) / 200000 * 1e9
        print(f"{name:40s} {t:7.1f} ns")
    print("load average after", os.getloadavg())


if __name__ == "__main__":
    main()
