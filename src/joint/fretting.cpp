// Fretting data: cycles, loop metrics (Fig. 6.1, Eq. 6.1) and synthetic experiments
// (Eq. 5.3 and the apparatus of Fig. 5.7).
#include "asperity/joint/fretting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>

#include <boost/math/distributions/students_t.hpp>

#include <Eigen/LU>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/random.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::joint {

namespace {

std::vector<double> moving_average(const std::vector<double>& x, std::size_t w) {
  const std::size_t n = x.size();
  if (w <= 1 || n < 3) return x;
  const std::size_t h = w / 2;
  std::vector<double> c(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) c[i + 1] = c[i] + x[i];
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t k = std::min({h, i, n - 1 - i});  // symmetric window, shrinks at the ends
    out[i] = (c[i + k + 1] - c[i - k]) / static_cast<double>(2 * k + 1);
  }
  return out;
}

// Turning points of s: a maximum is confirmed once the signal falls by more than h
// below it, a minimum once it rises by more than h. Returns (index, +1 max / -1 min).
std::vector<std::pair<std::size_t, int>> turning_points(const std::vector<double>& s, double h) {
  std::vector<std::pair<std::size_t, int>> out;
  if (s.empty()) return out;
  int dir = 0;
  std::size_t imax = 0, imin = 0, cand = 0;
  for (std::size_t i = 1; i < s.size(); ++i) {
    if (dir == 0) {
      if (s[i] > s[imax]) imax = i;
      if (s[i] < s[imin]) imin = i;
      if (s[i] - s[imin] > h) {
        out.emplace_back(imin, -1);
        dir = 1;
        cand = i;
      } else if (s[imax] - s[i] > h) {
        out.emplace_back(imax, 1);
        dir = -1;
        cand = i;
      }
    } else if (dir > 0) {
      if (s[i] >= s[cand]) {
        cand = i;
      } else if (s[cand] - s[i] > h) {
        out.emplace_back(cand, 1);
        dir = -1;
        cand = i;
      }
    } else {
      if (s[i] <= s[cand]) {
        cand = i;
      } else if (s[i] - s[cand] > h) {
        out.emplace_back(cand, -1);
        dir = 1;
        cand = i;
      }
    }
  }
  return out;
}

// Energy dissipated over the closed loop [a, b]: the closed integral of y dx by the
// trapezoidal rule. Signed: the loops run maximum -> minimum -> maximum of x, and a
// dissipative loop's unloading branch (leftwards) lies below its reloading branch
// (Masing: Q_m - 2 Q_l((x_m - x)/2) <= -Q_m + 2 Q_l((x + x_m)/2)), so it is positive.
double loop_energy(const std::vector<double>& x, const std::vector<double>& y, std::size_t a,
                   std::size_t b) {
  double A = 0.0;
  for (std::size_t i = a; i < b; ++i) A += 0.5 * (y[i] + y[i + 1]) * (x[i + 1] - x[i]);
  A += 0.5 * (y[b] + y[a]) * (x[a] - x[b]);  // close the loop
  return A;
}

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

struct Reversal {
  std::size_t r, end;
  int dir;  // -1: Q decreases after the reversal (unloading), +1: reloading
  double span;
  std::size_t cycle;
};

// The fit window of a reversal: samples r.. while |Qs - Qs[r]| <= span (not past end).
struct Window {
  std::vector<double> u, v;  // u = s (x - x0[r]) scaled, v = s y
};

struct StiffnessFit {
  std::vector<double> cycle_slope, cycle_slope_var;  // dv/du at u = 0 per cycle (NaN: no fit)
  std::vector<double> reversal_slope;                // per reversal
  /// Variance that the common shape coefficients' uncertainty gives the mean of the
  /// cycle slopes (shared by every cycle, so the cycles' spread does not show it):
  /// g' Cov(c) g with g the mean over cycles of d slope/d c.
  double shape_variance_of_mean = 0.0;
};

// Pooled fit of every branch after a reversal (AnalysisOptions): v = a_rev + b_cycle u +
// Sum_{k=2..p} c_k u^k. The per-cycle parameters (two intercepts and the slope) are
// projected out cycle by cycle (Frisch-Waugh), the common c_k solved from the pooled
// residual cross products, then each cycle's parameters from its own samples.
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

