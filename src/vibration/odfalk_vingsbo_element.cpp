// The Odfalk-Vingsbo elastic-plastic tangential law (thesis Eq. 3.10) as a vibration element:
// a Masing loop on the elastic backbone with the parallelogram of plastic slip in series
// (hysteresis::OdfalkVingsboHysteresis), its steady periodic response to sampled motion and
// the exact derivative of that response with respect to the samples.
//
// Steady state. Plastic slip flows at dQ/k_p while |Q| > Q_ty and |Q| grows (gamma of
// Eq. 3.10). Under displacement control a period with more outward flow on one side than on
// the other shifts delta_p, hence the elastic displacement x_e = x - delta_p, hence the
// forces: the motion settles where the flows balance. That limit does not depend on where
// the motion started (the Masing branches depend on x_e only through differences), but the
// approach to it is geometric with a ratio near 1 when k_p is large against the elastic
// stiffness (0.99 per period at k_p = 70 k_0), so it is not found by repeating periods.
// It is found by shooting: start the period at the sample where x_e is largest, on the
// descending branch of a reversal at force Q_top, and solve for the Q_top whose period
// returns with no net plastic slip, D(Q_top) = delta_p(end) - delta_p(start) = 0 (D rises
// with Q_top). Where no plastic slip occurs over a whole period for a range of Q_top
// (force range below 2 Q_ty), the limit is history-dependent as Masing's own: repeated
// periods from the virgin state give it when they stop slipping; when they are still
// slipping the limit is the end of that range the forces approach (the force touching
// +-Q_ty), found by bisection.
//
// Derivatives. Every state quantity carries its gradient with respect to the N samples
// (and, while shooting, Q_top): along a monotone step x_e solves
// x_e + delta_p(Q(x_e)) = x, so dx_e (1 + s_Q k_t) = dx - d delta_p - s_rest - s_Q dQ_rev
// with k_t the Masing tangent, s_Q the plastic compliance at the new force, s_rest the
// flow's dependence on the step's start and dQ_rev the branch's dependence on its
// reversal point. The shooting condition then gives dQ_top = -dD/dx / (dD/dQ_top) (or, at
// the end of a no-slip range, the touching condition's), so the tangent is exact for the
// samples' AFT path as the Masing element's is.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include <fmt/format.h>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/hysteresis/odfalk_vingsbo.hpp"
#include "asperity/vibration/elements.hpp"
#include "common.hpp"
#include "masing_memory.hpp"

namespace asperity::vibration {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// Plastic slip of one monotone force step Q_old -> Q_new (OdfalkVingsboSlip::peek) and its
// partial derivatives. `envelope` = +inf in steady state (the virgin rate 1/(2 k_p) beyond
// the largest |Q| so far is a transient).
struct Flow {
  double value = 0.0;
  double d_new = 0.0;       // d/dQ_new
  double d_old = 0.0;       // d/dQ_old
  double d_envelope = 0.0;  // d/d envelope
};

Flow plastic_flow(const hysteresis::OdfalkVingsboParameters& p, double Q_old, double Q_new,
                  double envelope) {
  const double Q_ty = p.fretting_yield_point, k_p = p.hardening_coefficient;
  // Outward flow on the side of positive force over [q0, q1], q1 > q0 (Eq. 3.10's gamma).
  const auto outward = [&](double q0, double q1) {
    Flow f;
    const double a = std::max(q0, Q_ty);
    if (!(q1 > a)) return f;
    const double da = q0 > Q_ty ? 1.0 : 0.0;  // d a / d q0
    if (envelope <= a) {
      f.value = (q1 - a) / (2.0 * k_p);
      f.d_new = 1.0 / (2.0 * k_p);
      f.d_old = -da / (2.0 * k_p);
    } else if (envelope < q1) {
      f.value = (envelope - a) / k_p + (q1 - envelope) / (2.0 * k_p);
      f.d_new = 1.0 / (2.0 * k_p);
      f.d_old = -da / k_p;
      f.d_envelope = 1.0 / (2.0 * k_p);
    } else {
      f.value = (q1 - a) / k_p;
      f.d_new = 1.0 / k_p;
      f.d_old = -da / k_p;
    }
    return f;
  };
  if (Q_new > Q_old) return outward(Q_old, Q_new);
  if (Q_new < Q_old) {
    Flow f = outward(-Q_old, -Q_new);
    f.value = -f.value;
    f.d_envelope = -f.d_envelope;
    return f;
  }
  return {};
}

struct SlipReversal {
  double x = 0.0;  // elastic displacement x_e at the reversal
  double Q = 0.0;
  double direction = 0.0;
  double closes_at = 0.0;
  bool permanent = false;  // the shooting period's top: never wiped, its branch extended oddly
  Eigen::VectorXd g_xe, g_Q;
};

struct Branch {
  std::size_t k = 0;  // active stack depth (0: virgin curve)
  double Q = 0.0;
  double kt = 0.0;
};

// The elastic-plastic contact along sampled displacement, with gradients of size m (0: none).
class Path {
 public:
  Path(const hysteresis::Backbone& b, const hysteresis::OdfalkVingsboParameters& p, Eigen::Index m)
      : b_(b), p_(p), m_(m) {
    g_xe_ = g_Q_ = g_dp_ = g_env_ = Eigen::VectorXd::Zero(m);
  }

