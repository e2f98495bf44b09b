#include "asperity/vibration/rough_contact.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "asperity/contact/material.hpp"
#include "asperity/core/error.hpp"
#include "asperity/core/parallel.hpp"
#include "asperity/core/validate.hpp"
#include "common.hpp"
#include "masing_memory.hpp"

namespace asperity::vibration {

namespace {

// Tangential tables 2^(1/8) apart in p: cubic Lagrange interpolation of Q_l/p in ln p errs
// by ~h^4/24 |d^4/d(ln p)^4 (Q_l/p)| ~ 1e-6 of Q_l/p (h = ln 2/8).
constexpr double kLnPressureStep = std::numbers::ln2 / 8.0;
// Normal table: spacing and reach in d* = d/sigma. A cubic B-spline errs by ~5 h^4/384 of the
// fourth derivative: 5e-9 of P* for h = 0.025. Compression past the prestress is tabulated
// over 1.5 sigma; unloading until the load is below kNormalTail of the prestress load.
constexpr double kNormalStep = 0.025;
constexpr double kCompressionReach = 1.5;
constexpr double kNormalTail = 1e-13;
constexpr int kMaxUnloadingNodes = 800;  // 20 sigma
// Steady periodic response: a period that changes no force by more than this fraction of the
// slip force from the previous one; at most kMaxPeriods periods.
constexpr double kPeriodicTolerance = 1e-13;
constexpr std::size_t kMaxPeriods = 64;

surface::RoughFlat make_flat(const RoughInterfaceParameters& c) {
  c.validate();
  return surface::RoughFlat::from_combined(c.E_star, c.G_star, c.H, c.nu, c.sigma, c.R, c.eta,
                                           c.model, c.friction, c.summit_sigma, c.summit_heights);
}

void require_finite_displacements(const Eigen::MatrixXd& u) {
  if (!u.allFinite()) {
    throw InvalidInput("rough_contact element: displacement samples hold a NaN or infinity");
  }
}

// d f*/d coord*(sample j, direction c): the sparse dependence of one force value.
struct ContactTerm {
  std::uint32_t j;
  std::uint16_t c;
  double v;
};
using Deriv = std::vector<ContactTerm>;

// Sorted by (j, c) with duplicates summed: bounds a list by the number of sample values.
void compress(Deriv& d) {
  std::sort(d.begin(), d.end(), [](const ContactTerm& a, const ContactTerm& b) {
    return a.j != b.j ? a.j < b.j : a.c < b.c;
  });
  std::size_t out = 0;
  for (std::size_t k = 0; k < d.size(); ++k) {
    if (out > 0 && d[out - 1].j == d[k].j && d[out - 1].c == d[k].c) {
      d[out - 1].v += d[k].v;
    } else {
      d[out++] = d[k];
    }
  }
  d.resize(out);
}

struct ContactReversal {
  double x;          // displacement* at the reversal
  double f;          // force* there
  double direction;  // of the branch that starts here
  double closes_at;  // where the branch meets the one it left (Masing's loop memory)
  std::uint32_t sample;
  Deriv D;    // d f / d(samples)
  double p;   // pressure* at the reversal
  double dp;  // its dp*/du_n*
  // Masing's value of the stack up to here on the backbone at p (with its derivative in p
  // and, for the Jacobian, in the samples, weight -1): fixed while this reversal is in the
  // stack, so computed once.
  bool memory_known = false;
  double memory = 0.0;
  double memory_dp = 0.0;
  Deriv memory_D;
};

// Lagrange basis on nodes 0..3 at tau, and its derivative.
void lagrange4(double t, double w[4], double dw[4]) {
  w[0] = -(t - 1.0) * (t - 2.0) * (t - 3.0) / 6.0;
  w[1] = t * (t - 2.0) * (t - 3.0) / 2.0;
  w[2] = -t * (t - 1.0) * (t - 3.0) / 2.0;
  w[3] = t * (t - 1.0) * (t - 2.0) / 6.0;
  dw[0] = -(3.0 * t * t - 12.0 * t + 11.0) / 6.0;
  dw[1] = (3.0 * t * t - 10.0 * t + 6.0) / 2.0;
  dw[2] = -(3.0 * t * t - 8.0 * t + 3.0) / 2.0;
  dw[3] = (3.0 * t * t - 6.0 * t + 2.0) / 6.0;
}

}  // namespace

void RoughInterfaceParameters::validate() const {
  core::require_positive("rough_contact.E_star", E_star);
  core::require_positive("rough_contact.G_star", G_star);
  core::require_positive("rough_contact.H", H);
  core::require_in_half_open("rough_contact.nu", nu, 0.0, 0.5);
  core::require_positive("rough_contact.sigma", sigma);
  core::require_positive("rough_contact.R", R);
  core::require_positive("rough_contact.eta", eta);
  if (summit_heights && !summit_sigma) {
    throw InvalidInput(
        "rough_contact: a summit-height table needs sigma to be the summit heights' standard "
        "deviation (summit_sigma)");
  }
  if (!(G_star < E_star)) {
    throw InvalidInput(fmt::format("rough_contact.G_star = {} Pa: must be below E_star = {} Pa",
                                   core::format_value(G_star), core::format_value(E_star)));
  }
  if (!(H < E_star)) {
    throw InvalidInput(fmt::format(
        "rough_contact.H = {} Pa: a hardness at or above E_star = {} Pa is not a metal pair",
        core::format_value(H), core::format_value(E_star)));
  }
}

RoughContactSurface::RoughContactSurface(const RoughInterfaceParameters& params, double p_low,
                                         double p_high)
    : params_(params),
      flat_(make_flat(params)),
      pressure_scale_(contact::hardness_factor(params.nu) * params.H),
      p_low_(p_low),
      p_high_(p_high) {
  core::require_positive("rough_contact pressure range low end", p_low);
  core::require_finite("rough_contact pressure range high end", p_high);
  const double p_max = flat_.max_load_star() * pressure_scale_;
  if (!(p_high > p_low) || !(p_high <= p_max)) {
    throw InvalidInput(fmt::format(
        "rough_contact pressure range [{}, {}] Pa: give 0 < low < high <= {} Pa (the load of "
        "this rough flat at d = -5 sigma_a, the largest it represents)",
        core::format_value(p_low), core::format_value(p_high), core::format_value(p_max)));
  }
  h_ = kLnPressureStep;
  const double span = std::log(p_high / p_low);
  const auto count = std::max<std::size_t>(4, static_cast<std::size_t>(std::ceil(span / h_)) + 1);
  // Nodes from p_low up; the last may lie above p_high (count >= 4, or the ceiling). When
  // that would pass the flat's largest load, the nodes end at p_high instead and the first
  // lies below p_low (the range is covered either way).
  ln_p_first_ = std::log(p_low / pressure_scale_);
  const double ln_p_top = std::log(p_high / pressure_scale_);
  if (ln_p_first_ + static_cast<double>(count - 1) * h_ > std::log(flat_.max_load_star()))
    ln_p_first_ = ln_p_top - static_cast<double>(count - 1) * h_;
  p_star_.resize(count);
  tables_.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    p_star_[k] = std::exp(ln_p_first_ + static_cast<double>(k) * h_);
  }
  core::parallel_for(count, [&](std::size_t k) {
    tables_[k] = flat_.backbone(flat_.separation_star(p_star_[k]));
  });
}

