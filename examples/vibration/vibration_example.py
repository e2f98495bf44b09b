#!/usr/bin/env python3
"""A jointed structure in a few lines of Python (asperity.vibration): two 1 kg masses on
springs, held together by the physics-based rough flat of Table 7.2 (the rough contact at
A0 = 1 cm^2 and P = 9 N, the assumptions of examples/dynamics). Prints the amplitude-
dependent frequency and damping of the first mode by EPMC next to the quasi-static
estimate, and the peak of the forced response at three force levels.

    python examples/vibration/vibration_example.py [FIGURE.png]

With a file name it also draws the mode (frequency and damping against amplitude) and
the response curves.
"""
from __future__ import annotations

import sys

import numpy as np

import asperity
from asperity import vibration as vib

k = 1e5  # [N/m] the springs of the structure, as examples/dynamics
M = np.diag([1.0, 1.0])  # [kg]
K = np.array([[2 * k, -k], [-k, 2 * k]])  # mass 1 - ground, 1 - 2, 2 - ground


def main(figure: str | None = None) -> None:
    contact = asperity.table_7_2_rough()  # E*, G*, H, sigma, R, eta of Table 7.2
    contact.A0, contact.P = 1e-4, 9.0  # assumed (Table 7.2 gives no A0)
    joint = vib.RoughFlat.from_contact(contact, T=[1.0, -1.0])  # between the two masses
    s = vib.Structure(M, K, rayleigh={"alpha": 0.0, "beta": 1e-6})
    hb = vib.HarmonicBalance(s, [joint], max_harmonic=5, time_points=256)

    x_slip = joint.core.slip_force / joint.core.initial_stiffness[0, 0]
    stuck, _ = vib.linear_modes(hb.stuck_stiffness(), M)
    free, _ = s.linear_modes()
    print(f"joint: Q_max = {joint.core.slip_force:.3f} N, stiffness "
          f"{joint.core.initial_stiffness[0, 0]:.4g} N/m (slip displacement {x_slip:.3g} m)")
    print(f"linear modes [Hz]: stuck {stuck / (2 * np.pi)}, joint removed {free / (2 * np.pi)}")

    # Mode 2 (masses in opposition) strains the joint; mode 1 moves both masses together.
    lo, hi = np.log10(1e-3 * x_slip), np.log10(3 * x_slip)
    mode = hb.nonlinear_mode(2, (lo, hi), output_dofs=[0, 1])
    qs = hb.quasi_static_mode(2, (10**lo, 10**hi), 400)  # cheap: a static push per point
    print("\nmode 2: modal amplitude a, EPMC and quasi-static frequency [Hz] and damping ratio")
    lq = np.log10(qs.amplitude)
    for k in np.linspace(0, len(mode.amplitude) - 1, 9).round().astype(int):
        a, f, z = mode.amplitude[k], mode.frequency_hz[k], mode.damping_ratio[k]
        fq = np.interp(np.log10(a), lq, qs.frequency_hz)
        zq = 10 ** np.interp(np.log10(a), lq, np.log10(qs.damping_ratio))  # power law
        print(f"  a = {a:9.3g}   f = {f:9.3f} ({fq:.3f})   zeta = {z:.4e} ({zq:.4e})")

    # Forced response of mass 1 around mode 2 under F cos(w t) on mass 1.
    w2 = stuck[1]
    F = hb.force(cos={1: [1.0, 0.0]})
    curves = hb.frequency_response(F, omega=(0.5 * w2, 1.1 * w2), force_scales=[0.1, 0.5, 2.0],
                                   output_dofs=[0])
    print("\nforced response of mass 1: force [N], peak amplitude [m] at [Hz]")
    for c in curves:
        j = int(np.argmax(c.output_amplitude[:, 0]))
        print(f"  {c.force_scale:5.2f}   {c.output_amplitude[j, 0]:.4g} at "
              f"{c.omega[j] / (2 * np.pi):.3f}")

    if figure:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(3, 1, figsize=(6, 9))
        vib.plot_mode(mode, axes=ax[:2], label="EPMC, mode 2", quasi_static=qs)
        vib.plot_response(curves, ax=ax[2], force=F, backbone=mode)
        fig.tight_layout()
        fig.savefig(figure, dpi=120)
        print(f"\nwrote {figure}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
