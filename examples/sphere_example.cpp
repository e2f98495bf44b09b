// Example: the micro-scale fretting experiment of Table 3.1/3.2 (steel ball on a steel
// flat) with the four physics-based partial slip models of chapter 3.
//
// Prints the model parameters of Table 3.2 and, with an output directory argument,
// writes the data of Fig. 3.2, 3.4, 3.6, 3.7 and 3.8 as CSV files.
#include <asperity/contact/asperity_model.hpp>
#include <cstdio>
#include <fstream>
#include <string>

using namespace asperity::contact;

int main(int argc, char** argv) {
  const Material ball{.E = 207e9, .nu = 0.3, .G = 82.7e9, .H = 6.83e9};
  const Material flat{.E = 207e9, .nu = 0.3, .G = 82.7e9, .H = 7.48e9};
  const auto pair = ContactPair::combine(ball, flat, 2.5e-3);
  const FrictionParameters params{.mu_cfc = 0.284};
  const auto crit = pair.critical();
  std::printf("omega_c = %.3f um, a_c = %.4f mm, P_c = %.1f N\n", crit.omega_c * 1e6,
              crit.a_c * 1e3, crit.P_c);
  for (double P : {35.0, 23.0}) {
    const auto hertz = PartialSlipModel::from_load(pair, ModelName::cfc, P, params);
    std::printf("P = %4.1f N: omega* = %.3f, 8G*a = %.2f N/um, mu =", P, hertz.omega_star(),
                hertz.K_T() * 1e-6);
    for (auto m : kAllModels) {
      const auto model =
          PartialSlipModel::from_interference_star(pair, m, hertz.omega_star(), params);
      std::printf(" %s %.3f", std::string(to_string(m)).c_str(), model.mu());
    }
    std::printf("\n");
  }
  if (argc < 2) return 0;
  const std::string dir = argv[1];
  // Fig. 3.2 and 3.4: P/P_c and mu against omega/omega_c.
  std::ofstream f32(dir + "/fig_3_2_3_4.csv");
  f32 << "omega_star,P_hertz,P_ceb,P_ke,P_bke,mu_cfc,mu_ceb,mu_ke,mu_bke\n";
  for (int i = 1; i <= 400; ++i) {
    const double w = 0.025 * i;
    f32 << w;
    for (auto law : {NormalLaw::hertz, NormalLaw::ceb, NormalLaw::ke, NormalLaw::bke}) {
      f32 << ',' << normal_load_star(law, w, pair.nu);
    }
    for (auto law : {FrictionLaw::cfc, FrictionLaw::ceb, FrictionLaw::ke, FrictionLaw::bke}) {
      f32 << ',' << friction_coefficient(law, w, pair.nu, params);
    }
    f32 << '\n';
  }
  // Fig. 3.6-3.8 at omega* = 0.6 in the thesis's normalization. The loops use
  // delta*_max = 0.2, where (as Fig. 3.7's text says) only CFC reaches gross slip.
  std::ofstream loops(dir + "/fig_3_6_3_7.csv");
  std::ofstream energy(dir + "/fig_3_8.csv");
  loops << "model,branch,delta_star,Q_star\n";
  energy << "model,delta_max_star,energy_star\n";
  for (auto m : kAllModels) {
    const auto model = PartialSlipModel::from_interference_star(pair, m, 0.6, params);
    const auto loop = model.contact().loop(0.2 * model.delta_scale(), 200);
    for (std::size_t i = 0; i < loop.delta.size(); ++i) {
      loops << to_string(m) << ',' << loop.branch[i] << ',' << loop.delta[i] / model.delta_scale()
            << ',' << loop.Q[i] / crit.P_c << '\n';
    }
    for (int i = 0; i <= 200; ++i) {
      const double d = 0.05 * i * model.delta_scale();
      energy << to_string(m) << ',' << d / model.delta_scale() << ','
             << model.contact().energy_per_cycle(d) / model.energy_scale() << '\n';
    }
  }
  return 0;
}