// Noise of a sampled signal: the robust spread of its second differences,
// 1.4826 MAD / sqrt(6) (white noise: var(x[i+1] - 2 x[i] + x[i-1]) = 6 sigma^2). The
// signal's own second difference adds to it when it is sampled coarsely, so this is an
// upper bound on the noise.
double noise_level(const std::vector<double>& x) {
  if (x.size() < 5) return 0.0;
  std::vector<double> d2(x.size() - 2);
  for (std::size_t i = 1; i + 1 < x.size(); ++i) d2[i - 1] = x[i + 1] - 2.0 * x[i] + x[i - 1];
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const double med = median(d2);
  for (double& v : d2) v = std::abs(v - med);
  return 1.4826 * median(d2) / std::sqrt(6.0);
}

// Value at index i of a least-squares quadratic in time through the samples within
// +-hw of i: an extreme of a noisy signal without the upward bias of max().
double local_value(const std::vector<double>& v, std::size_t i, std::size_t hw) {
  const std::size_t a = i > hw ? i - hw : 0, b = std::min(v.size() - 1, i + hw);
  double S[5] = {0, 0, 0, 0, 0}, T[3] = {0, 0, 0};
  for (std::size_t j = a; j <= b; ++j) {
    const double x = static_cast<double>(j) - static_cast<double>(i);
    double p = 1.0;
    for (double& sv : S) {
      sv += p;
      p *= x;
    }
    T[0] += v[j];
    T[1] += v[j] * x;
    T[2] += v[j] * x * x;
  }
  const double det = S[0] * (S[2] * S[4] - S[3] * S[3]) - S[1] * (S[1] * S[4] - S[3] * S[2]) +
                     S[2] * (S[1] * S[3] - S[2] * S[2]);
  if (!(std::abs(det) > 0.0)) return v[i];
  const double da = T[0] * (S[2] * S[4] - S[3] * S[3]) - S[1] * (T[1] * S[4] - S[3] * T[2]) +
                    S[2] * (T[1] * S[3] - S[2] * T[2]);
  return da / det;
}

// delta where the branch [a, b] (monotone in time) first crosses Q = level.
double crossing(const std::vector<double>& delta, const std::vector<double>& Q, std::size_t a,
                std::size_t b, double level) {
  for (std::size_t i = a; i < b; ++i) {
    const double q0 = Q[i] - level, q1 = Q[i + 1] - level;
    if (q0 == 0.0) return delta[i];
    if ((q0 > 0.0) != (q1 > 0.0)) return delta[i] + (delta[i + 1] - delta[i]) * q0 / (q0 - q1);
  }
  return delta[b];
}

void resample(const std::vector<double>& v, std::size_t a, std::size_t b, std::size_t m,
              std::vector<double>& acc, std::size_t offset) {
  for (std::size_t j = 0; j < m; ++j) {
    const double pos = static_cast<double>(a) + static_cast<double>(b - a) *
                                                    static_cast<double>(j) /
                                                    static_cast<double>(m - 1);
    const auto i = std::min(static_cast<std::size_t>(pos), b - 1);
    const double f = pos - static_cast<double>(i);
    acc[offset + j] += v[i] + f * (v[i + 1] - v[i]);
  }
}

}  // namespace

std::string FrettingData::where(std::size_t i) const {
  if (i < lines.size()) return fmt::format("{}:{}", source, lines[i]);
  return fmt::format("{}: sample {}", source, i + 1);
}

void FrettingData::validate() const {
  const std::size_t n = t.size();
  if (delta.size() != n || Q.size() != n || (!Delta.empty() && Delta.size() != n)) {
    throw InvalidInput(
        fmt::format("{}: columns t, delta, Q (and Delta) must have equal length", source));
  }
  if (n < 10)
    throw InvalidInput(fmt::format("{}: {} samples: too few for a fretting cycle", source, n));
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(t[i]) || !std::isfinite(delta[i]) || !std::isfinite(Q[i]) ||
        (!Delta.empty() && !std::isfinite(Delta[i]))) {
      throw InvalidInput(fmt::format("{}: a value is not finite", where(i)));
    }
    if (i > 0 && !(t[i] > t[i - 1])) {
      throw InvalidInput(fmt::format(
          "{}: time t = {:.6g} s does not increase (previous {:.6g} s): time must be strictly "
          "increasing",
          where(i), t[i], t[i - 1]));
    }
  }
  std::vector<double> dt(n - 1);
  for (std::size_t i = 1; i < n; ++i) dt[i - 1] = t[i] - t[i - 1];
  auto sorted = dt;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const double med = sorted[sorted.size() / 2];
  for (std::size_t i = 0; i < dt.size(); ++i) {
    if (dt[i] > 5.0 * med) {
      throw InvalidInput(fmt::format(
          "{}: a gap in time ({:.6g} s to {:.6g} s, a step of {:.6g} s where the median step is "
          "{:.6g} s): samples are missing",
          where(i + 1), t[i], t[i + 1], dt[i], med));
    }
  }
}

