// Stiffness at the reversals of fretting loops (section 6.3): the pooled fit of every
// branch after a reversal (AnalysisOptions), for analyze_fretting.
#include "fretting_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/QR>

namespace asperity::joint::detail {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using QR = Eigen::ColPivHouseholderQR<MatrixXd>;

// The fit window of a reversal: samples r.. while |Qs - Qs[r]| <= span (not past end).
struct Window {
  std::vector<double> u, v;  // u = s (x - x0[r]) scaled, v = s y
};

bool full_rank(const QR& qr) {
  return qr.rank() == qr.cols();
}

// (A'A)^-1 = P R^-1 R^-T P' from A P = Q R (full column rank).
MatrixXd inverse_gram(const QR& qr) {
  const Index n = qr.cols();
  const MatrixXd Rinv = qr.matrixR().topLeftCorner(n, n).triangularView<Eigen::Upper>().solve(
      MatrixXd::Identity(n, n));
  const MatrixXd PRinv = qr.colsPermutation() * Rinv;
  return PRinv * PRinv.transpose();
}

// Shape columns u^2 .. u^(q+1) of the pooled fit.
MatrixXd shape_design(const VectorXd& u, std::size_t q) {
  MatrixXd S(u.size(), static_cast<Index>(q));
  for (std::size_t j = 0; j < q; ++j) S.col(static_cast<Index>(j)) = u.array().pow(double(j + 2));
  return S;
}

// A cycle's samples and its local design: one indicator per reversal and u.
struct Cycle {
  VectorXd u, v;
  MatrixXd L, S;
  QR qr;
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
  const auto as_vector = [](const std::vector<double>& a) {
    return Eigen::Map<const VectorXd>(a.data(), static_cast<Index>(a.size()));
  };
  // Per cycle: the shape columns and v with the local parameters projected out
  // (Frisch-Waugh: residuals of the least squares on L), stacked over the cycles.
  std::vector<Cycle> cyc(ncycles);
  std::vector<std::size_t> fitted;
  Index nrows = 0;
  for (std::size_t c = 0; c < ncycles; ++c) {
    const auto& ks = of_cycle[c];
    if (ks.size() != 2) continue;
    auto& C = cyc[c];
    const Index n0 = static_cast<Index>(win[ks[0]].u.size());
    const Index n = n0 + static_cast<Index>(win[ks[1]].u.size());
    C.u.resize(n);
    C.v.resize(n);
    C.u << as_vector(win[ks[0]].u), as_vector(win[ks[1]].u);
    C.v << as_vector(win[ks[0]].v), as_vector(win[ks[1]].v);
    C.L = MatrixXd::Zero(n, 3);
    C.L.col(0).head(n0).setOnes();
    C.L.col(1).tail(n - n0).setOnes();
    C.L.col(2) = C.u;
    C.S = shape_design(C.u, q);
    C.qr.compute(C.L);
    if (!full_rank(C.qr)) continue;
    fitted.push_back(c);
    nrows += n;
  }
  const Index qi = static_cast<Index>(q);
  VectorXd shape = VectorXd::Zero(qi);
  QR shape_qr;
  if (q > 0) {
    MatrixXd St(nrows, qi);
    VectorXd vt(nrows);
    Index row = 0;
    for (std::size_t c : fitted) {
      const auto& C = cyc[c];
      const Index n = C.u.size();
      St.middleRows(row, n) = C.S - C.L * C.qr.solve(C.S);
      vt.segment(row, n) = C.v - C.L * C.qr.solve(C.v);
      row += n;
    }
    shape_qr.compute(St);
    if (nrows < qi || !full_rank(shape_qr)) return out;
    shape = shape_qr.solve(vt);
    if (!shape.allFinite()) return out;
  }
  // Per cycle: (intercepts, slope) from v - shape; the residual variance for the
  // covariance of the slope.
  double rss = 0.0;
  std::size_t nobs = 0, npar = q;
  for (std::size_t c : fitted) {
    const auto& C = cyc[c];
    const VectorXd v_less_shape = C.v - C.S * shape;
    const VectorXd theta = C.qr.solve(v_less_shape);
    out.cycle_slope[c] = theta(2) / U;
    out.cycle_slope_var[c] = inverse_gram(C.qr)(2, 2) / (U * U);
    npar += 3;
    rss += (v_less_shape - C.L * theta).squaredNorm();
    nobs += static_cast<std::size_t>(C.u.size());
  }
  const double s2 = nobs > npar ? rss / static_cast<double>(nobs - npar) : nan;
  for (double& v : out.cycle_slope_var) v *= s2;
  // b_i = theta_i(v) - g_i' c with g_i = [(L'L)^-1 L'S]_slope; Cov(c) = s2 M^-1,
  // M = S~'S~ the pooled residual cross products.
  if (q > 0 && !fitted.empty()) {
    VectorXd g = VectorXd::Zero(qi);
    for (std::size_t c : fitted) g += cyc[c].qr.solve(cyc[c].S).row(2).transpose();
    g /= static_cast<double>(fitted.size());
    out.shape_variance_of_mean = s2 * g.dot(inverse_gram(shape_qr) * g) / (U * U);
  }
  // Per reversal: intercept and slope of v - shape on its own samples.
  for (std::size_t k = 0; k < revs.size(); ++k) {
    const auto& w = win[k];
    if (w.u.size() < min_samples) continue;
    const VectorXd u = as_vector(w.u);
    MatrixXd A(u.size(), 2);
    A.col(0).setOnes();
    A.col(1) = u;
    const QR qr(A);
    if (!full_rank(qr)) continue;
    const VectorXd v_less_shape = as_vector(w.v) - shape_design(u, q) * shape;
    out.reversal_slope[k] = qr.solve(v_less_shape)(1) / U;
  }
  return out;
}

}  // namespace asperity::joint::detail
