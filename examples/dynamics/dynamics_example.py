#!/usr/bin/env python3
"""Thesis chapter 7 in a few lines of Python: the base-excited single-DOF system of
Eq. 7.1 (non-dimensional, section 7.2) after the half-sine pulse of Table 7.2 with no
friction, Dankowicz friction and the physics-based law of the Table 7.2 rough contact;
modal frequency and damping from the spectrum and from the first free-decay cycle, and
the energy balance of each run.

    python examples/dynamics/dynamics_example.py [RESPONSE.png]

Assumptions as in examples/dynamics/README.md: Table 7.2 gives no nominal area and no
unit for A, so A0 = 1 cm^2, k = 1e5 N/m, A = 18 um and P = 5 k A = 9 N. With a file
name it also draws the three responses and the friction loops.
"""
from __future__ import annotations

import sys

import asperity

EPS = 0.032  # Table 7.2
K, A = 1e5, 18e-6  # structural stiffness [N/m] and displacement scale [m] (assumed)


def models() -> dict:
    rough = asperity.table_7_2_rough()  # E* 106 GPa, G* 22.9 GPa, H 5.8 GPa, sigma 2.7 um ...
    rough.A0 = 1e-4
    rough.P = 5.0 * K * A
    return {
        "none": asperity.NoFriction(),
        "dankowicz": asperity.Dankowicz(F_max=1.5, delta=0.011),
        "physics": asperity.make_physics_based(asperity.epb_backbone(rough), K, A),
    }


def main(argv: list[str]) -> int:
    dt = 0.05
    runs = {}
    print(f"{'friction':10s} {'f (spectrum)':>12s} {'zeta':>8s} {'f (cycle 1)':>12s} "
          f"{'zeta':>8s} {'energy err':>10s} {'steps':>6s}")
    for name, model in models().items():
        # Dormand-Prince 5(4) (the default) at the thesis's tolerances, rtol 1e-6, atol 1e-7.
        tr = asperity.simulate(asperity.ImpulseExcitation(), model, epsilon=EPS, duration=200.0,
                               output_interval=dt, locate_reversals=True)
        m = asperity.modal_estimate(asperity.Periodogram(asperity.uniform_samples(tr, dt), dt),
                                    0.02, 5.0)
        d = asperity.free_decay(tr, 0.1)
        f1 = d["frequency"][0] if len(d["frequency"]) else float("nan")
        z1 = d["damping_ratio"][0] if len(d["damping_ratio"]) else float("nan")
        print(f"{name:10s} {m.frequency:12.4f} {m.damping_ratio:8.4f} {f1:12.4f} {z1:8.4f} "
              f"{tr.energy_balance_error():10.2e} {tr.steps:6d}")
        runs[name] = tr
    if len(argv) > 1:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4))
        for name, tr in runs.items():
            keep = tr.tau <= 20.0
            ax1.plot(tr.tau[keep], tr.u[keep], label=name)
            if name != "none":
                ax2.plot(tr.u[keep], tr.friction[keep], label=name)
        ax1.set(xlabel="tau", ylabel="u = x/A", title="Impulse response (Fig. 7.3-7.4 style)")
        ax2.set(xlabel="u", ylabel="F_s = f_s/(k A)", title="Friction force vs displacement")
        ax1.legend()
        ax2.legend()
        fig.tight_layout()
        fig.savefig(argv[1], dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
