#!/usr/bin/env python3
"""Synthetic profilometer scans of the two milled halves of the thesis's steel joint.

Writes four 4 mm line scans (x[mm], z[um], 1 um spacing) whose roughness, processed
the way `asperity roughness` does by default (least-squares line levelling, ISO
16610-21 Gaussian band-pass with lc = 0.8 mm and ls = 20 um, weights truncated at
+-lc and the ends discarded, forward/central differences for the slopes and
curvatures, Eq. 5.1 with the geometric rule for m2 and m4), reproduces the
"before experiments" columns of Table 5.4 (Eriten 2012):

    PZT half:        sigma = 1.763 um, eta = 3.34e-4 um^-2, R = 40.76 um
    load-cell half:  sigma = 2.015 um, eta = 2.51e-4 um^-2, R = 44.77 um

Each half has a scan across the milling marks (maximum slope: periodic feed marks
plus random roughness) and one along them (minimum slope: random roughness only).
Each scan is a weighted sum of three band-limited components; the weights are
solved (Newton) so that the processed scan has the target moments. The split
between the directions is m0 equal, m2 and m4 in the ratio RHO and RHO^2.

Usage: python3 make_profiles.py [output directory]   (numpy only)
"""
import math
import pathlib
import sys

import numpy as np

DX = 1.0          # um
LENGTH = 4000.0   # um
LC, LS = 800.0, 20.0
RHO = 1.25        # m2_max / m2e = m2e / m2_min

HALVES = {
    "pzt": (1.763, 3.34e-4, 40.76),
    "lc": (2.015, 2.51e-4, 44.77),
}


def moments_from_parameters(sigma, eta, R):
    m4 = math.pi * (0.375 / R) ** 2
    return np.array([sigma ** 2, m4 / (6 * math.pi * math.sqrt(3) * eta), m4])


def gauss_lowpass(z, cutoff):
    alpha = math.sqrt(math.log(2) / math.pi)
    h = int(math.floor(cutoff / DX + 1e-9))
    k = np.arange(-h, h + 1) * DX / (alpha * cutoff)
    w = np.exp(-math.pi * k ** 2)
    w /= w.sum()
    return np.convolve(z, w, mode="valid"), h


def process(z):
    i = np.arange(z.size) - 0.5 * (z.size - 1)
    z = z - z.mean()
    z = z - (i @ z) / (i @ i) * i
    mean_line, h = gauss_lowpass(z, LC)
    r = z[h:z.size - h] - mean_line
    r, _ = gauss_lowpass(r, LS)
    return r


def derivatives(r):
    return r, np.diff(r) / DX, np.diff(r, 2) / DX ** 2


def gram(bands):
    """G[n][i, j] = <D^n b_i D^n b_j> for n = 0, 1, 2 of the processed bands."""
    d = [derivatives(process(b)) for b in bands]
    return [np.array([[np.mean(d[i][n] * d[j][n]) for j in range(len(bands))]
                      for i in range(len(bands))]) for n in range(3)]


def random_band(rng, x, lam_lo, lam_hi, count=60):
    z = np.zeros_like(x)
    for lam in np.exp(rng.uniform(math.log(lam_lo), math.log(lam_hi), count)):
        z += rng.normal() * np.sin(2 * math.pi * x / lam + rng.uniform(0, 2 * math.pi))
    return z / np.std(z)


def feed_marks(rng, x, feed):
    """Marks left by a milling cutter at feed `feed`: a rounded cusp shape (fundamental
    plus a second harmonic) with slowly wandering phase and depth."""
    phase = 2 * math.pi * (x / feed + 0.05 * random_band(rng, x, 300, 1500, 10))
    z = np.sin(phase) + 0.2 * np.sin(2 * phase + 0.5)
    z *= 1 + 0.1 * random_band(rng, x, 200, 800, 10)
    return (z - z.mean()) / np.std(z)


def solve(bands, target):
    G = gram(bands)
    # Start from the uncorrelated solution, then Newton on c^T G_n c = target_n.
    diag = np.array([[G[n][i, i] for i in range(3)] for n in range(3)])
    c = np.sqrt(np.abs(np.linalg.solve(diag, target)))
    for _ in range(50):
        f = np.array([c @ G[n] @ c for n in range(3)]) / target - 1
        if np.max(np.abs(f)) < 1e-12:
            break
        J = np.array([2 * (G[n] @ c) / target[n] for n in range(3)])
        c = c - np.linalg.solve(J, f)
    else:
        raise RuntimeError("no convergence")
    return c


def main():
    out = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent)
    x = np.arange(0.0, LENGTH + DX / 2, DX)
    for seed, (name, params) in enumerate(HALVES.items()):
        rng = np.random.default_rng(2012 + seed)
        m = moments_from_parameters(*params)
        targets = {"max": m * np.array([1, RHO, RHO ** 2]), "min": m * np.array([1, 1 / RHO, 1 / RHO ** 2])}
        for direction in ("max", "min"):
            t = targets[direction]
            lam = 2 * math.pi / math.sqrt(t[1] / t[0])  # the scan's mean wavelength
            bands = {
                "max": [random_band(rng, x, 1.25 * lam, 1.8 * lam), feed_marks(rng, x, lam),
                        random_band(rng, x, 0.6 * lam, 0.8 * lam)],
                "min": [random_band(rng, x, 1.25 * lam, 1.8 * lam), random_band(rng, x, 0.85 * lam, 1.15 * lam),
                        random_band(rng, x, 0.6 * lam, 0.8 * lam)],
            }
            c = solve(bands[direction], t)
            z = sum(ci * b for ci, b in zip(c, bands[direction]))
            z += 0.8e-3 * x  # a small tilt, removed by the levelling
            path = out / f"{name}_{direction}.csv"
            with open(path, "w") as f:
                f.write("x[mm],z[um]\n")
                for xi, zi in zip(x, z):
                    f.write(f"{xi / 1000:.4f},{zi:.5f}\n")
            r = process(np.loadtxt(path, delimiter=",", skiprows=1)[:, 1])
            got = np.array([np.mean(d ** 2) for d in derivatives(r)])
            print(f"{path.name}: weights {np.round(c, 4)}, moments / target - 1 = "
                  f"{np.array2string(got / targets[direction] - 1, precision=1)}")


if __name__ == "__main__":
    main()
