// Fretting data: cycles, loop metrics (Fig. 6.1, Eq. 6.1) and synthetic experiments
// (Eq. 5.3 and the apparatus of Fig. 5.7).
#include "asperity/joint/fretting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"

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

double trapezoid_loop_area(const std::vector<double>& x, const std::vector<double>& y,
                           std::size_t a, std::size_t b) {
  double A = 0.0;
  for (std::size_t i = a; i < b; ++i) A += 0.5 * (y[i] + y[i + 1]) * (x[i + 1] - x[i]);
  A += 0.5 * (y[b] + y[a]) * (x[a] - x[b]);  // close the loop
  return std::abs(A);
}

// Slope dy/dx at the reversal at index r of a least-squares quadratic y(x - x0[r]) over
// the samples from r, moving towards `end`, until the smoothed force Qs leaves
// |Qs - Qs[r]| <= span. x is the regressor: Q with y = delta, or the imposed Delta with
// y = Q; x0 is x's reference at r (the smoothed Qs, or Delta itself).
double slope_at_reversal(const std::vector<double>& x, const std::vector<double>& y,
                         const std::vector<double>& x0, const std::vector<double>& Qs,
                         std::size_t r, std::size_t end, double span) {
  const double xr = x0[r];
  // Normal equations of y = a + b q + c q^2, q = x - xr.
  double S[5] = {0, 0, 0, 0, 0}, T[3] = {0, 0, 0};
  std::size_t n = 0;
  for (std::size_t i = r; i <= end; ++i) {
    if (std::abs(Qs[i] - Qs[r]) > span) break;
    const double q = x[i] - xr;
    double p = 1.0;
    for (double& sv : S) {
      sv += p;
      p *= q;
    }
    T[0] += y[i];
    T[1] += y[i] * q;
    T[2] += y[i] * q * q;
    ++n;
  }
  if (n < 6) return std::numeric_limits<double>::quiet_NaN();
  // Solve the 3x3 system [[S0 S1 S2][S1 S2 S3][S2 S3 S4]] (a b c) = T by Cramer's rule.
  const double a11 = S[0], a12 = S[1], a13 = S[2], a22 = S[2], a23 = S[3], a33 = S[4];
  const double det =
      a11 * (a22 * a33 - a23 * a23) - a12 * (a12 * a33 - a23 * a13) + a13 * (a12 * a23 - a22 * a13);
  const double db = a11 * (T[1] * a33 - a23 * T[2]) - T[0] * (a12 * a33 - a23 * a13) +
                    a13 * (a12 * T[2] - T[1] * a13);
  return db / det;
}

struct Reversal {
  std::size_t r, end;
  int dir;  // -1: Q decreases after the reversal (unloading), +1: reloading
  double span;
};

