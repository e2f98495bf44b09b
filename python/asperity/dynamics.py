"""Dynamics case files and matplotlib figures mirroring the thesis's Fig. 7.3-7.7 (ch. 7).

``run_case(path)`` runs a case file of ``asperity dynamics`` (docs/dynamics.md) through
the same C++ code as the command and returns the summary (the content of summary.json)
and the time histories as numpy arrays; warnings about the run's accuracy or cost are
also issued as :class:`RuntimeWarning`. The plotting helpers take such results:

* :func:`plot_spectra` - power spectra of impulse responses (Fig. 7.3, 7.4), each
  normalised by its own peak (the pulses differ in amplitude, e.g. the 200 A Coulomb
  pulse, whose raw power is ~1e6 times the others');
* :func:`plot_ramp` - ramp responses (Fig. 7.5);
* :func:`plot_harmonic` - steady harmonic responses, phase portraits above and friction
  force against displacement below (Fig. 7.6, 7.7);
* :func:`thesis_figures` - all five from the shipped examples (examples/dynamics).

Everything is in the non-dimensional variables of section 7.2 (u = x/A, tau = sqrt(k/m) t,
F_s = f_s/(k A)); the assumptions behind the physics-based cases (A0 = 1 cm^2, A = 18 um,
P = 9 N; Table 7.2 gives no A0) are stated in the figure titles.
"""
from __future__ import annotations

import os
import warnings
from typing import Mapping, Sequence

import numpy as np

from . import _core, _optional

ASSUMPTIONS = "EPB: A0 = 1 cm^2, A = 18 um, P = 9 N (assumed; Table 7.2 gives no A0)"


def _issue(result: dict, source: str) -> dict:
    for w in result["warnings"]:
        warnings.warn(f"{source}: {w}", RuntimeWarning, stacklevel=3)
    return result


def run_case(path: str | os.PathLike) -> dict:
    """Runs a dynamics case file; returns a dict with ``summary`` (summary.json as a dict),
    ``arrays`` (numpy arrays tau, u, v, y, friction, [z], work_base, dissipated_damper,
    work_friction, energy, event and, when the scales allow, t [s], x [m], xdot [m/s],
    base [m], f_s [N]), ``spectrum`` (dict frequency, power; decays only, else None),
    ``warnings`` (also issued as RuntimeWarning) and ``trajectory``."""
    return _issue(_core.run_dynamics_case(os.fspath(path)), os.fspath(path))


def run_case_text(text: str, base_dir: str | os.PathLike = ".") -> dict:
    """:func:`run_case` for case-file text (``base_dir`` resolves a [joint]'s profiles)."""
    return _issue(_core.run_dynamics_case_text(text, os.fspath(base_dir)), "<string>")


def _axes(ax):
    if ax is None:
        plt = _optional.pyplot()

        _, ax = plt.subplots()
    return ax


def normalised_spectrum(result: dict, f_max: float | None = None):
    """``(frequency, power / peak power)`` of a decay's spectrum; the peak is the largest
    value up to ``f_max`` (all when None). Half power is then 0.5."""
    sp = result["spectrum"]
    if sp is None:
        raise ValueError("the result has no spectrum (only impulse and free decays have one)")
    f, p = np.asarray(sp["frequency"]), np.asarray(sp["power"])
    keep = f <= f_max if f_max is not None else np.ones_like(f, dtype=bool)
    return f[keep], p[keep] / p[keep].max()


def plot_spectra(results: Mapping[str, dict], ax=None, f_max: float = 4.0,
                 title: str = "Power spectra of the impulse response"):
    """Fig. 7.3 / 7.4: power spectra of impulse responses on a log axis, each normalised by
    its peak, with each run's modal frequency (the spectral peak) in the legend."""
    ax = _axes(ax)
    for label, r in results.items():
        f, p = normalised_spectrum(r, f_max)
        mf = r["summary"]["modal_frequency"]
        ax.semilogy(f, p, label=f"{label} (peak {mf:.3g})" if mf else f"{label} (no peak)")
    ax.set_xlabel("non-dimensional frequency [cycles per unit tau]")
    ax.set_ylabel("power / peak power")
    ax.set_xlim(0.0, f_max)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    return ax


def plot_ramp(results: Mapping[str, dict], ax=None, tau_max: float = 30.0,
              title: str = "Ramp response (alpha = 1)"):
    """Fig. 7.5: u(tau) of ramp responses, the base y = tau dashed, each run's end of the
    first stick (|u'| < 5 % of the base velocity) marked."""
    ax = _axes(ax)
    base_drawn = False
    for label, r in results.items():
        a = r["arrays"]
        keep = a["tau"] <= tau_max
        if not base_drawn:
            ax.plot(a["tau"][keep], a["y"][keep], "k--", lw=1, label="base y = tau")
            base_drawn = True
        slip = r["summary"].get("first_slip")
        line, = ax.plot(a["tau"][keep], a["u"][keep],
                        label=f"{label} (stick until {slip:.3g})" if slip else label)
        if slip:
            ax.axvline(slip, color=line.get_color(), lw=0.8, ls=":")
    ax.set_xlabel("tau")
    ax.set_ylabel("u = x/A")
    ax.set_xlim(0.0, tau_max)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper left")
    return ax


