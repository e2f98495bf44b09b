"""What one sample runs, by kind of case: ``joint`` (``asperity predict``), ``dynamics``
(``asperity dynamics``) and the hook for ``vibration``.

A runner is an object with

* ``check(text, base_dir)``: parse and validate case text without the expensive part
  (raises ``asperity.InvalidInput``); used on every variation's extremes before any work;
* ``run(text, base_dir) -> {name: numpy array}``: the sample's outputs, each of a fixed
  shape for a given sweep (SI units);
* ``dims(name) -> tuple``: the dimension names of an output (beyond ``sample``).

:func:`register_runner` adds a kind. **Vibration cases are not wired yet**: the vibration
layer is being built in parallel; when its Python face exists, register a runner for
``"vibration"`` (cases with a ``[vibration]`` table) that returns, e.g., frequency and
damping per mode, and nothing else in the sweep changes.
"""
from __future__ import annotations

import math
import warnings

import numpy as np

from .. import _core

_RUNNERS: dict = {}


def register_runner(kind: str, runner) -> None:
    """Makes cases of ``kind`` (see :func:`asperity.sweep.spec.case_kind`) runnable."""
    _RUNNERS[kind] = runner


def runner_for(kind: str):
    from .spec import SweepError

    if kind not in _RUNNERS:
        if kind == "vibration":
            raise SweepError("[vibration] case: vibration samples are not wired into "
                             "asperity.sweep yet (register_runner('vibration', ...) when the "
                             "vibration layer has a Python face); joint and dynamics cases run")
        raise SweepError(f"case kind {kind!r}: no runner (known: {', '.join(sorted(_RUNNERS))})")
    return _RUNNERS[kind]


class JointRunner:
    """``asperity.predict`` of a joint case: per load case (dimension ``load``) preload,
    mu, stiffness, Q_max, separation, mean_pressure, contact_area_ratio; per load and
    amplitude (dimensions ``load``, ``amplitude``) delta_max, Q_peak, energy, imposed.
    Amplitudes are ordered as: the joint amplitudes (``amplitudes``) by delta_max, then
    the imposed ones (``imposed``) by the imposed value; ``imposed`` is NaN for the first
    kind (as in ``asperity.predict``). Sample-level: the combined sigma, eta, R, beta, psi.
    """

    LOAD = ("preload", "mu", "stiffness", "Q_max", "separation", "mean_pressure",
            "contact_area_ratio")
    AMPLITUDE = ("delta_max", "Q_peak", "energy", "imposed")
    ROUGHNESS = ("sigma", "eta", "R", "beta", "psi")

    def check(self, text: str, base_dir: str) -> dict:
        return _core.check_case_text(text, base_dir)

    def run(self, text: str, base_dir: str) -> dict:
        p = _core.predict_case_text(text, base_dir, 2)  # loops are not kept: 2 points
        out = {k: np.asarray([p["roughness"][k]], dtype=float).reshape(()) for k in
               self.ROUGHNESS}
        for k in self.LOAD:
            out[k] = np.asarray([ld[k] for ld in p["loads"]], dtype=float)
        rows = {k: [] for k in self.AMPLITUDE}
        for ld in p["loads"]:
            imposed = np.asarray(ld["imposed"], dtype=float)
            direct = np.flatnonzero(np.isnan(imposed))
            direct = direct[np.argsort(np.asarray(ld["delta_max"])[direct], kind="stable")]
            via = np.flatnonzero(~np.isnan(imposed))
            via = via[np.argsort(imposed[via], kind="stable")]
            order = np.concatenate([direct, via]).astype(int)
            for k in self.AMPLITUDE:
                rows[k].append(np.asarray(ld[k], dtype=float)[order])
        for k in self.AMPLITUDE:
            out[k] = np.asarray(rows[k], dtype=float).reshape(len(p["loads"]), -1)
        return out

    def dims(self, name: str) -> tuple:
        if name in self.LOAD:
            return ("load",)
        if name in self.AMPLITUDE:
            return ("load", "amplitude")
        return ()


class DynamicsRunner:
    """``asperity.dynamics.run_case_text`` of a dynamics case: every number of its summary
    (summary.json; nested tables flattened as ``a_b``), a scalar per sample; a summary
    value that is absent (null, e.g. no modal peak found) is NaN."""

    def check(self, text: str, base_dir: str) -> dict:
        # No parse-only binding for dynamics cases: the key paths and units are checked
        # against the case file; values are checked when the sample runs.
        return {}

    @staticmethod
    def _flatten(d: dict, prefix: str = "") -> dict:
        out = {}
        for k, v in d.items():
            name = f"{prefix}{k}"
            if isinstance(v, dict):
                out.update(DynamicsRunner._flatten(v, name + "_"))
            elif isinstance(v, bool):
                out[name] = float(v)
            elif isinstance(v, (int, float)):
                out[name] = float(v)
            elif v is None:
                out[name] = math.nan
        return out

    def run(self, text: str, base_dir: str) -> dict:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            r = _core.run_dynamics_case_text(text, base_dir)
        return {k: np.asarray(v, dtype=float).reshape(())
                for k, v in self._flatten(r["summary"]).items()}

    def dims(self, name: str) -> tuple:
        return ()


register_runner("joint", JointRunner())
register_runner("dynamics", DynamicsRunner())
