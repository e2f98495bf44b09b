// Sparse shift-invert modes and Dirichlet DOF elimination (modes.hpp).
#include "asperity/fem/modes.hpp"

#include <fmt/format.h>

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::fem {

namespace {

// y = (K - sigma M)^-1 x for Spectra's shift-invert mode; the factorization is made by
// set_shift().
class ShiftInvertOperator {
 public:
  using Scalar = double;

  ShiftInvertOperator(const SparseMatrix& K, const SparseMatrix& M, SparseFactorization choice)
      : K_(K), M_(M), choice_(choice) {}

  [[nodiscard]] Eigen::Index rows() const { return K_.rows(); }
  [[nodiscard]] Eigen::Index cols() const { return K_.cols(); }

  void set_shift(double sigma) {
    SparseMatrix A = K_ - sigma * M_;
    A.makeCompressed();
    std::string tried;
    if (choice_ == SparseFactorization::simplicial_ldlt) {
      ldlt_ = std::make_unique<Eigen::SimplicialLDLT<SparseMatrix>>();
      ldlt_->compute(A);
      if (ldlt_->info() == Eigen::Success && ldlt_->vectorD().array().isFinite().all() &&
          (ldlt_->vectorD().array() != 0.0).all()) {
        // LDLT without pivoting is backward stable for a positive definite A (a shift
        // below every eigenvalue); for an indefinite one it may not be: the normwise
        // backward error |A x - b| / (|A|_F |x| + |b|) of one solve of a test vector
        // checks it.
        const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), 1.0, 2.0);
        const Eigen::VectorXd x = ldlt_->solve(b);
        if (x.allFinite() && (A * x - b).norm() <= 1e-10 * (A.norm() * x.norm() + b.norm())) {
          name_ = "SimplicialLDLT";
          return;
        }
      }
      ldlt_.reset();
      tried = "SimplicialLDLT failed, then ";
    }
    lu_ = std::make_unique<Eigen::SparseLU<SparseMatrix>>();
    lu_->analyzePattern(A);
    lu_->factorize(A);
    if (lu_->info() != Eigen::Success) {
      throw NumericalError(fmt::format(
          "K - shift M (shift {} rad^2/s^2, {} DOFs) could not be factorized: {}SparseLU "
          "reported \"{}\" (a shift equal to an eigenvalue, or a structure with "
          "unconstrained rigid-body motion and shift 0?)",
          core::format_value(sigma), K_.rows(), tried, lu_->lastErrorMessage()));
    }
    name_ = "SparseLU";
  }

  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Map<const Eigen::VectorXd> x(x_in, K_.rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, K_.rows());
    if (ldlt_) {
      y = ldlt_->solve(x);
    } else {
      y = lu_->solve(x);
    }
  }

  [[nodiscard]] const std::string& name() const { return name_; }

 private:
  const SparseMatrix& K_;
  const SparseMatrix& M_;
  SparseFactorization choice_;
  std::unique_ptr<Eigen::SimplicialLDLT<SparseMatrix>> ldlt_;
  std::unique_ptr<Eigen::SparseLU<SparseMatrix>> lu_;
  std::string name_;
};

}  // namespace

SparseModes sparse_modes(const SparseMatrix& K, const SparseMatrix& M, int count, double shift,
                         SparseFactorization factorization) {
  const Eigen::Index n = K.rows();
  if (K.cols() != n || M.rows() != n || M.cols() != n) {
    throw InvalidInput(
        fmt::format("K is {} x {} and M is {} x {}: both must be square and of the "
                    "same size",
                    K.rows(), K.cols(), M.rows(), M.cols()));
  }
  if (count < 1 || count >= n) {
    throw InvalidInput(
        fmt::format("count = {} modes is not allowed: it must be from 1 to {} "
                    "(fewer than the {} DOFs)",
                    count, n - 1, n));
  }
  core::require_finite("shift", shift);
  ShiftInvertOperator op(K, M, factorization);
  using MassProduct = Spectra::SparseSymMatProd<double>;
  MassProduct mass(M);
  const auto nev = static_cast<Eigen::Index>(count);
  // Lanczos basis sizes tried in turn (ARPACK's advice: ncv >= 2 nev).
  std::vector<Eigen::Index> bases = {std::max<Eigen::Index>(2 * nev + 1, 20),
                                     std::max<Eigen::Index>(4 * nev + 1, 60)};
  std::string tried;
  for (auto ncv : bases) {
    ncv = std::min(ncv, n);
    if (ncv <= nev) continue;
    Spectra::SymGEigsShiftSolver<ShiftInvertOperator, MassProduct, Spectra::GEigsMode::ShiftInvert>
        solver(op, mass, nev, ncv, shift);
    solver.init();
    const Eigen::Index max_iterations = 1000;
    const double tolerance = 1e-12;
    solver.compute(Spectra::SortRule::LargestMagn, max_iterations, tolerance,
                   Spectra::SortRule::SmallestAlge);
    if (solver.info() == Spectra::CompInfo::Successful) {
      SparseModes modes;
      modes.omega2 = solver.eigenvalues();
      Eigen::MatrixXd shapes = solver.eigenvectors();
      std::vector<Eigen::Index> order(static_cast<std::size_t>(modes.omega2.size()));
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(),
                [&](Eigen::Index a, Eigen::Index b) { return modes.omega2[a] < modes.omega2[b]; });
      SparseModes sorted;
      sorted.factorization = op.name();
      sorted.omega2.resize(modes.omega2.size());
      sorted.shapes.resize(n, modes.omega2.size());
      for (std::size_t k = 0; k < order.size(); ++k) {
        const auto kk = static_cast<Eigen::Index>(k);
        Eigen::VectorXd phi = shapes.col(order[k]);
        const double norm2 = phi.dot(M * phi);
        phi /= std::sqrt(norm2);
        Eigen::Index largest = 0;
        phi.cwiseAbs().maxCoeff(&largest);
        if (phi[largest] < 0) phi = -phi;
        sorted.omega2[kk] = modes.omega2[order[k]];
        sorted.shapes.col(kk) = phi;
      }
      return sorted;
    }
    tried +=
        fmt::format("{}Lanczos basis {} with {} restarts at tolerance {:g} ({})",
                    tried.empty() ? "" : "; ", ncv, max_iterations, tolerance,
                    solver.info() == Spectra::CompInfo::NotConverging ? "not converged" : "failed");
  }
  throw NumericalError(fmt::format(
      "the {} eigenpairs of (K, M) ({} DOFs) above shift {} rad^2/s^2 were not found by Spectra's "
      "shift-invert Lanczos ({} factorization): tried {}",
      count, n, core::format_value(shift), op.name(), tried));
}

