// Stiffness at the reversals of fretting loops (section 6.3): the pooled fit of every
// branch after a reversal (AnalysisOptions), for analyze_fretting.
#include "fretting_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>

namespace asperity::joint::detail {

namespace {

// Solves the n x n system A z = b (row-major, small n) by LU with partial pivoting
// (Eigen); NaN when singular (an exactly zero pivot).
std::vector<double> solve_small(const std::vector<double>& A, const std::vector<double>& b) {
  const auto n = static_cast<Eigen::Index>(b.size());
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(Eigen::Map<const RowMajor>(A.data(), n, n));
  std::vector<double> z(b.size(), std::numeric_limits<double>::quiet_NaN());
  if (n == 0 || !(lu.matrixLU().diagonal().cwiseAbs().minCoeff() > 0.0)) return z;
  Eigen::Map<Eigen::VectorXd>(z.data(), n) =
      lu.solve(Eigen::Map<const Eigen::VectorXd>(b.data(), n));
  return z;
}

// Inverse of a small symmetric positive matrix (column by column).
std::vector<double> inverse_small(const std::vector<double>& A, std::size_t n) {
  std::vector<double> inv(n * n);
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<double> e(n, 0.0);
    e[j] = 1.0;
    const auto z = solve_small(A, e);
    for (std::size_t i = 0; i < n; ++i) inv[i * n + j] = z[i];
  }
  return inv;
}

// The fit window of a reversal: samples r.. while |Qs - Qs[r]| <= span (not past end).
struct Window {
  std::vector<double> u, v;  // u = s (x - x0[r]) scaled, v = s y
};

}  // namespace

