#include "asperity/vibration/harmonic_balance.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include <fmt/format.h>
#include <kissfft/kissfft.hh>

#include "asperity/core/error.hpp"
#include "asperity/core/parallel.hpp"

namespace asperity::vibration {

void HarmonicBalanceOptions::validate() const {
  if (harmonics.empty()) {
    throw InvalidInput("harmonic_balance.harmonics is empty: give the harmonics to keep, with 1");
  }
  for (std::size_t k = 0; k < harmonics.size(); ++k) {
    if (harmonics[k] < 0 || harmonics[k] > 4096) {
      throw InvalidInput(
          fmt::format("harmonic_balance.harmonics[{}] = {}: harmonics are integers in [0, 4096]",
                      k + 1, harmonics[k]));
    }
    if (k > 0 && harmonics[k] <= harmonics[k - 1]) {
      throw InvalidInput(
          fmt::format("harmonic_balance.harmonics must be distinct and ascending: {} follows {}",
                      harmonics[k], harmonics[k - 1]));
    }
  }
  if (std::find(harmonics.begin(), harmonics.end(), 1) == harmonics.end()) {
    throw InvalidInput(
        "harmonic_balance.harmonics does not hold 1: the fundamental harmonic is needed (add 1)");
  }
  const std::size_t H = static_cast<std::size_t>(harmonics.back());
  if (time_points % 2 != 0 || time_points < 2 * H + 2 || time_points > (std::size_t{1} << 20)) {
    throw InvalidInput(fmt::format(
        "harmonic_balance.time_points = {}: it must be even, at least 2 H + 2 = {} for the highest "
        "harmonic H = {}, and at most 2^20 (a few times 2 H; 256 to 1024 is usual)",
        time_points, 2 * H + 2, H));
  }
}

struct HarmonicBasis::Fft {
  explicit Fft(std::size_t n) : half(n / 2, false) {}
  kissfft<double> half;  // a real transform of n points through n/2 complex ones (immutable)
};

namespace {
// Per-thread scratch, so that const evaluation is thread-safe.
std::vector<std::complex<double>>& spectrum_scratch(std::size_t n) {
  thread_local std::vector<std::complex<double>> buffer;
  if (buffer.size() < n) buffer.resize(n);
  return buffer;
}
}  // namespace

HarmonicBasis::HarmonicBasis(const HarmonicBalanceOptions& options) {
  options.validate();
  harmonics_ = options.harmonics;
  n_t_ = options.time_points;
  for (int h : harmonics_) {
    harm_.push_back(h);
    kind_.push_back(0);
    if (h > 0) {
      harm_.push_back(h);
      kind_.push_back(1);
    }
  }
  n_c_ = harm_.size();
  const auto N = static_cast<Eigen::Index>(n_t_);
  const auto nc = static_cast<Eigen::Index>(n_c_);
  E_.resize(N, nc);
  P_.resize(nc, N);
  D_ = Eigen::MatrixXd::Zero(nc, nc);
  for (Eigen::Index i = 0; i < N; ++i) {
    const double theta = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(N);
    for (Eigen::Index c = 0; c < nc; ++c) {
      const double ht = harm_[c] * theta;
      const double e = kind_[c] == 0 ? std::cos(ht) : std::sin(ht);
      E_(i, c) = e;
      P_(c, i) = (harm_[c] == 0 ? 1.0 : 2.0) * e / static_cast<double>(N);
    }
  }
  // d/dtheta: a cos(h t) -> -h a sin(h t); b sin(h t) -> h b cos(h t).
  for (Eigen::Index c = 0; c < nc; ++c) {
    if (harm_[c] == 0 || kind_[c] != 0) continue;
    const double h = harm_[c];
    D_(c + 1, c) = -h;
    D_(c, c + 1) = h;
  }
  fft_ = std::make_shared<const Fft>(n_t_);
  const int H2 = 2 * harmonics_.back();
  use_fft_ = static_cast<double>(H2 + 1) > 2.0 * std::log2(static_cast<double>(n_t_)) + 4.0;
  if (!use_fft_) {
    trig_.resize(N, 2 * (H2 + 1));
    for (Eigen::Index i = 0; i < N; ++i) {
      const double theta = 2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(N);
      for (int m = 0; m <= H2; ++m) {
        trig_(i, m) = std::cos(m * theta);
        trig_(i, H2 + 1 + m) = std::sin(m * theta);
      }
    }
  }
}

long HarmonicBasis::index_of(int h, int kind) const {
  for (std::size_t c = 0; c < n_c_; ++c) {
    if (harm_[c] == h && kind_[c] == kind) return static_cast<long>(c);
  }
  return -1;
}

namespace {

// X_m = sum_i s_i exp(-i m theta_i) for any m >= 0, from the half spectrum of a real
// transform (kissfft::transform_real layout: dst[0] = (X_0, X_{N/2})).
std::complex<double> spectrum_at(const std::vector<std::complex<double>>& dst, std::size_t N,
                                 std::size_t m) {
  m %= N;
  const std::size_t half = N / 2;
  if (m == 0) return {dst[0].real(), 0.0};
  if (m == half) return {dst[0].imag(), 0.0};
  if (m < half) return dst[m];
  return std::conj(dst[N - m]);
}

}  // namespace

void HarmonicBasis::project(const double* s, double* out) const {
  if (!use_fft_) {
    const Eigen::Map<const Eigen::VectorXd> sv(s, static_cast<Eigen::Index>(n_t_));
    Eigen::Map<Eigen::VectorXd>(out, static_cast<Eigen::Index>(n_c_)).noalias() = P_ * sv;
    return;
  }
  auto& buffer = spectrum_scratch(n_t_ / 2);
  fft_->half.transform_real(s, buffer.data());
  const double inv = 1.0 / static_cast<double>(n_t_);
  for (std::size_t c = 0; c < n_c_; ++c) {
    const auto X = spectrum_at(buffer, n_t_, static_cast<std::size_t>(harm_[c]));
    const double w = harm_[c] == 0 ? inv : 2.0 * inv;
    out[c] = kind_[c] == 0 ? w * X.real() : -w * X.imag();
  }
}

void HarmonicBasis::project_diagonal(const double* s, Eigen::Ref<Eigen::MatrixXd> out) const {
  const double inv = 1.0 / static_cast<double>(n_t_);
  const int H2 = 2 * harmonics_.back();
  // C_m = (1/N) sum s cos(m theta), S_m = (1/N) sum s sin(m theta), m = 0 .. 2H.
  thread_local std::vector<double> Cm, Sm;
  Cm.resize(static_cast<std::size_t>(H2) + 1);
  Sm.resize(static_cast<std::size_t>(H2) + 1);
  if (use_fft_) {
    auto& buffer = spectrum_scratch(n_t_ / 2);
    fft_->half.transform_real(s, buffer.data());
    for (int m = 0; m <= H2; ++m) {
      const auto X = spectrum_at(buffer, n_t_, static_cast<std::size_t>(m));
      Cm[static_cast<std::size_t>(m)] = inv * X.real();
      Sm[static_cast<std::size_t>(m)] = -inv * X.imag();
    }
  } else {
    const Eigen::Map<const Eigen::VectorXd> sv(s, static_cast<Eigen::Index>(n_t_));
    thread_local Eigen::VectorXd cs;
    cs.noalias() = trig_.transpose() * sv;
    for (int m = 0; m <= H2; ++m) {
      Cm[static_cast<std::size_t>(m)] = inv * cs(m);
      Sm[static_cast<std::size_t>(m)] = inv * cs(H2 + 1 + m);
    }
  }
  auto C = [&](int m) { return Cm[static_cast<std::size_t>(m < 0 ? -m : m)]; };
  auto S = [&](int m) {
    return m < 0 ? -Sm[static_cast<std::size_t>(-m)] : Sm[static_cast<std::size_t>(m)];
  };
  for (std::size_t r = 0; r < n_c_; ++r) {
    const int a = harm_[r];
    const double w = a == 0 ? 1.0 : 2.0;
    for (std::size_t c = 0; c < n_c_; ++c) {
      const int b = harm_[c];
      double v = 0.0;
      if (kind_[r] == 0 && kind_[c] == 0) {
        v = 0.5 * (C(a - b) + C(a + b));
      } else if (kind_[r] == 1 && kind_[c] == 1) {
        v = 0.5 * (C(a - b) - C(a + b));
      } else if (kind_[r] == 0) {  // cos a * sin b
        v = 0.5 * (S(a + b) - S(a - b));
      } else {  // sin a * cos b
        v = 0.5 * (S(a + b) + S(a - b));
      }
      out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = w * v;
    }
  }
}

// ---------------------------------------------------------------------------------------

HarmonicBalance::HarmonicBalance(Structure structure, std::vector<PlacedElement> elements,
                                 const HarmonicBalanceOptions& options)
    : s_(std::move(structure)), elements_(std::move(elements)), basis_(options) {
  s_.validate();
  const Eigen::Index n = s_.dofs();
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    PlacedElement& pe = elements_[e];
    if (pe.name.empty()) pe.name = fmt::format("element {}", e + 1);
    if (!pe.element) throw InvalidInput(fmt::format("{}: no element given", pe.name));
    const auto dirs = static_cast<Eigen::Index>(pe.element->directions());
    if (pe.T.rows() != dirs || pe.T.cols() != n) {
      throw InvalidInput(fmt::format(
          "{} ({}): T is {} x {} but must be {} x {} (one row per element direction, one column "
          "per structure DOF)",
          pe.name, pe.element->type(), pe.T.rows(), pe.T.cols(), dirs, n));
    }
    if (!pe.T.allFinite()) {
      throw InvalidInput(fmt::format("{}: T holds a NaN or infinity", pe.name));
    }
    if (pe.T.cwiseAbs().maxCoeff() == 0.0) {
      throw InvalidInput(fmt::format("{}: T is zero: the element acts on no DOF", pe.name));
    }
  }
  unknowns_ = n * static_cast<Eigen::Index>(basis_.coefficients());
}

