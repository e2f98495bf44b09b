#include "asperity/fem/reduction.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <unordered_map>

#include <fmt/format.h>
#include <Eigen/SparseCholesky>

#include "asperity/core/error.hpp"
#include "asperity/core/parallel.hpp"

namespace asperity::fem {
namespace {

using Sparse = Eigen::SparseMatrix<double>;

// The flexibility of a free-free structure with inertia relief (Spectra operator, shift 0):
// y = P K_ff^-1 P^T x on the DOFs v, K_ff the stiffness on a statically determinate
// support (f_index: v -> free index, -1 for the six held DOFs). P^T x removes the load's
// rigid-body resultant (x - M R G R^T x), P makes the displacement M-orthogonal to the
// rigid-body modes R (y - R G (M R)^T y), G = (R^T M R)^-1.
class InertiaReliefFlexibility {
 public:
  using Scalar = double;
  InertiaReliefFlexibility(const Eigen::SimplicialLDLT<Sparse>& ldlt,
                           const std::vector<Eigen::Index>& f_index, Eigen::Index nf,
                           const Eigen::MatrixXd& R, const Eigen::MatrixXd& MR,
                           const Eigen::MatrixXd& G)
      : ldlt_(ldlt), f_index_(f_index), nf_(nf), R_(R), MR_(MR), G_(G) {}
  [[nodiscard]] Eigen::Index rows() const { return R_.rows(); }
  [[nodiscard]] Eigen::Index cols() const { return R_.rows(); }
  void set_shift(double) {}
  void perform_op(const double* x, double* y) const {
    const Eigen::Index n = R_.rows();
    Eigen::Map<const Eigen::VectorXd> xv(x, n);
    Eigen::Map<Eigen::VectorXd> yv(y, n);
    const Eigen::VectorXd load = xv - MR_ * (G_ * (R_.transpose() * xv));
    Eigen::VectorXd lf(nf_);
    for (Eigen::Index i = 0; i < n; ++i)
      if (const auto f = f_index_[static_cast<std::size_t>(i)]; f >= 0) lf[f] = load[i];
    const Eigen::VectorXd zf = ldlt_.solve(lf);
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = 0; i < n; ++i)
      if (const auto f = f_index_[static_cast<std::size_t>(i)]; f >= 0) z[i] = zf[f];
    yv = z - R_ * (G_ * (MR_.transpose() * z));
  }

 private:
  const Eigen::SimplicialLDLT<Sparse>& ldlt_;
  const std::vector<Eigen::Index>& f_index_;
  Eigen::Index nf_;
  const Eigen::MatrixXd& R_;
  const Eigen::MatrixXd& MR_;
  const Eigen::MatrixXd& G_;
};

struct LowestModes {
  Eigen::VectorXd omega2;
  Eigen::MatrixXd shapes;
};

Sparse block(const Sparse& A, Eigen::Index r0, Eigen::Index c0, Eigen::Index nr, Eigen::Index nc) {
  return Sparse(A.block(r0, c0, nr, nc));
}

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
  const Eigen::SparseMatrix<double> r = Eigen::SparseMatrix<double>(row).transpose();
  const Eigen::SparseMatrix<double> rt = r * elimination;
  return Eigen::RowVectorXd(rt * basis);
}

