#!/usr/bin/env python3
"""Regenerates the thesis's Fig. 4.4-4.7 (fretting loops and energy per cycle of the rough
flat) under docs/figures/, and prints our Table 4.1 beside the thesis's.

Conditions (section 4.3): beta = 0.04, P* = 0.001, delta*_max = 0.6, nu = 0.3, identical
materials (G*/E* = (1 - nu)/(2 (2 - nu)) = 0.2059), mu_cfc = 0.3; psi = 0.5 (Fig. 4.4),
1 (Fig. 4.5), 2 (Fig. 4.6). Loops follow Masing's rules on the tabulated backbone, which
equals the direct Eq. 4.11-4.13 integrals (tested).

Usage: python scripts/figures_ch4.py [OUTDIR]  (default docs/figures)
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import asperity  # noqa: E402
from asperity import plotting  # noqa: E402

MODELS = ["cfc", "ceb", "ke", "bke"]
#: Where each model's markers start, so that they do not sit on one another.
STYLES_OFFSET = {"cfc": 0, "ceb": 22, "ke": 44, "bke": 66}
G_OVER_E = 0.7 / 3.4
P_STAR = 1e-3
TABLE_4_1 = {"cfc": (0.3, 0.3, 0.3), "ceb": (0.83, 0.29, 0.03), "ke": (1.02, 0.68, 0.29),
             "bke": (1.18, 0.94, 0.63)}
PSIS = (0.5, 1.0, 2.0)


def flat(model, psi):
    return asperity.RoughFlat(model, beta=0.04, psi=psi, nu=0.3, G_over_E=G_OVER_E, mu_cfc=0.3)


def loop(backbone, dm, n=300):
    x = np.concatenate([np.linspace(0, dm, n), np.linspace(dm, -dm, 2 * n)[1:],
                        np.linspace(-dm, dm, 2 * n)[1:]])
    return x, asperity.Hysteresis(backbone).forces(x)


#: Line style, marker and colour per model, from the chapter 3 figures (plotting.MODEL_STYLES)
#: so that the curves stay apart in grayscale; a marker every few points adds to it.
STYLES = {m: dict(color=plotting.MODEL_STYLES[m]["color"], linestyle=plotting.MODEL_STYLES[m]["linestyle"],
                  marker=mk, markersize=4.5, markerfacecolor="white")
          for m, mk in zip(MODELS, ("o", "s", "^", "D"))}
PSI_LINES = {0.5: "-", 1.0: "--", 2.0: ":"}
X_LABEL = r"$\delta^* = \delta/\sigma$"
Q_LABEL = r"$Q^* = Q/(K H A_0)$"
DPI = 150


def main(out):
    os.makedirs(out, exist_ok=True)
    mu = {}
    for fig, psi in zip((4.4, 4.5, 4.6), PSIS):
        fig_, ax = plt.subplots(figsize=(6.5, 4.8))
        for m in MODELS:
            f = flat(m, psi)
            d = f.separation_star(P_STAR)
            mu[(m, psi)] = f.static_friction_star(d) / P_STAR
            name = plotting.MODEL_STYLES[m]["label"]
            if mu[(m, psi)] == 0.0:
                ax.plot([], [], **STYLES[m], label=rf"{name} ($\mu$ = 0: no loop)")
                continue
            x, q = loop(f.backbone(d), 0.6)
            ax.plot(x, q, **STYLES[m], markevery=(STYLES_OFFSET[m], 90),
                    label=rf"{name} ($\mu$ = {mu[(m, psi)]:.3g})")
        ax.axhline(0.0, color="0.8", linewidth=0.5, zorder=0)
        ax.axvline(0.0, color="0.8", linewidth=0.5, zorder=0)
        ax.set_xlabel(X_LABEL)
        ax.set_ylabel(Q_LABEL)
        ax.set_title(rf"Fig. {fig}: fretting loops, $\psi$ = {psi}, $\beta$ = 0.04, $P^*$ = $10^{{-3}}$")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=10, loc="best", framealpha=0.9)
        fig_.tight_layout()
        fig_.savefig(os.path.join(out, f"fig_{str(fig).replace('.', '_')}.png"), dpi=DPI)
        plt.close(fig_)

    # Fig. 4.7: (a) linear, as the thesis; (b) log-log, where the cubic small-amplitude
    # regime (Mindlin: W ~ delta^3) is a straight line of slope 3.
    fig_, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.6))
    lin = np.linspace(0.0, 1.0, 101)
    log = np.geomspace(1e-3, 1.0, 121)
    small = None
    for m in MODELS:
        for psi in PSIS:
            f = flat(m, psi)
            d = f.separation_star(P_STAR)
            if f.static_friction_star(d) == 0.0:
                continue
            bb = f.backbone(d)
            style = dict(STYLES[m], linestyle=PSI_LINES[psi])
            ax1.plot(lin, bb.energy_per_cycle(lin), **style, markevery=(STYLES_OFFSET[m], 20))
            w = np.asarray(bb.energy_per_cycle(log))
            ax2.loglog(log, w, **style, markevery=(STYLES_OFFSET[m] // 2, 15))
            if small is None or w[0] < small[1]:
                small = (log[0], w[0])
    # Slope-3 guide through the lowest curve's first point, a decade below it.
    g = np.geomspace(1e-3, 1e-1, 2)
    ax2.loglog(g, small[1] / 10 * (g / small[0]) ** 3, color="black", linewidth=1.0,
               linestyle=(0, (6, 3)), label=r"slope 3 ($W^* \propto \delta^{*3}_{max}$)")
    for ax in (ax1, ax2):
        ax.set_xlabel(r"$\delta^*_{max}$")
        ax.set_ylabel(r"$W^* = W/(K H A_0 \sigma)$")
        ax.grid(alpha=0.3, which="both" if ax is ax2 else "major")
    ax1.set_title("(a) linear scale")
    ax2.set_title("(b) log scale: cubic at small amplitude")
    # Two legends: colour and marker name the model, line style the plasticity index.
    from matplotlib.lines import Line2D
    models = [Line2D([], [], **dict(STYLES[m], linestyle="-"), label=plotting.MODEL_STYLES[m]["label"])
              for m in MODELS]
    psis = [Line2D([], [], color="0.3", linestyle=PSI_LINES[p], label=rf"$\psi$ = {p}") for p in PSIS]
    first = ax1.legend(handles=models, fontsize=10, loc="upper left", title="model")
    ax1.add_artist(first)
    ax1.legend(handles=psis, fontsize=10, loc="upper center", title="plasticity index")
    ax2.legend(fontsize=10, loc="lower right")
    fig_.suptitle(r"Fig. 4.7: energy per cycle against amplitude, $\beta$ = 0.04, $P^*$ = $10^{-3}$")
    fig_.tight_layout()
    fig_.savefig(os.path.join(out, "fig_4_7.png"), dpi=DPI)
    plt.close(fig_)

    print("Table 4.1 (mu of the flat, P* = 1e-3): ours / thesis")
    print("model  " + "  ".join(f"psi={p:<14}" for p in PSIS))
    for m in MODELS:
        cells = [f"{mu[(m, p)]:.3f} / {TABLE_4_1[m][i]:<6}" for i, p in enumerate(PSIS)]
        print(f"{m:<6} " + "  ".join(cells))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join("docs", "figures"))