// ---------------------------------------------------------------------------------------

RoughContactElement::RoughContactElement(std::shared_ptr<const RoughContactSurface> surface,
                                         double area, double pressure, std::string name)
    : surface_(std::move(surface)), area_(area), p0_(pressure), name_(std::move(name)) {
  if (!surface_)
    throw InvalidInput(fmt::format("{}: a rough_contact element needs its surface", name_));
  if (!(std::isfinite(area) && area > 0.0)) {
    throw InvalidInput(
        fmt::format("{}: area = {} m^2: give a finite area > 0", name_, core::format_value(area)));
  }
  if (!(pressure >= surface_->p_low() && pressure <= surface_->p_high())) {
    throw InvalidInput(fmt::format(
        "{}: prestress pressure = {} Pa: give a value in the surface's table range [{}, {}] Pa "
        "(an element out of contact at the prestress carries no rough_contact law)",
        name_, core::format_value(pressure), core::format_value(surface_->p_low()),
        core::format_value(surface_->p_high())));
  }
  const surface::RoughFlat& flat = surface_->flat();
  p0_star_ = p0_ / surface_->pressure_scale();
  d0_star_ = flat.separation_star(p0_star_);
  table0_ = flat.backbone(d0_star_);
  stencil0_ = stencil(p0_star_);

  // Normal law after the prestress set: one spline on each side of d0 (the third derivative
  // is singular at the set from the compression side, where asperities first touch, like
  // (d0 - d)^{-1/2}), both ending at d0 with the slope of the unloading side there
  // (continuous: newly touching asperities add no stiffness at first contact), from a
  // one-sided difference of order 4.
  const auto after_set = [&](double d) { return flat.normal_load_after_set_star(d, d0_star_); };
  const double P0 = after_set(d0_star_);
  std::vector<double> unloading{P0};
  for (int k = 1; k <= kMaxUnloadingNodes; ++k) {
    const double P = after_set(d0_star_ + k * kNormalStep);
    unloading.push_back(P);
    if (P < kNormalTail * p0_star_) break;
  }
  const double hs = kNormalStep / 16.0;
  double fd[5] = {P0, 0, 0, 0, 0};
  for (int k = 1; k <= 4; ++k) fd[k] = after_set(d0_star_ + k * hs);
  const double slope0 =
      (-25.0 * fd[0] + 48.0 * fd[1] - 36.0 * fd[2] + 16.0 * fd[3] - 3.0 * fd[4]) / (12.0 * hs);
  const auto n_low = static_cast<std::size_t>(std::round(kCompressionReach / kNormalStep));
  std::vector<double> compression(n_low + 1);
  compression[n_low] = P0;
  core::parallel_for(n_low, [&](std::size_t k) {
    compression[k] = after_set(d0_star_ - static_cast<double>(n_low - k) * kNormalStep);
  });
  d_lo_ = d0_star_ - static_cast<double>(n_low) * kNormalStep;
  d_hi_ = d0_star_ + static_cast<double>(unloading.size() - 1) * kNormalStep;
  using Spline = boost::math::interpolators::cardinal_cubic_b_spline<double>;
  compression_ =
      std::make_shared<const Spline>(compression.data(), compression.size(), d_lo_, kNormalStep,
                                     std::numeric_limits<double>::quiet_NaN(), slope0);
  unloading_ = std::make_shared<const Spline>(unloading.data(), unloading.size(), d0_star_,
                                              kNormalStep, slope0, 0.0);
  p_ref_star_ = P0;
}