CraigBampton craig_bampton(const Sparse& K, const Sparse& M, const Eigen::Matrix3Xd& nodes,
                           const std::vector<Interface>& interfaces,
                           const ReductionOptions& options,
                           const std::vector<Eigen::VectorXd>& static_loads) {
  options.validate();
  PhaseClock clock;
  const Eigen::Index n = K.rows();
  std::vector<const InterfacePatch*> patches;
  for (const auto& itf : interfaces)
    for (const auto& p : itf.patches) patches.push_back(&p);
  const auto np = static_cast<Eigen::Index>(patches.size());
  const Eigen::Index ng = 3 * np, nv = n - ng;

  // One interior node of side B per patch (used by no other patch) is eliminated.
  std::unordered_map<std::int32_t, int> uses;
  for (const auto* p : patches)
    for (const auto& w : p->weights) ++uses[w.node_a], ++uses[w.node_b];
  std::vector<std::int32_t> master(patches.size(), -1);
  std::vector<double> master_weight(patches.size(), 0.0);
  std::vector<char> is_master(static_cast<std::size_t>(nodes.cols()), 0);
  for (std::size_t p = 0; p < patches.size(); ++p) {
    for (const auto& w : patches[p]->weights)
      if (uses[w.node_b] == 1 && w.node_a != w.node_b && w.weight > master_weight[p])
        master[p] = w.node_b, master_weight[p] = w.weight;
    if (master[p] < 0)
      throw InvalidInput(fmt::format(
          "interface patch {} (centroid ({:.4g}, {:.4g}, {:.4g}) m) has no node of its own: too "
          "many `patches` for the interface mesh; give fewer patches or refine the interface",
          p, patches[p]->centroid.x(), patches[p]->centroid.y(), patches[p]->centroid.z()));
    is_master[static_cast<std::size_t>(master[p])] = 1;
  }
  std::vector<Eigen::Index> v_index(static_cast<std::size_t>(n), -1);
  {
    Eigen::Index next = 0;
    for (Eigen::Index d = 0; d < n; ++d)
      if (!is_master[static_cast<std::size_t>(d / 3)])
        v_index[static_cast<std::size_t>(d)] = next++;
  }
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index d = 0; d < n; ++d)
    if (v_index[static_cast<std::size_t>(d)] >= 0)
      t.emplace_back(d, v_index[static_cast<std::size_t>(d)], 1.0);
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const double cm = master_weight[p];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index row = 3 * Eigen::Index{master[p]} + k;
      t.emplace_back(row, nv + 3 * static_cast<Eigen::Index>(p) + k, 1.0 / cm);
      for (const auto& w : patches[p]->weights) {
        if (w.node_b != master[p])
          t.emplace_back(row, v_index[static_cast<std::size_t>(3 * Eigen::Index{w.node_b} + k)],
                         -w.weight / cm);
        t.emplace_back(row, v_index[static_cast<std::size_t>(3 * Eigen::Index{w.node_a} + k)],
                       w.weight / cm);
      }
    }
  }
  CraigBampton cb;
  cb.interface_dofs = ng;
  cb.elimination.resize(n, n);
  cb.elimination.setFromTriplets(t.begin(), t.end());
  const Sparse& Tc = cb.elimination;
  const Sparse Kt = Sparse(Tc.transpose() * K * Tc);
  const Sparse Mt = Sparse(Tc.transpose() * M * Tc);
  const Sparse Mvv = block(Mt, 0, 0, nv, nv);

  // Rigid-body modes (the constraint holds for them: no relative motion).
  const Eigen::MatrixXd R = rigid_body_modes(nodes);
  Eigen::MatrixXd Rt = Eigen::MatrixXd::Zero(n, 6);
  for (Eigen::Index d = 0; d < n; ++d)
    if (const auto j = v_index[static_cast<std::size_t>(d)]; j >= 0) Rt.row(j) = R.row(d);

  LowestModes tied;
  // Constraint modes: static response to unit g on a statically determinate 3-2-1 support.
  auto node_ok = [&](Eigen::Index i) { return !is_master[static_cast<std::size_t>(i)]; };
  Eigen::Index a = -1;
  for (Eigen::Index i = 0; i < nodes.cols(); ++i)
    if (node_ok(i) && (a < 0 || nodes(0, i) < nodes(0, a))) a = i;
  Eigen::Index b = a;
  for (Eigen::Index i = 0; i < nodes.cols(); ++i)
    if (node_ok(i) && (nodes.col(i) - nodes.col(a)).norm() > (nodes.col(b) - nodes.col(a)).norm())
      b = i;
  const Eigen::Vector3d ab = nodes.col(b) - nodes.col(a);
  Eigen::Index c = a;
  double cd = -1;
  for (Eigen::Index i = 0; i < nodes.cols(); ++i) {
    if (!node_ok(i)) continue;
    const double d = ab.cross(nodes.col(i) - nodes.col(a)).norm();
    if (d > cd) cd = d, c = i;
  }
  Eigen::Index free_b;
  ab.cwiseAbs().maxCoeff(&free_b);
  Eigen::Index fix_c;
  ab.cross(nodes.col(c) - nodes.col(a)).cwiseAbs().maxCoeff(&fix_c);
  std::vector<Eigen::Index> support{3 * a, 3 * a + 1, 3 * a + 2};
  for (Eigen::Index k = 0; k < 3; ++k)
    if (k != free_b) support.push_back(3 * b + k);
  support.push_back(3 * c + fix_c);
  std::vector<char> held(static_cast<std::size_t>(nv), 0);
  for (const auto d : support)
    held[static_cast<std::size_t>(v_index[static_cast<std::size_t>(d)])] = 1;
  std::vector<Eigen::Index> f_index(static_cast<std::size_t>(nv), -1);
  Eigen::Index nf = 0;
  for (Eigen::Index i = 0; i < nv; ++i)
    if (!held[static_cast<std::size_t>(i)]) f_index[static_cast<std::size_t>(i)] = nf++;
  std::vector<Eigen::Triplet<double>> tf, tg;
  for (Eigen::Index col = 0; col < Kt.outerSize(); ++col)
    for (Sparse::InnerIterator it(Kt, col); it; ++it) {
      const Eigen::Index r = it.row();
      if (r >= nv) continue;
      const Eigen::Index fr = f_index[static_cast<std::size_t>(r)];
      if (fr < 0) continue;
      if (col < nv) {
        const Eigen::Index fc = f_index[static_cast<std::size_t>(col)];
        if (fc >= 0) tf.emplace_back(fr, fc, it.value());
      } else {
        tg.emplace_back(fr, col - nv, it.value());
      }
    }
  Sparse Kff(nf, nf), Kfg(nf, ng);
  Kff.setFromTriplets(tf.begin(), tf.end());
  Kfg.setFromTriplets(tg.begin(), tg.end());
  cb.phases.push_back(clock.lap("transformation and support"));
  Eigen::SimplicialLDLT<Sparse> ldlt;
  ldlt.analyzePattern(Kff);
  cb.phases.push_back(clock.lap("ordering"));
  ldlt.factorize(Kff);
  cb.phases.push_back(clock.lap("factorisation"));
  cb.factor_nonzeros = ldlt.matrixL().nestedExpression().nonZeros() + nf;
  const auto D = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || D.minCoeff() <= 1e-12 * D.maxCoeff())
    throw InvalidInput(
        "the structure with its interfaces tied and a statically determinate support is "
        "singular: it has more rigid-body modes than a free-free structure allows (6)");

  const Eigen::Index nt = nv + ng;
  const auto ns = static_cast<Eigen::Index>(static_loads.size());
  const int count = std::min<int>(options.fixed_interface_modes, static_cast<int>(nf) - 7);
  const Eigen::Index nm = 6 + std::max(count, 0);
  const Eigen::Index nr = ng + nm + ns;
  cb.basis = Eigen::MatrixXd::Zero(nt, nr);

  // Fixed-interface (tied) modes from the same factorisation: the free-free tied
  // structure's flexibility with inertia relief, F = P K_ff^-1 P^T (P removes the
  // rigid-body part: loads are made self-equilibrated, displacements mass-orthogonal to
  // the rigid-body modes), whose eigenpairs under M are the elastic modes (1/omega^2);
  // the six rigid-body modes are added exactly.
  const Eigen::MatrixXd Rv = Rt.topRows(nv);
  const Eigen::MatrixXd MRv = Mvv * Rv;
  const Eigen::MatrixXd G = (Rv.transpose() * MRv).inverse();
  auto tied_modes = [&] {
    InertiaReliefFlexibility op(ldlt, f_index, nf, Rv, MRv, G);
    Spectra::SparseSymMatProd<double> bop(Mvv);
    Eigen::MatrixXd shapes(nv, nm);
    Eigen::VectorXd omega2 = Eigen::VectorXd::Zero(nm);
    // Rigid-body modes, mass-orthonormal (Cholesky of R^T M R).
    const Eigen::MatrixXd L = Eigen::LLT<Eigen::MatrixXd>(Rv.transpose() * MRv).matrixL();
    shapes.leftCols(6) = Rv * L.transpose().inverse();
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
            count, nv, ncv));
      omega2.tail(count) = eigs.eigenvalues();
      cb.eigensolver_operations = eigs.num_operations();
      shapes.rightCols(count) = eigs.eigenvectors();
    }
    cb.rigid_body_modes = 6;
    cb.tied_omega2 = omega2;
    tied.omega2 = omega2;
    tied.shapes = std::move(shapes);
  };
  // Constraint modes: one right-hand side -K_fg e_j per interface DOF, solved kSolveBlock
  // at a time.
  auto constraint_modes = [&](Eigen::Index c0) {
    const Eigen::Index nc = std::min(kSolveBlock, ng - c0);
    SolveBlock Y = SolveBlock::Zero(nf, kSolveBlock);
    for (Eigen::Index j = 0; j < nc; ++j)
      for (Sparse::InnerIterator it(Kfg, c0 + j); it; ++it) Y(it.row(), j) = -it.value();
    solve_in_place(ldlt, Y);
    for (Eigen::Index i = 0; i < nv; ++i)
      if (const auto fi = f_index[static_cast<std::size_t>(i)]; fi >= 0)
        cb.basis.row(i).segment(c0, nc) = Y.row(fi).head(nc);
  };
  // The static loads' responses K_ff^-1 f (g = 0), kSolveBlock at a time.
  for (Eigen::Index s = 0; s < ns; ++s)
    if (static_loads[static_cast<std::size_t>(s)].size() != n)
      throw InvalidInput(fmt::format("reduction: static load {} has {} entries for {} DOFs", s,
                                     static_loads[static_cast<std::size_t>(s)].size(), n));
  Eigen::MatrixXd load_response = Eigen::MatrixXd::Zero(nt, ns);
  auto load_responses = [&](Eigen::Index s0) {
    const Eigen::Index nc = std::min(kSolveBlock, ns - s0);
    SolveBlock Y = SolveBlock::Zero(nf, kSolveBlock);
    for (Eigen::Index j = 0; j < nc; ++j) {
      const Eigen::VectorXd ft = Tc.transpose() * static_loads[static_cast<std::size_t>(s0 + j)];
      for (Eigen::Index i = 0; i < nv; ++i)
        if (const auto fi = f_index[static_cast<std::size_t>(i)]; fi >= 0) Y(fi, j) = ft[i];
    }
    solve_in_place(ldlt, Y);
    for (Eigen::Index i = 0; i < nv; ++i)
      if (const auto fi = f_index[static_cast<std::size_t>(i)]; fi >= 0)
        load_response.row(i).segment(s0, nc) = Y.row(fi).head(nc);
  };
  // All only read the factor: the Lanczos run (one solve at a time, bound by reading L)
  // takes one thread while the blocks of constraint modes and load responses go to the
  // others.
  {
    const auto blocks = static_cast<std::size_t>((ng + kSolveBlock - 1) / kSolveBlock);
    const auto load_blocks = static_cast<std::size_t>((ns + kSolveBlock - 1) / kSolveBlock);
    core::parallel_for(1 + blocks + load_blocks, [&](std::size_t k) {
      if (k == 0)
        tied_modes();
      else if (k <= blocks)
        constraint_modes(static_cast<Eigen::Index>(k - 1) * kSolveBlock);
      else
        load_responses(static_cast<Eigen::Index>(k - 1 - blocks) * kSolveBlock);
    });
  }
  cb.phases.push_back(clock.lap("fixed-interface and constraint modes"));
  cb.basis.block(nv, 0, ng, ng).setIdentity();
  {
    const Eigen::MatrixXd MR = Mt.topLeftCorner(nt, nt) * Rt.topRows(nt).eval();
    const Eigen::MatrixXd A = Rt.topRows(nt).transpose() * MR;
    const Eigen::MatrixXd coef = A.ldlt().solve(MR.transpose() * cb.basis.leftCols(ng));
    cb.basis.leftCols(ng) -= Rt.topRows(nt) * coef;
  }
  // The patches' DOFs in their local frames: g_global = F^T g_local.
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const auto c0 = 3 * static_cast<Eigen::Index>(p);
    const Eigen::MatrixXd cols = cb.basis.middleCols(c0, 3) * patches[p]->frame.transpose();
    cb.basis.middleCols(c0, 3) = cols;
  }
  cb.basis.block(0, ng, nv, nm) = tied.shapes;
  // Load-dependent Ritz vectors of the static loads (g = 0), M-orthogonal to the rigid-body
  // and fixed-interface modes and to each other: classical Gram-Schmidt against the kept
  // columns, all mass-normalised (the rigid-body modes among them), twice for round-off.
  for (Eigen::Index s = 0; s < ns; ++s) {
    Eigen::VectorXd v = load_response.col(s);
    const Eigen::Index kept = nm + s;
    for (int pass = 0; pass < 2; ++pass) {
      const Eigen::VectorXd Mv = Mt * v;
      v -= cb.basis.middleCols(ng, kept) * (cb.basis.middleCols(ng, kept).transpose() * Mv);
    }
    const double norm = std::sqrt(v.dot(Mt * v));
    if (!(norm > 0))
      throw NumericalError(fmt::format(
          "reduction: static load {} has no response beyond the kept modes (a zero load?)", s));
    cb.basis.col(ng + kept) = v / norm;
  }
  cb.static_vectors = ns;
  cb.phases.push_back(clock.lap("load vectors"));
  // B^T K B and B^T M B, symmetric: the upper triangle a block of columns at a time (no
  // n_t x n_r products kept), mirrored. K Psi vanishes on the rows solved for (K_ff Psi_f +
  // K_fg = 0, and K R = 0 for the rigid-body part taken out), so the rows of B^T K B of the
  // constraint modes Psi need K Psi only on the rest, Q: the interface DOFs and the six
  // held ones (Craig-Bampton's K_bb - K_bi K_ii^-1 K_ib, Psi^T K B = (K Psi)_Q^T B_Q).
  cb.K.resize(nr, nr);
  cb.M.resize(nr, nr);
  {
    std::vector<Eigen::Index> q_index(static_cast<std::size_t>(nt), -1);
    Eigen::Index nq = 0;
    for (Eigen::Index i = 0; i < nt; ++i)
      if (i >= nv || f_index[static_cast<std::size_t>(i)] < 0)
        q_index[static_cast<std::size_t>(i)] = nq++;
    std::vector<Eigen::Triplet<double>> tq;
    Eigen::MatrixXd BQ(nq, nr);
    for (Eigen::Index col = 0; col < Kt.outerSize(); ++col)
      for (Sparse::InnerIterator it(Kt, col); it; ++it)
        if (const auto qi = q_index[static_cast<std::size_t>(it.row())]; qi >= 0)
          tq.emplace_back(qi, col, it.value());
    for (Eigen::Index i = 0; i < nt; ++i)
      if (const auto qi = q_index[static_cast<std::size_t>(i)]; qi >= 0)
        BQ.row(qi) = cb.basis.row(i);
    Sparse KQ(nq, nt);
    KQ.setFromTriplets(tq.begin(), tq.end());
    const Eigen::MatrixXd KPsiQ = KQ * cb.basis.leftCols(ng);
    cb.K.topRows(ng).noalias() = KPsiQ.transpose() * BQ;
  }
  {
    constexpr Eigen::Index kProductBlock = 64;
    const auto blocks = static_cast<std::size_t>((nr + kProductBlock - 1) / kProductBlock);
    core::parallel_for(blocks, [&](std::size_t k) {
      const Eigen::Index c0 = static_cast<Eigen::Index>(k) * kProductBlock;
      const Eigen::Index nc = std::min(kProductBlock, nr - c0);
      const auto upper = cb.basis.leftCols(c0 + nc).transpose();
      const Eigen::MatrixXd MB = Mt * cb.basis.middleCols(c0, nc);
      cb.M.block(0, c0, c0 + nc, nc).noalias() = upper * MB;
      // Rows >= ng of K (the tied modes' and load vectors' columns).
      const Eigen::Index k0 = std::max(c0, ng);
      if (k0 < c0 + nc) {
        const Eigen::Index kc = c0 + nc - k0;
        const Eigen::MatrixXd KB = Kt * cb.basis.middleCols(k0, kc);
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
