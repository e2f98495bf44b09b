#!/usr/bin/env python3
"""The Brake-Reuss beam's mode-1 backbones side by side (docs/brb.md): the thesis's physics
(brb_epmc.toml), the constant-mu reference (brb_epmc_constant_mu.toml) and the published
prediction of Porter and Brake's rough-contact model (MSSP 192, 2023, 110210) as stored
by the tmdsimpy project (examples/structures/results/brb_epmc_meso.yaml, MIT licence:
LICENSE-tmdsimpy.txt beside this file), against the tip accelerometer's first-harmonic
acceleration.

Run after the vibration runs (their --out directories as below; the constant-mu one is
optional):

    python3 examples/brb/plot_backbones.py out/brb_epmc [out/brb_epmc_constant_mu] \
        docs/figures/brb_backbones.png

The published model adds a mass-proportional linear damping of 0.087 % of critical at
168.6 Hz (tmdsimpy examples/structures/brb_epmc.py, `damp_ab`); our runs add none, so its
damping is drawn as published and also with that linear part subtracted (dashed).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The published backbone (tmdsimpy examples/structures/results/brb_epmc_meso.yaml, all 22
# points): tip acceleration [m/s^2], frequency [rad/s], damping ratio [-].
PUBLISHED_ACCEL = [
    1.267290666388e-01, 1.443588984054e-01, 1.644394378426e-01, 2.320923022423e-01,
    4.451364361840e-01, 8.536133421213e-01, 1.636866421150e+00, 3.132489350605e+00,
    5.955911291107e+00, 1.114462744867e+01, 1.689737948310e+01, 2.155215907706e+01,
    2.684469018263e+01, 3.465854736959e+01, 3.738724484990e+01, 4.157427539787e+01,
    4.708815114165e+01, 5.061437687876e+01, 5.343616825589e+01, 5.699144458250e+01,
    6.102723297700e+01, 6.646200043554e+01]
PUBLISHED_OMEGA = [
    1.134915600438e+03, 1.134913068877e+03, 1.134909024334e+03, 1.134898786893e+03,
    1.134883028246e+03, 1.134786253213e+03, 1.134576126695e+03, 1.133781108008e+03,
    1.131171606921e+03, 1.122198183591e+03, 1.107305848701e+03, 1.094670098874e+03,
    1.082058156524e+03, 1.066685496980e+03, 1.061766563044e+03, 1.054435640336e+03,
    1.045399042958e+03, 1.039974178734e+03, 1.035820231613e+03, 1.030809806798e+03,
    1.025356792630e+03, 1.018337157852e+03]
PUBLISHED_ZETA = [
    8.779562039979e-04, 8.797140401396e-04, 8.822346930100e-04, 8.846896685690e-04,
    8.890647985611e-04, 9.564389105676e-04, 1.074547211145e-03, 1.538052284778e-03,
    3.078124796678e-03, 8.386452963274e-03, 1.611454625048e-02, 2.104501215886e-02,
    2.456079742182e-02, 2.798795721181e-02, 2.924151353427e-02, 3.113625322953e-02,
    3.330270955559e-02, 3.454347985576e-02, 3.545773203813e-02, 3.655423995987e-02,
    3.776980082351e-02, 3.939926377489e-02]
TWO_PI = 6.283185307179586
# Their linear damping C = alpha M, alpha = 2 zeta_0 omega_0 (zeta_0 = 0.087 %, omega_0 =
# 2 pi 168.622 rad/s), adds alpha / (2 omega) to a mode's damping ratio.
PUBLISHED_ALPHA = 2 * 0.087e-2 * TWO_PI * 168.622


def read(directory):
    with open(f"{directory}/nonlinear_mode.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return ([float(r["tip_z_acceleration_m_s2"]) for r in rows],
            [float(r["frequency_hz"]) for r in rows],
            [float(r["damping_ratio"]) for r in rows])


def main(argv):
    if len(argv) not in (3, 4):
        sys.exit(__doc__)
    runs = [(argv[1], "thesis's physics (BKE, no fitted mu)", "-")]
    if len(argv) == 4:
        runs.append((argv[2], "constant mu = 0.03 (CFC)", "--"))
    out = argv[-1]
    fig, (ax_f, ax_z) = plt.subplots(1, 2, figsize=(10, 4.2))
    for directory, label, style in runs:
        a, f, z = read(directory)
        ax_f.semilogx(a, f, style, color="black", label=label)
        ax_z.loglog(a, z, style, color="black", label=label)
    pf = [w / TWO_PI for w in PUBLISHED_OMEGA]
    pz_joint = [z - PUBLISHED_ALPHA / (2 * w) for z, w in zip(PUBLISHED_ZETA, PUBLISHED_OMEGA)]
    ax_f.semilogx(PUBLISHED_ACCEL, pf, "o", mfc="none", color="tab:red",
                  label="published (Porter & Brake 2023, mu = 0.03)")
    ax_z.loglog(PUBLISHED_ACCEL, PUBLISHED_ZETA, "o", mfc="none", color="tab:red",
                label="published, as stored")
    ax_z.loglog(PUBLISHED_ACCEL, pz_joint, "x", color="tab:red",
                label="published minus its linear 0.087 %")
    ax_f.set_xlabel("tip acceleration, first harmonic [m/s^2]")
    ax_z.set_xlabel("tip acceleration, first harmonic [m/s^2]")
    ax_f.set_ylabel("frequency [Hz]")
    ax_z.set_ylabel("damping ratio")
    ax_f.set_title("BRB mode 1: frequency")
    ax_z.set_title("BRB mode 1: damping ratio")
    for ax in (ax_f, ax_z):
        ax.grid(True, which="both", alpha=0.3)
    ax_f.legend(fontsize=8, loc="lower left")
    ax_z.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv)
