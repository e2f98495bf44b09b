#pragma once
// Predictions for a joint case (thesis ch. 5-6, Fig. 4.3): per load case the rough
// flat's separation, static friction, friction coefficient, tangential stiffness and
// backbone; per amplitude the peak force, the energy per cycle (Masing, exact) and the
// fretting regime. SI units throughout.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "asperity/hysteresis/masing.hpp"
#include "asperity/joint/case.hpp"

namespace asperity::joint {

struct AmplitudePrediction {
  double delta_max = 0.0;  ///< displacement amplitude [m]
  double Q_peak = 0.0;     ///< force at delta_max on the backbone [N]
  double energy = 0.0;     ///< energy per symmetric cycle [J]
  double Q_ratio = 0.0;    ///< Q_peak/Q_max
  std::string regime;      ///< "partial slip" (Q_peak < 0.999 Q_max) or "gross slip"
};

struct LoadPrediction {
  double preload = 0.0;     ///< P [N]
  double torque = 0.0;      ///< bolt torque per bolt [N m], 0 when the preload was given
  double P_star = 0.0;      ///< P/(K H A0)
  double separation = 0.0;  ///< mean-plane separation d [m] (d* sigma_s)
  double d_star = 0.0;
  double Q_max = 0.0;               ///< static friction force [N] (Eq. 4.7)
  double mu = 0.0;                  ///< Q_max/P
  double stiffness = 0.0;           ///< tangential stiffness at every reversal [N/m]
  double contact_area_ratio = 0.0;  ///< real over nominal area
  double mean_pressure = 0.0;       ///< P/A0 [Pa]
  /// Backbone in SI units (x [m], Q [N]): a ScaledBackbone over the rough flat's table.
  std::shared_ptr<const hysteresis::Backbone> backbone;
  std::vector<AmplitudePrediction> amplitudes;
};

struct JointPrediction {
  surface::SpectralMoments combined;
  double sigma = 0.0, eta = 0.0, R = 0.0, beta = 0.0, psi = 0.0;
  double force_scale = 0.0;  ///< K H A0 [N]
  std::vector<LoadPrediction> loads;
};

/// Predicts every load case of `c`. `progress(i, n)` (if given) is called after each.
[[nodiscard]] JointPrediction predict(
    const JointCase& c, const std::function<void(std::size_t, std::size_t)>& progress = {});

/// Predictions at one preload (SI) for given amplitudes.
[[nodiscard]] LoadPrediction predict_load(const surface::RoughFlat& flat, double preload,
                                          const std::vector<double>& amplitudes);

/// A steady symmetric fretting loop of amplitude delta_max on an SI backbone, from
/// (delta_max, Q_peak) down to -delta_max and back (Masing's rules), `n` points per
/// branch. Returns {delta, Q}.
[[nodiscard]] std::pair<std::vector<double>, std::vector<double>> steady_loop(
    const hysteresis::Backbone& backbone, double delta_max, std::size_t n = 100);

}  // namespace asperity::joint