FrettingData read_fretting_csv(const std::string& path) {
  const auto table = core::read_csv_table(path);
  FrettingData d;
  d.source = path;
  const auto col = [&](const char* name, core::Dimension dm, bool required) -> std::vector<double> {
    const auto* c = table.find(name);
    if (!c) {
      if (!required) return {};
      std::string have;
      for (const auto& cc : table.columns) have += (have.empty() ? "" : ", ") + cc.name;
      throw InvalidInput(fmt::format(
          "{}: column \"{}\" is missing (found: {}); expected a header like t[s],delta[um],Q[N]",
          path, name, have));
    }
    return table.si_values(*c, dm);
  };
  d.t = col("t", core::dim::time, true);
  d.delta = col("delta", core::dim::length, true);
  d.Q = col("Q", core::dim::force, true);
  d.Delta = col("Delta", core::dim::length, false);
  // Line numbers of the data rows, by the reader's rules (core/csv.hpp): blank lines and
  // lines starting with '#' are skipped, the first other line is the header.
  {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    std::size_t no = 0;
    bool header = false;
    while (std::getline(in, line)) {
      ++no;
      const auto first = line.find_first_not_of(" \t\r");
      if (first == std::string::npos || line[first] == '#') continue;
      if (no == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0 && line.size() == 3) continue;
      if (!header) {
        header = true;
        continue;
      }
      d.lines.push_back(no);
    }
    if (d.lines.size() != d.t.size()) d.lines.clear();  // unexpected: fall back to sample numbers
  }
  d.validate();
  return d;
}

