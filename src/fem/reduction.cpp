#include "asperity/fem/reduction.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <ctime>

#include <fmt/format.h>
#include <Eigen/SparseCholesky>

#include "asperity/core/error.hpp"
#include "asperity/core/parallel.hpp"

namespace asperity::fem {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

// The tied structure's flexibility on a statically determinate support: u = F_c f with
// K~ u + C^T lambda = f, C u = 0, u_held = 0 (K~ = K + the stabilisation, equal to K on
// C u = 0). With z = K~_ff^-1 f and the constraint modes Psi0 = X S^-1 (X = K~_ff^-1 C^T,
// S = C X): lambda = S^-1 C z, u = z - Psi0 (C z).
class TiedFlexibility {
 public:
  TiedFlexibility(const Eigen::SimplicialLDLT<Sparse>& ldlt,
                  const std::vector<Eigen::Index>& f_index, Eigen::Index nf, const Sparse& C,
                  Eigen::Ref<const Eigen::MatrixXd> Psi0)
      : ldlt_(ldlt), f_index_(f_index), nf_(nf), C_(C), Psi0_(Psi0) {}
  [[nodiscard]] Eigen::VectorXd apply(const Eigen::VectorXd& f) const {
    const Eigen::Index n = f.size();
    Eigen::VectorXd ff(nf_);
    for (Eigen::Index i = 0; i < n; ++i)
      if (const auto fi = f_index_[static_cast<std::size_t>(i)]; fi >= 0) ff[fi] = f[i];
    const Eigen::VectorXd zf = ldlt_.solve(ff);
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = 0; i < n; ++i)
      if (const auto fi = f_index_[static_cast<std::size_t>(i)]; fi >= 0) z[i] = zf[fi];
    const Eigen::VectorXd Cz = C_ * z;
    z.noalias() -= Psi0_ * Cz;
    return z;
  }

 private:
  const Eigen::SimplicialLDLT<Sparse>& ldlt_;
  const std::vector<Eigen::Index>& f_index_;
  Eigen::Index nf_;
  const Sparse& C_;
  Eigen::Ref<const Eigen::MatrixXd> Psi0_;  // a view of the basis's first columns
};

// The flexibility of the free-free tied structure with inertia relief (Spectra operator,
// shift 0): y = P F_c P^T x. P^T x removes the load's rigid-body resultant
// (x - M R G R^T x), P makes the displacement M-orthogonal to the rigid-body modes R
// (y - R G (M R)^T y), G = (R^T M R)^-1.
class InertiaReliefFlexibility {
 public:
  using Scalar = double;
  InertiaReliefFlexibility(const TiedFlexibility& tied, const Eigen::MatrixXd& R,
                           const Eigen::MatrixXd& MR, const Eigen::MatrixXd& G)
      : tied_(tied), R_(R), MR_(MR), G_(G) {}
  [[nodiscard]] Eigen::Index rows() const { return R_.rows(); }
  [[nodiscard]] Eigen::Index cols() const { return R_.rows(); }
  void set_shift(double) {}
  void perform_op(const double* x, double* y) const {
    const Eigen::Index n = R_.rows();
    Eigen::Map<const Eigen::VectorXd> xv(x, n);
    Eigen::Map<Eigen::VectorXd> yv(y, n);
    const Eigen::VectorXd z = tied_.apply(xv - MR_ * (G_ * (R_.transpose() * xv)));
    yv = z - R_ * (G_ * (MR_.transpose() * z));
  }

 private:
  const TiedFlexibility& tied_;
  const Eigen::MatrixXd& R_;
  const Eigen::MatrixXd& MR_;
  const Eigen::MatrixXd& G_;
};

struct LowestModes {
  Eigen::VectorXd omega2;
  Eigen::MatrixXd shapes;
};

// Right-hand sides solved together: one pass over the factor serves them all.
constexpr Eigen::Index kSolveBlock = 32;
using SolveBlock = Eigen::Matrix<double, Eigen::Dynamic, kSolveBlock, Eigen::RowMajor>;

