#include "asperity/vibration/stability.hpp"

// g++ 12 at -O3 reports writes into Eigen's dynamic matrices as potential null
// dereferences (a known false positive of -Wnull-dereference).
#pragma GCC diagnostic ignored "-Wnull-dereference"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <optional>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::vibration {

void HillOptions::validate() const {
  if (reported_exponents < 1 || reported_exponents > 1000) {
    throw InvalidInput(fmt::format(
        "stability.reported_exponents = {}: must be in [1, 1000] (the exponents of largest real "
        "part reported per point)",
        reported_exponents));
  }
  if (!(tolerance > 0.0) || !(tolerance <= 1e-2)) {
    throw InvalidInput(fmt::format(
        "stability.tolerance = {}: must be in (0, 1e-2] (max Re lambda / omega above which a "
        "solution is unstable)",
        core::format_value(tolerance)));
  }
}

namespace {

// Velocity tangent J_v = sum_e T_e^T (P diag(df/dv) E) T_e of the velocity-dependent
// elements, on the coefficients (the part of dF/dU that multiplies omega D).
Eigen::MatrixXd velocity_tangent(const HarmonicBalance& hb, const Eigen::VectorXd& U,
                                 double omega) {
  const Eigen::Index n = hb.dofs();
  const auto nc = static_cast<Eigen::Index>(hb.basis().coefficients());
  const Eigen::MatrixXd& E = hb.basis().synthesis();
  const Eigen::MatrixXd& D = hb.basis().derivative();
  Eigen::MatrixXd Jv = Eigen::MatrixXd::Zero(hb.unknowns(), hb.unknowns());
  const Eigen::Map<const Eigen::MatrixXd> X(U.data(), nc, n);
  PeriodicResponse resp;
  Eigen::MatrixXd blk(nc, nc);
  for (const PlacedElement& pe : hb.elements()) {
    const Element& el = *pe.element;
    if (!el.velocity_dependent()) continue;
    const auto dirs = static_cast<Eigen::Index>(el.directions());
    const Eigen::MatrixXd Xe = X * pe.T.transpose();
    const Eigen::MatrixXd u = E * Xe;
    const Eigen::MatrixXd v = omega * (E * (D * Xe));
    el.periodic_response(u, v, true, resp);
    for (Eigen::Index d = 0; d < dirs; ++d) {
      for (Eigen::Index e = 0; e < dirs; ++e) {
        const Eigen::Index col = d + dirs * e;
        if (resp.dv.size() == 0 || resp.dv.col(col).cwiseAbs().maxCoeff() == 0.0) continue;
        hb.basis().project_diagonal(resp.dv.col(col).data(), blk);
        for (Eigen::Index p = 0; p < n; ++p) {
          for (Eigen::Index q = 0; q < n; ++q) {
            const double w = pe.T(d, p) * pe.T(e, q);
            if (w != 0.0) Jv.block(p * nc, q * nc, nc, nc) += w * blk;
          }
        }
      }
    }
  }
  return Jv;
}

// Spectral centre sum_k k |p_k|^2 / sum_k |p_k|^2 of an eigenvector's periodic part in
// complex harmonics k = -H..H: a cos(h t) + b sin(h t) = (a - i b)/2 e^{i h t} + (a + i b)/2
// e^{-i h t}.
double spectral_centre(const HarmonicBasis& b, Eigen::Index dofs,
                       const Eigen::Ref<const Eigen::VectorXcd>& p) {
  const auto nc = static_cast<Eigen::Index>(b.coefficients());
  const std::complex<double> i(0.0, 1.0);
  double moment = 0.0, total = 0.0;
  for (Eigen::Index dof = 0; dof < dofs; ++dof) {
    for (Eigen::Index c = 0; c < nc; ++c) {
      const int h = b.harmonic_of(static_cast<std::size_t>(c));
      if (h == 0) {
        total += std::norm(p(dof * nc + c));
        continue;
      }
      if (b.kind_of(static_cast<std::size_t>(c)) != 0) continue;
      const std::complex<double> a = p(dof * nc + c), s = p(dof * nc + c + 1);
      const double wp = 0.25 * std::norm(a - i * s), wm = 0.25 * std::norm(a + i * s);
      moment += h * (wp - wm);
      total += wp + wm;
    }
  }
  return total > 0.0 ? moment / total : 0.0;
}

}  // namespace

