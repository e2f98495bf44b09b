"""Statistics and plots of a finished sweep, read back from its NetCDF parts one output
at a time (memory: 8 bytes x samples x the output's size per sample).

* ``summary.csv``: per output and index (load, amplitude, and any other dimension): n, mean, sd, min, quantiles
  5/25/50/75/95 %, max, over the samples that succeeded;
* ``sensitivity.csv``: Spearman's rank correlation of each output (per index) with each
  varied input (a choice of words by the order of its options);
* ``bands_vs_preload.png`` (joint cases): mu and stiffness against the preload, quantile
  bands over preload bins; ``bands_vs_amplitude.png``: energy per cycle against the joint
  amplitude, per load case; ``histograms.png``: mu and stiffness per load case (or every
  scalar output of a dynamics case); ``sensitivity.png``.
"""
from __future__ import annotations

import csv
import os

import numpy as np

QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)


def _load(parts, name, idx=None):
    """One output (or coordinate) over all parts, in sample order."""
    import xarray as xr

    out = []
    for p in parts:
        with xr.open_dataset(p, engine="scipy") as ds:
            a = ds[name].values
            out.append(a if idx is None else a[(slice(None),) + idx])
    return np.concatenate(out) if out else np.array([])


def _codes(values: np.ndarray, v) -> np.ndarray:
    """A varied input as numbers for rank correlation."""
    if values.dtype.kind in "fiu":
        return values.astype(float)
    order = {str(x.toml): i for i, x in enumerate(v.values)}
    return np.array([order.get(str(x), np.nan) for x in values], dtype=float)


def spearman(x: np.ndarray, y: np.ndarray) -> float:
    """Spearman's rho (average ranks for ties); NaN when either side is constant."""
    from scipy.stats import spearmanr

    keep = np.isfinite(x) & np.isfinite(y)
    if keep.sum() < 3 or np.ptp(x[keep]) == 0 or np.ptp(y[keep]) == 0:
        return float("nan")
    return float(spearmanr(x[keep], y[keep]).statistic)


def _index_label(dims, idx) -> dict:
    return {d: i + 1 for d, i in zip(dims, idx)}


def summarize(out_dir: str, sweep, schema, parts: list, plots: bool = True,
              info: dict | None = None) -> None:
    if not parts:
        return
    ok = _load(parts, "ok").astype(bool)
    inputs = {v.key: _codes(_load(parts, v.key), v) for v in sweep.variations}
    # One index column per dimension any output has (joint cases: load, amplitude;
    # vibration cases: modal_amplitude, curve, linear_mode).
    dims_all = ["load", "amplitude"]
    for k in schema.names:
        dims_all += [d for d in schema.dims[k] if d not in dims_all]
    with open(os.path.join(out_dir, "summary.csv"), "w", newline="") as fs, \
            open(os.path.join(out_dir, "sensitivity.csv"), "w", newline="") as fr:
        ws, wr = csv.writer(fs), csv.writer(fr)
        ws.writerow(["output"] + dims_all + ["n", "mean", "sd", "min"]
                    + [f"q{int(q * 100):02d}" for q in QUANTILES] + ["max"])
        wr.writerow(["output"] + dims_all + ["input", "spearman_rho", "n"])
        for k in schema.names:
            for idx in np.ndindex(*schema.shapes[k]):
                y = _load(parts, k, idx)[ok]
                y = y[np.isfinite(y)] if y.size else y
                lab = _index_label(schema.dims[k], idx)
                cols = [k] + [lab.get(d, "") for d in dims_all]
                if y.size:
                    ws.writerow(cols + [y.size, f"{y.mean():.9g}",
                                        f"{y.std(ddof=1) if y.size > 1 else 0.0:.9g}",
                                        f"{y.min():.9g}"]
                                + [f"{q:.9g}" for q in np.quantile(y, QUANTILES)]
                                + [f"{y.max():.9g}"])
                else:
                    ws.writerow(cols + [0] + [""] * (4 + len(QUANTILES)))
                yall = _load(parts, k, idx)
                for key, x in inputs.items():
                    sel = ok & np.isfinite(yall)
                    rho = spearman(x[sel], yall[sel])
                    wr.writerow(cols + [key, "" if np.isnan(rho) else f"{rho:.6f}",
                                        int(sel.sum())])
    if plots:
        import matplotlib

        matplotlib.use("Agg")
        plot_all(out_dir, sweep, schema, parts, ok, inputs)


