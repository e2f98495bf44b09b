// Eigen's dense LDLT and LU inlined at -O3 make g++ 12 report potential null dereferences
// (a known false positive of -Wnull-dereference).
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include "asperity/vibration/quasi_static_fretting.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "asperity/core/error.hpp"
#include "asperity/core/numerics.hpp"
#include "asperity/core/validate.hpp"
#include "asperity/fem/gap_map.hpp"
#include "asperity/vibration/harmonic_balance.hpp"
#include "asperity/vibration/rough_contact.hpp"

namespace asperity::vibration {

void QuasiStaticFrettingOptions::validate() const {
  if (harmonics < 1 || harmonics > 64) {
    throw InvalidInput(
        fmt::format("quasi-static fretting harmonics = {}: give 1 to 64", harmonics));
  }
  if (time_points % 2 != 0 || time_points < static_cast<std::size_t>(2 * harmonics + 2) ||
      time_points > (std::size_t{1} << 16)) {
    throw InvalidInput(fmt::format(
        "quasi-static fretting time_points = {}: give an even number from 2 H + 2 = {} to 65536",
        time_points, 2 * harmonics + 2));
  }
  if (!(tolerance > 0.0 && tolerance < 1e-3)) {
    throw InvalidInput(
        fmt::format("quasi-static fretting tolerance = {}: give a value in [1e-14, 1e-3)",
                    core::format_value(tolerance)));
  }
  if (max_iterations < 1) {
    throw InvalidInput(
        fmt::format("quasi-static fretting max_iterations = {}: give 1 or more", max_iterations));
  }
}

namespace {

struct Newton {
  int iterations = 0;
  double residual = 0.0;
  bool converged = false;
};

// Newton's method on R(U) = K U + F_nl(U) - F at omega = 0 from U (updated in place).
Newton solve(const HarmonicBalance& hb, Eigen::VectorXd& U, const Eigen::VectorXd& F, double scale,
             const QuasiStaticFrettingOptions& o) {
  Newton n;
  Eigen::VectorXd R;
  Eigen::MatrixXd J;
  for (n.iterations = 0; n.iterations <= o.max_iterations; ++n.iterations) {
    const bool last = n.iterations == o.max_iterations;
    hb.residual(U, 0.0, F, R, last ? nullptr : &J, nullptr);
    n.residual = R.norm() / scale;
    if (!std::isfinite(n.residual)) return n;
    if (n.residual <= o.tolerance) {
      n.converged = true;
      return n;
    }
    if (last) return n;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(J);
    const Eigen::VectorXd step = lu.solve(R);
    if (!step.allFinite()) return n;
    // Backtracking on |R| (Armijo): the elements' slip limits make R only piecewise smooth,
    // where full steps can cycle between two pieces.
    double lambda = 1.0;
    Eigen::VectorXd trial = U - step, R_trial;
    for (int b = 0; b < 8; ++b) {
      hb.residual(trial, 0.0, F, R_trial, nullptr, nullptr);
      if (R_trial.norm() <= (1.0 - 1e-4 * lambda) * R.norm()) break;
      lambda *= 0.5;
      trial = U - lambda * step;
    }
    U = std::move(trial);
  }
  return n;
}

}  // namespace

QuasiStaticFretting quasi_static_fretting(const fem::GrippedJoint& joint,
                                          const std::vector<PlacedElement>& elements,
                                          const std::vector<double>& tip_amplitudes,
                                          const QuasiStaticFrettingOptions& options) {
  options.validate();
  for (std::size_t i = 0; i < tip_amplitudes.size(); ++i) {
    const double a = tip_amplitudes[i];
    if (!(std::isfinite(a) && a > 0.0 && a < 1e-2)) {
      throw InvalidInput(fmt::format(
          "tip amplitude {} = {} m: give a finite value in (0, 1e-2) m (fretting, not sliding)",
          i + 1, core::format_value(a)));
    }
  }
  const auto& m = joint.model;
  const Eigen::Index n = m.dofs(), z = joint.drive_dof;
  const double k = joint.drive_stiffness;
  HarmonicBalanceOptions hbo;
  hbo.harmonics.clear();
  for (int h = 0; h <= options.harmonics; ++h) hbo.harmonics.push_back(h);
  hbo.time_points = options.time_points;
  Structure s{.M = m.M, .K = m.K, .C = Eigen::MatrixXd::Zero(n, n)};
  const HarmonicBalance hb(std::move(s), elements, hbo);
  const auto& basis = hb.basis();
  const auto sine1 = static_cast<std::size_t>(basis.index_of(1, 1));

  QuasiStaticFretting out;
  // The stuck joint: K + sum T^T K0 T; its flexibility at z gives dQ/d delta = 1/s - k.
  const Eigen::MatrixXd K_stuck = hb.stuck_stiffness();
  const Eigen::LDLT<Eigen::MatrixXd> stuck(K_stuck);
  Eigen::VectorXd ez = Eigen::VectorXd::Zero(n);
  ez[z] = 1.0;
  const Eigen::VectorXd x_unit = stuck.solve(ez);  // per unit force on z
  out.stiffness = 1.0 / x_unit[z] - k;

  const Eigen::MatrixXd& E = basis.synthesis();
  Eigen::VectorXd U_prev;
  double a_prev = 0.0;
  for (const double a : tip_amplitudes) {
    const auto load_at = [&](double amp) {
      Eigen::VectorXd f = Eigen::VectorXd::Zero(hb.unknowns());
      f[hb.index(z, sine1)] = k * amp;
      return f;
    };
    // From the previous cycle scaled (or the stuck joint's), in amplitude steps that halve
    // when Newton's method fails and double again when it converges.
    const auto stuck_guess = [&](double amp) {
      Eigen::VectorXd U = Eigen::VectorXd::Zero(hb.unknowns());
      for (Eigen::Index d = 0; d < n; ++d) U[hb.index(d, sine1)] = k * amp * x_unit[d];
      return U;
    };
    double from = U_prev.size() != 0 ? a_prev : 0.0;
    Eigen::VectorXd U_from = U_prev;
    double step = a - from;
    int halvings = 0, total = 0;
    Newton nw;
    while (from != a) {
      const double to = std::abs(a - from) <= std::abs(step) ? a : from + step;
      Eigen::VectorXd trial = from > 0.0 ? Eigen::VectorXd(U_from * (to / from)) : stuck_guess(to);
      nw = solve(hb, trial, load_at(to), k * to, options);
      total += nw.iterations;
      if (nw.converged) {
        U_from = std::move(trial);
        from = to;
        step *= 2.0;
        continue;
      }
      if (++halvings > 12) {
        throw NumericalError(fmt::format(
            "quasi-static fretting: Newton's method did not converge at tip amplitude {} m "
            "(residual {} of k Delta_0 after {} iterations; last converged amplitude {} m): near "
            "the interface's gross slip the rough-contact elements' jumps at their 2-D limit stop "
            "Newton's method (docs/structures.md); try smaller tip amplitudes, or more harmonics "
            "and time points",
            core::format_value(to), core::format_value(nw.residual), total,
            core::format_value(from)));
      }
      step *= 0.5;
    }
    const Eigen::VectorXd& U = U_from;
    U_prev = U;
    a_prev = a;

    FrettingCycle c;
    c.tip_amplitude = a;
    c.iterations = total;
    c.residual = nw.residual;
    Eigen::VectorXd zc(static_cast<Eigen::Index>(basis.coefficients()));
    for (std::size_t j = 0; j < basis.coefficients(); ++j)
      zc[static_cast<Eigen::Index>(j)] = U[hb.index(z, j)];
    c.delta = E * zc;
    const auto Nt = static_cast<Eigen::Index>(basis.time_points());
    c.force.resize(Nt);
    for (Eigen::Index i = 0; i < Nt; ++i) {
      const double theta =
          2.0 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(Nt);
      c.force[i] = k * (a * std::sin(theta) - c.delta[i]);
    }
    c.force_amplitude = 0.5 * (c.force.maxCoeff() - c.force.minCoeff());
    c.displacement_amplitude = 0.5 * (c.delta.maxCoeff() - c.delta.minCoeff());
    // W = closed integral Q d delta = k closed integral Delta d delta (closed integral of
    // delta d delta vanishes) = -pi k Delta_0 a_1, a_1 the cosine coefficient of delta's
    // first harmonic: exact for the truncated series.
    c.energy = -std::numbers::pi * k * a * zc[basis.index_of(1, 0)];
    out.cycles.push_back(std::move(c));
  }
  return out;
}

StructureFretting structure_fretting(const fem::StructureCase& c,
                                     const fem::StructureOptions& options) {
  if (!c.fretting.given) {
    throw InvalidInput(
        fmt::format("{}: no [fretting] table (the apparatus: grips, drive "
                    "stiffness, tip amplitudes)",
                    c.path));
  }
  if (c.bolts.empty()) {
    throw InvalidInput(fmt::format(
        "{}: [fretting]: the apparatus's joint needs a [[bolt]] preload to press its interface",
        c.path));
  }
  const auto& f = c.fretting;
  StructureFretting out;
  fem::AssembledStructure as = fem::assemble_structure(c, options);
  out.costs = as.costs;
  out.mesh_nodes = as.mesh.node_count();
  out.mesh_dofs = 3 * as.mesh.node_count();
  out.total_mass = as.total_mass;
  auto clock = std::chrono::steady_clock::now();
  const auto step = [&](std::string name) {
    const auto now = std::chrono::steady_clock::now();
    out.costs.push_back({std::move(name), std::chrono::duration<double>(now - clock).count(),
                         fem::peak_resident_memory_mib()});
    clock = now;
  };
  if (options.progress)
    options.progress(fmt::format("condensing {} DOFs in the apparatus's grips", out.mesh_dofs));
  fem::GrippedJoint joint = [&] {
    try {
      return fem::condense_gripped(as.mesh, as.K, as.interfaces, as.bolts, f.fixture);
    } catch (const InvalidInput& e) {
      throw InvalidInput(fmt::format("{}: [fretting].{}", c.path, e.what()));
    }
  }();
  out.interface_elements = joint.model.elements.size();
  out.held_nodes = joint.held_nodes;
  out.driven_nodes = joint.driven_nodes;
  as = {};  // the mesh and matrices are not needed any more
  step("condensation in the grips");

  Eigen::VectorXd gap;
  if (c.rough.gap) gap = fem::gap_at_elements(*c.rough.gap, joint.model, c.rough.gap_origin);
  const Eigen::VectorXd given = joint.model.bolt_preload;
  std::vector<double> totals = f.total_preloads;
  if (totals.empty()) totals.push_back(given.sum());
  QuasiStaticFrettingOptions qo;
  qo.harmonics = f.harmonics;
  qo.time_points = f.time_points;
  for (const double total : totals) {
    if (options.progress)
      options.progress(fmt::format("fretting at {} N of bolt preload", core::format_value(total)));
    PreloadFretting run;
    run.total_preload = total;
    joint.model.bolt_preload = given * (total / given.sum());
    run.prestress = fem::apply_rough_contact(c, joint.model, gap);
    const auto placed = interface_rough_contact(joint.model, c.rough.model, {}, "interface element",
                                                c.path + ": [fretting]");
    run.elements_in_contact = placed.elements.size();
    run.fretting = quasi_static_fretting(joint, placed.elements, f.tip_amplitudes, qo);
    const auto& cy = run.fretting.cycles;
    for (std::size_t i = 1; i < cy.size(); ++i) {
      const bool defined = cy[i].energy > 0.0 && cy[i - 1].energy > 0.0 &&
                           cy[i].force_amplitude > cy[i - 1].force_amplitude &&
                           cy[i - 1].force_amplitude > 0.0;
      run.exponents.push_back(defined
                                  ? std::log(cy[i].energy / cy[i - 1].energy) /
                                        std::log(cy[i].force_amplitude / cy[i - 1].force_amplitude)
                                  : std::numeric_limits<double>::quiet_NaN());
    }
    out.runs.push_back(std::move(run));
    step(fmt::format("fretting at {} N", core::format_value(total)));
  }
  return out;
}

}  // namespace asperity::vibration
