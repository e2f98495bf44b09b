#!/usr/bin/env python3
"""Convergence of harmonic balance in the number of harmonics H and of time samples N_t,
for the single-DOF Jenkins oscillator of issue 10's example case (m = 1 kg, k = 1 N/m,
c = 0.01 N s/m, Jenkins k_t = 0.25 N/m, F_s = 0.2 N; slip onset at a_s = F_s/k_t = 0.8 m).

Prints Markdown tables (for docs/vibration.md):
  1. the peak first-harmonic amplitude of the forced response under F cos(w t) for a few
     force levels: the frequency-response continuation finds the peak's neighbourhood,
     an 81-point scan and a golden-section search on w (harmonic balance solved by Newton
     at each w with the analytic Jacobian) locate the maximum to 1e-10 in w;
  2. the nonlinear mode (EPMC): natural frequency and damping ratio at a few modal
     amplitudes (each continuation ends on the amplitude exactly).
Each entry is given with its relative difference to the finest discretization (H = 7,
N_t = 2048). Odd H only: the Jenkins element is odd-symmetric, even harmonics vanish.

Usage: python bench/vibration_convergence.py [--quick]
(PYTHONPATH must reach the asperity package, e.g. build/<preset>/python.)
Nothing here is timed: it measures discretization error, not speed.
"""
from __future__ import annotations

import argparse
import math
import warnings

import numpy as np

import asperity.vibration as vib

M, K, C, KT, FS = 1.0, 1.0, 0.01, 0.25, 0.2


def system(H: int, Nt: int) -> vib.HarmonicBalance:
    s = vib.Structure([[M]], [[K]], [[C]])
    return vib.HarmonicBalance(s, [vib.Jenkins(KT, FS)], max_harmonic=H, time_points=Nt)


def newton(hb, w, F, U):
    for _ in range(60):
        R, J, _ = hb.residual(U, w, F)
        dU = np.linalg.solve(J, -R)
        lam, n0 = 1.0, np.linalg.norm(R)
        while lam > 1e-6 and np.linalg.norm(hb.residual(U + lam * dU, w, F, jacobian=False)) > (
                1 - 1e-4 * lam) * n0:
            lam /= 2
        U = U + lam * dU
        if np.abs(dU).max() <= 1e-13 * max(np.abs(U).max(), 1e-300):
            return U
    raise RuntimeError(f"Newton did not converge at w = {w}")


def frf_peak(H: int, Nt: int, force: float) -> float:
    hb = system(H, Nt)
    F = hb.force(cos={1: [force]})
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an incomplete curve must not pass silently
        (c,) = hb.frequency_response(F, omega=(0.7, 1.4), output_dofs=[0], step=0.01,
                                     max_step=0.02)
    a = c.output_amplitude[:, 0]
    k = int(np.argmax(a))
    lo, hi = c.omega[max(k - 1, 0)], c.omega[min(k + 1, len(a) - 1)]
    if lo > hi:
        lo, hi = hi, lo
    U0 = c.harmonics[k]
    cache = {}

    def amp(w):
        U = newton(hb, w, F, cache.get("U", U0))
        cache["U"] = U
        return hb.harmonic_amplitude(U, 0, 1)

    # A scan first: at small N_t the sampled slip onset makes a(w) rippled (several local
    # maxima within 1e-4), so the golden-section search starts from the scan's best point.
    ws = np.linspace(lo, hi, 81)
    amps = [amp(w) for w in ws]
    j = int(np.argmax(amps))
    lo, hi = ws[max(j - 1, 0)], ws[min(j + 1, len(ws) - 1)]
    cache.pop("U", None)
    g = (math.sqrt(5) - 1) / 2
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = amp(x1), amp(x2)
    while hi - lo > 1e-10:
        if f1 > f2:
            hi, x2, f2 = x2, x1, f1
            x1 = hi - g * (hi - lo)
            f1 = amp(x1)
        else:
            lo, x1, f1 = x1, x2, f2
            x2 = lo + g * (hi - lo)
            f2 = amp(x2)
    return max(f1, f2)


def epmc_at(H: int, Nt: int, amplitude: float):
    hb = system(H, Nt)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = hb.nonlinear_mode(1, (-1.0, math.log10(amplitude)))
    return r.omega[-1], r.damping_ratio[-1]


def table(title, rows, cols, cell, ref):
    print(f"\n{title}\n")
    print("| H \\ N_t | " + " | ".join(str(c) for c in cols) + " |")
    print("|---" * (len(cols) + 1) + "|")
    for H in rows:
        out = []
        for Nt in cols:
            if Nt < 2 * H + 2:
                out.append("-")
                continue
            v = cell(H, Nt)
            out.append(f"{v:.6g} ({v / ref - 1:+.1e})")
        print(f"| {H} | " + " | ".join(out) + " |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer N_t (64, 256, 1024)")
    args = ap.parse_args()
    Hs = [1, 3, 5, 7]
    Nts = [64, 256, 1024] if args.quick else [64, 128, 256, 512, 1024, 2048]
    print(f"SDOF Jenkins: m = {M}, k = {K}, c = {C}, k_t = {KT}, F_s = {FS} (a_s = {FS / KT})")
    print("Entries: value (relative difference to H = 7, N_t = 2048).")
    for force in (0.02, 0.05, 0.1):
        ref = frf_peak(7, 2048, force)
        table(f"Peak first-harmonic amplitude [m] of the response to {force} cos(w t) N",
              Hs, Nts, lambda H, Nt: frf_peak(H, Nt, force), ref)
    for a in (1.0, 2.0, 5.0):
        w_ref, z_ref = epmc_at(7, 2048, a)
        table(f"EPMC natural frequency [rad/s] at modal amplitude a = {a} m", Hs, Nts,
              lambda H, Nt: epmc_at(H, Nt, a)[0], w_ref)
        table(f"EPMC damping ratio at modal amplitude a = {a} m", Hs, Nts,
              lambda H, Nt: epmc_at(H, Nt, a)[1], z_ref)


if __name__ == "__main__":
    main()
