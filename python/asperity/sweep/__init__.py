"""Parameter sweeps and uncertainty of joint, dynamics and vibration cases on Dask (issue 12).

A sweep is a case file plus what varies (:mod:`asperity.sweep.spec`): grids and
distributions of any case key addressed by its path, Monte Carlo (random, Sobol or Latin
hypercube) with a seed. Every sample runs the case (``asperity.predict`` for a joint,
``asperity.dynamics`` for a dynamics case, ``asperity.vibration`` for a vibration case;
:mod:`asperity.sweep.runners`) on a ``dask.distributed`` cluster (a LocalCluster with one
worker per core by default), and the results stream to disk as an xarray Dataset in
NetCDF parts (dimension ``sample``, the varied keys as coordinates) and a Parquet file,
with ``summary.csv``, ``sensitivity.csv``, ``failures.csv`` and plots
(:mod:`asperity.sweep.stats`). Command: ``asperity sweep --help`` (or
``python -m asperity.sweep --help``).

>>> from asperity import sweep
>>> s = sweep.load("examples/sweeps/steel420_bolt_load.toml")        # doctest: +SKIP
>>> info = sweep.run(s, "out/sweep")                                  # doctest: +SKIP
>>> ds = sweep.open_results("out/sweep")                              # doctest: +SKIP
"""
from __future__ import annotations

from .engine import connect, open_results, run, run_batch  # noqa: F401
from .runners import register_runner, runner_for  # noqa: F401
from .spec import (Sweep, SweepError, build, case_kind, parse_path,  # noqa: F401
                   parse_variation, parse_vary_flag, read_toml, to_toml)
from .sweepfile import load  # noqa: F401

__all__ = ["Sweep", "SweepError", "build", "load", "run", "open_results", "connect",
           "register_runner", "runner_for", "parse_path", "parse_variation", "to_toml",
           "case_kind"]
