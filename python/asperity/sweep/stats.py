"""Statistics and plots of a finished sweep, read back from its NetCDF parts one output
at a time (memory: 8 bytes x samples x the output's size per sample).

* ``summary.csv``: per output and index (load, amplitude, and any other dimension, with
  the index's value and unit): units, varies, n, mean, sd, min, quantiles 5/25/50/75/95 %,
  max, over the samples that succeeded; a constant output (:func:`is_constant`): its
  value, min and max only;
* ``sensitivity.csv``: Spearman's rank correlation of each output (per index) with each
  varied input (a choice of words by the order of its options);
* ``bands_vs_preload.png`` (joint cases): mu and stiffness against the preload, quantile
  bands over preload bins; ``bands_vs_amplitude.png``: energy per cycle against the joint
  amplitude, per load case; ``bands_vs_modal_amplitude.png`` (vibration cases): frequency
  and damping ratio against the modal amplitude; ``histograms.png``: mu and stiffness per
  load case (or every scalar output of a dynamics case) that vary; ``sensitivity.png``.
"""
from __future__ import annotations

import csv
import os

import numpy as np

QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)
# An output whose range over the samples is at most this fraction of its magnitude is
# reported as constant (its value, min and max; no spread, histogram or rank correlation).
# Rounding alone differs by ~1e-15..1e-12 relative, but continuations and integrators
# resolve an output only to their step and tolerance: the peak damping ratio of a Jenkins
# element, independent of its slip force by scaling (k_t, F_s -> amplitude scales with
# F_s), scatters by 2e-5 relative over a sweep of F_s (examples/vibration/jenkins_sdof.toml,
# the point where the continuation sampled the peak). 1e-4 keeps that constant and is
# below any variation worth a histogram.
CONSTANT_RTOL = 1e-4


def is_constant(y: np.ndarray) -> bool:
    """True when the finite values of ``y`` do not vary (see CONSTANT_RTOL)."""
    y = np.asarray(y, dtype=float)
    y = y[np.isfinite(y)]
    if y.size == 0:
        return False
    return bool(np.ptp(y) <= CONSTANT_RTOL * np.max(np.abs(y)))


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
    from .engine import writing

    if not parts:
        return
    with writing(os.path.join(out_dir, "summary.csv") + " (or sensitivity.csv)"):
        _tables(out_dir, sweep, schema, parts, info)
    if plots:
        import matplotlib

        matplotlib.use("Agg")
        ok = _load(parts, "ok").astype(bool)
        inputs = {v.key: _codes(_load(parts, v.key), v) for v in sweep.variations}
        plot_all(out_dir, sweep, schema, parts, ok, inputs)


def _units(schema, name) -> str:
    u = schema.attrs.get(name, {}).get("units", "1")
    return "" if u == "1" else f" [{u}]"


def _tables(out_dir, sweep, schema, parts, info):
    ok = _load(parts, "ok").astype(bool)
    inputs = {v.key: _codes(_load(parts, v.key), v) for v in sweep.variations}
    # One index column per dimension any output has (joint cases: load, amplitude;
    # vibration cases: modal_amplitude, curve, linear_mode).
    dims_all = ["load", "amplitude"]
    for k in schema.names:
        dims_all += [d for d in schema.dims[k] if d not in dims_all]
    dims_all = [d for d in dims_all if d in schema.sizes]
    # The value of each index (schema.coords: preload [N], amplitude [m] ...), by its unit.
    value_cols = [f"{d}_value [{schema.coords[d][1].get('units', '1')}]" for d in dims_all]
    constants = []
    with open(os.path.join(out_dir, "summary.csv"), "w", newline="") as fs, \
            open(os.path.join(out_dir, "sensitivity.csv"), "w", newline="") as fr:
        ws, wr = csv.writer(fs), csv.writer(fr)
        ws.writerow(["output", "units"] + dims_all + value_cols + ["varies", "n", "mean", "sd",
                                                                    "min"]
                    + [f"q{int(q * 100):02d}" for q in QUANTILES] + ["max"])
        wr.writerow(["output"] + dims_all + ["input", "spearman_rho", "n"])
        for k in schema.names:
            units = schema.attrs.get(k, {}).get("units", "1")
            for idx in np.ndindex(*schema.shapes[k]):
                y = _load(parts, k, idx)[ok]
                y = y[np.isfinite(y)] if y.size else y
                lab = _index_label(schema.dims[k], idx)
                pos = dict(zip(schema.dims[k], idx))
                values = [f"{schema.coords[d][0][pos[d]]:.9g}" if d in pos else ""
                          for d in dims_all]
                cols = [k, units] + [lab.get(d, "") for d in dims_all] + values
                scols = [k] + [lab.get(d, "") for d in dims_all]
                if y.size and is_constant(y):
                    # Constant: its value, no spread to describe and nothing to rank.
                    ws.writerow(cols + ["no", y.size, f"{y.mean():.9g}", "", f"{y.min():.9g}"]
                                + [""] * len(QUANTILES) + [f"{y.max():.9g}"])
                    constants.append((k, idx, float(y.mean())))
                    continue
                cols = cols + ["yes" if y.size else ""]
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
                    wr.writerow(scols + [key, "" if np.isnan(rho) else f"{rho:.6f}",
                                         int(sel.sum())])
    if info is not None:
        info["constant_outputs"] = sorted({k for k, _, _ in constants})


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