std::vector<std::int32_t> node_dofs(std::span<const std::int32_t> nodes) {
  std::vector<std::int32_t> dofs;
  dofs.reserve(3 * nodes.size());
  for (const auto node : nodes) {
    for (std::int32_t c = 0; c < 3; ++c) dofs.push_back(3 * node + c);
  }
  std::sort(dofs.begin(), dofs.end());
  dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
  return dofs;
}

std::vector<std::int32_t> complement_dofs(Eigen::Index size,
                                          std::span<const std::int32_t> removed) {
  std::vector<char> out(static_cast<std::size_t>(size), 0);
  for (const auto dof : removed) {
    if (dof < 0 || dof >= size) {
      throw InvalidInput(fmt::format("DOF {} is out of range: the matrix has {} DOFs", dof, size));
    }
    out[static_cast<std::size_t>(dof)] = 1;
  }
  std::vector<std::int32_t> kept;
  for (Eigen::Index i = 0; i < size; ++i) {
    if (!out[static_cast<std::size_t>(i)]) kept.push_back(static_cast<std::int32_t>(i));
  }
  return kept;
}

SparseMatrix restrict_dofs(const SparseMatrix& A, std::span<const std::int32_t> kept) {
  std::vector<int> position(static_cast<std::size_t>(A.rows()), -1);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const auto dof = kept[k];
    if (dof < 0 || dof >= A.rows() || (k > 0 && dof <= kept[k - 1])) {
      throw InvalidInput(fmt::format(
          "kept DOF {} (entry {}) is not allowed: DOFs must be ascending, unique and below {}", dof,
          k, A.rows()));
    }
    position[static_cast<std::size_t>(dof)] = static_cast<int>(k);
  }
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(A.nonZeros()));
  for (const auto col : kept) {
    for (SparseMatrix::InnerIterator it(A, col); it; ++it) {
      const int row = position[static_cast<std::size_t>(it.row())];
      if (row >= 0) {
        entries.emplace_back(row, position[static_cast<std::size_t>(col)], it.value());
      }
    }
  }
  const auto m = static_cast<Eigen::Index>(kept.size());
  SparseMatrix out(m, m);
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

SparseMatrix eliminate_dofs(const SparseMatrix& A, std::span<const std::int32_t> clamped) {
  const auto kept = complement_dofs(A.rows(), clamped);
  return restrict_dofs(A, kept);
}

Eigen::MatrixXd expand_dofs(const Eigen::MatrixXd& reduced, std::span<const std::int32_t> kept,
                            Eigen::Index size) {
  if (reduced.rows() != static_cast<Eigen::Index>(kept.size())) {
    throw InvalidInput(fmt::format("{} rows given for {} kept DOFs", reduced.rows(), kept.size()));
  }
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(size, reduced.cols());
  for (std::size_t k = 0; k < kept.size(); ++k) {
    if (kept[k] < 0 || kept[k] >= size) {
      throw InvalidInput(fmt::format("kept DOF {} is out of range: size {}", kept[k], size));
    }
    full.row(kept[k]) = reduced.row(static_cast<Eigen::Index>(k));
  }
  return full;
}

}  // namespace asperity::fem
