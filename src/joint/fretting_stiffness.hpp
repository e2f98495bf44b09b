#pragma once
// Internal to the fretting analysis (asperity/joint/fretting.hpp): the stiffness at the
// reversals (section 6.3, AnalysisOptions), a pooled least-squares fit of the branches
// after each reversal; used by analyze_fretting (fretting.cpp).
#include <cstddef>
#include <vector>

namespace asperity::joint::detail {

struct Reversal {
  std::size_t r, end;
  int dir;  // -1: Q decreases after the reversal (unloading), +1: reloading
  double span;
  std::size_t cycle;
};

struct StiffnessFit {
  std::vector<double> cycle_slope, cycle_slope_var;  // dv/du at u = 0 per cycle (NaN: no fit)
  std::vector<double> reversal_slope;                // per reversal
  /// Variance that the common shape coefficients' uncertainty gives the mean of the
  /// cycle slopes (shared by every cycle, so the cycles' spread does not show it):
  /// g' Cov(c) g with g the mean over cycles of d slope/d c.
  double shape_variance_of_mean = 0.0;
};

// Pooled fit of every branch after a reversal (AnalysisOptions): v = a_rev + b_cycle u +
// Sum_{k=2..p} c_k u^k. The per-cycle parameters (two intercepts and the slope) are
// projected out cycle by cycle (Frisch-Waugh), the common c_k solved from the pooled
// residual cross products, then each cycle's parameters from its own samples.
StiffnessFit fit_reversals(const std::vector<double>& x, const std::vector<double>& y,
                           const std::vector<double>& x0, const std::vector<double>& Qs,
                           const std::vector<Reversal>& revs, std::size_t ncycles, int degree);

}  // namespace asperity::joint::detail