def _load_label(schema, i: int) -> str:
    """``load 2 (331 N)``: the load case by number and its preload in the unvaried case."""
    values, attrs = schema.coords.get("load", (None, {}))
    if values is not None and attrs.get("units") == "N" and i < len(values):
        return f"load {i + 1} ({values[i]:.0f} N)"
    return f"load {i + 1}"


def _amplitude_label(schema, j: int) -> str:
    values, attrs = schema.coords.get("amplitude", (None, {}))
    if values is not None and attrs.get("units") == "m" and j < len(values):
        return f"{values[j] * 1e6:.3g} um"
    return f"amplitude {j + 1}"


def _save(fig, out_dir, name):
    from .engine import writing

    path = os.path.join(out_dir, name)
    with writing(path):
        fig.savefig(path, dpi=110, bbox_inches="tight", pad_inches=0.1)


def plot_all(out_dir, sweep, schema, parts, ok, inputs):
    import matplotlib.pyplot as plt

    names = set(schema.names)

    def varies(k):
        y = _load(parts, k)[ok]
        return y.size > 0 and not is_constant(y.ravel())

    if {"preload", "mu", "stiffness"} <= names and varies("preload"):
        P = _load(parts, "preload")[ok]
        shown = [(k, scale, unit) for k, scale, unit in (("mu", 1.0, ""), ("stiffness", 1e-6,
                                                                           " [N/um]"))
                 if varies(k)]
        if shown:
            fig, axs = plt.subplots(1, len(shown), figsize=(5 * len(shown), 4), squeeze=False)
            for ax, (k, scale, unit) in zip(axs[0], shown):
                y = _load(parts, k)[ok]
                _bands(ax, P.ravel(), y.ravel() * scale)
                ax.set_xlabel("preload [N]")
                ax.set_ylabel(k + unit)
                ax.ticklabel_format(axis="y", useOffset=False)
                ax.legend()
            fig.suptitle(f"{len(P)} samples: quantile bands over preload bins")
            fig.tight_layout()
            _save(fig, out_dir, "bands_vs_preload.png")
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
            lab = f"{_load_label(schema, i)}, median P {np.nanmedian(P[:, i]):.0f} N"
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
        _save(fig, out_dir, "bands_vs_amplitude.png")
        plt.close(fig)
    if "mode_frequency_hz" in names and schema.sizes.get("modal_amplitude", 0) > 1:
        _vibration_bands(plt, out_dir, schema, parts, ok)
    # Histograms: the outputs that vary (a constant one is named in the title instead).
    hist = [k for k in ("mu", "stiffness") if k in names] or \
        [k for k in schema.names if not schema.dims[k]]
    constant = [k for k in hist if not varies(k)]
    hist = [k for k in hist if k not in constant][:6]
    if hist:
        nl = max(schema.sizes.get("load", 1), 1) if hist[0] in ("mu", "stiffness") else 1
        fig, axs = plt.subplots(len(hist), 1, figsize=(6, 2.6 * len(hist) + 0.4),
                                squeeze=False)
        for ax, k in zip(axs[:, 0], hist):
            y = _load(parts, k)[ok]
            y = y.reshape(len(y), -1) if y.ndim > 1 else y[:, None]
            for i in range(y.shape[1] if nl > 1 else 1):
                yy = y[:, i][np.isfinite(y[:, i])]
                if yy.size:
                    ax.hist(yy * (1e-6 if k == "stiffness" else 1), bins=40, alpha=0.6,
                            label=_load_label(schema, i) if nl > 1 else None)
            ax.set_xlabel(k + (" [N/um]" if k == "stiffness" else _units(schema, k)))
            ax.ticklabel_format(axis="x", useOffset=False)
            ax.set_ylabel("samples")
            if nl > 1:
                ax.legend(fontsize=8)
        if constant:
            import textwrap

            fig.suptitle(textwrap.fill(
                "constant over the samples (no histogram): " + ", ".join(constant[:8])
                + (f" and {len(constant) - 8} more (summary.csv)" if len(constant) > 8
                   else ""), 90), fontsize=8)
        fig.tight_layout()
        _save(fig, out_dir, "histograms.png")
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
            if is_constant(y[ok, i]):
                continue
            na = schema.sizes.get("amplitude", 1)
            lab = k if y.shape[1] == 1 else (
                f"{k}, {_load_label(schema, i // na)}, {_amplitude_label(schema, na - 1)}"
                if k == "energy" else f"{k}, {_load_label(schema, i)}")
            labels.append(lab)
            rows.append([spearman(x[ok], y[ok, i]) for x in inputs.values()])
    if rows:
        r = np.array(rows)
        fig, ax = plt.subplots(figsize=(3.2 + 1.3 * r.shape[1], 1.2 + 0.32 * r.shape[0]),
                               layout="constrained")
        im = ax.imshow(np.nan_to_num(r), cmap="RdBu_r", vmin=-1, vmax=1, aspect="auto")
        ax.set_xticks(range(r.shape[1]), [k.replace(".", ".\n") for k in inputs], fontsize=7)
        ax.set_yticks(range(r.shape[0]), labels, fontsize=8)
        for (i, j), val in np.ndenumerate(r):
            ax.text(j, i, "-" if np.isnan(val) else f"{val:.2f}", ha="center", va="center",
                    fontsize=7)
        fig.colorbar(im, ax=ax, label="Spearman rank correlation rho")
        _save(fig, out_dir, "sensitivity.png")
        plt.close(fig)