RoughContactElement::Stencil RoughContactElement::stencil(double p_star) const {
  Stencil s;
  const double L = std::log(p_star);
  const double t = (L - surface_->ln_p_first()) / surface_->ln_p_step();
  const auto n = static_cast<double>(surface_->tables());
  if (!(t > 0.0)) {
    s.w[0] = 1.0;  // below the lowest table: its shape, scaled with p
    return s;
  }
  if (t > n - 1.0) {
    throw NumericalError(fmt::format(
        "{}: normal pressure {} Pa is above the {} Pa the interface's tangential tables reach "
        "(the pressure range of its rough_contact surface): a larger range is needed",
        name_, core::format_value(p_star * surface_->pressure_scale()),
        core::format_value(surface_->table_pressure_star(surface_->tables() - 1) *
                           surface_->pressure_scale())));
  }
  const double k0 = std::clamp(std::floor(t) - 1.0, 0.0, n - 4.0);
  s.k0 = static_cast<std::size_t>(k0);
  lagrange4(t - k0, s.w, s.dw);
  for (double& d : s.dw) d /= surface_->ln_p_step();
  return s;
}

RoughContactElement::Blend RoughContactElement::blend(double p) const {
  const Stencil st = stencil(p);
  Blend out;
  const auto add = [&](std::size_t k, double a, double b) {
    for (std::size_t j = 0; j < out.n; ++j) {
      if (out.k[j] == k) {
        out.a[j] += a;
        out.b[j] += b;
        return;
      }
    }
    out.k[out.n] = k;
    out.a[out.n] = a;
    out.b[out.n] = b;
    ++out.n;
  };
  for (int m = 0; m < 4; ++m) {
    if (st.w[m] != 0.0 || st.dw[m] != 0.0) {
      const std::size_t k = st.k0 + static_cast<std::size_t>(m);
      const double pk = surface_->table_pressure_star(k);
      add(k, st.w[m] / pk, st.dw[m] / pk);
    }
  }
  for (int m = 0; m < 4; ++m) {
    if (stencil0_.w[m] != 0.0) {
      const std::size_t k = stencil0_.k0 + static_cast<std::size_t>(m);
      add(k, -stencil0_.w[m] / surface_->table_pressure_star(k), 0.0);
    }
  }
  return out;
}