// Slope at the reversals pooled over all of them: y' = s y, q = s (x - x0[r]) (s = +-1
// the direction), y' = a_r + b q + c q^2 + d q^3 with one intercept a_r per reversal and
// common b, c, d (least squares after removing each reversal's means); returns b.
// Pooling is what makes the slope usable when the noise is comparable with the motion
// over the fit window.
double pooled_slope(const std::vector<double>& x, const std::vector<double>& y,
                    const std::vector<double>& x0, const std::vector<double>& Qs,
                    const std::vector<Reversal>& revs) {
  constexpr int P = 3;
  double A[P][P] = {}, B[P] = {};
  for (const auto& rv : revs) {
    const double s = rv.dir;
    const double Qr = Qs[rv.r], xr = x0[rv.r];
    std::size_t j = rv.r;
    while (j <= rv.end && std::abs(Qs[j] - Qr) <= rv.span) ++j;
    const std::size_t n = j - rv.r;
    if (n < 6) continue;
    double mx[P] = {}, my = 0.0;
    for (std::size_t i = rv.r; i < j; ++i) {
      const double q = s * (x[i] - xr);
      double p = q;
      for (double& v : mx) {
        v += p / static_cast<double>(n);
        p *= q;
      }
      my += s * y[i] / static_cast<double>(n);
    }
    for (std::size_t i = rv.r; i < j; ++i) {
      const double q = s * (x[i] - xr);
      double u[P];
      double p = q;
      for (int k = 0; k < P; ++k) {
        u[k] = p - mx[k];
        p *= q;
      }
      const double v = s * y[i] - my;
      for (int k = 0; k < P; ++k) {
        B[k] += u[k] * v;
        for (int l = 0; l < P; ++l) A[k][l] += u[k] * u[l];
      }
    }
  }
  // Gaussian elimination with partial pivoting (3 x 3).
  for (int k = 0; k < P; ++k) {
    int piv = k;
    for (int i = k + 1; i < P; ++i) {
      if (std::abs(A[i][k]) > std::abs(A[piv][k])) piv = i;
    }
    if (!(std::abs(A[piv][k]) > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    for (int l = 0; l < P; ++l) std::swap(A[k][l], A[piv][l]);
    std::swap(B[k], B[piv]);
    for (int i = k + 1; i < P; ++i) {
      const double f = A[i][k] / A[k][k];
      for (int l = k; l < P; ++l) A[i][l] -= f * A[k][l];
      B[i] -= f * B[k];
    }
  }
  double c[P];
  for (int k = P - 1; k >= 0; --k) {
    double v = B[k];
    for (int l = k + 1; l < P; ++l) v -= A[k][l] * c[l];
    c[k] = v / A[k][k];
  }
  return c[0];
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
      throw InvalidInput(fmt::format("{}: data row {}: value is not finite", source, i + 1));
    }
    if (i > 0 && !(t[i] > t[i - 1])) {
      throw InvalidInput(fmt::format(
          "{}: data row {}: time t = {} s does not increase (previous {} s): time must be strictly "
          "increasing",
          source, i + 1, t[i], t[i - 1]));
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
          "{}: data row {}: a gap in time ({} s to {} s, the median step is {} s): samples are "
          "missing",
          source, i + 2, t[i], t[i + 1], med));
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
  d.validate();
  return d;
}

