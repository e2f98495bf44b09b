#include "asperity/vibration/structure.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "asperity/core/error.hpp"
#include "asperity/core/validate.hpp"

namespace asperity::vibration {

void RayleighDamping::validate() const {
  core::require_non_negative("rayleigh.alpha", alpha);
  core::require_non_negative("rayleigh.beta", beta);
}

namespace {

void require_finite_matrix(const char* name, const Eigen::MatrixXd& A) {
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    for (Eigen::Index i = 0; i < A.rows(); ++i) {
      if (!std::isfinite(A(i, j))) {
        throw InvalidInput(fmt::format(
            "{} matrix: entry ({}, {}) is {}: every entry must be finite", name, i, j, A(i, j)));
      }
    }
  }
}

void require_symmetric(const char* name, const Eigen::MatrixXd& A) {
  const double scale = A.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 0; j < A.cols(); ++j) {
    for (Eigen::Index i = j + 1; i < A.rows(); ++i) {
      if (std::abs(A(i, j) - A(j, i)) > 1e-10 * scale) {
        throw InvalidInput(fmt::format(
            "{} matrix is not symmetric: entry ({}, {}) = {} but ({}, {}) = {}; give a symmetric "
            "matrix",
            name, i, j, core::format_value(A(i, j)), j, i, core::format_value(A(j, i))));
      }
    }
  }
}

}  // namespace

void Structure::validate() {
  const Eigen::Index n = M.rows();
  if (n == 0 || M.cols() != n) {
    throw InvalidInput(
        fmt::format("mass matrix is {} x {}: it must be square and not empty", M.rows(), M.cols()));
  }
  if (K.rows() != n || K.cols() != n) {
    throw InvalidInput(fmt::format(
        "stiffness matrix is {} x {} but the mass matrix is {} x {}: give both for the same DOFs",
        K.rows(), K.cols(), n, n));
  }
  if (C.size() == 0) C = Eigen::MatrixXd::Zero(n, n);
  if (C.rows() != n || C.cols() != n) {
    throw InvalidInput(fmt::format(
        "damping matrix is {} x {} but the mass matrix is {} x {}: give both for the same DOFs",
        C.rows(), C.cols(), n, n));
  }
  require_finite_matrix("mass", M);
  require_finite_matrix("stiffness", K);
  require_finite_matrix("damping", C);
  require_symmetric("mass", M);
  require_symmetric("stiffness", K);
  const Eigen::LLT<Eigen::MatrixXd> llt(M);
  bool pd = llt.info() == Eigen::Success;
  if (pd) {
    // Cholesky succeeds on matrices that are singular to round-off: require a pivot ratio.
    const Eigen::VectorXd d = Eigen::MatrixXd(llt.matrixL()).diagonal();
    pd = d.minCoeff() > 1e-8 * d.maxCoeff();
  }
  if (!pd) {
    throw InvalidInput(
        "mass matrix is not positive definite (singular, or a DOF without mass): give every DOF "
        "a mass, or condense massless DOFs out of the model");
  }
}

Eigen::MatrixXd rayleigh(const Eigen::MatrixXd& M, const Eigen::MatrixXd& K,
                         const RayleighDamping& d) {
  d.validate();
  return d.alpha * M + d.beta * K;
}