RoughContactElement::Tangential RoughContactElement::tangential_at(double x, double p,
                                                                   const Blend& b) const {
  const auto v0 = table0_->value_and_slope_non_negative(x);
  double F = v0.Q / p0_star_, Fx = v0.dQ / p0_star_, FL = 0.0;
  for (std::size_t j = 0; j < b.n; ++j) {
    const auto v = surface_->table(b.k[j]).value_and_slope_non_negative(x);
    F += b.a[j] * v.Q;
    Fx += b.a[j] * v.dQ;
    FL += b.b[j] * v.Q;
  }
  return {p * F, p * Fx, F + FL};  // d(p F(ln p))/dp = F + dF/d ln p
}

RoughContactElement::Tangential RoughContactElement::tangential_star(double x, double p) const {
  if (!(p > 0.0)) return {};
  return tangential_at(x, p, blend(p));
}

RoughContactElement::Tangential RoughContactElement::limit_at(double p, const Blend& b) const {
  double F = table0_->limit() / p0_star_, FL = 0.0;
  for (std::size_t j = 0; j < b.n; ++j) {
    const double l = surface_->table(b.k[j]).limit();
    F += b.a[j] * l;
    FL += b.b[j] * l;
  }
  return {p * F, 0.0, F + FL};
}

RoughContactElement::Tangential RoughContactElement::limit_star(double p) const {
  if (!(p > 0.0)) return {};
  return limit_at(p, blend(p));
}

RoughContactElement::Pressure RoughContactElement::pressure(double u_n) const {
  const double d = d0_star_ - u_n / surface_->sigma();
  if (d >= d_hi_) return {};
  if (!(d >= d_lo_)) {  // also NaN: the splines do not check their range
    throw NumericalError(fmt::format(
        "{}: closure u_n = {} m presses the surfaces {:.3g} sigma past their prestress; the "
        "element's normal law is tabulated over {} sigma (d/sigma from {:.4g})",
        name_, core::format_value(u_n), d0_star_ - d, kCompressionReach, d_lo_));
  }
  // P*(d) - P*_spline(d0) + p0*: exactly the prestress load at u_n = 0.
  const auto& spline = d < d0_star_ ? *compression_ : *unloading_;
  const double P = spline(d) - p_ref_star_ + p0_star_;
  if (!(P > 0.0)) return {};
  return {P, -spline.prime(d)};  // dP*/dy*, y* = u_n/sigma
}