  // Shooting: at elastic displacement xe_top (sample `top`) just reversed from the force
  // Q_top (gradient: unit vector q_index), delta_p = 0, moving down next.
  void start_at_top(double x_top, Eigen::Index top, double Q_top, Eigen::Index q_index) {
    shooting_ = true;
    envelope_ = inf;
    x_prev_ = xe_ = x_top;
    Q_ = Q_top;
    dp_ = 0.0;
    if (m_ > 0) {
      g_xe_.setZero();
      g_xe_(top) = 1.0;
      g_Q_.setZero();
      g_Q_(q_index) = 1.0;
      g_dp_.setZero();
    }
    stack_.clear();
    push_reversal(-1);
  }

  void step(double x, Eigen::Index sample) {
    const int d = detail::sign_of(x - x_prev_);
    if (d == 0) return;  // no motion: the force and its dependence stay
    if (dir_prev_ != 0.0 && d != static_cast<int>(dir_prev_)) push_reversal(d);
    dir_prev_ = d;
    const double carried = x_prev_ - (xe_ + dp_);
    const auto residual = [&](double xe) {
      return xe + dp_ + plastic_flow(p_, Q_, branch(xe).Q, envelope_).value + carried - x;
    };
    const double xe1 = x - dp_ - carried;  // the whole step elastic (x itself from rest)
    double xe = xe1;
    const double r1 = residual(xe1);
    if (d > 0 ? r1 > 0.0 : r1 < 0.0) {
      xe = core::find_root(residual, d > 0 ? xe_ : xe1, d > 0 ? xe1 : xe_,
                           "Odfalk-Vingsbo element: elastic displacement of a step", 52);
    }
    const Branch br = branch(xe);
    const Flow s = plastic_flow(p_, Q_, br.Q, envelope_);
    if (s.value != 0.0) slipped_ = true;
    if (m_ > 0) {
      Eigen::VectorXd dQ_rev = Eigen::VectorXd::Zero(m_);
      if (br.k > 0) {
        const SlipReversal& r = stack_[br.k - 1];
        dQ_rev = r.g_Q - br.kt * r.g_xe;
      }
      Eigen::VectorXd rest = s.d_old * g_Q_;
      if (s.d_envelope != 0.0) rest += s.d_envelope * g_env_;
      Eigen::VectorXd g_x = Eigen::VectorXd::Zero(m_);
      g_x(sample) = 1.0;
      g_xe_ = (g_x - g_dp_ - rest - s.d_new * dQ_rev) / (1.0 + s.d_new * br.kt);
      const Eigen::VectorXd g_Q_new = br.kt * g_xe_ + dQ_rev;
      g_dp_ += rest + s.d_new * g_Q_new;
      g_Q_ = g_Q_new;
    }
    stack_.resize(br.k);
    xe_ = xe;
    Q_ = br.Q;
    dp_ += s.value;
    x_prev_ = x;
    if (std::abs(Q_) > envelope_) {
      envelope_ = std::abs(Q_);
      if (m_ > 0) g_env_ = Q_ > 0.0 ? g_Q_ : Eigen::VectorXd(-g_Q_);
    }
  }