// K^-1 Y in place for a block of right-hand sides (rows of Y), with the factors of
// P K P^T = L D L^T. The triangular solves are bound by reading L, so a block of
// kSolveBlock columns costs about one column's read of L; the rows of Y stay contiguous.
void solve_in_place(const Eigen::SimplicialLDLT<Sparse>& ldlt, SolveBlock& Y) {
  const Sparse& L = ldlt.matrixL().nestedExpression();  // strictly lower, column-major
  const Eigen::VectorXd& D = ldlt.vectorD();
  const Eigen::Index n = L.rows();
  const auto* outer = L.outerIndexPtr();
  const auto* inner = L.innerIndexPtr();
  const double* value = L.valuePtr();
  SolveBlock Z = ldlt.permutationP() * Y;
  double* z = Z.data();
  for (Eigen::Index j = 0; j < n; ++j) {
    const double* zj = z + j * kSolveBlock;
    for (auto p = outer[j]; p < outer[j + 1]; ++p) {
      double* zi = z + Eigen::Index{inner[p]} * kSolveBlock;
      const double l = value[p];
      for (Eigen::Index k = 0; k < kSolveBlock; ++k) zi[k] -= l * zj[k];
    }
  }
  for (Eigen::Index j = 0; j < n; ++j) Z.row(j) /= D[j];
  for (Eigen::Index j = n - 1; j >= 0; --j) {
    double* zj = z + j * kSolveBlock;
    for (auto p = outer[j]; p < outer[j + 1]; ++p) {
      const double* zi = z + Eigen::Index{inner[p]} * kSolveBlock;
      const double l = value[p];
      for (Eigen::Index k = 0; k < kSolveBlock; ++k) zj[k] -= l * zi[k];
    }
  }
  Y = ldlt.permutationPinv() * Z;
}

// Wall and processor (all threads) seconds since the last call.
class PhaseClock {
 public:
  ReductionPhase lap(const char* name) {
    const auto now = std::chrono::steady_clock::now();
    const std::clock_t cpu = std::clock();
    ReductionPhase p{name, std::chrono::duration<double>(now - wall_).count(),
                     static_cast<double>(cpu - cpu_) / CLOCKS_PER_SEC};
    wall_ = now;
    cpu_ = cpu;
    return p;
  }

 private:
  std::chrono::steady_clock::time_point wall_ = std::chrono::steady_clock::now();
  std::clock_t cpu_ = std::clock();
};

// Three spread-out points among point(i), i < count, with ok(i): the one of smallest x,
// the farthest from it, the farthest from the line through both (first: -1 when none is ok).
template <class Point, class Ok>
std::array<Eigen::Index, 3> spread_points(Eigen::Index count, Point point, Ok ok) {
  Eigen::Index a = -1;
  for (Eigen::Index i = 0; i < count; ++i)
    if (ok(i) && (a < 0 || point(i).x() < point(a).x())) a = i;
  if (a < 0) return {-1, -1, -1};
  Eigen::Index b = a;
  for (Eigen::Index i = 0; i < count; ++i)
    if (ok(i) && (point(i) - point(a)).norm() > (point(b) - point(a)).norm()) b = i;
  const Eigen::Vector3d ab = point(b) - point(a);
  Eigen::Index c = a;
  for (Eigen::Index i = 0; i < count; ++i)
    if (ok(i) && ab.cross(point(i) - point(a)).norm() > ab.cross(point(c) - point(a)).norm()) c = i;
  return {a, b, c};
}

}  // namespace

void ReductionOptions::validate() const {
  if (fixed_interface_modes < 0 || fixed_interface_modes > 2000)
    throw InvalidInput(
        fmt::format("reduction: `fixed_interface_modes` = {} is not allowed; give 0 to 2000",
                    fixed_interface_modes));
}

Eigen::MatrixXd rigid_body_modes(const Eigen::Matrix3Xd& nodes) {
  const Eigen::Index n = nodes.cols();
  const Eigen::Vector3d c = nodes.rowwise().mean();
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(3 * n, 6);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d r = nodes.col(i) - c;
    for (int k = 0; k < 3; ++k) R(3 * i + k, k) = 1.0;
    // rotation about x, y, z: e_k x r
    R(3 * i + 1, 3) = -r.z(), R(3 * i + 2, 3) = r.y();
    R(3 * i + 0, 4) = r.z(), R(3 * i + 2, 4) = -r.x();
    R(3 * i + 0, 5) = -r.y(), R(3 * i + 1, 5) = r.x();
  }
  return R;
}

Eigen::RowVectorXd CraigBampton::reduce_row(const Eigen::SparseVector<double>& row) const {
  Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(basis.cols());
  for (Eigen::SparseVector<double>::InnerIterator it(row); it; ++it)
    r += it.value() * basis.row(it.index());
  return r;
}