def _steady(r: dict, cycles: int | None):
    a = r["arrays"]
    s = r["summary"]
    n = cycles if cycles is not None else s["steady_loop"]["cycles"]
    keep = a["tau"] >= s["duration"] - n / s["excitation_parameters"]["frequency"]
    return a["u"][keep], a["v"][keep], a["friction"][keep]


def plot_harmonic(results: Mapping[str, dict], axes: Sequence | None = None,
                  cycles: int | None = None, title: str = "Steady harmonic response"):
    """Fig. 7.6 / 7.7: for each run (columns) the phase portrait u' against u (top) and the
    friction force F_s against u (bottom) over the last ``cycles`` periods (the summary's
    loop cycles by default)."""
    if axes is None:
        plt = _optional.pyplot()

        fig, axes = plt.subplots(2, len(results), figsize=(5.5 * len(results), 8.5),
                                 squeeze=False)
        fig.suptitle(title)
    axes = np.asarray(axes).reshape(2, len(results))
    for col, (label, r) in enumerate(results.items()):
        u, v, F = _steady(r, cycles)
        amp = r["summary"]["steady_loop"]["displacement_amplitude_over_base"]
        axes[0, col].plot(u, v)
        axes[0, col].set(xlabel="u", ylabel="u'",
                         title=f"{label}: |u| <= {100 * amp:.2g} % of the base amplitude")
        axes[1, col].plot(u, F)
        axes[1, col].set(xlabel="u", ylabel="F_s = f_s/(k A)",
                         title=f"{label}: {r['summary']['steady_loop']['energy_per_cycle']:.3g}"
                               " dissipated per cycle")
        for ax in axes[:, col]:
            ax.grid(True, alpha=0.3)
            ax.ticklabel_format(style="sci", scilimits=(-2, 3))
    return axes


def thesis_figures(examples_dir: str | os.PathLike, out_dir: str | os.PathLike | None = None):
    """Runs the shipped examples (examples/dynamics) and draws Fig. 7.3-7.7 with
    matplotlib; returns ``{"7.3": fig, ...}`` and, with ``out_dir``, writes
    fig_7_3.png ... fig_7_7.png there."""
    plt = _optional.pyplot()

    d = os.fspath(examples_dir)

    def run(name):
        return run_case(os.path.join(d, name + ".toml"))

    figs = {}
    fig, ax = plt.subplots(figsize=(9, 6))
    plot_spectra({"no friction": run("impulse_none"),
                  "Coulomb, pulse 200 A": run("impulse_coulomb_large"),
                  "Coulomb, unit pulse": run("impulse_coulomb"),
                  "Dankowicz": run("impulse_dankowicz")}, ax,
                 title="Fig. 7.3: impulse response, Coulomb and Dankowicz (Table 7.2)")
    figs["7.3"] = fig
    fig, ax = plt.subplots(figsize=(9, 6))
    plot_spectra({"no friction": run("impulse_none"), "EPB rough": run("impulse_physics_rough"),
                  "EPB smooth": run("impulse_physics_smooth")}, ax,
                 title=f"Fig. 7.4: impulse response, EPB\n{ASSUMPTIONS}")
    figs["7.4"] = fig
    fig, ax = plt.subplots(figsize=(9, 6))
    plot_ramp({"Coulomb, k = 1e4": run("ramp_coulomb_soft"),
               "Dankowicz, k = 1e4": run("ramp_dankowicz_soft"),
               "EPB rough, k = 1e4": run("ramp_physics_rough_soft"),
               "Dankowicz, k = 1e5": run("ramp_dankowicz_hard"),
               "EPB rough, k = 1e5": run("ramp_physics_rough_hard")}, ax,
              title=f"Fig. 7.5: ramp response, soft and hard structure\n{ASSUMPTIONS}")
    figs["7.5"] = fig
    axes = plot_harmonic({"Coulomb": run("harmonic_coulomb"),
                          "Dankowicz": run("harmonic_dankowicz")},
                         title="Fig. 7.6: steady harmonic response, Coulomb and Dankowicz")
    figs["7.6"] = axes[0, 0].figure
    axes = plot_harmonic({"EPB smooth": run("harmonic_physics_smooth"),
                          "EPB rough": run("harmonic_physics_rough")},
                         title=f"Fig. 7.7: steady harmonic response, EPB\n{ASSUMPTIONS}")
    figs["7.7"] = axes[0, 0].figure
    if out_dir is not None:
        os.makedirs(out_dir, exist_ok=True)
        for key, f in figs.items():
            f.tight_layout()
            f.savefig(os.path.join(out_dir, f"fig_{key.replace('.', '_')}.png"), dpi=110)
    return figs


__all__ = ["run_case", "run_case_text", "normalised_spectrum", "plot_spectra", "plot_ramp",
           "plot_harmonic", "thesis_figures", "ASSUMPTIONS"]