def _bands(ax, x, y, bins=24, color="#1f4e9a", label=None):
    keep = np.isfinite(x) & np.isfinite(y)
    x, y = x[keep], y[keep]
    if x.size < 5:
        return
    edges = np.unique(np.quantile(x, np.linspace(0, 1, min(bins, max(x.size // 10, 2)) + 1)))
    which = np.clip(np.digitize(x, edges[1:-1]), 0, len(edges) - 2)
    xc, qs = [], []
    for b in range(len(edges) - 1):
        yy = y[which == b]
        if yy.size >= 3:
            xc.append(np.median(x[which == b]))
            qs.append(np.quantile(yy, QUANTILES))
    if not xc:
        return
    xc, qs = np.array(xc), np.array(qs)
    ax.fill_between(xc, qs[:, 0], qs[:, 4], color=color, alpha=0.2, label="5-95 %")
    ax.fill_between(xc, qs[:, 1], qs[:, 3], color=color, alpha=0.4, label="25-75 %")
    ax.plot(xc, qs[:, 2], color=color, label=label or "median")


def plot_all(out_dir, sweep, schema, parts, ok, inputs):
    import matplotlib.pyplot as plt

    names = set(schema.names)
    if {"preload", "mu", "stiffness"} <= names:
        P = _load(parts, "preload")[ok]
        fig, axs = plt.subplots(1, 2, figsize=(10, 4))
        for ax, k, scale, unit in ((axs[0], "mu", 1.0, ""), (axs[1], "stiffness", 1e-6,
                                                                " [N/um]")):
            y = _load(parts, k)[ok]
            _bands(ax, P.ravel(), y.ravel() * scale)
            ax.set_xlabel("preload [N]")
            ax.set_ylabel(k + unit)
            ax.legend()
        fig.suptitle(f"{len(P)} samples: quantile bands over preload bins")
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, "bands_vs_preload.png"), dpi=110)
        plt.close(fig)
    if {"energy", "delta_max"} <= names and schema.sizes.get("amplitude", 0) > 1:
        E = _load(parts, "energy")[ok]
        D = _load(parts, "delta_max")[ok]
        P = _load(parts, "preload")[ok]
        imposed = np.isfinite(_load(parts, "imposed")[ok]).any(axis=(0, 1)) if \
            "imposed" in names else np.zeros(E.shape[2], bool)
        fig, ax = plt.subplots(figsize=(6.5, 4.8))
        colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        for i in range(E.shape[1]):
            c = colors[i % len(colors)]
            lab = f"load {i + 1} (P ~ {np.nanmedian(P[:, i]):.0f} N)"
            j = np.flatnonzero(~imposed)  # joint amplitudes: a band over amplitude
            if j.size:
                q = np.nanquantile(E[:, i][:, j], QUANTILES, axis=0)
                x = np.nanmedian(D[:, i][:, j], axis=0) * 1e6
                ax.fill_between(x, q[0], q[4], color=c, alpha=0.2)
                ax.plot(x, q[2], "o-", color=c, label=lab)
                lab = None
            for k in np.flatnonzero(imposed):  # imposed amplitudes: the joint's varies too
                qe = np.nanquantile(E[:, i, k], QUANTILES)
                qd = np.nanquantile(D[:, i, k], QUANTILES) * 1e6
                ax.errorbar(qd[2], qe[2], xerr=[[qd[2] - qd[0]], [qd[4] - qd[2]]],
                            yerr=[[qe[2] - qe[0]], [qe[4] - qe[2]]], fmt="D", color=c,
                            mfc="none", capsize=3, label=lab)
                lab = None
        if imposed.any():
            ax.plot([], [], "D", color="0.3", mfc="none", label="imposed amplitude (5-95 %)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("joint amplitude delta_max [um] (median)")
        ax.set_ylabel("energy per cycle [J]: median, 5-95 %")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, "bands_vs_amplitude.png"), dpi=110)
        plt.close(fig)
    hist = [k for k in ("mu", "stiffness") if k in names] or \
        [k for k in schema.names if not schema.dims[k]][:6]
    if hist:
        nl = max(schema.sizes.get("load", 1), 1) if hist[0] in ("mu", "stiffness") else 1
        fig, axs = plt.subplots(len(hist), 1, figsize=(6, 2.6 * len(hist)), squeeze=False)
        for ax, k in zip(axs[:, 0], hist):
            y = _load(parts, k)[ok]
            y = y.reshape(len(y), -1) if y.ndim > 1 else y[:, None]
            for i in range(y.shape[1] if nl > 1 else 1):
                yy = y[:, i][np.isfinite(y[:, i])]
                if yy.size:
                    ax.hist(yy * (1e-6 if k == "stiffness" else 1), bins=40, alpha=0.6,
                            label=f"load {i + 1}" if nl > 1 else None)
            ax.set_xlabel(k + (" [N/um]" if k == "stiffness" else ""))
            ax.set_ylabel("samples")
            if nl > 1:
                ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, "histograms.png"), dpi=110)
        plt.close(fig)
    # Sensitivity: rho of the main outputs per load with each input.
    rows, labels = [], []
    main = [k for k in ("mu", "stiffness", "energy") if k in names] or \
        [k for k in schema.names if not schema.dims[k]][:12]
    for k in main:
        y = _load(parts, k)
        y = y.reshape(len(y), -1)
        for i in range(y.shape[1]):
            if k == "energy" and (i + 1) % schema.sizes.get("amplitude", 1):
                continue  # energy: the largest amplitude of each load case
            na = schema.sizes.get("amplitude", 1)
            lab = k if y.shape[1] == 1 else (
                f"{k} load {i // na + 1}, amplitude {na}" if k == "energy"
                else f"{k} load {i + 1}")
            labels.append(lab)
            rows.append([spearman(x[ok], y[ok, i]) for x in inputs.values()])
    if rows:
        r = np.array(rows)
        fig, ax = plt.subplots(figsize=(1.6 + 1.3 * r.shape[1], 0.9 + 0.32 * r.shape[0]))
        im = ax.imshow(np.nan_to_num(r), cmap="RdBu_r", vmin=-1, vmax=1, aspect="auto")
        ax.set_xticks(range(r.shape[1]), [k.replace(".", ".\n") for k in inputs], fontsize=7)
        ax.set_yticks(range(r.shape[0]), labels, fontsize=8)
        for (i, j), val in np.ndenumerate(r):
            ax.text(j, i, "-" if np.isnan(val) else f"{val:.2f}", ha="center", va="center",
                    fontsize=7)
        fig.colorbar(im, ax=ax, label="Spearman rho")
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, "sensitivity.png"), dpi=110)
        plt.close(fig)