FrettingAnalysis analyze_fretting(const FrettingData& data, double P, const AnalysisOptions& opt) {
  data.validate();
  if (!(P > 0.0) || !std::isfinite(P)) throw InvalidInput(fmt::format("P = {} N must be > 0", P));
  if (!(opt.stiffness_window > 0.0 && opt.stiffness_window <= 0.5)) {
    throw InvalidInput("stiffness window must be in (0, 0.5]");
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
  // Stiffness at a reversal from the slope b of the fit (see AnalysisOptions): 1/b for
  // delta(Q), 1/(1/b - c) for Q(Delta) with the apparatus compliance c.
  out.stiffness_from_imposed = imposed && opt.stiffness_from_imposed;
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
  }
  const double c_app = out.apparatus_compliance;
  const auto& fit_x = out.stiffness_from_imposed ? data.Delta : data.Q;
  const auto& fit_y = out.stiffness_from_imposed ? data.Q : data.delta;
  const auto& fit_x0 = out.stiffness_from_imposed ? data.Delta : Qs;
  const auto stiffness_of = [&](double b) {
    return out.stiffness_from_imposed ? 1.0 / (1.0 / b - c_app) : 1.0 / b;
  };
  const std::size_t m = std::max<std::size_t>(opt.loop_points, 10);
  std::vector<double> acc_d(2 * m, 0.0), acc_Q(2 * m, 0.0);
  std::vector<Reversal> reversals;
  for (std::size_t k = 0; k + 2 < tp.size(); ++k) {
    if (tp[k].second != 1) continue;
    const std::size_t a = tp[k].first, mid = tp[k + 1].first, b = tp[k + 2].first;
    const double down = s[a] - s[mid], up = s[b] - s[mid];
    if (std::min(down, up) < 0.85 * std::max(down, up)) continue;  // ramps of Eq. 5.3
    CycleMetrics c;
    c.t_start = data.t[a];
    c.t_end = data.t[b];
    c.energy = trapezoid_loop_area(ds, Qs, a, b);
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
    c.stiffness_unloading = stiffness_of(slope_at_reversal(fit_x, fit_y, fit_x0, Qs, a, mid, span));
    c.stiffness_reloading = stiffness_of(slope_at_reversal(fit_x, fit_y, fit_x0, Qs, mid, b, span));
    reversals.push_back({a, mid, -1, span});
    reversals.push_back({mid, b, 1, span});
    c.stiffness = 0.5 * (c.stiffness_unloading + c.stiffness_reloading);
    const double x_down = crossing(ds, Qs, a, mid, c.Q_center);
    const double x_up = crossing(ds, Qs, mid, b, c.Q_center);
    c.sliding = std::max(0.0, 0.5 * (x_down - x_up));
    c.partial_slip = c.delta_max - c.sliding;
    out.cycles.push_back(c);
    resample(data.delta, a, mid, m, acc_d, 0);
    resample(data.delta, mid, b, m, acc_d, m);
    resample(data.Q, a, mid, m, acc_Q, 0);
    resample(data.Q, mid, b, m, acc_Q, m);
  }
  if (out.cycles.empty()) {
    throw InvalidInput(fmt::format(
        "{}: fewer than one complete fretting cycle (maximum -> minimum -> maximum of the "
        "displacement) found",
        data.source));
  }
  const double nc = static_cast<double>(out.cycles.size());
  CycleMetrics& mean = out.mean;
  mean.t_start = out.cycles.front().t_start;
  mean.t_end = out.cycles.back().t_end;
  for (const auto& c : out.cycles) {
    mean.energy += c.energy / nc;
    mean.Q_max += c.Q_max / nc;
    mean.delta_max += c.delta_max / nc;
    mean.Q_center += c.Q_center / nc;
    mean.delta_center += c.delta_center / nc;
    mean.stiffness += c.stiffness / nc;
    mean.stiffness_unloading += c.stiffness_unloading / nc;
    mean.stiffness_reloading += c.stiffness_reloading / nc;
    mean.sliding += c.sliding / nc;
    mean.partial_slip += c.partial_slip / nc;
  }
  out.mu = mean.Q_max / P;  // Eq. 6.1
  mean.stiffness = stiffness_of(pooled_slope(fit_x, fit_y, fit_x0, Qs, reversals));
  mean.stiffness_unloading = mean.stiffness_reloading = mean.stiffness;
  out.loop_delta.resize(2 * m);
  out.loop_Q.resize(2 * m);
  for (std::size_t j = 0; j < 2 * m; ++j) {
    out.loop_delta[j] = acc_d[j] / nc;
    out.loop_Q[j] = acc_Q[j] / nc;
  }
  out.loop_energy = trapezoid_loop_area(out.loop_delta, out.loop_Q, 0, 2 * m - 1);
  if (!std::isfinite(mean.stiffness)) {
    throw InvalidInput(fmt::format(
        "{}: too few samples after a reversal to fit the stiffness (sample faster, or widen the "
        "stiffness window)",
        data.source));
  }
  if (!(mean.stiffness > 0.0)) {
    throw InvalidInput(fmt::format(
        "{}: the joint's compliance at the reversals is not resolved (fitted stiffness {:.4g} "
        "N/um): the noise is too large against the joint's motion in the fit window (widen the "
        "stiffness window, record more cycles or sample faster)",
        data.source, mean.stiffness * 1e-6));
  }
  return out;
}

double power_law_exponent(const std::vector<double>& Q_max, const std::vector<double>& energy) {
  if (Q_max.size() != energy.size() || Q_max.size() < 2) {
    throw InvalidInput("power law: give at least two runs (energy and Q_max each)");
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(Q_max.size());
  for (std::size_t i = 0; i < Q_max.size(); ++i) {
    if (!(Q_max[i] > 0.0) || !(energy[i] > 0.0))
      throw InvalidInput("power law: values must be > 0");
    const double x = std::log(Q_max[i]), y = std::log(energy[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double den = n * sxx - sx * sx;
  if (!(std::abs(den) > 1e-12 * n * sxx))
    throw InvalidInput("power law: the runs have the same Q_max");
  return (n * sxy - sx * sy) / den;
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
  if (!(o.sample_rate > 0.0) || !(o.pzt_stiffness > 0.0) || !(o.load_cell_stiffness > 0.0) ||
      !(o.noise_delta >= 0.0) || !(o.noise_Q >= 0.0)) {
    throw InvalidInput("synthetic experiment: sample rate and stiffnesses must be > 0, noise >= 0");
  }
  const double compliance = 1.0 / o.pzt_stiffness + 1.0 / o.load_cell_stiffness;
  const auto n = static_cast<std::size_t>(std::floor(o.excitation.duration() * o.sample_rate)) + 1;
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
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> nd(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    d.delta[i] += o.noise_delta * nd(rng);
    d.Q[i] += o.noise_Q * nd(rng);
  }
  return d;
}

}  // namespace asperity::joint