  [[nodiscard]] double Q() const { return Q_; }
  [[nodiscard]] double xe() const { return xe_; }
  [[nodiscard]] double plastic_slip() const { return dp_; }
  [[nodiscard]] const Eigen::VectorXd& g_Q() const { return g_Q_; }
  [[nodiscard]] const Eigen::VectorXd& g_dp() const { return g_dp_; }
  /// True if any step since the last call slipped plastically.
  bool take_slipped() { return std::exchange(slipped_, false); }

 private:
  void push_reversal(int d) {
    dir_prev_ = d;
    SlipReversal r;
    r.x = xe_;
    r.Q = Q_;
    r.direction = d;
    if (stack_.empty()) {
      r.closes_at = -xe_;
      if (shooting_) {
        r.permanent = true;
        r.closes_at = d * -inf;
      }
    } else if (stack_.size() == 1 && stack_.front().permanent) {
      r.closes_at = d * inf;  // the top is the period's largest x_e: never reached again
    } else {
      r.closes_at = stack_.back().x;
    }
    r.g_xe = g_xe_;
    r.g_Q = g_Q_;
    stack_.push_back(std::move(r));
  }

  // The active Masing branch at xe (Hysteresis::active_branch), without changing the stack.
  [[nodiscard]] Branch branch(double xe) const {
    const std::size_t k =
        detail::masing_active_depth(stack_, xe, [](const SlipReversal& r) { return r.permanent; });
    Branch br;
    br.k = k;
    if (k == 0) {
      const double ax = std::abs(xe);
      br.Q = std::copysign(b_.force(ax), xe);
      br.kt = b_.stiffness(ax);
    } else {
      const SlipReversal& r = stack_[k - 1];
      const double half = r.direction * (xe - r.x) * 0.5;  // < 0 only past a permanent top
      br.Q = r.Q + r.direction * 2.0 * std::copysign(b_.force(std::abs(half)), half);
      br.kt = b_.stiffness(std::abs(half));
    }
    return br;
  }