namespace {

// kw K (x) I + cw C (x) D + mw M (x) D^2 (D^2 = diag(-h^2)), skipping zero blocks.
Eigen::MatrixXd kronecker_sum(const Structure& s, const Eigen::MatrixXd& C, const HarmonicBasis& b,
                              Eigen::Index unknowns, double kw, double cw, double mw) {
  const Eigen::Index n = s.dofs();
  const auto nc = static_cast<Eigen::Index>(b.coefficients());
  const Eigen::MatrixXd& D = b.derivative();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(unknowns, unknowns);
  for (Eigen::Index q = 0; q < n; ++q) {
    for (Eigen::Index p = 0; p < n; ++p) {
      const double k = kw * s.K(p, q), c = cw * C(p, q), m = mw * s.M(p, q);
      if (k == 0.0 && c == 0.0 && m == 0.0) continue;
      auto blk = A.block(p * nc, q * nc, nc, nc);
      for (Eigen::Index r = 0; r < nc; ++r) {
        const int h = b.harmonic_of(static_cast<std::size_t>(r));
        blk(r, r) += k - h * h * m;
      }
      if (c != 0.0) blk += c * D;
    }
  }
  return A;
}

}  // namespace

Eigen::MatrixXd HarmonicBalance::dynamic_stiffness(double omega,
                                                   const Eigen::MatrixXd& C_eff) const {
  return kronecker_sum(s_, C_eff, basis_, unknowns_, 1.0, omega, omega * omega);
}