void RoughContactElement::periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& /*v*/,
                                            bool tangent, PeriodicResponse& out) const {
  require_finite_displacements(u);
  if (u.cols() != 3) {
    throw InvalidInput(
        fmt::format("{}: rough_contact takes 3 directions (t1, t2, n), got {}", name_, u.cols()));
  }
  const auto n = static_cast<std::size_t>(u.rows());
  out.f.setZero(u.rows(), 3);
  out.history.clear();
  if (tangent) {
    out.du.setZero(u.rows(), 9);
  } else {
    out.du.resize(0, 0);
  }
  out.dv.resize(0, 0);
  if (n == 0) return;
  const double sig = surface_->sigma();
  const double force_scale = surface_->pressure_scale() * area_;
  const double stiffness_scale = force_scale / sig;

  struct Direction {
    std::vector<ContactReversal> stack;
    double x_prev = 0.0, f_prev = 0.0, dir_prev = 0.0;
    double origin = 0.0;  // centre of the virgin curve: 0, or where the element last separated
    std::uint32_t origin_sample = 0;
    bool origin_has_sample = false;
    std::uint32_t s_prev = 0;
    bool prev_has_sample = false;
    double p_at_prev = 0.0, dp_at_prev = 0.0;  // pressure* at sample s_prev
    Deriv D_prev;
  };
  Direction dirs[2];
  Deriv g_D[2];
  // The state a period starts from, as it matters for the next (the memory caches follow
  // from it): equal states give equal periods, bit for bit.
  const auto same_terms = [](const Deriv& a, const Deriv& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](auto& x, auto& y) {
             return x.j == y.j && x.c == y.c && x.v == y.v;
           });
  };
  const auto same_state = [&](const Direction& a, const Direction& b) {
    if (a.stack.size() != b.stack.size() || a.x_prev != b.x_prev || a.f_prev != b.f_prev ||
        a.dir_prev != b.dir_prev || a.origin != b.origin || a.origin_sample != b.origin_sample ||
        a.origin_has_sample != b.origin_has_sample || a.s_prev != b.s_prev ||
        a.prev_has_sample != b.prev_has_sample || a.p_at_prev != b.p_at_prev ||
        a.dp_at_prev != b.dp_at_prev || !same_terms(a.D_prev, b.D_prev))
      return false;
    for (std::size_t k = 0; k < a.stack.size(); ++k) {
      const ContactReversal& x = a.stack[k];
      const ContactReversal& y = b.stack[k];
      if (x.x != y.x || x.f != y.f || x.direction != y.direction || x.closes_at != y.closes_at ||
          x.sample != y.sample || x.p != y.p || x.dp != y.dp || !same_terms(x.D, y.D))
        return false;
    }
    return true;
  };
  Direction started[2];
  // Masing's value at the top reversal of a stack built from the virgin curve centred at
  // `origin`, on the backbone at pressure* q: M_0 = sign Q_l(|x_0 - origin|), then
  // M_j = M_{j-1} + 2 d_{j-1} Q_l(|x_j - x_{j-1}|/2) (Eq. 4.11-4.13). dq: dM/dq; into D
  // (when given) its x-derivatives times `weight`.
  const auto memory_value = [&](const std::vector<ContactReversal>& stack, double origin, double q,
                                const Blend& B, double& dq, Deriv* D, double weight, int c,
                                const std::uint32_t* origin_sample) {
    const auto cc = static_cast<std::uint16_t>(c);
    const double rel0 = stack.front().x - origin;
    const double sgn0 = rel0 < 0.0 ? -1.0 : 1.0;
    const Tangential t0 = tangential_at(std::abs(rel0), q, B);
    double M = rel0 == 0.0 ? 0.0 : sgn0 * t0.Q;
    dq = rel0 == 0.0 ? 0.0 : sgn0 * t0.Qp;
    if (D) {
      D->push_back({stack.front().sample, cc, weight * t0.Qx});
      if (origin_sample) D->push_back({*origin_sample, cc, -weight * t0.Qx});
    }
    for (std::size_t j = 1; j < stack.size(); ++j) {
      const ContactReversal& a = stack[j - 1];
      const ContactReversal& b = stack[j];
      const Tangential t = tangential_at(0.5 * std::abs(b.x - a.x), q, B);
      M += a.direction * 2.0 * t.Q;
      dq += a.direction * 2.0 * t.Qp;
      if (D) {
        D->push_back({b.sample, cc, weight * t.Qx});
        D->push_back({a.sample, cc, -weight * t.Qx});
      }
    }
    return M;
  };
  // The normal law and the tables' blend at each sample's pressure: the same in every period.
  std::vector<Pressure> pressures(n);
  std::vector<Blend> blends(n);
  for (std::size_t k = 0; k < n; ++k) {
    pressures[k] = pressure(u(static_cast<Eigen::Index>(k), 2));
    if (pressures[k].p > 0.0) blends[k] = blend(pressures[k].p);
  }
  Deriv D_f[2];
  // Periods are repeated until one repeats the previous (the steady response): one repeat
  // under Masing's rules in one direction at constant load, a few more where the traction
  // limit returns a 2-D trial force or the load varies (shakedown of the reversal forces).
  Eigen::MatrixXd previous;
  for (std::size_t step = 0;; ++step) {
    const auto i = static_cast<std::uint32_t>(step % n);
    if (i == 0 && step >= n) {
      // The second period started where the first left off: the third would repeat it.
      if (step == 2 * n && same_state(dirs[0], started[0]) && same_state(dirs[1], started[1]))
        break;
      if (step == n) {
        started[0] = dirs[0];
        started[1] = dirs[1];
      }
      if (step >= 2 * n) {
        const double diff = (out.f - previous).cwiseAbs().maxCoeff();
        if (diff <= kPeriodicTolerance * force_scale * table0_->limit()) break;
        if (step >= kMaxPeriods * n) {
          throw NumericalError(
              fmt::format("{}: the response to the sampled period is not periodic after {} periods "
                          "(change {:.3g} N in the last); the path may be too coarsely sampled",
                          name_, kMaxPeriods, diff));
        }
      }
      previous = out.f;
      out.history.clear();
      if (tangent) out.du.setZero();
    }
    const auto ii = static_cast<Eigen::Index>(i);
    const Pressure& pr = pressures[i];
    const double p = pr.p;
    const Blend& B = blends[i];
    double g[2];
    for (int c = 0; c < 2; ++c) {
      Direction& s = dirs[c];
      const double x = u(ii, c) / sig;
      Deriv& D = g_D[c];
      D.clear();
      if (!(p > 0.0)) {
        // Separated: no traction; the surfaces touch again with a fresh virgin curve here.
        s.stack.clear();
        s.origin = x;
        s.origin_sample = i;
        s.origin_has_sample = true;
        s.dir_prev = 0.0;
        s.prev_has_sample = false;
        s.D_prev.clear();
        g[c] = 0.0;
        s.x_prev = x;
        continue;
      }
      const int d = detail::sign_of(x - s.x_prev);
      if (d != 0) {
        if (s.dir_prev != 0.0 && d != static_cast<int>(s.dir_prev)) {
          ContactReversal r{s.x_prev,
                            s.f_prev,
                            static_cast<double>(d),
                            s.stack.empty() ? 2.0 * s.origin - s.x_prev : s.stack.back().x,
                            s.s_prev,
                            {},
                            s.p_at_prev,
                            s.dp_at_prev};
          if (tangent && s.prev_has_sample) {
            r.D = s.D_prev;
            compress(r.D);
          }
          s.stack.push_back(std::move(r));
        }
        s.dir_prev = d;
        s.stack.resize(detail::masing_active_depth(s.stack, x));
      }
      if (s.stack.empty()) {
        const double rel = x - s.origin;
        const Tangential t = tangential_at(std::abs(rel), p, B);
        const double sgn = rel < 0.0 ? -1.0 : 1.0;
        g[c] = rel == 0.0 ? 0.0 : sgn * t.Q;
        if (tangent) {
          D.push_back({i, static_cast<std::uint16_t>(c), t.Qx});
          if (s.origin_has_sample)
            D.push_back({s.origin_sample, static_cast<std::uint16_t>(c), -t.Qx});
          D.push_back({i, 2, sgn * t.Qp * pr.dp});
        }
      } else {
        ContactReversal& r = s.stack.back();
        const Tangential t = tangential_at(0.5 * std::abs(x - r.x), p, B);
        g[c] = r.f + r.direction * 2.0 * t.Q;
        if (tangent) {
          D = r.D;
          D.push_back({i, static_cast<std::uint16_t>(c), t.Qx});
          D.push_back({r.sample, static_cast<std::uint16_t>(c), -t.Qx});
          D.push_back({i, 2, r.direction * 2.0 * t.Qp * pr.dp});
        }
        // The reversal force follows the pressure: the memory's Masing value at the reversal
        // at p(t) minus the one at p_r (zero at constant load). Every branch is then Masing's
        // construction on the backbone at p(t), and a branch meets the one it left at the
        // latter's reversal with the same force (docs/rough_contact.md, "Normal-load
        // variation").
        const std::uint32_t* origin_sample = s.origin_has_sample ? &s.origin_sample : nullptr;
        if (!r.memory_known) {
          r.memory = memory_value(s.stack, s.origin, r.p, blend(r.p), r.memory_dp,
                                  tangent ? &r.memory_D : nullptr, -1.0, c, origin_sample);
          r.memory_known = true;
        }
        double dM_now = 0.0;
        g[c] += memory_value(s.stack, s.origin, p, B, dM_now, tangent ? &D : nullptr, 1.0, c,
                             origin_sample) -
                r.memory;
        if (tangent) {
          D.insert(D.end(), r.memory_D.begin(), r.memory_D.end());
          D.push_back({i, 2, dM_now * pr.dp});
          D.push_back({r.sample, 2, -r.memory_dp * r.dp});
        }
      }
    }
    // The rough flat's static friction bounds the traction vector (Eq. 4.7).
    double f[2] = {g[0], g[1]};
    D_f[0].clear();
    D_f[1].clear();
    const double mag = std::hypot(g[0], g[1]);
    const Tangential lim = p > 0.0 ? limit_at(p, B) : Tangential{};
    const bool capped = mag > lim.Q;
    if (capped) {
      if (mag > 0.0) {
        const double e[2] = {g[0] / mag, g[1] / mag};
        const double ratio = lim.Q / mag;
        for (int a = 0; a < 2; ++a) {
          f[a] = e[a] * lim.Q;
          if (!tangent) continue;
          for (int b = 0; b < 2; ++b) {
            const double m = ratio * ((a == b ? 1.0 : 0.0) - e[a] * e[b]);
            if (m == 0.0) continue;
            for (const ContactTerm& term : g_D[b]) D_f[a].push_back({term.j, term.c, m * term.v});
          }
          D_f[a].push_back({i, 2, e[a] * lim.Qp * pr.dp});
        }
      } else {
        f[0] = f[1] = 0.0;
      }
    } else if (tangent) {
      D_f[0] = g_D[0];
      D_f[1] = g_D[1];
    }
    for (int c = 0; c < 2; ++c) {
      Direction& s = dirs[c];
      const double x = u(ii, c) / sig;
      if (p > 0.0 && x != s.x_prev) {
        s.s_prev = i;
        s.prev_has_sample = true;
        s.p_at_prev = p;
        s.dp_at_prev = pr.dp;
      }
      if (p > 0.0 && tangent) s.D_prev = D_f[c];
      s.f_prev = f[c];
      s.x_prev = x;
    }
    if (step < n) continue;
    out.f(ii, 0) = force_scale * f[0];
    out.f(ii, 1) = force_scale * f[1];
    out.f(ii, 2) = force_scale * (p - p0_star_);
    if (!tangent) continue;
    out.du(ii, 2 + 3 * 2) = stiffness_scale * pr.dp;
    for (int c = 0; c < 2; ++c) {
      for (const ContactTerm& term : D_f[c]) {
        const double v = stiffness_scale * term.v;
        if (term.j == i) {
          out.du(ii, c + 3 * term.c) += v;
        } else {
          out.history.push_back({i, term.j, static_cast<std::uint16_t>(c), term.c, v});
        }
      }
    }
  }
}