  const hysteresis::Backbone& b_;
  hysteresis::OdfalkVingsboParameters p_;
  Eigen::Index m_;
  bool shooting_ = false;
  bool slipped_ = false;
  double x_prev_ = 0.0, xe_ = 0.0, Q_ = 0.0, dp_ = 0.0, envelope_ = 0.0, dir_prev_ = 0.0;
  Eigen::VectorXd g_xe_, g_Q_, g_dp_, g_env_;
  std::vector<SlipReversal> stack_;
};

class OdfalkVingsboElement final : public Element {
 public:
  OdfalkVingsboElement(std::shared_ptr<const hysteresis::Backbone> elastic,
                       const hysteresis::OdfalkVingsboParameters& p,
                       dynamics::SummaryObject parameters)
      : elastic_(std::move(elastic)), p_(p), parameters_(std::move(parameters)) {
    if (!elastic_) throw InvalidInput("an odfalk_vingsbo element needs an elastic backbone");
    p_.validate();
    parameters_.emplace_back("tangential", "odfalk_vingsbo");
    parameters_.emplace_back("fretting_yield_point_N", p_.fretting_yield_point);
    parameters_.emplace_back("hardening_coefficient_N_per_m", p_.hardening_coefficient);
  }
  /// The case file's element type ("rough_flat") when `parameters` name one.
  [[nodiscard]] std::string type() const override {
    for (const auto& [key, value] : parameters_) {
      if (key == "type" && std::holds_alternative<std::string>(value.data)) {
        return std::get<std::string>(value.data);
      }
    }
    return "odfalk_vingsbo";
  }
  void periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& v, bool tangent,
                         PeriodicResponse& out) const override;
  void static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                       Eigen::MatrixXd& K) const override;
  [[nodiscard]] Eigen::MatrixXd initial_stiffness() const override {
    return Eigen::MatrixXd::Constant(1, 1, elastic_->initial_stiffness());
  }
  [[nodiscard]] double slip_force() const override { return elastic_->limit(); }
  /// Eq. 3.10's parallelogram is not Masing's loop on the virgin curve x_l(Q) + plastic/2.
  [[nodiscard]] bool masing_from_virgin_curve() const override { return false; }
  [[nodiscard]] dynamics::SummaryObject describe() const override { return parameters_; }

 private:
  struct Period {
    Eigen::VectorXd Q;  // force at each sample
    Eigen::MatrixXd G;  // row i: dQ_i / d(samples, Q_top)
    Eigen::VectorXd xe;
    double drift = 0.0;  // delta_p after the period less before
    Eigen::VectorXd g_drift;
    bool slipped = false;
  };
  // One shooting period from the top sample at force Q_top.
  Period shoot(const Eigen::VectorXd& x, Eigen::Index top, double Q_top, bool gradients) const;

  std::shared_ptr<const hysteresis::Backbone> elastic_;
  hysteresis::OdfalkVingsboParameters p_;
  dynamics::SummaryObject parameters_;
};

OdfalkVingsboElement::Period OdfalkVingsboElement::shoot(const Eigen::VectorXd& x, Eigen::Index top,
                                                         double Q_top, bool gradients) const {
  const Eigen::Index n = x.size();
  Path path(*elastic_, p_, gradients ? n + 1 : 0);
  path.start_at_top(x(top), top, Q_top, n);
  Period P;
  P.Q.resize(n);
  P.xe.resize(n);
  if (gradients) P.G.resize(n, n + 1);
  for (Eigen::Index s = 1; s <= n; ++s) {
    const Eigen::Index i = (top + s) % n;
    path.step(x(i), i);
    P.Q(i) = path.Q();
    P.xe(i) = path.xe();
    if (gradients) P.G.row(i) = path.g_Q().transpose();
  }
  P.slipped = path.take_slipped();
  P.drift = path.plastic_slip();
  if (gradients) P.g_drift = path.g_dp();
  // The top sample's force is Q_top itself (the period's end returns to it when D = 0).
  P.Q(top) = Q_top;
  P.xe(top) = x(top);
  if (gradients) {
    P.G.row(top).setZero();
    P.G(top, n) = 1.0;
  }
  return P;
}