Eigen::MatrixXd HarmonicBalance::dynamic_stiffness_derivative(double omega,
                                                              const Eigen::MatrixXd& C_eff) const {
  return kronecker_sum(s_, C_eff, basis_, unknowns_, 0.0, 1.0, 2.0 * omega);
}

namespace {
// Element evaluation goes parallel from this many elements and element-samples on.
constexpr std::size_t kParallelElements = 8;
constexpr std::size_t kParallelSamples = 8192;
}  // namespace

void HarmonicBalance::nonlinear_force(const Eigen::VectorXd& U, double omega, Eigen::VectorXd& F,
                                      Eigen::MatrixXd* dF_dU, Eigen::VectorXd* dF_domega) const {
  if (U.size() != unknowns_) {
    throw InvalidInput(
        fmt::format("harmonic balance: {} unknowns given, {} expected", U.size(), unknowns_));
  }
  const Eigen::Index n = dofs();
  const auto nc = static_cast<Eigen::Index>(basis_.coefficients());
  const auto N = static_cast<Eigen::Index>(basis_.time_points());
  const Eigen::MatrixXd& E = basis_.synthesis();
  const Eigen::MatrixXd& P = basis_.projection();
  const Eigen::MatrixXd& D = basis_.derivative();
  F.setZero(unknowns_);
  if (dF_dU) dF_dU->setZero(unknowns_, unknowns_);
  if (dF_domega) dF_domega->setZero(unknowns_);
  const bool tangent = dF_dU != nullptr || dF_domega != nullptr;
  ++counters_.residual_evaluations;
  if (dF_dU) ++counters_.jacobian_evaluations;
  const Eigen::Map<const Eigen::MatrixXd> X(U.data(), nc, n);  // coefficients x DOFs
  // One element's contribution: its force coefficients Fe (nc x dirs), d Fe / d omega and
  // its Jacobian Je ((nc dirs) x (nc dirs), index c + nc d), each only when asked for.
  struct Contribution {
    Eigen::MatrixXd Fe, Fw, Je;
  };
  const auto evaluate = [&](const PlacedElement& pe, PeriodicResponse& resp, Contribution& out) {
    const Element& el = *pe.element;
    const auto dirs = static_cast<Eigen::Index>(el.directions());
    const Eigen::MatrixXd Xe = X * pe.T.transpose();  // nc x dirs
    const Eigen::MatrixXd u = E * Xe;                 // N x dirs
    Eigen::MatrixXd v;
    if (el.velocity_dependent()) v = omega * (E * (D * Xe));
    el.periodic_response(u, v, tangent, resp);
    if (!resp.f.allFinite()) {
      throw NumericalError(
          fmt::format("{} ({}): a force sample is not finite", pe.name, el.type()));
    }
    out.Fe.resize(nc, dirs);
    for (Eigen::Index d = 0; d < dirs; ++d) {
      basis_.project(resp.f.col(d).data(), out.Fe.col(d).data());
    }
    out.Fw.resize(0, 0);
    if (dF_domega && el.velocity_dependent() && omega != 0.0) {
      // v = omega E D Xe: d f / d omega = (df/dv) v / omega.
      out.Fw.setZero(nc, dirs);
      Eigen::VectorXd sig(N), coef(nc);
      for (Eigen::Index d = 0; d < dirs; ++d) {
        sig.setZero();
        for (Eigen::Index e = 0; e < dirs; ++e) {
          sig += resp.dv.col(d + dirs * e).cwiseProduct(v.col(e)) / omega;
        }
        basis_.project(sig.data(), coef.data());
        out.Fw.col(d) = coef;
      }
    }
    if (!dF_dU) return;
    Eigen::MatrixXd& Je = out.Je;
    Je.setZero(nc * dirs, nc * dirs);
    Eigen::MatrixXd blk(nc, nc);
    for (Eigen::Index d = 0; d < dirs; ++d) {
      for (Eigen::Index e = 0; e < dirs; ++e) {
        const Eigen::Index col = d + dirs * e;
        if (resp.du.col(col).cwiseAbs().maxCoeff() > 0.0) {
          basis_.project_diagonal(resp.du.col(col).data(), blk);
          Je.block(nc * d, nc * e, nc, nc) += blk;
        }
        if (resp.dv.size() > 0 && resp.dv.col(col).cwiseAbs().maxCoeff() > 0.0) {
          basis_.project_diagonal(resp.dv.col(col).data(), blk);
          Je.block(nc * d, nc * e, nc, nc) += omega * blk * D;
        }
      }
    }
    if (!resp.history.empty()) {
      // Per touched column (j, e): W(:, d) = sum over terms (i, d, j, e) of value P(:, i);
      // then Je(d, e) += W(:, d) E(j, :). Hysteretic elements touch few columns (the
      // reversal and slip samples), so W is kept compact.
      const Eigen::Index cols = N * dirs;
      thread_local std::vector<int> slot;
      thread_local std::vector<Eigen::Index> touched;
      thread_local Eigen::MatrixXd W;
      slot.assign(static_cast<std::size_t>(cols), -1);
      touched.clear();
      if (W.rows() != nc * dirs) W.resize(nc * dirs, 16);
      for (const HistoryTerm& t : resp.history) {
        const Eigen::Index col = static_cast<Eigen::Index>(t.j) + N * t.d_src;
        int& k = slot[static_cast<std::size_t>(col)];
        if (k < 0) {
          k = static_cast<int>(touched.size());
          touched.push_back(col);
          if (W.cols() < static_cast<Eigen::Index>(touched.size())) {
            W.conservativeResize(nc * dirs, std::max<Eigen::Index>(16, 2 * W.cols()));
          }
          W.col(k).setZero();
        }
        double* w = W.col(k).data() + nc * t.d;
        const double* p = P.col(t.i).data();
        for (Eigen::Index c = 0; c < nc; ++c) w[c] += t.value * p[c];
      }
      for (std::size_t k = 0; k < touched.size(); ++k) {
        const Eigen::Index col = touched[k];
        const Eigen::Index j = col % N, e = col / N;
        Je.middleCols(nc * e, nc).noalias() += W.col(static_cast<Eigen::Index>(k)) * E.row(j);
      }
    }
  };
  const auto accumulate = [&](const PlacedElement& pe, const Contribution& c) {
    const auto dirs = static_cast<Eigen::Index>(pe.element->directions());
    Eigen::Map<Eigen::MatrixXd>(F.data(), nc, n) += c.Fe * pe.T;
    if (c.Fw.size() > 0) Eigen::Map<Eigen::MatrixXd>(dF_domega->data(), nc, n) += c.Fw * pe.T;
    if (!dF_dU) return;
    // Structure: dF/dX += (T^T (x) I) Je (T (x) I).
    for (Eigen::Index d = 0; d < dirs; ++d) {
      for (Eigen::Index p = 0; p < n; ++p) {
        const double tdp = pe.T(d, p);
        if (tdp == 0.0) continue;
        for (Eigen::Index e = 0; e < dirs; ++e) {
          for (Eigen::Index q = 0; q < n; ++q) {
            const double teq = pe.T(e, q);
            if (teq == 0.0) continue;
            dF_dU->block(p * nc, q * nc, nc, nc) += tdp * teq * c.Je.block(nc * d, nc * e, nc, nc);
          }
        }
      }
    }
  };

  // Many elements (a finite-element interface): evaluated in parallel over the elements
  // (core::parallel_for, ASPERITY_THREADS), then summed in element order, so that the
  // result does not depend on the thread count. Few or cheap ones stay on this thread,
  // where a team of threads would cost more than it saves.
  const std::size_t ne = elements_.size();
  if (ne >= kParallelElements && ne * static_cast<std::size_t>(N) >= kParallelSamples &&
      core::worker_count() > 1) {
    std::vector<Contribution> parts(ne);
    core::parallel_for(ne, [&](std::size_t k) {
      PeriodicResponse resp;
      evaluate(elements_[k], resp, parts[k]);
    });
    for (std::size_t k = 0; k < ne; ++k) accumulate(elements_[k], parts[k]);
    return;
  }
  // The elements' responses reuse this thread's storage from one evaluation to the next
  // (a dense history, 3-D dry friction on a curved slip path, holds 6 N_t^2 terms); a call
  // nested in an element's response (a Python element running its own harmonic balance)
  // takes fresh storage.
  thread_local PeriodicResponse reused;
  thread_local int depth = 0;
  PeriodicResponse fresh;
  PeriodicResponse& resp = depth == 0 ? reused : fresh;
  struct Depth {
    int& d;
    explicit Depth(int& x) : d(x) { ++d; }
    ~Depth() { --d; }
    Depth(const Depth&) = delete;
    Depth& operator=(const Depth&) = delete;
  } const guard(depth);
  Contribution c;
  for (const PlacedElement& pe : elements_) {
    evaluate(pe, resp, c);
    accumulate(pe, c);
  }
}

