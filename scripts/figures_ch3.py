#!/usr/bin/env python3
"""Regenerates the asperity-scale figures of the thesis's chapter 3 as PNG files.

    python scripts/figures_ch3.py [OUTPUT_DIR]      # default: docs/figures

Fig. 3.2  P* = P/P_c against omega* = omega/omega_c for Hertz, CEB, KE, BKE (nu = 0.3)
Fig. 3.4  friction coefficient against omega* for CFC (0.284), CEB, KE, BKE
Fig. 3.6  tangential loading up to sliding inception, omega* = 0.6 (thesis variables)
Fig. 3.7  fretting loops for one displacement amplitude, omega* = 0.6
Fig. 3.8  energy per cycle against the displacement amplitude, omega* = 0.6

Material: Table 3.1 (steel ball R = 2.5 mm on a steel flat, nu = 0.3, mu_cfc = 0.284).
Normalization of section 3.3-3.4: delta* = 16 G* a_c delta/(3 P_c), Q* = Q/P_c,
Delta W* = G* a_c Delta W/P_c^2. Needs the asperity package (`pip install .`).
"""
from __future__ import annotations

import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import asperity  # noqa: E402
from asperity import plotting, thesis  # noqa: E402

OMEGA_STAR = 0.6  # section 3.4: "a normalized penetration of 0.6"
#: Fig. 3.7 amplitude: the thesis does not print it; it says every loop but CFC's is
#: in partial slip, so it lies between CFC's slip displacement (0.170) and CEB's (0.234).
DELTA_STAR_FIG_3_7 = 0.2
DPI = 150


def models_at(omega_star: float) -> dict:
    pair, params = thesis.micro_pair(), thesis.micro_params()
    return {
        name: asperity.PartialSlipModel.from_interference_star(pair, name, omega_star, params)
        for name in asperity.models
    }


def fig_3_2(out: pathlib.Path) -> None:
    nu = thesis.micro_pair().nu
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.2))
    plotting.plot_normal_laws(nu, np.linspace(0.0, 12.0, 2401), ax=ax1)
    ax1.set_xlim(0, 12)
    ax1.set_ylim(0, 35)
    ax1.set_title("(a) linear scale")
    plotting.plot_normal_laws(nu, np.geomspace(1e-2, 300.0, 3001), ax=ax2)
    ax2.set_xscale("log")
    ax2.set_yscale("log")
    ax2.set_title("(b) log scale: KE branches at 1, 6, 110")
    fig.suptitle(r"Fig. 3.2: dimensionless normal load vs interference, $\nu$ = %.1f" % nu)
    fig.tight_layout()
    fig.savefig(out / "fig_3_2.png", dpi=DPI)
    plt.close(fig)


def fig_3_4(out: pathlib.Path) -> None:
    nu = thesis.micro_pair().nu
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    w = np.linspace(0.01, 10.0, 4000)
    plotting.plot_friction_laws(nu, w, thesis.micro_params(), ax=ax)
    # Table 3.2's interferences: Exp. 2 (23 N) at 0.283, Exp. 1 (35 N) at 0.374.
    for w_exp in (0.283, 0.374):
        ax.axvline(w_exp, color="0.6", linewidth=0.8, zorder=0)
    ax.text(0.45, 2.0, "thin lines: $\\omega^*$ of Table 3.2\n(Exp. 2: 0.283, Exp. 1: 0.374)",
            ha="left", va="center", fontsize=8, color="0.3")
    ax.axhline(0.26, color="tab:red", linewidth=0.5, alpha=0.5)
    ax.text(9.9, 0.2, "BKE asymptote 0.26", ha="right", va="top", fontsize=8, color="tab:red")
    ax.set_xlim(0, 10)
    ax.set_ylim(0, 3)
    ax.set_title(r"Fig. 3.4: friction coefficient vs $\omega^*$ (CFC: s/H = 0.284)")
    fig.tight_layout()
    fig.savefig(out / "fig_3_4.png", dpi=DPI)
    plt.close(fig)