def _vibration_bands(plt, out_dir, schema, parts, ok):
    """Frequency [Hz] and damping ratio against the modal amplitude (log axis): median
    and 5-95 % / 25-75 % bands over the samples at each grid amplitude; the quasi-static
    estimate's median dashed."""
    la = _load(parts, "mode_log10_amplitude")[ok]
    if la.size == 0:
        return
    a = 10.0 ** np.nanmedian(la, axis=0)
    fig, axs = plt.subplots(1, 2, figsize=(10, 4))
    for ax, k, qk, label in ((axs[0], "mode_frequency_hz", "quasi_static_frequency_hz",
                              "frequency [Hz]"),
                             (axs[1], "mode_damping_ratio", "quasi_static_damping_ratio",
                              "damping ratio")):
        y = _load(parts, k)[ok]
        with np.errstate(all="ignore"):
            import warnings

            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                q = np.nanquantile(y, QUANTILES, axis=0)
        ax.fill_between(a, q[0], q[4], color="#1f4e9a", alpha=0.2, label="5-95 %")
        ax.fill_between(a, q[1], q[3], color="#1f4e9a", alpha=0.4, label="25-75 %")
        ax.plot(a, q[2], color="#1f4e9a", label="median, nonlinear mode")
        if qk in schema.names:
            yq = _load(parts, qk)[ok]
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                ax.plot(a, np.nanmedian(yq, axis=0), "--", color="0.3",
                        label="median, quasi-static estimate")
        ax.set_xscale("log")
        ax.set_xlabel("modal amplitude [sqrt(kg) m]")
        ax.set_ylabel(label)
        ax.ticklabel_format(axis="y", useOffset=False)
        ax.legend(fontsize=8)
    fig.suptitle(f"{int(ok.sum())} samples: bands over the samples at each modal amplitude")
    fig.tight_layout()
    _save(fig, out_dir, "bands_vs_modal_amplitude.png")
    plt.close(fig)