StiffnessFit fit_reversals(const std::vector<double>& x, const std::vector<double>& y,
                           const std::vector<double>& x0, const std::vector<double>& Qs,
                           const std::vector<Reversal>& revs, std::size_t ncycles, int degree) {
  const std::size_t q = static_cast<std::size_t>(std::max(0, degree - 1));  // shape columns
  std::vector<Window> win(revs.size());
  double U = 0.0;
  for (std::size_t k = 0; k < revs.size(); ++k) {
    const auto& rv = revs[k];
    const double s = rv.dir;
    for (std::size_t i = rv.r; i <= rv.end && std::abs(Qs[i] - Qs[rv.r]) <= rv.span; ++i) {
      win[k].u.push_back(s * (x[i] - x0[rv.r]));
      win[k].v.push_back(s * y[i]);
      U = std::max(U, std::abs(win[k].u.back()));
    }
  }
  StiffnessFit out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.cycle_slope.assign(ncycles, nan);
  out.cycle_slope_var.assign(ncycles, nan);
  out.reversal_slope.assign(revs.size(), nan);
  if (!(U > 0.0)) return out;
  for (auto& w : win) {
    for (double& u : w.u) u /= U;  // conditioning: u in [0, 1]
  }
  const std::size_t min_samples = static_cast<std::size_t>(degree) + 3;
  // Reversals of each cycle (two each).
  std::vector<std::vector<std::size_t>> of_cycle(ncycles);
  for (std::size_t k = 0; k < revs.size(); ++k) {
    if (win[k].u.size() >= min_samples) of_cycle[revs[k].cycle].push_back(k);
  }
  const auto pw = [](double u, std::size_t k) { return std::pow(u, static_cast<double>(k)); };
  // Local design of a cycle: one indicator per reversal and u (m = nrev + 1 columns).
  struct Local {
    std::vector<double> LL, LS, Lv;  // L'L (m x m), L'S (m x q), L'v (m)
    std::vector<double> SS, Sv;      // S'S (q x q), S'v (q)
    std::size_t m = 0;
  };
  std::vector<Local> loc(ncycles);
  std::vector<double> M(q * q, 0.0), mv(q, 0.0);
  for (std::size_t c = 0; c < ncycles; ++c) {
    const auto& ks = of_cycle[c];
    if (ks.size() != 2) continue;
    auto& L = loc[c];
    L.m = ks.size() + 1;
    const std::size_t m = L.m;
    L.LL.assign(m * m, 0.0);
    L.LS.assign(m * q, 0.0);
    L.Lv.assign(m, 0.0);
    L.SS.assign(q * q, 0.0);
    L.Sv.assign(q, 0.0);
    for (std::size_t r = 0; r < ks.size(); ++r) {
      const auto& w = win[ks[r]];
      for (std::size_t i = 0; i < w.u.size(); ++i) {
        std::vector<double> l(m, 0.0), sh(q);
        l[r] = 1.0;
        l[m - 1] = w.u[i];
        for (std::size_t j = 0; j < q; ++j) sh[j] = pw(w.u[i], j + 2);
        for (std::size_t a = 0; a < m; ++a) {
          for (std::size_t b = 0; b < m; ++b) L.LL[a * m + b] += l[a] * l[b];
          for (std::size_t j = 0; j < q; ++j) L.LS[a * q + j] += l[a] * sh[j];
          L.Lv[a] += l[a] * w.v[i];
        }
        for (std::size_t j = 0; j < q; ++j) {
          for (std::size_t jj = 0; jj < q; ++jj) L.SS[j * q + jj] += sh[j] * sh[jj];
          L.Sv[j] += sh[j] * w.v[i];
        }
      }
    }
    // Residual cross products S~'S~ = S'S - S'L (L'L)^-1 L'S, S~'v~ likewise.
    const auto inv = inverse_small(L.LL, m);
    for (std::size_t j = 0; j < q; ++j) {
      for (std::size_t jj = 0; jj < q; ++jj) {
        double corr = 0.0;
        for (std::size_t a = 0; a < m; ++a) {
          for (std::size_t b = 0; b < m; ++b)
            corr += L.LS[a * q + j] * inv[a * m + b] * L.LS[b * q + jj];
        }
        M[j * q + jj] += L.SS[j * q + jj] - corr;
      }
      double corr = 0.0;
      for (std::size_t a = 0; a < m; ++a) {
        for (std::size_t b = 0; b < m; ++b) corr += L.LS[a * q + j] * inv[a * m + b] * L.Lv[b];
      }
      mv[j] += L.Sv[j] - corr;
    }
  }
  const std::vector<double> shape = q > 0 ? solve_small(M, mv) : std::vector<double>{};
  for (double cv : shape) {
    if (!std::isfinite(cv)) return out;
  }
  const auto shape_at = [&](double u) {
    double v = 0.0;
    for (std::size_t j = 0; j < q; ++j) v += shape[j] * pw(u, j + 2);
    return v;
  };
  // Per cycle: (intercepts, slope) from v - shape; the residual variance for the
  // covariance of the slope.
  double rss = 0.0;
  std::size_t nobs = 0, npar = q;
  for (std::size_t c = 0; c < ncycles; ++c) {
    const auto& L = loc[c];
    if (L.m == 0) continue;
    const std::size_t m = L.m;
    std::vector<double> rhs(m);
    for (std::size_t a = 0; a < m; ++a) {
      double v = L.Lv[a];
      for (std::size_t j = 0; j < q; ++j) v -= L.LS[a * q + j] * shape[j];
      rhs[a] = v;
    }
    const auto theta = solve_small(L.LL, rhs);
    out.cycle_slope[c] = theta[m - 1] / U;
    out.cycle_slope_var[c] = inverse_small(L.LL, m)[(m - 1) * m + (m - 1)] / (U * U);
    npar += m;
    const auto& ks = of_cycle[c];
    for (std::size_t r = 0; r < ks.size(); ++r) {
      const auto& w = win[ks[r]];
      for (std::size_t i = 0; i < w.u.size(); ++i) {
        const double e = w.v[i] - theta[r] - theta[m - 1] * w.u[i] - shape_at(w.u[i]);
        rss += e * e;
        ++nobs;
      }
    }
  }
  const double s2 = nobs > npar ? rss / static_cast<double>(nobs - npar) : nan;
  for (double& v : out.cycle_slope_var) v *= s2;
  // b_i = theta_i(v) - g_i' c with g_i = [(L'L)^-1 L'S]_slope; Cov(c) = s2 M^-1.
  if (q > 0) {
    std::vector<double> g(q, 0.0);
    std::size_t nfit = 0;
    for (std::size_t c = 0; c < ncycles; ++c) {
      const auto& L = loc[c];
      if (L.m == 0) continue;
      const std::size_t m = L.m;
      const auto inv = inverse_small(L.LL, m);
      for (std::size_t j = 0; j < q; ++j) {
        double v = 0.0;
        for (std::size_t a = 0; a < m; ++a) v += inv[(m - 1) * m + a] * L.LS[a * q + j];
        g[j] += v;
      }
      ++nfit;
    }
    if (nfit > 0) {
      for (double& v : g) v /= static_cast<double>(nfit);
      const auto Minv = inverse_small(M, q);
      double var = 0.0;
      for (std::size_t j = 0; j < q; ++j) {
        for (std::size_t jj = 0; jj < q; ++jj) var += g[j] * Minv[j * q + jj] * g[jj];
      }
      out.shape_variance_of_mean = s2 * var / (U * U);
    }
  }
  // Per reversal: intercept and slope of v - shape on its own samples.
  for (std::size_t k = 0; k < revs.size(); ++k) {
    const auto& w = win[k];
    if (w.u.size() < min_samples) continue;
    double S0 = 0, S1 = 0, S2 = 0, T0 = 0, T1 = 0;
    for (std::size_t i = 0; i < w.u.size(); ++i) {
      const double u = w.u[i], v = w.v[i] - shape_at(w.u[i]);
      S0 += 1;
      S1 += u;
      S2 += u * u;
      T0 += v;
      T1 += u * v;
    }
    const double det = S0 * S2 - S1 * S1;
    if (std::abs(det) > 0.0) out.reversal_slope[k] = (S0 * T1 - S1 * T0) / det / U;
  }
  return out;
}

}  // namespace asperity::joint::detail
