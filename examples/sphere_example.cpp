// Example: the micro-scale fretting experiment of Table 3.1/3.2 (steel ball on a steel
// flat) with the four physics-based partial slip models of chapter 3.
//
//   sphere_example [OUTPUT_DIR]
//
// Prints the model parameters of Table 3.2 in the thesis's reading: every model at the
// load P as given, with Hertz's interference and contact radius for that load
// ("the penetration for all the models is estimated to be 2.77 um", section 3.5) and
// its own friction coefficient. With an output directory (created if missing) it also
// writes the data of Fig. 3.2, 3.4, 3.6, 3.7 and 3.8 as CSV files; exits 1 with a
// message if they cannot be written whole.
#include <asperity/contact/asperity_model.hpp>
#include <asperity/core/error.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

using namespace asperity::contact;

namespace {

/// An output file that must be written whole: check() after writing reports failure.
class OutputFile {
 public:
  explicit OutputFile(std::filesystem::path path) : path_(std::move(path)), out_(path_) {}
  std::ofstream& stream() { return out_; }
  bool close() {
    out_.close();
    if (out_.fail()) {
      std::fprintf(stderr, "sphere_example: cannot write %s\n", path_.c_str());
      return false;
    }
    return true;
  }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
};

}  // namespace

int main(int argc, char** argv) try {
  const Material ball{.E = 207e9, .nu = 0.3, .G = 82.7e9, .H = 6.83e9};
  const Material flat{.E = 207e9, .nu = 0.3, .G = 82.7e9, .H = 7.48e9};
  const auto pair = ContactPair::combine(ball, flat, 2.5e-3);
  const FrictionParameters params{.mu_cfc = 0.284};
  const auto crit = pair.critical();
  std::printf("omega_c = %.3f um, a_c = %.4f mm, P_c = %.1f N\n", crit.omega_c * 1e6,
              crit.a_c * 1e3, crit.P_c);
  std::printf("Table 3.2 reading: P as given, Hertz's interference and radius for all models\n");
  for (double P : {35.0, 23.0}) {
    const auto hertz =
        PartialSlipModel::from_load(pair, ModelName::cfc, P, params, InterferenceReading::hertz);
    std::printf("P = %4.1f N: omega* = %.3f, 8G*a = %.2f N/um, mu =", P, hertz.omega_star(),
                hertz.K_T() * 1e-6);
    for (auto m : kAllModels) {
      const auto model =
          PartialSlipModel::from_load(pair, m, P, params, InterferenceReading::hertz);
      std::printf(" %s %.3f", std::string(to_string(m)).c_str(), model.mu());
    }
    std::printf("\n");
  }
  if (argc < 2) return 0;
  const std::filesystem::path dir = argv[1];
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    std::fprintf(stderr, "sphere_example: cannot create the output directory %s: %s\n", dir.c_str(),
                 ec ? ec.message().c_str() : "it is not a directory");
    return 1;
  }
  // Fig. 3.2 and 3.4: P/P_c and mu against omega/omega_c.
  OutputFile fig32(dir / "fig_3_2_3_4.csv");
  auto& f32 = fig32.stream();
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
  OutputFile loops_file(dir / "fig_3_6_3_7.csv");
  OutputFile energy_file(dir / "fig_3_8.csv");
  auto& loops = loops_file.stream();
  auto& energy = energy_file.stream();
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
  const bool written = fig32.close() && loops_file.close() && energy_file.close();
  if (written) std::printf("wrote %s/{fig_3_2_3_4,fig_3_6_3_7,fig_3_8}.csv\n", dir.c_str());
  return written ? 0 : 1;
} catch (const asperity::Error& e) {
  std::fprintf(stderr, "sphere_example: %s\n", e.what());
  return 1;
}
