// Example: the rough flat of the thesis's two-bolt steel 420 lap joint (chapter 5, Table
// 5.4's combined roughness, 170 mm^2 nominal area) at a 526 N preload, in SI units: its
// friction coefficient and tangential stiffness, and the friction force along a
// displacement history with an inner loop, followed by Masing's rules with loop memory.
//
//   rough_flat_hysteresis
//
// The same joint as `asperity flat --E1 200GPa ... --P 526N` in the README. Built with
// the library (examples/CMakeLists.txt) and, installed in share/asperity/examples, against
// the installed package (its CMakeLists.txt: find_package(asperity)).
#include <asperity/core/error.hpp>
#include <asperity/hysteresis/masing.hpp>
#include <asperity/surface/rough_flat.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  using asperity::contact::Material;
  using asperity::contact::ModelName;
  try {
    // Steel 420 (Table 5.3), both halves; combined roughness of Table 5.4.
    const Material steel{.E = 200e9, .nu = 0.24, .G = 80.7e9, .H = 5.8e9};
    const double sigma = 2.677e-6;  // m
    const double eta = 2.91e8;      // 1/m^2 (2.91e-4 um^-2)
    const double R = 30.14e-6;      // m
    const double A0 = 170e-6;       // m^2
    const double P = 526.0;         // N
    const auto flat = asperity::surface::RoughFlat::from_dimensional(steel, steel, sigma, eta, R,
                                                                     A0, ModelName::bke);

    // Q_l(delta) in newtons of delta in metres: the tabulated backbone at the separation
    // carrying P, scaled by sigma_s and K H A0.
    const auto backbone = flat.backbone_at_preload(P);
    const double Q_max = backbone->limit();
    std::printf("preload P = %.0f N: mu = Q_max/P = %.4f, k = %.1f N/um\n", P, Q_max / P,
                backbone->initial_stiffness() * 1e-6);
    const double amplitude = 0.25e-6;  // m, partial slip
    std::printf("at delta_max = 0.25 um: Q = %.2f N, energy per cycle = %.2f uJ\n",
                backbone->force(amplitude),
                asperity::hysteresis::energy_per_cycle(*backbone, amplitude) * 1e6);

    // A history in metres: 0 -> 0.25 um -> -0.25 um -> 0.1 um -> 0 (inner loop) -> 0.1 um
    // -> 0.25 um.
    const std::vector<double> turns{0.0, 0.25e-6, -0.25e-6, 0.1e-6, 0.0, 0.1e-6, 0.25e-6};
    std::vector<double> x;
    for (std::size_t i = 0; i + 1 < turns.size(); ++i) {
      for (int k = 0; k < 200; ++k) {
        x.push_back(turns[i] + (turns[i + 1] - turns[i]) * k / 200.0);
      }
    }
    x.push_back(turns.back());
    asperity::hysteresis::Hysteresis h(backbone);
    std::printf("    delta[um]        Q[N]\n");
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double Q = h.update(x[i]);
      if (i % 200 == 0) std::printf("%13.3f %11.3f\n", x[i] * 1e6, Q);
    }
    // Masing memory: the inner loop 0.1 -> 0 -> 0.1 um closes, and the path returns to the
    // virgin curve's point at 0.25 um (the first reversal).
    const double Q_virgin = backbone->force(amplitude);
    const bool closed = std::abs(h.Q() - Q_virgin) <= 1e-9 * Q_max;
    std::printf("back at 0.25 um: Q = %.3f N, virgin curve %.3f N: Masing memory %s\n", h.Q(),
                Q_virgin, closed ? "holds" : "FAILED");
    return closed ? 0 : 1;
  } catch (const asperity::Error& e) {
    std::fprintf(stderr, "rough_flat_hysteresis: %s\n", e.what());
    return 1;
  }
}