void HarmonicBalance::residual(const Eigen::VectorXd& U, double omega, const Eigen::VectorXd& F_ex,
                               Eigen::VectorXd& R, Eigen::MatrixXd* dR_dU,
                               Eigen::VectorXd* dR_domega) const {
  if (F_ex.size() != unknowns_) {
    throw InvalidInput(fmt::format("harmonic balance: excitation has {} coefficients, {} expected",
                                   F_ex.size(), unknowns_));
  }
  Eigen::VectorXd Fnl;
  nonlinear_force(U, omega, Fnl, dR_dU, dR_domega);
  const Eigen::MatrixXd A = dynamic_stiffness(omega, s_.C);
  R = A * U + Fnl - F_ex;
  if (dR_dU) *dR_dU += A;
  if (dR_domega) *dR_domega += dynamic_stiffness_derivative(omega, s_.C) * U;
}

Eigen::VectorXd HarmonicBalance::time_history(const Eigen::VectorXd& U, Eigen::Index dof,
                                              std::size_t samples) const {
  const auto nc = static_cast<Eigen::Index>(basis_.coefficients());
  const Eigen::VectorXd x = U.segment(dof * nc, nc);
  if (samples == 0) return basis_.synthesis() * x;
  Eigen::VectorXd out(static_cast<Eigen::Index>(samples));
  for (std::size_t i = 0; i < samples; ++i) {
    const double theta =
        2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(samples);
    double s = 0.0;
    for (Eigen::Index c = 0; c < nc; ++c) {
      const double ht = basis_.harmonic_of(static_cast<std::size_t>(c)) * theta;
      s += x(c) * (basis_.kind_of(static_cast<std::size_t>(c)) == 0 ? std::cos(ht) : std::sin(ht));
    }
    out(static_cast<Eigen::Index>(i)) = s;
  }
  return out;
}

double HarmonicBalance::harmonic_amplitude(const Eigen::VectorXd& U, Eigen::Index dof,
                                           int h) const {
  const auto nc = static_cast<Eigen::Index>(basis_.coefficients());
  const long ic = basis_.index_of(h, 0);
  if (ic < 0) return 0.0;
  const double a = U(dof * nc + ic);
  const long is = basis_.index_of(h, 1);
  const double b = is < 0 ? 0.0 : U(dof * nc + is);
  return std::hypot(a, b);
}

double HarmonicBalance::max_displacement(const Eigen::VectorXd& U, Eigen::Index dof) const {
  const std::size_t samples = std::max<std::size_t>(
      basis_.time_points(), 8 * static_cast<std::size_t>(basis_.max_harmonic()));
  return time_history(U, dof, samples).cwiseAbs().maxCoeff();
}

Eigen::MatrixXd HarmonicBalance::stuck_stiffness() const {
  Eigen::MatrixXd K = s_.K;
  for (const PlacedElement& pe : elements_) {
    K += pe.T.transpose() * pe.element->initial_stiffness() * pe.T;
  }
  return K;
}

}  // namespace asperity::vibration