void OdfalkVingsboElement::periodic_response(const Eigen::MatrixXd& u, const Eigen::MatrixXd& /*v*/,
                                             bool tangent, PeriodicResponse& out) const {
  if (!u.allFinite()) {
    throw InvalidInput("element displacement samples hold a NaN or infinity");
  }
  const Eigen::Index n = u.rows();
  out.f.setZero(n, 1);
  out.history.clear();
  out.dv.resize(0, 0);
  if (tangent) {
    out.du.setZero(n, 1);
  } else {
    out.du.resize(0, 0);
  }
  if (n == 0) return;
  const Eigen::VectorXd x = u.col(0);
  const auto emit = [&](const Eigen::VectorXd& Q, const Eigen::MatrixXd& G) {
    out.f.col(0) = Q;
    if (!tangent) return;
    for (Eigen::Index i = 0; i < n; ++i) {
      out.du(i, 0) = G(i, i);
      for (Eigen::Index j = 0; j < n; ++j) {
        if (j != i && G(i, j) != 0.0) {
          out.history.push_back(
              {static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), 0, 0, G(i, j)});
        }
      }
    }
  };
  if (x.maxCoeff() == x.minCoeff()) {
    // No motion: the monotone push from rest to x_0 at every sample.
    Eigen::VectorXd f0;
    Eigen::MatrixXd K0;
    static_response(x.head(1), f0, K0);
    out.f.setConstant(f0(0));
    if (tangent) out.du.setConstant(K0(0, 0));
    return;
  }

  // Periods from the virgin state (at rest, u = 0): a period that no longer slips and
  // repeats the one before is the steady state (Masing's own when Q_ty is never reached).
  Path virgin(*elastic_, p_, tangent ? n : 0);
  Eigen::VectorXd Q_prev = Eigen::VectorXd::Constant(n, inf), Q(n), xe(n);
  Eigen::MatrixXd G(tangent ? n : 0, tangent ? n : 0);
  const double scale = std::max(elastic_->limit(), p_.fretting_yield_point);
  int periods_run = 0;
  const auto run_virgin = [&](int up_to) {
    for (; periods_run < up_to; ++periods_run) {
      for (Eigen::Index i = 0; i < n; ++i) {
        virgin.step(x(i), i);
        Q(i) = virgin.Q();
        xe(i) = virgin.xe();
        if (tangent) G.row(i) = virgin.g_Q().transpose();
      }
      const bool slipped = virgin.take_slipped();
      // Masing periods repeat to rounding (the same operations on the same branches).
      const bool repeats = (Q - Q_prev).cwiseAbs().maxCoeff() <= 1e-12 * scale;
      Q_prev = Q;
      if (periods_run > 0 && !slipped && repeats) {
        ++periods_run;
        return true;
      }
    }
    return false;
  };
  if (run_virgin(3)) {
    emit(Q, G);
    return;
  }

  // Shooting on Q_top (D rises with it) from the last virgin period's value.
  Eigen::Index top = 0;
  xe.maxCoeff(&top);
  double Q_guess = Q(top);
  for (int attempt = 0; attempt < 3; ++attempt) {
    const auto drift = [&](double Qt) { return shoot(x, top, Qt, false).drift; };
    double lo = Q_guess, hi = Q_guess;
    double D_lo = drift(lo), D_hi = D_lo;
    double step = 1e-3 * scale;
    while (D_lo > 0.0 || D_hi < 0.0) {
      if (step > 8.0 * scale) {
        throw NumericalError(fmt::format(
            "odfalk_vingsbo element: no steady loop found: the net plastic slip per period "
            "keeps its sign for Q_top within {:.6g} N of {:.6g} N (Q_ty = {:.6g} N, k_p = {:.6g} "
            "N/m)",
            8.0 * scale, Q_guess, p_.fretting_yield_point, p_.hardening_coefficient));
      }
      if (D_lo > 0.0) {
        hi = lo;
        D_hi = D_lo;
        lo = Q_guess - step;
        D_lo = drift(lo);
      } else {
        lo = hi;
        D_lo = D_hi;
        hi = Q_guess + step;
        D_hi = drift(hi);
      }
      step *= 2.0;
    }
    double Q_top = D_lo == 0.0 ? lo : D_hi == 0.0 ? hi : 0.0;
    if (D_lo != 0.0 && D_hi != 0.0) {
      Q_top = core::find_root(drift, lo, hi, "Odfalk-Vingsbo element: steady force at the top", 52);
    }
    Period P = shoot(x, top, Q_top, tangent);
    // A period without plastic slip lies in a range of Q_top where D = 0: the limit of the
    // slipping transient is the end of that range it approaches, where the force touches
    // +-Q_ty (found by bisection on whether the period slips).
    bool touching = false;
    if (!P.slipped) {
      const double D_guess = drift(Q_guess);
      if (D_guess == 0.0) {
        // The transient's level is itself a steady one: where the periods stop slipping.
        if (!run_virgin(200)) {
          throw NumericalError(
              "odfalk_vingsbo element: 200 periods from rest neither stopped slipping nor "
              "reached a balanced plastic flow");
        }
        emit(Q, G);
        return;
      }
      {
        double a = Q_top, b = Q_guess;  // a: no slip, b: slips
        for (int it = 0; it < 200 && a != b; ++it) {
          const double mid = 0.5 * (a + b);
          if (mid == a || mid == b) break;
          (shoot(x, top, mid, false).slipped ? b : a) = mid;
        }
        Q_top = a;
        P = shoot(x, top, Q_top, tangent);
        touching = true;
      }
    }
    // The top must be the period's largest elastic displacement, as assumed.
    Eigen::Index top_found = top;
    if (P.xe.maxCoeff(&top_found) > P.xe(top) + 1e-12 * (x.maxCoeff() - x.minCoeff())) {
      top = top_found;
      Q_guess = P.Q(top);
      continue;
    }
    if (tangent) {
      // dQ_top/dx from the condition that fixes it: D = 0, or the touching force = +-Q_ty.
      Eigen::RowVectorXd condition;
      if (touching) {
        Eigen::Index i_max = 0, i_min = 0;
        const double Q_max = P.Q.maxCoeff(&i_max), Q_min = P.Q.minCoeff(&i_min);
        const Eigen::Index i_touch =
            std::abs(Q_max - p_.fretting_yield_point) <= std::abs(Q_min + p_.fretting_yield_point)
                ? i_max
                : i_min;
        condition = P.G.row(i_touch);
      } else {
        condition = P.g_drift.transpose();
      }
      const double d_Qtop = condition(n);
      if (!(std::abs(d_Qtop) > 0.0)) {
        throw NumericalError(
            "odfalk_vingsbo element: the steady loop's force level does not depend on its "
            "condition (a period with no plastic slip and no reversal)");
      }
      const Eigen::RowVectorXd dQtop_dx = -condition.head(n) / d_Qtop;
      const Eigen::MatrixXd J = P.G.leftCols(n) + P.G.col(n) * dQtop_dx;
      emit(P.Q, J);
    } else {
      emit(P.Q, Eigen::MatrixXd());
    }
    return;
  }
  throw NumericalError(
      "odfalk_vingsbo element: the sample of the largest elastic displacement kept changing "
      "while solving for the steady loop");
}