def fig_3_6(out: pathlib.Path, models: dict) -> None:
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    plotting.plot_loading(models, ax=ax)
    # Full stick (Eq. 3.6, B.14): delta = Q/(8 G* a), with the Hertzian radius.
    hertz = models["cfc"]
    q = np.linspace(0.0, 0.3, 2)
    ax.plot(q * hertz.critical.P_c / hertz.K_T / hertz.delta_scale, q, color="0.5",
            linewidth=0.8, linestyle="--", label="full stick (Eq. 3.6)")
    ax.legend()
    ax.set_xlim(0, None)
    ax.set_ylim(0, None)
    ax.set_title(r"Fig. 3.6: loading up to sliding inception, $\omega^*$ = %.1f" % OMEGA_STAR)
    fig.tight_layout()
    fig.savefig(out / "fig_3_6.png", dpi=DPI)
    plt.close(fig)


def fig_3_7(out: pathlib.Path, models: dict) -> None:
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    delta_max = DELTA_STAR_FIG_3_7 * models["cfc"].delta_scale
    plotting.plot_loops(models, delta_max, ax=ax, points=301)
    ax.set_title(r"Fig. 3.7: fretting loops, $\omega^*$ = %.1f, $\delta^*_{max}$ = %.2f"
                 % (OMEGA_STAR, DELTA_STAR_FIG_3_7))
    fig.tight_layout()
    fig.savefig(out / "fig_3_7.png", dpi=DPI)
    plt.close(fig)


def fig_3_8(out: pathlib.Path, models: dict) -> None:
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.2))
    scale = models["cfc"].delta_scale
    plotting.plot_energy(models, np.linspace(0.0, 1.2, 601) * scale, ax=ax1)
    ax1.set_xlim(0, 1.2)
    ax1.set_ylim(0, None)
    ax1.set_title("(a) linear scale")
    plotting.plot_energy(models, np.geomspace(1e-2, 1.2, 400) * scale, ax=ax2)
    ax2.set_xscale("log")
    ax2.set_yscale("log")
    ax2.set_title(r"(b) log scale: $\Delta W \propto \delta_{max}^3/\mu$ when small (B.20)")
    for m in models.values():
        s = m.contact.slip_displacement / m.delta_scale
        for ax in (ax1, ax2):
            ax.axvline(s, color=plotting.MODEL_STYLES[m.model]["color"], linewidth=0.5,
                       alpha=0.5, zorder=0)
    fig.suptitle(r"Fig. 3.8: energy per cycle vs amplitude, $\omega^*$ = %.1f "
                 r"(thin lines: onset of gross slip)" % OMEGA_STAR)
    fig.tight_layout()
    fig.savefig(out / "fig_3_8.png", dpi=DPI)
    plt.close(fig)


def summary(models: dict) -> None:
    print(f"omega* = {OMEGA_STAR}: model  mu      K_T*    Q_max*  slip delta*")
    for name, m in models.items():
        k_star = m.K_T * m.delta_scale / m.critical.P_c
        print(f"  {name:4s} {m.mu:7.3f} {k_star:7.3f} {m.Q_max / m.critical.P_c:7.3f} "
              f"{m.contact.slip_displacement / m.delta_scale:7.3f}")
    scale = models["cfc"].delta_scale
    for d in (0.05, 1.2):
        W = {n: float(m.energy_curve(d * scale) / m.energy_scale) for n, m in models.items()}
        order = " > ".join(sorted(W, key=W.get, reverse=True))
        print(f"  Delta W* at delta* = {d}: {order}  "
              + ", ".join(f"{n} {w:.3g}" for n, w in W.items()))


def main(argv: list[str]) -> int:
    out = pathlib.Path(argv[1]) if len(argv) > 1 else (
        pathlib.Path(__file__).resolve().parent.parent / "docs" / "figures")
    out.mkdir(parents=True, exist_ok=True)
    models = models_at(OMEGA_STAR)
    fig_3_2(out)
    fig_3_4(out)
    fig_3_6(out, models)
    fig_3_7(out, models)
    fig_3_8(out, models)
    summary(models)
    print(f"wrote fig_3_2.png, fig_3_4.png, fig_3_6.png, fig_3_7.png, fig_3_8.png to {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
