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

MODELS = ["cfc", "ceb", "ke", "bke"]
COLORS = {"cfc": "tab:blue", "ceb": "tab:orange", "ke": "tab:green", "bke": "tab:red"}
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


def main(out):
    os.makedirs(out, exist_ok=True)
    mu = {}
    for fig, psi in zip((4.4, 4.5, 4.6), PSIS):
        plt.figure(figsize=(6.4, 4.8))
        for m in MODELS:
            f = flat(m, psi)
            d = f.separation_star(P_STAR)
            mu[(m, psi)] = f.static_friction_star(d) / P_STAR
            if mu[(m, psi)] == 0.0:
                plt.plot([], [], color=COLORS[m], label=f"{m.upper()} (mu = 0: no loop)")
                continue
            x, q = loop(f.backbone(d), 0.6)
            plt.plot(x, q, color=COLORS[m], label=f"{m.upper()} (mu = {mu[(m, psi)]:.3g})")
        plt.xlabel("delta* = delta / sigma")
        plt.ylabel("Q* = Q / (K H A0)")
        plt.title(f"Fig. {fig}: fretting loops, psi = {psi}, beta = 0.04, P* = 1e-3")
        plt.grid(alpha=0.3)
        plt.legend(fontsize=8)
        plt.tight_layout()
        plt.savefig(os.path.join(out, f"fig_{str(fig).replace('.', '_')}.png"), dpi=120)
        plt.close()

    plt.figure(figsize=(6.4, 4.8))
    amps = np.linspace(0.0, 1.0, 101)
    for m in MODELS:
        for psi, ls in zip(PSIS, ("-", "--", ":")):
            f = flat(m, psi)
            d = f.separation_star(P_STAR)
            if f.static_friction_star(d) == 0.0:
                continue
            w = f.backbone(d).energy_per_cycle(amps)
            plt.plot(amps, w, ls, color=COLORS[m], label=f"{m.upper()} psi={psi}")
    plt.xlabel("delta*_max")
    plt.ylabel("W* = W / (K H A0 sigma)")
    plt.title("Fig. 4.7: energy per cycle, P* = 1e-3")
    plt.grid(alpha=0.3)
    plt.legend(fontsize=7, ncol=2)
    plt.tight_layout()
    plt.savefig(os.path.join(out, "fig_4_7.png"), dpi=120)
    plt.close()

    print("Table 4.1 (mu of the flat, P* = 1e-3): ours / thesis")
    print("model  " + "  ".join(f"psi={p:<14}" for p in PSIS))
    for m in MODELS:
        cells = [f"{mu[(m, p)]:.3f} / {TABLE_4_1[m][i]:<6}" for i, p in enumerate(PSIS)]
        print(f"{m:<6} " + "  ".join(cells))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join("docs", "figures"))