void OdfalkVingsboElement::static_response(const Eigen::VectorXd& u, Eigen::VectorXd& f,
                                           Eigen::MatrixXd& K) const {
  core::require_finite("element displacement", u(0));
  f.resize(1);
  K.resize(1, 1);
  // The virgin curve: |u| = x_e + (Q_l(x_e) - Q_ty)^+ / (2 k_p), rising in x_e
  // (hysteresis::odfalk_vingsbo_cycle's relation).
  const double x = std::abs(u(0));
  const auto plastic_of = [&](double Q) {
    return std::max(0.0, Q - p_.fretting_yield_point) / (2.0 * p_.hardening_coefficient);
  };
  const auto g = [&](double xe) { return xe + plastic_of(elastic_->force(xe)) - x; };
  const double xe =
      x == 0.0 || g(x) <= 0.0 ? x : core::find_root(g, 0.0, x, "Odfalk-Vingsbo virgin curve", 52);
  const double Q = elastic_->force(xe);
  f(0) = std::copysign(Q, u(0));
  const double kt = elastic_->stiffness(xe);
  const double plastic = Q > p_.fretting_yield_point ? 0.5 / p_.hardening_coefficient : 0.0;
  K(0, 0) = kt / (1.0 + plastic * kt);
}

}  // namespace

std::shared_ptr<const Element> make_odfalk_vingsbo_element(
    std::shared_ptr<const hysteresis::Backbone> elastic_si,
    const hysteresis::OdfalkVingsboParameters& p, dynamics::SummaryObject parameters) {
  return std::make_shared<OdfalkVingsboElement>(std::move(elastic_si), p, std::move(parameters));
}

}  // namespace asperity::vibration