FrettingAnalysis analyze_fretting(const FrettingData& data, double P, const AnalysisOptions& opt) {
  data.validate();
  if (!(P > 0.0) || !std::isfinite(P)) throw InvalidInput(fmt::format("P = {} N must be > 0", P));
  if (!(opt.stiffness_window > 0.0 && opt.stiffness_window <= 0.5)) {
    throw InvalidInput(
        fmt::format("stiffness window = {} must be in (0, 0.5]", opt.stiffness_window));
  }
  if (opt.stiffness_degree < 1 || opt.stiffness_degree > 4) {
    throw InvalidInput(
        fmt::format("stiffness fit degree = {} must be 1, 2, 3 or 4", opt.stiffness_degree));
  }
  const std::size_t n = data.t.size();
  const bool imposed = !data.Delta.empty();
  // The period from the turning points of the force (its noise is small against its
  // swing) or of the imposed displacement; then the displacement is smoothed over 1/50
  // of a period and its own turning points split the cycles.
  const auto& coarse = imposed ? data.Delta : data.Q;
  const auto [clo, chi] = std::minmax_element(coarse.begin(), coarse.end());
  if (!(*chi - *clo > 0.0))
    throw InvalidInput(fmt::format("{}: the signals do not move", data.source));
  const auto tp0 = turning_points(coarse, 0.4 * (*chi - *clo));
  const double spc = tp0.size() >= 3
                         ? 2.0 * static_cast<double>(tp0.back().first - tp0.front().first) /
                               static_cast<double>(tp0.size() - 1)
                         : static_cast<double>(n);
  std::size_t w = static_cast<std::size_t>(spc / 50.0);
  w = std::max<std::size_t>(1, w | 1U);
  const auto ds = moving_average(data.delta, w);
  const auto Qs = moving_average(data.Q, w);
  const auto& s = imposed ? data.Delta : ds;
  const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
  const double range = *hi - *lo;
  if (!(range > 0.0))
    throw InvalidInput(fmt::format("{}: the displacement does not move", data.source));
  // Threshold: 0.4 of the median swing of s between the coarse turning points (the
  // cycles may be much smaller than the whole record's range, e.g. after a ramp).
  double h = 0.4 * range;
  if (tp0.size() >= 3) {
    std::vector<double> swings;
    for (std::size_t k = 1; k < tp0.size(); ++k)
      swings.push_back(std::abs(s[tp0[k].first] - s[tp0[k - 1].first]));
    std::nth_element(swings.begin(),
                     swings.begin() + static_cast<std::ptrdiff_t>(swings.size() / 2), swings.end());
    h = std::min(h, 0.4 * swings[swings.size() / 2]);
  }
  const auto tp = turning_points(s, h);

  FrettingAnalysis out;
  out.P = P;
  out.noise_delta = noise_level(data.delta);
  out.noise_Q = noise_level(data.Q);
  out.stiffness_from_imposed = imposed && opt.stiffness_from_imposed;
  double c_app_variance = 0.0;
  if (out.stiffness_from_imposed) {
    // Delta - delta = c Q + e, least squares over every sample (Fig. 5.7: linear springs).
    double mq = 0.0, mr = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      mq += data.Q[i] / static_cast<double>(n);
      mr += (data.Delta[i] - data.delta[i]) / static_cast<double>(n);
    }
    double sqq = 0.0, sqr = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      sqq += (data.Q[i] - mq) * (data.Q[i] - mq);
      sqr += (data.Q[i] - mq) * (data.Delta[i] - data.delta[i] - mr);
    }
    const double c = sqr / sqq;
    double ss = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double e = data.Delta[i] - data.delta[i] - mr - c * (data.Q[i] - mq);
      ss += e * e;
    }
    out.apparatus_compliance = c;
    out.apparatus_residual_rms = std::sqrt(ss / static_cast<double>(n));
    c_app_variance = ss / static_cast<double>(n - 2) / sqq;  // least squares: s^2 / Sxx
  }
  const double c_app = out.apparatus_compliance;
  // The fit (AnalysisOptions): Q(Delta), compliance C = 1/b - c; or delta(Q), C = b.
  const auto& fit_x = out.stiffness_from_imposed ? data.Delta : data.Q;
  const auto& fit_y = out.stiffness_from_imposed ? data.Q : data.delta;
  const auto& fit_x0 = out.stiffness_from_imposed ? data.Delta : Qs;
  const auto compliance_of = [&](double b) {
    return out.stiffness_from_imposed ? 1.0 / b - c_app : b;
  };
  const auto stiffness_of = [&](double b) { return 1.0 / compliance_of(b); };
  const std::size_t m = std::max<std::size_t>(opt.loop_points, 10);
  std::vector<double> acc_d(2 * m, 0.0), acc_Q(2 * m, 0.0);
  std::vector<double> acc_ds(2 * m, 0.0), acc_Qs(2 * m, 0.0);  // smoothed: for its energy
  std::vector<Reversal> reversals;
  std::vector<double> floor2;  // per cycle: variance of the energy from sensor noise
  double window_span = 0.0;
  for (std::size_t k = 0; k + 2 < tp.size(); ++k) {
    if (tp[k].second != 1) continue;
    const std::size_t a = tp[k].first, mid = tp[k + 1].first, b = tp[k + 2].first;
    const double down = s[a] - s[mid], up = s[b] - s[mid];
    if (std::min(down, up) < 0.85 * std::max(down, up)) continue;  // ramps of Eq. 5.3
    CycleMetrics c;
    c.t_start = data.t[a];
    c.t_end = data.t[b];
    c.first_sample = a;
    c.last_sample = b;
    c.energy = loop_energy(ds, Qs, a, b);
    const auto [qlo, qhi] = std::minmax_element(Qs.begin() + static_cast<std::ptrdiff_t>(a),
                                                Qs.begin() + static_cast<std::ptrdiff_t>(b) + 1);
    c.Q_max = 0.5 * (*qhi - *qlo);
    c.Q_center = 0.5 * (*qhi + *qlo);
    // Displacement extremes: local quadratic fits over +-1/25 period at the reversals.
    const auto hw = static_cast<std::size_t>(spc / 25.0);
    const double dhi = 0.5 * (local_value(data.delta, a, hw) + local_value(data.delta, b, hw));
    const double dlo = local_value(data.delta, mid, hw);
    c.delta_max = 0.5 * (dhi - dlo);
    c.delta_center = 0.5 * (dhi + dlo);
    const double span = opt.stiffness_window * 2.0 * c.Q_max;
    window_span += span;
    reversals.push_back({a, mid, -1, span, out.cycles.size()});
    reversals.push_back({mid, b, 1, span, out.cycles.size()});
    const double x_down = crossing(ds, Qs, a, mid, c.Q_center);
    const double x_up = crossing(ds, Qs, mid, b, c.Q_center);
    c.sliding = std::max(0.0, 0.5 * (x_down - x_up));
    c.partial_slip = c.delta_max - c.sliding;
    // Energy noise (FrettingAnalysis::energy_noise_floor): the area's change by the noise e
    // of delta is -Sum e dQ, of variance s_d^2 Sum dQ^2 (the moving average does not reduce
    // it: the weights dQ vary slowly), likewise for Q; the increments of the smoothed
    // signals carry 2 s^2/w^2 of noise each, removed; the product of the two noises adds
    // N 2 s_d^2 s_Q^2/w^3.
    double sq = 0.0, sd = 0.0;
    for (std::size_t i = a; i < b; ++i) {
      sq += (Qs[i + 1] - Qs[i]) * (Qs[i + 1] - Qs[i]);
      sd += (ds[i + 1] - ds[i]) * (ds[i + 1] - ds[i]);
    }
    const double N = static_cast<double>(b - a), ww = static_cast<double>(w);
    const double vd = out.noise_delta * out.noise_delta, vq = out.noise_Q * out.noise_Q;
    sq = std::max(0.0, sq - N * 2.0 * vq / (ww * ww));
    sd = std::max(0.0, sd - N * 2.0 * vd / (ww * ww));
    floor2.push_back(vd * sq + vq * sd + N * 2.0 * vd * vq / (ww * ww * ww));
    out.cycles.push_back(c);
    resample(data.delta, a, mid, m, acc_d, 0);
    resample(data.delta, mid, b, m, acc_d, m);
    resample(data.Q, a, mid, m, acc_Q, 0);
    resample(data.Q, mid, b, m, acc_Q, m);
    resample(ds, a, mid, m, acc_ds, 0);
    resample(ds, mid, b, m, acc_ds, m);
    resample(Qs, a, mid, m, acc_Qs, 0);
    resample(Qs, mid, b, m, acc_Qs, m);
  }
  if (out.cycles.empty()) {
    throw InvalidInput(fmt::format(
        "{}: fewer than one complete fretting cycle (maximum -> minimum -> maximum of the "
        "displacement) found",
        data.source));
  }
  const std::size_t ncyc = out.cycles.size();
  const double nc = static_cast<double>(ncyc);
  window_span /= nc;

  // Stiffness: pooled fit, per-cycle compliances, their mean and its standard error.
  const auto fit = fit_reversals(fit_x, fit_y, fit_x0, Qs, reversals, ncyc, opt.stiffness_degree);
  std::vector<double> C(ncyc);
  std::size_t nC = 0;
  double sumC = 0.0;
  std::vector<std::size_t> unresolved;
  for (std::size_t i = 0; i < ncyc; ++i) {
    auto& c = out.cycles[i];
    C[i] = compliance_of(fit.cycle_slope[i]);
    c.stiffness = 1.0 / C[i];
    c.stiffness_unloading = stiffness_of(fit.reversal_slope[2 * i]);
    c.stiffness_reloading = stiffness_of(fit.reversal_slope[2 * i + 1]);
    c.stiffness_resolved = std::isfinite(C[i]) && C[i] > 0.0;
    if (!c.stiffness_resolved) unresolved.push_back(i + 1);
    if (std::isfinite(C[i])) {
      sumC += C[i];
      ++nC;
    }
  }
  if (nC == 0) {
    throw InvalidInput(fmt::format(
        "{}: too few samples after the reversals to fit the stiffness (sample faster, or widen "
        "the stiffness window)",
        data.source));
  }
  const double Cmean = sumC / static_cast<double>(nC);
  // Standard error of mean(C_i): the cycles' own scatter (spread of the C_i; with fewer
  // than 3 cycles the fit's covariance), plus what they share: the common shape
  // coefficients and, with Delta, the apparatus compliance c.
  double varC = 0.0;
  double bmean = 0.0;
  for (std::size_t i = 0; i < ncyc; ++i) {
    if (std::isfinite(C[i])) bmean += fit.cycle_slope[i] / static_cast<double>(nC);
  }
  // dC/db: -1/b^2 for Q(Delta), 1 for delta(Q).
  const double dCdb2 = out.stiffness_from_imposed ? 1.0 / (bmean * bmean * bmean * bmean) : 1.0;
  if (nC >= 3) {
    double ss = 0.0;
    for (double v : C) {
      if (std::isfinite(v)) ss += (v - Cmean) * (v - Cmean);
    }
    varC = ss / static_cast<double>(nC - 1) / static_cast<double>(nC);
  } else {
    for (std::size_t i = 0; i < ncyc; ++i) {
      if (std::isfinite(C[i])) varC += fit.cycle_slope_var[i] * dCdb2;
    }
    varC /= static_cast<double>(nC * nC);
  }
  varC += fit.shape_variance_of_mean * dCdb2;
  if (out.stiffness_from_imposed) varC += c_app_variance;
  const double seC = std::sqrt(varC);
  if (!(Cmean > 0.0)) {
    throw InvalidInput(fmt::format(
        "{}: the joint's compliance at the reversals is not resolved (mean fitted compliance "
        "{:.4g} um/N +- {:.2g}): the noise is too large against the joint's motion in the fit "
        "window (widen the stiffness window, record more cycles or sample faster)",
        data.source, Cmean * 1e6, seC * 1e6));
  }
  CycleMetrics& mean = out.mean;
  mean.t_start = out.cycles.front().t_start;
  mean.t_end = out.cycles.back().t_end;
  mean.first_sample = out.cycles.front().first_sample;
  mean.last_sample = out.cycles.back().last_sample;
  double sumW2 = 0.0, sumfloor2 = 0.0;
  double Cu = 0.0, Cr = 0.0;
  std::size_t nu = 0, nr = 0;
  for (std::size_t i = 0; i < ncyc; ++i) {
    const auto& c = out.cycles[i];
    mean.energy += c.energy / nc;
    mean.Q_max += c.Q_max / nc;
    mean.delta_max += c.delta_max / nc;
    mean.Q_center += c.Q_center / nc;
    mean.delta_center += c.delta_center / nc;
    mean.sliding += c.sliding / nc;
    mean.partial_slip += c.partial_slip / nc;
    sumfloor2 += floor2[i];
    if (std::isfinite(1.0 / c.stiffness_unloading)) {
      Cu += 1.0 / c.stiffness_unloading;
      ++nu;
    }
    if (std::isfinite(1.0 / c.stiffness_reloading)) {
      Cr += 1.0 / c.stiffness_reloading;
      ++nr;
    }
  }
  for (const auto& c : out.cycles) sumW2 += (c.energy - mean.energy) * (c.energy - mean.energy);
  mean.stiffness = 1.0 / Cmean;
  mean.stiffness_unloading = nu ? static_cast<double>(nu) / Cu : 0.0;
  mean.stiffness_reloading = nr ? static_cast<double>(nr) / Cr : 0.0;
  mean.stiffness_resolved = true;
  out.stiffness_standard_error = seC / (Cmean * Cmean);  // d(1/C) = dC / C^2
  out.mu = mean.Q_max / P;                               // Eq. 6.1
  out.energy_noise_floor = std::sqrt(sumfloor2 / nc) / std::sqrt(nc);
  out.energy_standard_error =
      ncyc >= 3 ? std::sqrt(sumW2 / (nc - 1.0) / nc) : out.energy_noise_floor;
  out.energy_resolved = mean.energy > 3.0 * out.energy_noise_floor;
  out.stiffness_window_motion = window_span * Cmean;
  out.stiffness_noise = out.stiffness_from_imposed ? c_app * out.noise_Q : out.noise_delta;

  out.loop_delta.resize(2 * m);
  out.loop_Q.resize(2 * m);
  for (std::size_t j = 0; j < 2 * m; ++j) {
    out.loop_delta[j] = acc_d[j] / nc;
    out.loop_Q[j] = acc_Q[j] / nc;
  }
  // Energy of the averaged loop from the smoothed signals: on raw samples the product of
  // the two sensors' noises would add a random area of its own.
  for (std::size_t j = 0; j < 2 * m; ++j) {
    acc_ds[j] /= nc;
    acc_Qs[j] /= nc;
  }
  out.loop_energy = loop_energy(acc_ds, acc_Qs, 0, 2 * m - 1);

  // Warnings: results the noise does not support.
  const double rel_se = out.stiffness_standard_error / mean.stiffness;
  const double snr = out.stiffness_noise > 0.0 ? out.stiffness_window_motion / out.stiffness_noise
                                               : std::numeric_limits<double>::infinity();
  if (rel_se > 0.05 || snr < 3.0) {
    out.warnings.push_back(fmt::format(
        "stiffness {:.4g} N/um has a standard error of {:.1f} %: within the fit window the joint "
        "moves {:.3g} um against a displacement noise of {:.3g} um ({}); sample faster or record "
        "more cycles for a tighter value",
        mean.stiffness * 1e-6, 100.0 * rel_se, out.stiffness_window_motion * 1e6,
        out.stiffness_noise * 1e6,
        out.stiffness_from_imposed ? "c times the force noise, the noise of Delta - c Q"
                                   : "the displacement sensor's"));
  }
  if (!unresolved.empty()) {
    std::string list;
    for (auto i : unresolved) list += (list.empty() ? "" : ", ") + std::to_string(i);
    out.warnings.push_back(fmt::format(
        "per-cycle stiffness not resolved (negative or infinite: noise larger than the joint's "
        "compliance) in cycle{} {}; the mean uses their compliances, which average out",
        unresolved.size() > 1 ? "s" : "", list));
  }
  if (!out.energy_resolved) {
    out.warnings.push_back(fmt::format(
        "energy per cycle {:.4g} uJ is below 3 times the noise floor ({:.3g} uJ, from the "
        "estimated noise {:.3g} um and {:.3g} N): the loop is too thin for the sensors and the "
        "value is not resolved",
        mean.energy * 1e6, out.energy_noise_floor * 1e6, out.noise_delta * 1e6, out.noise_Q));
  }
  return out;
}

