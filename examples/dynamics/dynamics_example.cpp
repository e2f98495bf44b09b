// Thesis chapter 7 in a few lines of C++: the base-excited single-DOF system with
// three friction laws, their modal frequency and damping from the impulse response,
// and the energy balance of each run.
//
//   g++ -std=c++20 dynamics_example.cpp -lasperity -lfmt   (or link asperity::asperity)
#include <cmath>
#include <cstdio>
#include <memory>

#include "asperity/dynamics/analysis.hpp"
#include "asperity/hysteresis/backbones.hpp"

int main() {
  using namespace asperity::dynamics;
  const SystemParameters system{.epsilon = 0.032};  // Table 7.2

  // A Cattaneo-Mindlin-shaped backbone standing in for the rough flat's
  // (surface::RoughFlat::backbone gives the physics-based one).
  auto backbone = std::make_shared<asperity::hysteresis::FunctionBackbone>(
      [](double x) { return x >= 0.0108 ? 1.5 : 1.5 * (1.0 - std::pow(1.0 - x / 0.0108, 1.5)); },
      1.5, 1.5 * 1.5 / 0.0108);

  const NoFriction none;
  const Dankowicz dankowicz({.F_max = 1.5, .delta = 0.011});
  const HysteresisFriction physics(backbone);  // Masing memory (default)

  SimulationOptions options;
  options.duration = 200.0;
  options.output_interval = 0.05;
  options.locate_reversals = true;
  options.integrator.method = Method::bogacki_shampine_32;  // MATLAB ode23, as the thesis

  for (const FrictionModel* model :
       {static_cast<const FrictionModel*>(&none), static_cast<const FrictionModel*>(&dankowicz),
        static_cast<const FrictionModel*>(&physics)}) {
    const Trajectory tr = simulate(system, ImpulseExcitation{}, *model, options);
    const Periodogram spectrum(uniform_samples(tr, options.output_interval),
                               options.output_interval);
    const ModalEstimate m = modal_estimate(spectrum, 0.02, 5.0);
    const auto decay = free_decay(tr, 0.1);
    std::printf(
        "%-10s modal frequency %.4f, half-power damping %.4f; first cycle: f %.4f, "
        "zeta %.4f; energy balance error %.2e; %zu steps\n",
        model->name().c_str(), m.frequency, m.damping_ratio,
        decay.empty() ? 0.0 : decay.front().frequency,
        decay.empty() ? 0.0 : decay.front().damping_ratio, tr.energy_balance_error(),
        tr.stats.steps);
  }
  return 0;
}
