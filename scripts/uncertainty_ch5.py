#!/usr/bin/env python3
"""The uncertainty study of docs/uncertainty.md: runs examples/sweeps/steel420_bolt_load.toml
and steel420_material.toml (asperity.sweep, the default LocalCluster) into OUT (default
out/uncertainty), draws the figures of the document into FIGDIR (default docs/figures)
and prints the tables. Usage: scripts/uncertainty_ch5.py [OUT] [FIGDIR]"""
import os
import pathlib
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from asperity import sweep  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]
# Table 5.6 (PZT tip amplitude 6.75 um): preload [N], measured delta_max [um], mu.
TABLE_5_6 = {"P": [234, 331, 526, 721], "delta_max": [4.26, 2.69, 1.32, 0.79],
             "mu": [0.479, 0.508, 0.420, 0.323]}


def run(name, out):
    s = sweep.load(str(ROOT / "examples" / "sweeps" / f"{name}.toml"))
    info = sweep.run(s, str(out), progress=sys.stderr.isatty())
    print(f"{name}: {info['samples']} samples, {info['failed']} failed, {info['engine']}, "
          f"{info['samples_per_s']:.1f} samples/s")
    return s, sweep.open_results(str(out)).load()


def q(a, qs=(0.05, 0.5, 0.95)):
    return np.nanquantile(a, qs, axis=0)


def table(ds, label):
    """Per load case: nominal preload; 5/50/95 % of preload, static mu, the 6.75 um loop's
    Q_peak/P (model) and Q_peak/P_nominal (as the experiment computes mu), delta_max,
    stiffness; against Table 5.6."""
    ok = ds["ok"].values.astype(bool)
    P = ds["preload"].values[ok]
    Pn = np.array(TABLE_5_6["P"], float)
    imp = int(np.flatnonzero(np.isfinite(ds["imposed"].values[ok][0, 0]))[0])
    Qp = ds["Q_peak"].values[ok][:, :, imp]
    dm = ds["delta_max"].values[ok][:, :, imp] * 1e6
    rows = {"preload [N]": P, "static mu": ds["mu"].values[ok],
            "Q_peak/P at 6.75 um (model)": Qp / P,
            "Q_peak/P_nominal at 6.75 um (as measured)": Qp / Pn,
            "delta_max at 6.75 um [um]": dm,
            "stiffness [N/um]": ds["stiffness"].values[ok] * 1e-6}
    print(f"\n{label} ({ok.sum()} samples): 5 % / median / 95 % per load case\n")
    print("| quantity | " + " | ".join(f"{p:.0f} N (nominal)" for p in Pn) + " |")
    print("| --- |" + " --- |" * 4)
    for k, v in rows.items():
        qq = q(v)
        print(f"| {k} | " + " | ".join(f"{qq[0, i]:.3g} / {qq[1, i]:.3g} / {qq[2, i]:.3g}"
                                       for i in range(4)) + " |")
    print("| Table 5.6 mu | " + " | ".join(f"{x}" for x in TABLE_5_6["mu"]) + " |")
    print("| Table 5.6 delta_max [um] | " + " | ".join(f"{x}" for x in TABLE_5_6["delta_max"])
          + " |")
    return rows


def bars(ax, x, y, color, label, dx):
    """Median (marker), 25-75 % (thick) and 5-95 % (thin) per load case."""
    qq = q(y, (0.05, 0.25, 0.5, 0.75, 0.95))
    xx = x + dx
    ax.vlines(xx, qq[0], qq[4], color=color, lw=1)
    ax.vlines(xx, qq[1], qq[3], color=color, lw=5, alpha=0.6)
    ax.plot(xx, qq[2], "o", color=color, label=label, ms=5)


def figure(rows_a, rows_b, figdir):
    Pn = np.array(TABLE_5_6["P"], float)
    sets = [(rows_a, "#1f4e9a", "bolt load", -14), (rows_b, "#c0392b",
                                                    "bolt load + H + sigma", 14)]
    fig, axs = plt.subplots(1, 3, figsize=(15, 4.6))
    ax = axs[0]
    for rows, c, lab, dx in sets:
        bars(ax, Pn, rows["Q_peak/P at 6.75 um (model)"], c, f"model Q/P ({lab})", dx)
    bars(ax, Pn, rows_a["Q_peak/P_nominal at 6.75 um (as measured)"], "#2e8b57",
         "model Q/P_nominal (bolt load)", 0)
    ax.plot(Pn, TABLE_5_6["mu"], "ks", label="Table 5.6 (measured)")
    ax.set_ylabel("mu at the 6.75 um PZT amplitude")
    ax = axs[1]
    for rows, c, lab, dx in sets:
        bars(ax, Pn, rows["delta_max at 6.75 um [um]"], c, f"model ({lab})", dx)
    ax.plot(Pn, TABLE_5_6["delta_max"], "ks", label="Table 5.6 (measured)")
    ax.set_ylabel("joint amplitude delta_max [um] at 6.75 um")
    ax = axs[2]
    for rows, c, lab, dx in sets:
        bars(ax, Pn, rows["stiffness [N/um]"], c, f"model ({lab})", dx)
    ax.set_ylabel("tangential stiffness [N/um]\n(Table 5.6 has no measured value)")
    for ax in axs:
        ax.set_xlabel("nominal preload [N] (Table 5.5, K = 0.2)")
        ax.set_xticks(Pn)
        ax.legend(fontsize=7)
    fig.suptitle("Chapter 5 joint, per load case: median, 25-75 % (thick), 5-95 % (thin) "
                 "against Table 5.6")
    fig.tight_layout()
    fig.savefig(os.path.join(figdir, "uncertainty_ch5_table_5_6.png"), dpi=110)
    plt.close(fig)


def main():
    out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "out" / "uncertainty")
    figdir = pathlib.Path(sys.argv[2] if len(sys.argv) > 2 else ROOT / "docs" / "figures")
    figdir.mkdir(parents=True, exist_ok=True)
    _, a = run("steel420_bolt_load", out / "bolt_load")
    _, b = run("steel420_material", out / "material")
    rows_a = table(a, "bolt load (nut factor, torque)")
    rows_b = table(b, "bolt load + hardness + roughness")
    figure(rows_a, rows_b, str(figdir))
    import shutil

    for src, dst in (("bolt_load/bands_vs_preload.png", "uncertainty_ch5_bands_vs_preload.png"),
                     ("bolt_load/bands_vs_amplitude.png", "uncertainty_ch5_energy.png"),
                     ("bolt_load/histograms.png", "uncertainty_ch5_histograms.png"),
                     ("material/sensitivity.png", "uncertainty_ch5_sensitivity.png")):
        shutil.copy(out / src, figdir / dst)
    print(f"\nfigures in {figdir}")


if __name__ == "__main__":
    main()
