#!/usr/bin/env python3
"""Example: the micro-scale fretting experiments of Table 3.1/3.2 (steel ball on a steel
flat, Varenberg et al., as modelled in the thesis's chapter 3) with the four
physics-based partial slip models.

    python examples/sphere_example.py [LOOPS.png]

Prints the critical values, then for each experiment (P = 35 N, delta_max = 1.5 um and
P = 23 N, delta_max = 10 um) and each model the normal state, the friction coefficient
(next to the thesis's Table 3.2), the stiffness 8 G* a and the fretting response at the
experiment's amplitude. With a file name it also draws the fretting loops.

It prints the thesis's reading of Table 3.2 (and of `asperity sphere`, whose default is
--interference hertz): every model at the load P as given, with Hertz's interference and
contact radius for that load (omega* = 0.374 and 0.283; "the penetration for all the
models is estimated to be 2.77 um", section 3.5) and its own friction coefficient.
`PartialSlipModel.from_load(pair, model, P)` (interference="own") would use each model's
own normal law instead: BKE's mu is then 0.8 % higher and its 8 G* a 5.5 % higher.
"""
from __future__ import annotations

import sys

import asperity
from asperity import thesis

#: Table 3.2: mu of (CFC, CEB, KE, BKE) per load [N].
TABLE_3_2 = {35.0: (0.284, 0.528, 0.858, 1.444), 23.0: (0.284, 0.626, 0.992, 1.639)}


def main(argv: list[str]) -> int:
    pair = thesis.micro_pair()  # Table 3.1, E = 207 GPa, nu = 0.3, H = 6.83 GPa, R = 2.5 mm
    params = thesis.micro_params()  # mu_cfc = s/H = 0.284 (AISI 304N)
    c = pair.critical
    print(f"E* = {pair.E_star / 1e9:.1f} GPa, G* = {pair.G_star / 1e9:.2f} GPa, K = {pair.K:.3f}")
    print(f"omega_c = {c.omega_c * 1e6:.3f} um, a_c = {c.a_c * 1e3:.4f} mm, "
          f"P_c = {c.P_c:.1f} N   (thesis: 7.41 um, 0.136 mm, 152.8 N)")

    all_models = {}
    for P, delta_max in thesis.MICRO_EXPERIMENTS:
        hertz = asperity.PartialSlipModel.from_load(pair, "cfc", P, params, interference="hertz")
        print(f"\nP = {P:g} N, delta_max = {delta_max * 1e6:g} um: omega* = "
              f"{hertz.omega_star:.3f}, omega = {hertz.omega * 1e6:.2f} um, "
              f"8G*a = {hertz.K_T * 1e-6:.2f} N/um (Hertz's interference and radius for "
              f"every model, as in Table 3.2)")
        print("  model  mu     (thesis)  Q_max [N]  slip [um]  Q(delta_max) [N]  "
              "energy [uJ]  regime")
        models = {}
        for name, mu_thesis in zip(asperity.models, TABLE_3_2[P]):
            m = asperity.PartialSlipModel.from_load(pair, name, P, params, interference="hertz")
            models[name] = m
            contact = m.contact
            print(f"  {name:5s} {m.mu:6.3f} ({mu_thesis:5.3f})  {m.Q_max:9.2f}  "
                  f"{contact.slip_displacement * 1e6:9.3f}  "
                  f"{contact.loading_force(delta_max):16.2f}  "
                  f"{contact.energy_per_cycle(delta_max) * 1e6:11.3f}  "
                  f"{contact.regime_for_displacement(delta_max)}")
        all_models[(P, delta_max)] = models

    if len(argv) > 1:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from asperity import plotting

        fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
        for ax, ((P, delta_max), models) in zip(axes, all_models.items()):
            plotting.plot_loops(models, delta_max, ax=ax, normalized=False)
            ax.set_title(f"P = {P:g} N, $\\delta_{{max}}$ = {delta_max * 1e6:g} $\\mu$m")
        fig.tight_layout()
        fig.savefig(argv[1], dpi=150)
        print(f"\nwrote {argv[1]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
