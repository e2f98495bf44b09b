"""The exact moments of a summit-height density linear between its points (as
surface::SummitHeightTable reads it), shared by the CLI test scripts. Standard library only."""


def linear_moments(z, p):
    """Integral, mean and variance of a density linear between its points (exact)."""
    I = m1 = m2 = 0.0
    for a, b, pa, pb in zip(z, z[1:], p, p[1:]):
        h = b - a
        I += 0.5 * h * (pa + pb)
        m1 += h / 6 * (pa * (2 * a + b) + pb * (a + 2 * b))
        m2 += h / 12 * (pa * (3 * a * a + 2 * a * b + b * b) + pb * (a * a + 2 * a * b + 3 * b * b))
    return I, m1 / I, m2 / I - (m1 / I) ** 2