void RoughContactElement::static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                                          Eigen::MatrixXd& K) const {
  if (u.size() != 3 || !u.allFinite()) {
    throw InvalidInput(fmt::format("{}: static response needs 3 finite displacements", name_));
  }
  const double sig = surface_->sigma();
  const double force_scale = surface_->pressure_scale() * area_;
  const Pressure pr = pressure(u(2));
  f.setZero(3);
  K.setZero(3, 3);
  f(2) = force_scale * (pr.p - p0_star_);
  K(2, 2) = force_scale / sig * pr.dp;
  if (!(pr.p > 0.0)) return;
  const Eigen::Vector2d x(u(0) / sig, u(1) / sig);
  const double r = x.norm();
  const Tangential t = tangential_star(r, pr.p);
  if (r == 0.0) {
    K(0, 0) = K(1, 1) = force_scale / sig * t.Qx;
    return;
  }
  const Eigen::Vector2d e = x / r;
  f.head<2>() = force_scale * t.Q * e;
  const Eigen::Matrix2d P = e * e.transpose();
  K.topLeftCorner<2, 2>() =
      force_scale / sig * (t.Qx * P + (t.Q / r) * (Eigen::Matrix2d::Identity() - P));
  K.block<2, 1>(0, 2) = force_scale / sig * t.Qp * pr.dp * e;
}

