// Fretting data: reading, cycles and loop metrics (Fig. 6.1, Eq. 6.1). The stiffness fit
// at the reversals is in fretting_stiffness.cpp, the energy-force power law in
// fretting_power_law.cpp, synthetic experiments in fretting_synthetic.cpp.
#include "asperity/joint/fretting.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include "asperity/core/csv.hpp"
#include "asperity/core/error.hpp"
#include "fretting_stiffness.hpp"

namespace asperity::joint {

namespace {

using detail::fit_reversals;
using detail::Reversal;

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
  // Eq. 6.1 with a preload that does not belong to the record: a dry metal contact does not
  // carry more than a few times its normal load (Blau: mu 0.2-1.5; the thesis's 0.33-0.35).
  if (out.mu > 3.0) {
    out.warnings.push_back(fmt::format(
        "mu = Q_max/P = {:.4g} (Eq. 6.1) is above 3 with the preload P = {:.6g} N: dry metal "
        "contacts give 0.2-1.5 (Blau), the thesis's joints 0.33-0.35 (ch. 5-6); check the "
        "preload (its unit, per bolt or total)",
        out.mu, P));
  }
  return out;
}

}  // namespace asperity::joint
