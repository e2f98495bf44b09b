"""Sweep files (TOML)::

    case = "../joints/steel420_two_bolts.toml"   # relative to this file
    samples = 2000          # draws per grid point (default 100 when something is drawn)
    seed = 12
    method = "random"       # random | sobol | lhs
    unset = ["excitation.amplitudes"]            # keys removed from the case
    [set]                                        # values given to every sample
    "excitation.imposed" = ["6.75 um"]
    [vary]
    "load.bolts.nut_factor" = "uniform(0.158, 0.267)"
    "load.bolts.total_torques[*]" = ...          # [*]: every element, the same value
    "joint.half[*].material.H" = "normal(5.8 GPa, 5 %)"
    "load.preload" = "200 N .. 800 N, 25 steps"  # a grid
    "roughness" = "choice(before, after)"        # options are [choices.roughness.*]
    [choices.roughness.before]
    "joint.half[1].roughness.sigma" = "1.763 um"
"""
from __future__ import annotations

import os

from .spec import SweepError, build, read_toml

_KEYS = {"case", "samples", "seed", "method", "unset", "set", "vary", "choices"}


def load(path: str, **override):
    """A :class:`Sweep` from a sweep file; keyword arguments (samples, seed, method)
    override the file's."""
    d = read_toml(path)
    unknown = sorted(set(d) - _KEYS)
    if unknown:
        raise SweepError(f"{path}: unknown key {unknown[0]!r} (allowed: {', '.join(sorted(_KEYS))})")
    if "case" not in d or not isinstance(d["case"], str):
        raise SweepError(f"{path}: case: missing; the case file to vary, relative to the sweep file")
    case = d["case"] if os.path.isabs(d["case"]) else os.path.join(
        os.path.dirname(os.path.abspath(path)), d["case"])
    for k in ("set", "vary", "choices"):
        if k in d and not isinstance(d[k], dict):
            raise SweepError(f"{path}: {k}: a table of key paths")
    if "unset" in d and not (isinstance(d["unset"], list)
                             and all(isinstance(x, str) for x in d["unset"])):
        raise SweepError(f"{path}: unset: an array of key paths")
    opts = {k: d[k] for k in ("samples", "seed", "method") if k in d}
    opts.update({k: v for k, v in override.items() if v is not None})
    return build(case, d.get("vary", {}), set_=d.get("set"), unset=d.get("unset"),
                 choices=d.get("choices"), **opts)