PeriodicStability hill_stability(const HarmonicBalance& hb_in, const Eigen::VectorXd& U_in,
                                 double omega, const Eigen::MatrixXd& C_eff,
                                 const HillOptions& options) {
  options.validate();
  if (U_in.size() != hb_in.unknowns()) {
    throw InvalidInput(fmt::format("hill_stability: {} unknowns given, {} expected", U_in.size(),
                                   hb_in.unknowns()));
  }
  if (!(omega > 0.0) || !std::isfinite(omega)) {
    throw InvalidInput(fmt::format("hill_stability: omega = {} must be positive and finite",
                                   core::format_value(omega)));
  }
  const Eigen::Index n = hb_in.dofs();
  if (C_eff.rows() != n || C_eff.cols() != n) {
    throw InvalidInput(
        fmt::format("hill_stability: the damping matrix is {} x {}, {} x {} expected", C_eff.rows(),
                    C_eff.cols(), n, n));
  }
  // The perturbation on all harmonics 0..H.
  const int H = hb_in.basis().max_harmonic();
  std::vector<int> all(static_cast<std::size_t>(H) + 1);
  std::iota(all.begin(), all.end(), 0);
  std::optional<HarmonicBalance> full;
  Eigen::VectorXd U_full;
  if (hb_in.basis().harmonics() != all) {
    full.emplace(hb_in.structure(), hb_in.elements(),
                 HarmonicBalanceOptions{all, hb_in.basis().time_points()});
    U_full = Eigen::VectorXd::Zero(full->unknowns());
    const std::size_t nc_in = hb_in.basis().coefficients();
    for (Eigen::Index dof = 0; dof < n; ++dof) {
      for (std::size_t c = 0; c < nc_in; ++c) {
        const long j =
            full->basis().index_of(hb_in.basis().harmonic_of(c), hb_in.basis().kind_of(c));
        U_full(full->index(dof, static_cast<std::size_t>(j))) = U_in(hb_in.index(dof, c));
      }
    }
  }
  const HarmonicBalance& hb = full ? *full : hb_in;
  const Eigen::VectorXd& U = full ? U_full : U_in;
  const Eigen::Index N = hb.unknowns();
  const auto nc = static_cast<Eigen::Index>(hb.basis().coefficients());
  const Eigen::MatrixXd& M = hb.structure().M;
  const Eigen::MatrixXd& Dm = hb.basis().derivative();

  // Delta_0 = A(omega) + dF_nl/dU; Delta_1 = C (x) I + 2 omega M (x) D + J_v.
  Eigen::VectorXd F;
  Eigen::MatrixXd Delta0;
  hb.nonlinear_force(U, omega, F, &Delta0, nullptr);
  Delta0 += hb.dynamic_stiffness(omega, C_eff);
  Eigen::MatrixXd Delta1 = velocity_tangent(hb, U, omega);
  for (Eigen::Index p = 0; p < n; ++p) {
    for (Eigen::Index q = 0; q < n; ++q) {
      auto blk = Delta1.block(p * nc, q * nc, nc, nc);
      blk.diagonal().array() += C_eff(p, q);
      if (M(p, q) != 0.0) blk += 2.0 * omega * M(p, q) * Dm;
    }
  }
  // Companion form: lambda [p; lambda p] = [0 I; -Delta_2^-1 Delta_0, -Delta_2^-1 Delta_1],
  // Delta_2^-1 = M^-1 (x) I.
  const Eigen::MatrixXd Minv = M.llt().solve(Eigen::MatrixXd::Identity(n, n));
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * N, 2 * N);
  A.topRightCorner(N, N).setIdentity();
  for (Eigen::Index p = 0; p < n; ++p) {
    for (Eigen::Index q = 0; q < n; ++q) {
      const double m = Minv(p, q);
      if (m == 0.0) continue;
      A.block(N + p * nc, 0, nc, N) -= m * Delta0.middleRows(q * nc, nc);
      A.block(N + p * nc, N, nc, N) -= m * Delta1.middleRows(q * nc, nc);
    }
  }
  if (!A.allFinite()) {
    throw NumericalError(
        fmt::format("Hill stability at omega = {}: the linearised system holds a NaN or infinity",
                    core::format_value(omega)));
  }
  const Eigen::EigenSolver<Eigen::MatrixXd> es(A, true);
  if (es.info() != Eigen::Success) {
    throw NumericalError(fmt::format(
        "Hill stability at omega = {}: the QR algorithm did not converge on the {} x {} "
        "eigenvalue problem (try fewer harmonics)",
        core::format_value(omega), 2 * N, 2 * N));
  }
  const Eigen::VectorXcd& lambda = es.eigenvalues();
  // The 2 n exponents whose eigenvectors are centred nearest harmonic 0 (the symmetric-
  // eigenvector criterion; Bentvelsen & Lazarus, Nonlinear Dyn. (2018)); the copies
  // lambda + i k omega are shifted by -k harmonics and, near the truncation's edge,
  // spoilt. Ties (conjugates, real eigenvectors) by |Im lambda| (Lazarus & Thomas 2010).
  std::vector<double> centre(static_cast<std::size_t>(2 * N));
  for (Eigen::Index j = 0; j < 2 * N; ++j) {
    centre[static_cast<std::size_t>(j)] =
        std::abs(spectral_centre(hb.basis(), n, es.eigenvectors().col(j).head(N)));
  }
  std::vector<Eigen::Index> idx(static_cast<std::size_t>(2 * N));
  std::iota(idx.begin(), idx.end(), Eigen::Index{0});
  std::stable_sort(idx.begin(), idx.end(), [&](Eigen::Index a, Eigen::Index b) {
    const double ca = centre[static_cast<std::size_t>(a)], cb = centre[static_cast<std::size_t>(b)];
    if (std::abs(ca - cb) > 1e-6) return ca < cb;
    return std::abs(lambda(a).imag()) < std::abs(lambda(b).imag());
  });
  idx.resize(static_cast<std::size_t>(2 * n));
  std::sort(idx.begin(), idx.end(),
            [&](Eigen::Index a, Eigen::Index b) { return lambda(a).real() > lambda(b).real(); });

  PeriodicStability out;
  const Eigen::Index reported =
      std::min<Eigen::Index>(2 * n, static_cast<Eigen::Index>(options.reported_exponents));
  out.exponents.resize(reported);
  for (Eigen::Index k = 0; k < reported; ++k)
    out.exponents(k) = lambda(idx[static_cast<std::size_t>(k)]);
  const std::complex<double> lead = lambda(idx.front());
  out.max_real_exponent = lead.real();
  // |mu| above e^700 is reported as e^700 (a double's range).
  out.max_multiplier_modulus =
      std::exp(std::min(700.0, lead.real() * 2.0 * std::numbers::pi / omega));
  out.stable = lead.real() <= options.tolerance * omega;
  if (!out.stable) {
    // Im lambda of a real multiplier is 0 (mu > 0) or omega/2 (mu < 0), to round-off.
    const double im = std::abs(lead.imag());
    if (im <= 1e-6 * omega) {
      out.instability = "fold";
    } else if (std::abs(im - 0.5 * omega) <= 1e-6 * omega) {
      out.instability = "period_doubling";
    } else {
      out.instability = "neimark_sacker";
    }
  }
  out.smallest_exponent =
      lambda(*std::min_element(idx.begin(), idx.end(), [&](Eigen::Index a, Eigen::Index b) {
        return std::abs(lambda(a)) < std::abs(lambda(b));
      }));
  return out;
}

}  // namespace asperity::vibration
