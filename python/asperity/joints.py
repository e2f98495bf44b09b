"""Matplotlib helpers for joint predictions and fretting analyses (thesis ch. 5-6).

``asperity.predict(case)`` and ``asperity.analyze_fretting(...)`` return dicts (SI
units); these helpers draw them in micrometres and newtons.
"""
from __future__ import annotations

import numpy as np

from . import _optional


def _axes(ax):
    if ax is None:
        plt = _optional.pyplot()

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


_GUIDES = {2: dict(color="0.35", linestyle="--"), 3: dict(color="black", linestyle="-.")}


def _power_guides(ax, q0, e0, qmin, qmax, guides):
    q = np.geomspace(qmin, qmax, 20)
    for n in guides:
        style = _GUIDES.get(n, dict(color="black", linestyle=":"))
        ax.loglog(q, e0 * (q / q0) ** n, label=f"slope {n}", **style)


def plot_energy_vs_force(prediction: dict, ax=None, guides=(2, 3)):
    """Energy per cycle against peak force, log-log, with power-law guides (Fig. 6.12-6.14)."""
    ax = _axes(ax)
    qs = []
    for ld in prediction["loads"]:
        ax.loglog(ld["Q_peak"], ld["energy"], "o-", label=f"P = {ld['preload']:.0f} N")
        qs.extend(ld["Q_peak"])
    first = prediction["loads"][0]
    _power_guides(ax, first["Q_peak"][0], first["energy"][0], min(qs), max(qs), guides)
    ax.set_xlabel("peak force [N]")
    ax.set_ylabel("energy per cycle [J]")
    ax.legend()
    return ax


def plot_runs_energy(analyses: list, ax=None, guides=(2, 3)):
    """Energy per cycle against peak force of several ``analyze_fretting`` runs: resolved
    runs filled, runs below their noise floor open (left out of the fit), the power law
    fitted to the resolved ones (``asperity.power_law_exponent``) and slope guides."""
    from . import _core

    ax = _axes(ax)
    q = np.array([a["mean"]["Q_max"] for a in analyses])
    e = np.array([a["mean"]["energy"] for a in analyses])
    ok = np.array([bool(a["energy_resolved"]) and a["mean"]["energy"] > 0 for a in analyses])
    floor = np.array([a["energy_noise_floor"] for a in analyses])
    ax.loglog(q[ok], e[ok], "o", color="#1f4e9a", label="runs")
    if (~ok).any():
        ax.loglog(q[~ok], np.where(e[~ok] > 0, e[~ok], floor[~ok]), "o", mfc="none",
                  color="#c0392b", label="below the noise floor (left out)")
    if ok.sum() >= 2:
        fit = _core.power_law_exponent(q[ok], e[ok])
        qq = np.geomspace(q[ok].min(), q[ok].max(), 20)
        lq, le = np.log(q[ok]).mean(), np.log(e[ok]).mean()
        ax.loglog(qq, np.exp(le + fit["exponent"] * (np.log(qq) - lq)), "-", color="#1f4e9a",
                  label=f"fit: n = {fit['exponent']:.2f}")
        q0, e0 = np.exp(lq), np.exp(le)
    else:
        q0, e0 = np.exp(np.log(q).mean()), np.exp(np.log(np.where(e > 0, e, floor)).mean())
    _power_guides(ax, q0, e0, q.min(), q.max(), guides)
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