Eigen::MatrixXd RoughContactElement::initial_stiffness() const {
  const double s = surface_->pressure_scale() * area_ / surface_->sigma();
  const double kt = s * table0_->initial_stiffness();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3, 3);
  K(0, 0) = K(1, 1) = kt;
  K(2, 2) = s * pressure(0.0).dp;
  return K;
}

double RoughContactElement::slip_force() const {
  return surface_->pressure_scale() * area_ * table0_->limit();
}

double RoughContactElement::gross_slip_fraction(const PeriodicResponse& r) const {
  const double scale = surface_->pressure_scale();  // K H: p* = p / (K H)
  int slipping = 0;
  for (Eigen::Index i = 0; i < r.f.rows(); ++i) {
    const double p_star = (p0_ + r.f(i, 2) / area_) / scale;
    if (!(p_star > 0.0)) continue;
    const double q_star = std::hypot(r.f(i, 0), r.f(i, 1)) / (scale * area_);
    if (q_star >= (1.0 - 1e-9) * limit_star(p_star).Q) ++slipping;
  }
  return r.f.rows() > 0 ? slipping / static_cast<double>(r.f.rows())
                        : std::numeric_limits<double>::quiet_NaN();
}

dynamics::SummaryObject RoughContactElement::describe() const {
  const RoughInterfaceParameters& c = surface_->parameters();
  return {{"type", std::string("rough_contact")},
          {"name", name_},
          {"area_m2", area_},
          {"prestress_pressure_Pa", p0_},
          {"prestress_separation_over_sigma", d0_star_},
          {"asperity_model", std::string(contact::to_string(c.model))},
          {"mu", table0_->limit() / p0_star_},
          {"E_star_Pa", c.E_star},
          {"G_star_Pa", c.G_star},
          {"H_Pa", c.H},
          {"sigma_m", c.sigma},
          {"summit_heights", c.summit_heights ? fmt::format("measured table ({} points)",
                                                            c.summit_heights->z_star().size())
                                              : std::string("gaussian")},
          {"R_m", c.R},
          {"eta_per_m2", c.eta}};
}

}  // namespace asperity::vibration