CraigBampton craig_bampton(const Sparse& K, const Sparse& M, const Eigen::Matrix3Xd& nodes,
                           const std::vector<Interface>& interfaces,
                           const ReductionOptions& options,
                           const std::vector<Eigen::VectorXd>& static_loads) {
  options.validate();
  PhaseClock clock;
  const Eigen::Index n = K.rows();
  const auto ns = static_cast<Eigen::Index>(static_loads.size());
  for (Eigen::Index s = 0; s < ns; ++s)
    if (static_loads[static_cast<std::size_t>(s)].size() != n)
      throw InvalidInput(fmt::format("reduction: static load {} has {} entries for {} DOFs", s,
                                     static_loads[static_cast<std::size_t>(s)].size(), n));

  // The constraint C u = g: every interface's patch relative displacements in the patches'
  // local frames (interface.hpp), stacked.
  std::vector<const InterfacePatch*> patches;
  std::vector<Eigen::Triplet<double>> tc;
  Eigen::Index ng = 0;
  std::vector<Eigen::Index> stabilised;  // three spread-out patches per interface
  for (const auto& itf : interfaces) {
    const Sparse L = itf.local_operator(n);
    for (Eigen::Index col = 0; col < L.outerSize(); ++col)
      for (Sparse::InnerIterator it(L, col); it; ++it)
        tc.emplace_back(ng + it.row(), col, it.value());
    const auto first = static_cast<Eigen::Index>(patches.size());
    const auto count = static_cast<Eigen::Index>(itf.patches.size());
    for (const auto& p : itf.patches) patches.push_back(&p);
    ng += L.rows();
    if (count == 0) continue;
    const auto [pa, pb, pc] = spread_points(
        count,
        [&](Eigen::Index p) -> const Eigen::Vector3d& {
          return patches[static_cast<std::size_t>(first + p)]->centroid;
        },
        [](Eigen::Index) { return true; });
    for (const auto p : {pa, pb, pc})
      if (std::find(stabilised.begin(), stabilised.end(), first + p) == stabilised.end())
        stabilised.push_back(first + p);
  }
  Sparse C(ng, n);
  C.setFromTriplets(tc.begin(), tc.end());

  // K~ = K + w C_s^T C_s over the stabilised patches' rows C_s. On C u = g it adds the
  // constant w |g_s|^2 / 2 to the strain energy, so the constraint modes and the tied
  // structure (C u = 0) are those of K; it joins bodies that only the interface joins (no
  // bolt), so that K~ on a 3-2-1 support is nonsingular. w: the mean diagonal of K.
  const double w = K.diagonal().cwiseAbs().mean();
  Sparse Ks = K;
  for (const auto p : stabilised) {
    const Sparse Cp = C.middleRows(3 * p, 3);
    Ks += w * Sparse(Cp.transpose() * Cp);
  }

  // Statically determinate 3-2-1 support on nodes outside the interfaces' patches.
  std::vector<char> in_patch(static_cast<std::size_t>(nodes.cols()), 0);
  for (const auto* p : patches)
    for (const auto& nw : p->weights)
      in_patch[static_cast<std::size_t>(nw.node_a)] =
          in_patch[static_cast<std::size_t>(nw.node_b)] = 1;
  auto node_ok = [&](Eigen::Index i) { return !in_patch[static_cast<std::size_t>(i)]; };
  const auto [a, b, c] = spread_points(
      nodes.cols(), [&](Eigen::Index i) { return nodes.col(i); }, node_ok);
  if (a < 0)
    throw InvalidInput(
        "reduction: every node of the mesh is on an interface patch; the bodies need nodes "
        "off the interfaces");
  const Eigen::Vector3d ab = nodes.col(b) - nodes.col(a);
  Eigen::Index free_b;
  ab.cwiseAbs().maxCoeff(&free_b);
  Eigen::Index fix_c;
  ab.cross(nodes.col(c) - nodes.col(a)).cwiseAbs().maxCoeff(&fix_c);
  std::vector<Eigen::Index> support{3 * a, 3 * a + 1, 3 * a + 2};
  for (Eigen::Index k = 0; k < 3; ++k)
    if (k != free_b) support.push_back(3 * b + k);
  support.push_back(3 * c + fix_c);
  std::vector<Eigen::Index> f_index(static_cast<std::size_t>(n), 0);
  for (const auto d : support) f_index[static_cast<std::size_t>(d)] = -1;
  Eigen::Index nf = 0;
  for (auto& f : f_index)
    if (f >= 0) f = nf++;
  std::vector<Eigen::Triplet<double>> tf;
  for (Eigen::Index col = 0; col < Ks.outerSize(); ++col)
    if (const auto fc = f_index[static_cast<std::size_t>(col)]; fc >= 0)
      for (Sparse::InnerIterator it(Ks, col); it; ++it)
        if (const auto fr = f_index[static_cast<std::size_t>(it.row())]; fr >= 0)
          tf.emplace_back(fr, fc, it.value());
  Sparse Kff(nf, nf);
  Kff.setFromTriplets(tf.begin(), tf.end());
  // C_f^T: column j is the interface DOF j's constraint row on the free DOFs.
  std::vector<Eigen::Triplet<double>> tct;
  for (Eigen::Index col = 0; col < C.outerSize(); ++col)
    if (const auto fc = f_index[static_cast<std::size_t>(col)]; fc >= 0)
      for (Sparse::InnerIterator it(C, col); it; ++it) tct.emplace_back(fc, it.row(), it.value());
  Sparse CfT(nf, ng);
  CfT.setFromTriplets(tct.begin(), tct.end());
  CraigBampton cb;
  cb.interface_dofs = ng;
  cb.phases.push_back(clock.lap("stabilisation and support"));
  Eigen::SimplicialLDLT<Sparse> ldlt;
  ldlt.analyzePattern(Kff);
  cb.phases.push_back(clock.lap("ordering"));
  ldlt.factorize(Kff);
  cb.phases.push_back(clock.lap("factorisation"));
  cb.factor_nonzeros = ldlt.matrixL().nestedExpression().nonZeros() + nf;
  const auto& D = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || D.size() == 0 || D.minCoeff() <= 1e-12 * D.maxCoeff())
    throw InvalidInput(
        "the structure with its interfaces tied and a statically determinate support is "
        "singular: it has more rigid-body modes than a free-free structure allows (6)");

  const int count = std::min<int>(options.fixed_interface_modes, static_cast<int>(nf) - 7);
  const Eigen::Index nm = 6 + std::max(count, 0);
  const Eigen::Index nr = ng + nm + ns;
  cb.basis = Eigen::MatrixXd::Zero(n, nr);
  auto scatter = [&](const SolveBlock& Y, Eigen::Index nc, auto&& target) {
    for (Eigen::Index i = 0; i < n; ++i)
      if (const auto fi = f_index[static_cast<std::size_t>(i)]; fi >= 0)
        target.row(i) = Y.row(fi).head(nc);
  };

  // X = K~_ff^-1 C_f^T, kSolveBlock right-hand sides per pass over the factor.
  {
    const auto blocks = static_cast<std::size_t>((ng + kSolveBlock - 1) / kSolveBlock);
    core::parallel_for(blocks, [&](std::size_t k) {
      const Eigen::Index c0 = static_cast<Eigen::Index>(k) * kSolveBlock;
      const Eigen::Index nc = std::min(kSolveBlock, ng - c0);
      SolveBlock Y = SolveBlock::Zero(nf, kSolveBlock);
      for (Eigen::Index j = 0; j < nc; ++j)
        for (Sparse::InnerIterator it(CfT, c0 + j); it; ++it) Y(it.row(), j) = it.value();
      solve_in_place(ldlt, Y);
      scatter(Y, nc, cb.basis.middleCols(c0, nc));
    });
  }
  cb.phases.push_back(clock.lap("constraint solves"));
  // The interface flexibility S = C X (symmetric positive definite when the patches'
  // averages are independent); the constraint modes Psi0 = X S^-1 (C Psi0 = I), and
  // Psi0^T K~ = S^-1 C (K~ Psi0 = C^T S^-1: the support carries no reaction, C^T S^-1 being
  // self-equilibrated), so Psi0^T K Psi0 = S^-1 - w C_s^T C_s-part and Psi0^T K Phi = 0
  // for every Phi with C Phi = 0 (Craig-Bampton's K_bb - K_bi K_ii^-1 K_ib).
  Eigen::MatrixXd S = C * cb.basis.leftCols(ng);
  S = (0.5 * (S + S.transpose())).eval();
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success ||
      llt.matrixLLT().diagonal().minCoeff() <= 1e-7 * llt.matrixLLT().diagonal().maxCoeff()) {
    throw InvalidInput(
        "the interface patches' relative displacements are not independent (their "
        "flexibility C K^-1 C^T is singular): too many `patches` for the interface mesh; "
        "give fewer patches or refine the interface");
  }
  const Eigen::MatrixXd S_inv = llt.solve(Eigen::MatrixXd::Identity(ng, ng));
  {
    constexpr Eigen::Index kRowBlock = 4096;
    const auto blocks = static_cast<std::size_t>((n + kRowBlock - 1) / kRowBlock);
    core::parallel_for(blocks, [&](std::size_t k) {
      const Eigen::Index r0 = static_cast<Eigen::Index>(k) * kRowBlock;
      const Eigen::Index nrb = std::min(kRowBlock, n - r0);
      const Eigen::MatrixXd rows = cb.basis.block(r0, 0, nrb, ng) * S_inv;
      cb.basis.block(r0, 0, nrb, ng) = rows;
    });
  }
  // Made mass-orthogonal to the rigid-body modes (which do not change g: C R = 0).
  const Eigen::MatrixXd R = rigid_body_modes(nodes);
  const Eigen::MatrixXd MR = M * R;
  const Eigen::MatrixXd G = (R.transpose() * MR).inverse();
  cb.basis.leftCols(ng) -= R * (G * (MR.transpose() * cb.basis.leftCols(ng)));
  cb.phases.push_back(clock.lap("interface flexibility"));

  // Fixed-interface (tied) modes: the free-free tied structure's flexibility with inertia
  // relief, whose eigenpairs under M are the elastic modes (1/omega^2); the six rigid-body
  // modes are added exactly. The static loads' responses F_c f (g = 0), kSolveBlock at a
  // time. Both only read the factor and Psi: the Lanczos run (one solve at a time, bound by
  // reading L) takes one thread, the load blocks the others.
  const TiedFlexibility tied_flexibility(ldlt, f_index, nf, C, cb.basis.leftCols(ng));
  LowestModes tied;
  auto tied_modes = [&] {
    InertiaReliefFlexibility op(tied_flexibility, R, MR, G);
    Spectra::SparseSymMatProd<double> bop(M);
    Eigen::MatrixXd shapes(n, nm);
    Eigen::VectorXd omega2 = Eigen::VectorXd::Zero(nm);
    // Rigid-body modes, mass-orthonormal (Cholesky of R^T M R).
    const Eigen::MatrixXd L = Eigen::LLT<Eigen::MatrixXd>(R.transpose() * MR).matrixL();
    shapes.leftCols(6) = R * L.transpose().inverse();
    if (count > 0) {
      const int ncv =
          static_cast<int>(std::min<Eigen::Index>(nf - 6, std::max(2 * count + 1, count + 20)));
      Spectra::SymGEigsShiftSolver<InertiaReliefFlexibility, Spectra::SparseSymMatProd<double>,
                                   Spectra::GEigsMode::ShiftInvert>
          eigs(op, bop, count, ncv, 0.0);
      eigs.init();
      eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-10, Spectra::SortRule::SmallestAlge);
      if (eigs.info() != Spectra::CompInfo::Successful)
        throw NumericalError(fmt::format(
            "the {} lowest modes of the tied structure ({} DOFs) did not converge (Spectra "
            "Lanczos on the inertia-relief flexibility, {} vectors, 1000 restarts)",
            count, n, ncv));
      omega2.tail(count) = eigs.eigenvalues();
      cb.eigensolver_operations = eigs.num_operations();
      shapes.rightCols(count) = eigs.eigenvectors();
    }
    cb.rigid_body_modes = 6;
    cb.tied_omega2 = omega2;
    tied.omega2 = omega2;
    tied.shapes = std::move(shapes);
  };
  Eigen::MatrixXd load_response = Eigen::MatrixXd::Zero(n, ns);
  auto load_responses = [&](Eigen::Index s0) {
    const Eigen::Index nc = std::min(kSolveBlock, ns - s0);
    SolveBlock Y = SolveBlock::Zero(nf, kSolveBlock);
    for (Eigen::Index j = 0; j < nc; ++j)
      for (Eigen::Index i = 0; i < n; ++i)
        if (const auto fi = f_index[static_cast<std::size_t>(i)]; fi >= 0)
          Y(fi, j) = static_loads[static_cast<std::size_t>(s0 + j)][i];
    solve_in_place(ldlt, Y);
    auto Z = load_response.middleCols(s0, nc);
    scatter(Y, nc, Z);
    const Eigen::MatrixXd CZ = C * Z;
    Z.noalias() -= cb.basis.leftCols(ng) * CZ;
  };
  {
    const auto load_blocks = static_cast<std::size_t>((ns + kSolveBlock - 1) / kSolveBlock);
    core::parallel_for(1 + load_blocks, [&](std::size_t k) {
      if (k == 0)
        tied_modes();
      else
        load_responses(static_cast<Eigen::Index>(k - 1) * kSolveBlock);
    });
  }
  cb.phases.push_back(clock.lap("tied modes and load responses"));
  cb.basis.middleCols(ng, nm) = tied.shapes;
  // Load-dependent Ritz vectors of the static loads (g = 0), M-orthogonal to the rigid-body
  // and fixed-interface modes and to each other: classical Gram-Schmidt against the kept
  // columns, all mass-normalised (the rigid-body modes among them), twice for round-off.
  // A load whose response is already in the basis to 1e-8 (relative, M-norm) is refused: the
  // vector left would be round-off, and its constraint C v = 0 would hold to round-off of
  // the response, not of itself.
  for (Eigen::Index s = 0; s < ns; ++s) {
    Eigen::VectorXd v = load_response.col(s);
    const double norm0 = std::sqrt(v.dot(M * v));
    const Eigen::Index kept = nm + s;
    for (int pass = 0; pass < 2; ++pass) {
      const Eigen::VectorXd Mv = M * v;
      v -= cb.basis.middleCols(ng, kept) * (cb.basis.middleCols(ng, kept).transpose() * Mv);
    }
    const double norm = std::sqrt(v.dot(M * v));
    if (!(norm > 1e-8 * norm0))
      throw InvalidInput(fmt::format(
          "reduction: static load {} adds nothing to the basis: its response is, to {:.1e} "
          "relative, a combination of the kept modes and the earlier loads (a zero load, or a "
          "multiple of an earlier one)",
          s, norm0 > 0 ? norm / norm0 : 0.0));
    cb.basis.col(ng + kept) = v / norm;
  }
  cb.static_vectors = ns;
  cb.phases.push_back(clock.lap("load vectors"));
  // B^T K B and B^T M B, symmetric: the upper triangle a block of columns at a time (no
  // n x n_r products kept), mirrored. The constraint modes' rows of K from S (above).
  cb.K = Eigen::MatrixXd::Zero(nr, nr);
  cb.M.resize(nr, nr);
  cb.K.topLeftCorner(ng, ng) = S_inv;
  for (const auto p : stabilised)
    for (Eigen::Index k = 0; k < 3; ++k) cb.K(3 * p + k, 3 * p + k) -= w;
  {
    constexpr Eigen::Index kProductBlock = 64;
    const auto blocks = static_cast<std::size_t>((nr + kProductBlock - 1) / kProductBlock);
    core::parallel_for(blocks, [&](std::size_t k) {
      const Eigen::Index c0 = static_cast<Eigen::Index>(k) * kProductBlock;
      const Eigen::Index nc = std::min(kProductBlock, nr - c0);
      const auto upper = cb.basis.leftCols(c0 + nc).transpose();
      const Eigen::MatrixXd MB = M * cb.basis.middleCols(c0, nc);
      cb.M.block(0, c0, c0 + nc, nc).noalias() = upper * MB;
      // Rows >= ng of K (the tied modes' and load vectors' columns).
      const Eigen::Index k0 = std::max(c0, ng);
      if (k0 < c0 + nc) {
        const Eigen::Index kc = c0 + nc - k0;
        const Eigen::MatrixXd KB = K * cb.basis.middleCols(k0, kc);
        cb.K.block(ng, k0, k0 + kc - ng, kc).noalias() =
            cb.basis.middleCols(ng, k0 + kc - ng).transpose() * KB;
      }
    });
  }
  for (Eigen::Index j = 0; j < nr; ++j)
    for (Eigen::Index i = j + 1; i < nr; ++i) cb.K(i, j) = cb.K(j, i), cb.M(i, j) = cb.M(j, i);
  cb.phases.push_back(clock.lap("reduced matrices"));
  return cb;
}

}  // namespace asperity::fem
