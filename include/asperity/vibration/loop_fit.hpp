#pragma once
// Least-squares fits of hysteresis loops (measured or synthetic fretting loops) by the
// joint elements a structural dynamicist uses: the Jenkins element (spring k_t in series
// with a Coulomb slider F_s) and Segalman's four-parameter Iwan model (F_S, K_T, chi,
// beta; dynamics/friction_model.hpp). Both are Masing elements, so a steady loop of
// displacement amplitude a about (x_c, Q_c) is, with the backbone B (odd in u):
//   unloading from x_top = x_c + a:  Q(x) = Q_c + B(a) - 2 B((x_top - x)/2)
//   reloading from x_bot = x_c - a:  Q(x) = Q_c - B(a) + 2 B((x - x_bot)/2)
// (Masing's rules; the element's periodic response gives the same loop). The result is
// written in the form a vibration case's [[element]] takes.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "asperity/vibration/elements.hpp"

namespace asperity::vibration {

enum class LoopModel { jenkins, iwan4 };
/// "jenkins" or "iwan4"; throws InvalidInput naming `field` otherwise.
LoopModel parse_loop_model(std::string_view text, std::string_view field = "fit");
std::string_view to_string(LoopModel m);

/// One closed steady loop: the unloading branch from the largest displacement to the
/// smallest, then the reloading branch back (as joint::FrettingAnalysis::loop_delta and
/// loop_Q hold it: `unloading` points of each). SI: delta [m], Q [N].
struct MeasuredLoop {
  std::vector<double> delta;
  std::vector<double> Q;
  std::size_t unloading = 0;  ///< points of the unloading branch (the first ones)
  std::string source;
  /// Throws InvalidInput unless the sizes agree, each branch has at least 5 points, every
  /// value is finite and the loop has a displacement and a force range.
  void validate() const;
};

struct FittedParameter {
  std::string name;  ///< "k_t", "F_s" | "F_S", "K_T", "chi", "beta"
  std::string unit;  ///< "N/m", "N" or "" (dimensionless)
  double value = 0.0;
  /// Standard error from the Gauss-Newton covariance s^2 (J^T J)^-1, s^2 = RSS/(n - p - loops)
  /// (the force offset of each loop is a nuisance parameter). Treats the residuals as
  /// independent: neighbouring points of an averaged loop are correlated, so this is a
  /// lower bound. Infinite when the data do not determine the parameter (a singular J^T J:
  /// e.g. F_S of loops that never reach macro-slip), and for chi or beta at a bound of
  /// their domain (chi > -1e-9 or < -1 + 1e-9, beta < 1e-9).
  double standard_error = 0.0;
};

struct LoopFit {
  LoopModel model = LoopModel::jenkins;
  std::vector<FittedParameter> parameters;
  double residual_rms = 0.0;       ///< rms of Q - Q_model over all points [N]
  double relative_residual = 0.0;  ///< residual_rms over the mean half peak-to-peak force
  std::size_t points = 0;
  std::size_t loops = 0;
  std::size_t iterations = 0;                ///< Levenberg-Marquardt iterations of the best start
  std::vector<double> Q_offsets;             ///< Q_c of each loop [N]
  std::vector<std::vector<double>> Q_model;  ///< the fitted loop at each loop's points [N]

  [[nodiscard]] double value(std::string_view name) const;
  /// The fitted element (make_jenkins_element / make_iwan4_element).
  [[nodiscard]] std::shared_ptr<const Element> element() const;
  /// The [[element]] table of a vibration case (`T` to be set by the user), with the
  /// standard errors and the residual as comments.
  [[nodiscard]] std::string case_toml() const;
};

/// The loop of a Masing backbone (force at each point of `loop`'s displacements, Q_c = 0):
/// the formula above with x_top, x_bot the largest and smallest displacement of the loop.
[[nodiscard]] std::vector<double> masing_loop(const hysteresis::Backbone& backbone,
                                              const MeasuredLoop& loop);

/// Fits `model` to all loops at once (shared parameters, a force offset Q_c per loop) by
/// Levenberg-Marquardt on log k, log F and, for iwan4, chi = -1/(1 + e^-z) and log beta,
/// from several starts (iwan4: chi in {-0.2, -0.5, -0.8} x beta in {0.03, 0.3} x
/// F_S in {1.02, 1.5} x the largest half peak-to-peak force); the initial stiffness starts
/// at the loops' slope right after the reversals. Throws InvalidInput for a bad loop and
/// NumericalError when no start converges to a finite residual.
[[nodiscard]] LoopFit fit_loops(const std::vector<MeasuredLoop>& loops, LoopModel model);

}  // namespace asperity::vibration