Eigen::MatrixXd read_matrix_market(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    throw InvalidInput(fmt::format("{}: no such file (a MatrixMarket .mtx file)", path));
  }
  if (!fs::is_regular_file(status)) {
    throw InvalidInput(fmt::format("{}: not a regular file (a MatrixMarket .mtx file)", path));
  }
  constexpr std::uintmax_t kMaxBytes = std::uintmax_t{1} << 30;
  if (fs::file_size(path, ec) > kMaxBytes) {
    throw InvalidInput(fmt::format("{}: larger than 1 GiB, the limit for a matrix file", path));
  }
  std::ifstream in(path);
  if (!in) throw InvalidInput(fmt::format("{}: cannot be read", path));
  std::string line;
  std::size_t line_no = 0;
  auto fail = [&](const std::string& what) -> void {
    throw InvalidInput(fmt::format("{}:{}: {}", path, line_no, what));
  };
  if (!std::getline(in, line)) fail("empty file; expected a %%MatrixMarket header");
  ++line_no;
  std::string banner, object, format, field, symmetry;
  {
    std::istringstream h(line);
    h >> banner >> object >> format >> field >> symmetry;
    for (auto* s : {&object, &format, &field, &symmetry}) {
      std::transform(s->begin(), s->end(), s->begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    }
  }
  if (banner != "%%MatrixMarket" || object != "matrix") {
    fail("not a MatrixMarket matrix: the first line must be '%%MatrixMarket matrix ...'");
  }
  if (format != "coordinate" && format != "array") {
    fail(fmt::format("format '{}' is not supported: coordinate or array", format));
  }
  if (field != "real" && field != "integer" && field != "double") {
    fail(fmt::format("field '{}' is not supported: real or integer", field));
  }
  if (symmetry != "general" && symmetry != "symmetric") {
    fail(fmt::format("symmetry '{}' is not supported: general or symmetric", symmetry));
  }
  const bool symmetric = symmetry == "symmetric";
  auto next_data_line = [&]() -> bool {
    while (std::getline(in, line)) {
      ++line_no;
      const auto p = line.find_first_not_of(" \t\r");
      if (p == std::string::npos || line[p] == '%') continue;
      return true;
    }
    return false;
  };
  if (!next_data_line()) fail("no size line");
  long long rows = 0, cols = 0, entries = 0;
  {
    std::istringstream s(line);
    s >> rows >> cols;
    if (format == "coordinate") s >> entries;
    if (!s || rows <= 0 || cols <= 0 || entries < 0) {
      fail(fmt::format("bad size line '{}': expected rows cols{}", line,
                       format == "coordinate" ? " entries" : ""));
    }
  }
  if (rows * cols > (1LL << 31) || rows > (1LL << 20) || cols > (1LL << 20)) {
    fail(fmt::format("{} x {} is too large (at most 2^31 entries for a dense structure)", rows,
                     cols));
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(rows, cols);
  auto parse_value = [&](std::istringstream& s) {
    double v = 0.0;
    if (!(s >> v) || !std::isfinite(v)) fail(fmt::format("bad value in '{}'", line));
    return v;
  };
  if (format == "coordinate") {
    for (long long k = 0; k < entries; ++k) {
      if (!next_data_line()) fail(fmt::format("{} entries announced, {} found", entries, k));
      std::istringstream s(line);
      long long i = 0, j = 0;
      if (!(s >> i >> j)) fail(fmt::format("bad entry '{}': expected row col value", line));
      if (i < 1 || i > rows || j < 1 || j > cols) {
        fail(fmt::format("entry ({}, {}) outside the {} x {} matrix (indices are 1-based)", i, j,
                         rows, cols));
      }
      const double v = parse_value(s);
      A(i - 1, j - 1) += v;
      if (symmetric && i != j) A(j - 1, i - 1) += v;
    }
  } else {
    // Column-major; symmetric arrays list the lower triangle only.
    for (long long j = 0; j < cols; ++j) {
      for (long long i = symmetric ? j : 0; i < rows; ++i) {
        if (!next_data_line()) fail("fewer values than the size line announces");
        std::istringstream s(line);
        const double v = parse_value(s);
        A(i, j) = v;
        if (symmetric) A(j, i) = v;
      }
    }
  }
  if (next_data_line()) fail("more data than the size line announces");
  return A;
}

LinearModes linear_modes(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
  if (es.info() != Eigen::Success) {
    throw NumericalError(
        "linear modes: the generalized eigenvalue problem (K, M) did not converge");
  }
  LinearModes out;
  const Eigen::VectorXd lambda = es.eigenvalues();
  out.omega.resize(lambda.size());
  out.shapes = es.eigenvectors();
  out.eigenvalues = lambda;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    out.omega(i) = std::sqrt(std::max(lambda(i), 0.0));
    Eigen::VectorXd phi = out.shapes.col(i);
    phi /= std::sqrt(phi.dot(M * phi));
    Eigen::Index imax = 0;
    phi.cwiseAbs().maxCoeff(&imax);
    if (phi(imax) < 0.0) phi = -phi;
    out.shapes.col(i) = phi;
  }
  return out;
}

}  // namespace asperity::vibration
