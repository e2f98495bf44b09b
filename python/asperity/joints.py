"""Matplotlib helpers for joint predictions and fretting analyses (thesis ch. 5-6).

``asperity.predict(case)`` and ``asperity.analyze_fretting(...)`` return dicts (SI
units); these helpers draw them in micrometres and newtons.
"""
from __future__ import annotations

import numpy as np


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    return ax


def plot_loops(prediction: dict, load: int = 0, ax=None):
    """Steady fretting loops of every amplitude at one load case (Fig. 5.9 style)."""
    ax = _axes(ax)
    ld = prediction["loads"][load]
    for a, loop in zip(ld["delta_max"], ld["loops"]):
        ax.plot(np.asarray(loop["delta"]) * 1e6, loop["Q"], label=f"{a * 1e6:.3g} um")
    ax.set_xlabel("delta [um]")
    ax.set_ylabel("Q [N]")
    ax.set_title(f"{prediction['name']}: P = {ld['preload']:.0f} N")
    ax.legend()
    return ax


def plot_energy_vs_force(prediction: dict, ax=None, guides=(2, 3)):
    """Energy per cycle against peak force, log-log, with power-law guides (Fig. 6.12-6.14)."""
    ax = _axes(ax)
    qs = []
    for ld in prediction["loads"]:
        ax.loglog(ld["Q_peak"], ld["energy"], "o-", label=f"P = {ld['preload']:.0f} N")
        qs.extend(ld["Q_peak"])
    first = prediction["loads"][0]
    q0, e0 = first["Q_peak"][0], first["energy"][0]
    q = np.geomspace(min(qs), max(qs), 20)
    for n in guides:
        ax.loglog(q, e0 * (q / q0) ** n, "--", label=f"slope {n}")
    ax.set_xlabel("peak force [N]")
    ax.set_ylabel("energy per cycle [J]")
    ax.legend()
    return ax


def plot_analysis(analysis: dict, prediction_loop: dict | None = None, ax=None):
    """The averaged measured loop of ``analyze_fretting``, optionally with a predicted loop
    (a dict with arrays ``delta`` and ``Q``, centred on the measured loop)."""
    ax = _axes(ax)
    x = np.append(analysis["loop_delta"], analysis["loop_delta"][0]) * 1e6
    y = np.append(analysis["loop_Q"], analysis["loop_Q"][0])
    ax.plot(x, y, label="measured (averaged)")
    if prediction_loop is not None:
        m = analysis["mean"]
        ax.plot((np.asarray(prediction_loop["delta"]) + m["delta_center"]) * 1e6,
                np.asarray(prediction_loop["Q"]) + m["Q_center"], "--", label="model")
    ax.set_xlabel("delta [um]")
    ax.set_ylabel("Q [N]")
    ax.legend()
    return ax