PowerLawFit fit_power_law(const std::vector<double>& Q_max, const std::vector<double>& energy) {
  if (Q_max.size() != energy.size() || Q_max.size() < 2) {
    throw InvalidInput("power law: give at least two runs (energy and Q_max each)");
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(Q_max.size());
  for (std::size_t i = 0; i < Q_max.size(); ++i) {
    if (!(Q_max[i] > 0.0) || !(energy[i] > 0.0))
      throw InvalidInput(
          fmt::format("power law: run {}: Q_max = {:.4g} N and energy = {:.4g} J "
                      "must be > 0",
                      i + 1, Q_max[i], energy[i]));
    const double x = std::log(Q_max[i]), y = std::log(energy[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double den = n * sxx - sx * sx;
  if (!(std::abs(den) > 1e-12 * n * sxx))
    throw InvalidInput("power law: the runs have the same Q_max");
  PowerLawFit f;
  f.runs = Q_max.size();
  f.exponent = (n * sxy - sx * sy) / den;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  f.standard_error = f.ci_low = f.ci_high = nan;
  if (Q_max.size() >= 3) {
    const double a = (sy - f.exponent * sx) / n;
    double rss = 0.0;
    for (std::size_t i = 0; i < Q_max.size(); ++i) {
      const double e = std::log(energy[i]) - a - f.exponent * std::log(Q_max[i]);
      rss += e * e;
    }
    const double sxx_c = sxx - sx * sx / n;
    f.standard_error = std::sqrt(rss / (n - 2.0) / sxx_c);
    const boost::math::students_t dist(n - 2.0);
    const double tq = boost::math::quantile(boost::math::complement(dist, 0.025));
    f.ci_low = f.exponent - tq * f.standard_error;
    f.ci_high = f.exponent + tq * f.standard_error;
  }
  return f;
}

double power_law_exponent(const std::vector<double>& Q_max, const std::vector<double>& energy) {
  return fit_power_law(Q_max, energy).exponent;
}

double Eq53Excitation::operator()(double t) const {
  const double T = 1.0 / frequency;
  const double t_ramp = 0.5 * T;
  const double t_end = t_ramp + static_cast<double>(cycles) * T;
  if (t <= 0.0) return 0.0;
  if (t <= t_ramp) return amplitude * t / t_ramp;  // A t
  if (t <= t_end) {  // 0.5 A (1 + sin 2 pi f t), phase pi at the end of the ramp
    return amplitude *
           (1.0 + std::sin(2.0 * std::numbers::pi * frequency * (t - t_ramp) + std::numbers::pi));
  }
  const double x_end =
      amplitude *
      (1.0 + std::sin(2.0 * std::numbers::pi * static_cast<double>(cycles) + std::numbers::pi));
  if (t <= t_end + t_ramp) return x_end * (1.0 - (t - t_end) / t_ramp);
  return 0.0;
}

FrettingData synthetic_experiment(std::shared_ptr<const hysteresis::Backbone> backbone,
                                  const SyntheticOptions& o) {
  if (!(o.excitation.amplitude > 0.0) || !(o.excitation.frequency > 0.0) ||
      o.excitation.cycles < 1) {
    throw InvalidInput("synthetic experiment: amplitude and frequency must be > 0, cycles >= 1");
  }
  core::require_positive("synthetic experiment: sample_rate", o.sample_rate);
  core::require_positive("synthetic experiment: pzt_stiffness", o.pzt_stiffness);
  core::require_positive("synthetic experiment: load_cell_stiffness", o.load_cell_stiffness);
  core::require_non_negative("synthetic experiment: noise_delta", o.noise_delta);
  core::require_non_negative("synthetic experiment: noise_Q", o.noise_Q);
  const double per_period = o.sample_rate / o.excitation.frequency;
  if (!(per_period >= kMinSamplesPerPeriod)) {
    throw InvalidInput(fmt::format(
        "synthetic experiment: sample_rate = {:.6g} Hz gives {:.3g} samples per period at "
        "frequency = {:.6g} Hz; at least {:.0f} are needed for the analysis to resolve the "
        "loop (sample_rate >= {:.6g} Hz)",
        o.sample_rate, per_period, o.excitation.frequency, kMinSamplesPerPeriod,
        kMinSamplesPerPeriod * o.excitation.frequency));
  }
  const double samples = std::floor(o.excitation.duration() * o.sample_rate) + 1.0;
  if (!(samples <= kMaxSyntheticSamples)) {
    throw InvalidInput(fmt::format(
        "synthetic experiment: {:.4g} samples (sample_rate = {:.6g} Hz over (cycles + 1)/frequency "
        "= {:.6g} s) exceed the limit of {:.0e}; lower the sample rate or the number of cycles",
        samples, o.sample_rate, o.excitation.duration(), kMaxSyntheticSamples));
  }
  const double compliance = 1.0 / o.pzt_stiffness + 1.0 / o.load_cell_stiffness;
  const auto n = static_cast<std::size_t>(samples);
  FrettingData d;
  d.source = "synthetic";
  d.t.resize(n);
  d.delta.resize(n);
  d.Q.resize(n);
  d.Delta.resize(n);
  hysteresis::Hysteresis h(std::move(backbone));
  double x = 0.0, D_prev = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / o.sample_rate;
    const double D = o.excitation(t);
    // Solve x + Q(x) c = D on [x, x + (D - D_prev)] (Q moves with x, so the residual is
    // monotone on the bracket) by regula falsi with the Illinois modification.
    double lo = x, hi = x + (D - D_prev);
    if (lo > hi) std::swap(lo, hi);
    const auto residual = [&](double xi) {
      auto copy = h;
      return xi + copy.update(xi) * compliance - D;
    };
    if (hi > lo) {
      double flo = residual(lo), fhi = residual(hi);
      int side = 0;
      double xm = lo;
      for (int it = 0; it < 100; ++it) {
        if (flo >= 0.0) {
          xm = lo;
          break;
        }
        if (fhi <= 0.0) {
          xm = hi;
          break;
        }
        xm = (lo * fhi - hi * flo) / (fhi - flo);
        if (!(xm > lo && xm < hi)) xm = 0.5 * (lo + hi);
        const double fm = residual(xm);
        if (std::abs(fm) <= 1e-13 * std::abs(D - D_prev) ||
            hi - lo <= 1e-15 * std::max(1e-9, std::abs(hi)))
          break;
        if (fm > 0.0) {
          hi = xm;
          fhi = fm;
          if (side == -1) flo *= 0.5;
          side = -1;
        } else {
          lo = xm;
          flo = fm;
          if (side == 1) fhi *= 0.5;
          side = 1;
        }
      }
      x = xm;
    }
    const double Q = h.update(x);
    d.t[i] = t;
    d.delta[i] = x;
    d.Q[i] = Q;
    d.Delta[i] = D;
    D_prev = D;
  }
  // The same seed gives the same noise with any standard library (core/random.hpp).
  core::StandardNormal nd(o.seed);
  for (std::size_t i = 0; i < n; ++i) {
    d.delta[i] += o.noise_delta * nd();
    d.Q[i] += o.noise_Q * nd();
  }
  return d;
}

}  // namespace asperity::joint
