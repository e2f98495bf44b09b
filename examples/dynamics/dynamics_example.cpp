// Thesis chapter 7 in a few lines of C++: the base-excited single-DOF system with
// three friction laws, their modal frequency and damping from the impulse response,
// and the energy balance of each run.
//
//   g++ -std=c++20 dynamics_example.cpp -lasperity -lfmt   (or link asperity::asperity)
#include <cstdio>
#include <memory>

#include "asperity/dynamics/analysis.hpp"
#include "asperity/dynamics/epb.hpp"

int main() {
  using namespace asperity::dynamics;
  const SystemParameters system{.epsilon = 0.032};  // Table 7.2

  // The physics-based law: the rough flat of Table 7.2 (rough contact, BKE asperities)
  // through Masing's rules. Assumed (Table 7.2 gives no A0; docs/dynamics.md):
  // A0 = 1 cm^2, P = 9 N, structure k = 1e5 N/m, displacement scale A = 18 um.
  EpbContact rough = table_7_2_rough();
  rough.A0 = 1e-4;
  rough.P = 9.0;
  const auto physics = make_physics_based(epb_backbone(rough), 1e5, 18e-6);

  const NoFriction none;
  const Dankowicz dankowicz({.F_max = 1.5, .delta = 0.011});

  SimulationOptions options;
  options.duration = 200.0;
  options.output_interval = 0.05;
  options.locate_reversals = true;
  // Dormand-Prince 5(4) (the default) at the thesis's tolerances, rtol 1e-6, atol 1e-7.

  for (const FrictionModel* model :
       {static_cast<const FrictionModel*>(&none), static_cast<const FrictionModel*>(&dankowicz),
        static_cast<const FrictionModel*>(physics.get())}) {
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
