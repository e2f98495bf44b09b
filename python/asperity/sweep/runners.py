"""What one sample runs, by kind of case: ``joint`` (``asperity predict``), ``dynamics``
(``asperity dynamics``) and the hook for ``vibration``.

A runner is an object with

* ``check(text, base_dir)``: parse and validate case text without the expensive part
  (raises ``asperity.InvalidInput``); used on every variation's extremes before any work;
* ``run(text, base_dir) -> {name: numpy array}``: the sample's outputs, each of a fixed
  shape for a given sweep (SI units);
* ``dims(name) -> tuple``: the dimension names of an output (beyond ``sample``);
* ``attrs(name) -> {"units": ..., "long_name": ...}``: CF attributes of an output
  (units in UDUNITS form, SI; ``"1"`` for dimensionless);
* ``coords(outputs, text) -> {dim: (values, attrs)}`` (optional): value coordinates of the
  dimensions, from the base case's outputs (a dimension without one keeps 1-based numbers).

:func:`register_runner` adds a kind. Vibration cases (``asperity vibration``, a
``[structure]`` table) return the nonlinear mode and the quasi-static estimate on a fixed
grid of modal amplitudes, and the peak of each forced response curve.
"""
from __future__ import annotations

import math
import tomllib
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

    ATTRS = {
        "preload": ("N", "bolt preload of the load case"),
        "mu": ("1", "friction coefficient mu (Q_max / preload)"),
        "stiffness": ("N m-1", "tangential joint stiffness (initial slope of the backbone)"),
        "Q_max": ("N", "tangential force at gross slip Q_max"),
        "separation": ("m", "mean separation of the rough surfaces"),
        "mean_pressure": ("Pa", "nominal contact pressure (preload / nominal area)"),
        "contact_area_ratio": ("1", "real over nominal contact area"),
        "delta_max": ("m", "joint amplitude delta_max of the loop"),
        "Q_peak": ("N", "tangential force at the loop tip"),
        "energy": ("J", "energy dissipated per cycle"),
        "imposed": ("m", "imposed amplitude (NaN for a joint amplitude)"),
        "sigma": ("m", "combined RMS roughness sigma (Eq. 5.1)"),
        "eta": ("m-2", "combined asperity density eta"),
        "R": ("m", "combined asperity summit radius R"),
        "beta": ("1", "roughness parameter beta = eta sigma R"),
        "psi": ("1", "plasticity index psi"),
    }

    def attrs(self, name: str) -> dict:
        units, long_name = self.ATTRS.get(name, ("1", name))
        return {"units": units, "long_name": long_name}

    def coords(self, outputs: dict, text: str) -> dict:
        """``load``: the unvaried case's preloads [N]; ``amplitude``: its joint
        amplitudes delta_max, or the imposed amplitude for an imposed one [m]."""
        imposed = np.asarray(outputs["imposed"], dtype=float)[0]
        amp = np.where(np.isnan(imposed), np.asarray(outputs["delta_max"], dtype=float)[0],
                       imposed)
        return {
            "load": (np.asarray(outputs["preload"], dtype=float), {
                "units": "N", "long_name": "preload of the load case in the unvaried case "
                "(each sample's own: variable preload)"}),
            "amplitude": (amp, {
                "units": "m", "long_name": "joint amplitude delta_max (an imposed amplitude: "
                "the imposed value) in the unvaried case"}),
        }


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

    def attrs(self, name: str) -> dict:
        # Dynamics cases are nondimensional (time tau, the case's scales): units "1".
        return {"units": "1", "long_name": f"summary.json {name.replace('_', ' ')} "
                "(nondimensional, time in tau)"}


