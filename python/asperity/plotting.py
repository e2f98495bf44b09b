"""matplotlib helpers for asperity results (fretting loops, energy curves, laws).

Plotting only: every number comes from the C++ library. Each helper draws into ``ax``
(a new figure's axes when omitted) and returns the axes. Normalized plots use the
thesis's variables of section 3.3-3.4: ``delta* = 16 G* a_c delta/(3 P_c)``,
``Q* = Q/P_c``, ``Delta W* = G* a_c Delta W/P_c^2``, ``P* = P/P_c``,
``omega* = omega/omega_c``.
"""
from __future__ import annotations

from typing import Iterable, Mapping, Sequence, Union

import numpy as np

from . import _core, _optional

#: Line styles per model name, shared by all helpers so figures agree.
MODEL_STYLES = {
    "cfc": dict(color="tab:blue", linestyle="-", label="CFC"),
    "ceb": dict(color="tab:orange", linestyle="--", label="CEB"),
    "ke": dict(color="tab:green", linestyle="-.", label="KE"),
    "bke": dict(color="tab:red", linestyle=":", label="BKE"),
    "hertz": dict(color="tab:blue", linestyle="-", label="Hertz"),
}

Models = Union[Mapping[str, "_core.PartialSlipModel"], Iterable["_core.PartialSlipModel"]]


def _axes(ax):
    if ax is not None:
        return ax
    plt = _optional.pyplot()

    _, ax = plt.subplots()
    return ax


def _style(name: str, **overrides) -> dict:
    style = dict(MODEL_STYLES.get(name, dict(label=name)))
    style.update(overrides)
    return style


def _models(models: Models):
    if isinstance(models, Mapping):
        return list(models.values())
    if isinstance(models, _core.PartialSlipModel):
        return [models]
    return list(models)


def plot_loop(loop: "_core.FrettingLoop", ax=None, delta_scale: float = 1.0,
              force_scale: float = 1.0, **kwargs):
    """Draws one fretting loop: ``loop.delta/delta_scale`` against ``loop.Q/force_scale``.

    Pass ``delta_scale=1e-6`` for micrometres, or the thesis scales (see
    :func:`asperity.thesis_normalization`) for the dimensionless loop.
    """
    ax = _axes(ax)
    ax.plot(np.asarray(loop.delta) / delta_scale, np.asarray(loop.Q) / force_scale, **kwargs)
    return ax


def plot_loops(models: Models, delta_max: float, ax=None, normalized: bool = True,
               points: int = 201):
    """Fretting loops of several :class:`PartialSlipModel` for one displacement amplitude
    ``delta_max`` [m] (Fig. 3.7). ``normalized`` plots ``Q*`` against ``delta*``;
    otherwise N against um.
    """
    ax = _axes(ax)
    for m in _models(models):
        loop = m.loop(delta_max, points)
        if normalized:
            plot_loop(loop, ax, m.delta_scale, m.critical.P_c, **_style(m.model))
        else:
            plot_loop(loop, ax, 1e-6, 1.0, **_style(m.model))
    ax.set_xlabel(r"$\delta^* = 16G^*a_c\delta/(3P_c)$" if normalized else r"$\delta$ [$\mu$m]")
    ax.set_ylabel(r"$Q^* = Q/P_c$" if normalized else r"$Q$ [N]")
    ax.axhline(0.0, color="0.8", linewidth=0.5, zorder=0)
    ax.axvline(0.0, color="0.8", linewidth=0.5, zorder=0)
    ax.legend()
    return ax


def plot_loading(models: Models, ax=None, points: int = 201, overshoot: float = 0.0,
                 normalized: bool = True):
    """Virgin loading curves up to the onset of gross slip of each model (Fig. 3.6),
    continued by ``overshoot`` times the slip displacement at constant ``mu P``.
    """
    ax = _axes(ax)
    for m in _models(models):
        slip = m.contact.slip_displacement
        delta = np.linspace(0.0, slip * (1.0 + overshoot), points)
        Q = m.contact.loading_force(delta)
        ds, qs = (m.delta_scale, m.critical.P_c) if normalized else (1e-6, 1.0)
        ax.plot(delta / ds, Q / qs, **_style(m.model))
        ax.plot([slip / ds], [m.Q_max / qs], marker="o", color=_style(m.model)["color"])
    ax.set_xlabel(r"$\delta^* = 16G^*a_c\delta/(3P_c)$" if normalized else r"$\delta$ [$\mu$m]")
    ax.set_ylabel(r"$Q^* = Q/P_c$" if normalized else r"$Q$ [N]")
    ax.legend()
    return ax


def plot_energy(models: Models, delta_max: Sequence[float], ax=None, normalized: bool = True):
    """Energy dissipated per cycle against the displacement amplitude (Fig. 3.8).

    ``delta_max`` in metres. ``normalized`` plots ``Delta W*`` against ``delta*``.
    """
    ax = _axes(ax)
    delta_max = np.asarray(delta_max, dtype=float)
    for m in _models(models):
        W = m.energy_curve(delta_max)
        ds, ws = (m.delta_scale, m.energy_scale) if normalized else (1e-6, 1e-9)
        ax.plot(delta_max / ds, W / ws, **_style(m.model))
    ax.set_xlabel(r"$\delta^*_{max}$" if normalized else r"$\delta_{max}$ [$\mu$m]")
    ax.set_ylabel(r"$\Delta W^* = G^*a_c\Delta W/P_c^2$" if normalized else r"$\Delta W$ [nJ]")
    ax.legend()
    return ax


def plot_normal_laws(nu: float, w: Sequence[float], ax=None,
                     laws: Sequence[str] = ("hertz", "ceb", "ke", "bke")):
    """``P* = P/P_c`` against ``omega* = omega/omega_c`` for the normal laws (Fig. 3.2).

    CEB and KE jump at their branch points (w = 1; 1, 6 and 110): with a fine grid the
    jumps show as near-vertical segments.
    """
    ax = _axes(ax)
    w = np.asarray(w, dtype=float)
    for law in laws:
        ax.plot(w, _core.normal_load_star(law, w, nu), **_style(law))
    ax.set_xlabel(r"$\omega^* = \omega/\omega_c$")
    ax.set_ylabel(r"$P^* = P/P_c$")
    ax.legend()
    return ax


def plot_friction_laws(nu: float, w: Sequence[float], params=None, ax=None,
                       laws: Sequence[str] = ("cfc", "ceb", "ke", "bke")):
    """Friction coefficient against ``omega* = omega/omega_c`` (Fig. 3.4)."""
    ax = _axes(ax)
    params = params if params is not None else _core.FrictionParameters()
    w = np.asarray(w, dtype=float)
    for law in laws:
        ax.plot(w, _core.friction_coefficient(law, w, nu, params), **_style(law))
    ax.set_xlabel(r"$\omega^* = \omega/\omega_c$")
    ax.set_ylabel(r"$\mu$")
    ax.legend()
    return ax