class VibrationRunner:
    """``asperity.vibration.run_case_text`` of a vibration case. The curves have as many
    points as their continuations took, so they are put on fixed grids: the nonlinear
    mode's and the quasi-static estimate's frequency [Hz] and damping ratio at
    ``GRID`` log-spaced modal amplitudes spanning the case's range (dimension
    ``modal_amplitude``; the grid itself is the output ``mode_log10_amplitude``, NaN
    beyond where a continuation stopped), linear interpolation in log10 a; per forced
    response curve (dimension ``curve``) the largest first-harmonic amplitude of the
    first output DOF [m] and its frequency [Hz]; the stuck structure's linear frequencies
    (dimension ``linear_mode``); and the peak damping ratio of the nonlinear mode with
    its modal amplitude."""

    GRID = 25
    MODE = ("mode_log10_amplitude", "mode_frequency_hz", "mode_damping_ratio",
            "quasi_static_frequency_hz", "quasi_static_damping_ratio")
    CURVE = ("response_peak_amplitude", "response_peak_frequency_hz")

    def check(self, text: str, base_dir: str) -> dict:
        from .._core import _vibration

        _vibration.check_case_text(text, base_dir)
        return {}

    def _grid(self, la: np.ndarray, values: np.ndarray, grid: np.ndarray) -> np.ndarray:
        order = np.argsort(la)
        la, values = la[order], values[order]
        out = np.interp(grid, la, values)
        out[(grid < la[0] - 1e-12) | (grid > la[-1] + 1e-12)] = math.nan
        return out

    def run(self, text: str, base_dir: str) -> dict:
        from .. import vibration

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            r = vibration.run_case_text(text, base_dir)
        s = r["summary"]
        out = {"linear_frequency_hz": np.asarray(
            s["structure"]["linear_frequencies_hz_elements_stuck"], dtype=float)}
        nm, qs = r["nonlinear_mode"], r["quasi_static_mode"]
        if nm is not None:
            la = np.asarray(nm["log10_amplitude"], dtype=float)
            # The case's requested range (from where the continuation starts to `to`),
            # whether or not the continuation got there.
            lo, hi = float(la[0]), float(la[-1])
            try:
                hi = float(tomllib.loads(text)["nonlinear_mode"]["log10_amplitude"]["to"])
            except (KeyError, TypeError, ValueError, tomllib.TOMLDecodeError):
                pass
            grid = np.linspace(min(lo, hi), max(lo, hi), self.GRID)
            out["mode_log10_amplitude"] = grid
            out["mode_frequency_hz"] = self._grid(la, np.asarray(nm["frequency_hz"]), grid)
            out["mode_damping_ratio"] = self._grid(la, np.asarray(nm["damping_ratio"]), grid)
            z = np.asarray(nm["damping_ratio"], dtype=float)
            k = int(np.argmax(z))
            out["mode_peak_damping_ratio"] = np.asarray(z[k])
            out["mode_peak_damping_amplitude"] = np.asarray(10.0 ** la[k])
            if qs is not None:
                lq = np.log10(np.asarray(qs["amplitude"], dtype=float))
                out["quasi_static_frequency_hz"] = self._grid(lq, np.asarray(qs["frequency_hz"]), grid)
                out["quasi_static_damping_ratio"] = self._grid(lq, np.asarray(qs["damping_ratio"]), grid)
        curves = r["frequency_response"]
        if curves:
            peak, at = [], []
            for c in curves:
                a = np.asarray(c["output_amplitude"], dtype=float)[:, 0]
                k = int(np.argmax(a))
                peak.append(a[k])
                at.append(float(np.asarray(c["omega"])[k]) / (2.0 * math.pi))
            out["response_peak_amplitude"] = np.asarray(peak)
            out["response_peak_frequency_hz"] = np.asarray(at)
            out["response_force_amplitude"] = np.asarray(
                [c.get("force_amplitude", math.nan) for c in curves], dtype=float)
        return out

    def dims(self, name: str) -> tuple:
        if name in self.MODE:
            return ("modal_amplitude",)
        if name in self.CURVE + ("response_force_amplitude",):
            return ("curve",)
        if name == "linear_frequency_hz":
            return ("linear_mode",)
        return ()

    ATTRS = {
        "linear_frequency_hz": ("Hz", "linear natural frequency, elements stuck"),
        "mode_log10_amplitude": ("1", "log10 of the modal amplitude [sqrt(kg) m] of the grid"),
        "mode_frequency_hz": ("Hz", "nonlinear mode: frequency"),
        "mode_damping_ratio": ("1", "nonlinear mode: damping ratio"),
        "quasi_static_frequency_hz": ("Hz", "quasi-static estimate: frequency"),
        "quasi_static_damping_ratio": ("1", "quasi-static estimate: damping ratio"),
        "mode_peak_damping_ratio": ("1", "largest damping ratio of the nonlinear mode"),
        "mode_peak_damping_amplitude": ("kg0.5 m", "modal amplitude of the largest damping "
                                        "ratio"),
        "response_peak_amplitude": ("m", "forced response: largest first-harmonic amplitude "
                                    "of the first output DOF"),
        "response_peak_frequency_hz": ("Hz", "forced response: frequency of the peak"),
        "response_force_amplitude": ("N", "forced response: forcing amplitude (norm of the "
                                     "harmonic force vector times force_scale)"),
    }

    def attrs(self, name: str) -> dict:
        units, long_name = self.ATTRS.get(name, ("1", name))
        return {"units": units, "long_name": long_name}

    def coords(self, outputs: dict, text: str) -> dict:
        """``modal_amplitude``: the unvaried case's grid [sqrt(kg) m]; ``curve``: its
        forcing amplitudes [N]; ``linear_mode``: the mode number (1-based)."""
        out = {}
        if "mode_log10_amplitude" in outputs:
            out["modal_amplitude"] = (10.0 ** np.asarray(outputs["mode_log10_amplitude"]), {
                "units": "kg0.5 m", "long_name": "modal amplitude of the mass-normalized first "
                "harmonic (grid of the unvaried case)"})
        if "response_force_amplitude" in outputs:
            out["curve"] = (np.asarray(outputs["response_force_amplitude"], dtype=float), {
                "units": "N", "long_name": "forcing amplitude of the forced-response curve in "
                "the unvaried case"})
        return out


register_runner("joint", JointRunner())
register_runner("dynamics", DynamicsRunner())
register_runner("vibration", VibrationRunner())
