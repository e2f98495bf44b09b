// Performance targets of the friction law (issue: "Coulomb-fast evaluation"), measured
// as ratios against references computed in the same run:
//   BM_RoughFlatForce            tabulated backbone through the Masing engine
//   BM_RoughFlatForceStrided     the same history in one Hysteresis::update_strided call
//   BM_RoughFlatForceQuadrature  the same forces with the backbone by direct quadrature
//   BM_TanhCoulombForce          regularized Coulomb F tanh(k v) (Eq. 7.2), k = 1e3: 73 % of
//                                its arguments are beyond |k v| = 22, where glibc's tanh
//                                returns +-1 at once (a cheap reference)
//   BM_TanhCoulombForceUnsaturated  the same with k scaled so that the history's largest
//                                velocity gives |k v| = 2: tanh always computed, as in a
//                                regularization resolving the velocities of an oscillation
//   BM_RoughFlatTableBuild       building the table for one load case
// Targets: RoughFlatForce <= 2x either Coulomb reference, >= 300x faster than the
// quadrature, table build < 5 ms. Each force benchmark processes one history sample per
// iteration. Ratios are of medians over repetitions (ratio_reporter.hpp): run with
// --benchmark_repetitions=N (any reporting mode).
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "asperity/hysteresis/masing.hpp"
#include "asperity/surface/rough_flat.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace asperity;

// Fig. 4.4 conditions with the BKE model: beta = 0.04, psi = 0.5, P* = 1e-3.
const surface::RoughFlat& flat() {
  static const surface::RoughFlat f(surface::RoughFlatParameters{.model = contact::ModelName::bke,
                                                                 .beta = 0.04,
                                                                 .psi = 0.5,
                                                                 .nu = 0.3,
                                                                 .G_over_E = 0.7 / 3.4});
  return f;
}

double separation() {
  static const double d = flat().separation_star(1e-3);
  return d;
}

// A random displacement history: random reversal points, 16 steps between them, within
// +-1.2 delta* (partial slip and some gross slip).
const std::vector<double>& history() {
  static const std::vector<double> h = [] {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uni(-1.2, 1.2);
    std::vector<double> out;
    double x = 0.0;
    while (out.size() < (1u << 16)) {
      const double target = uni(rng);
      for (int k = 1; k <= 16; ++k) out.push_back(x + (target - x) * k / 16.0);
      x = target;
    }
    return out;
  }();
  return h;
}

// The backbone by direct (adaptive) quadrature of Eq. 4.10 at every call.
class QuadratureBackbone final : public hysteresis::Backbone {
 public:
  QuadratureBackbone(const surface::RoughFlat& f, double d)
      : flat_(f), d_(d), limit_(f.static_friction_star(d)), k0_(f.stiffness_star(d)) {}
  double force(double x) const override { return flat_.loading_force_star(x, d_); }
  double displacement(double) const override { return 0.0; }
  double limit() const override { return limit_; }
  double initial_stiffness() const override { return k0_; }

 private:
  const surface::RoughFlat& flat_;
  double d_;
  double limit_;
  double k0_;
};

// One history sample per iteration through the Masing engine.
void run_history(benchmark::State& state, std::shared_ptr<const hysteresis::Backbone> backbone) {
  hysteresis::Hysteresis h(std::move(backbone));
  const auto& xs = history();
  std::size_t i = 0;
  double sink = 0.0;
  for (auto _ : state) {
    sink += h.update(xs[i]);
    i = (i + 1) & (xs.size() - 1);
  }
  benchmark::DoNotOptimize(sink);
}

void BM_RoughFlatForce(benchmark::State& state) {
  run_history(state, flat().backbone(separation()));
}
BENCHMARK(BM_RoughFlatForce);

// The same history through Hysteresis::update_strided, the batch path of Hysteresis::forces
// and the Python package's forces/displacements: one whole pass (65536 samples) per
// iteration; the ratio below is per sample.
void BM_RoughFlatForceStrided(benchmark::State& state) {
  hysteresis::Hysteresis h(flat().backbone(separation()));
  const auto& xs = history();
  std::vector<double> out(xs.size());
  for (auto _ : state) {
    h.update_strided(reinterpret_cast<const char*>(xs.data()), sizeof(double),
                     reinterpret_cast<char*>(out.data()), sizeof(double), xs.size());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(xs.size()));
}
BENCHMARK(BM_RoughFlatForceStrided);

void BM_RoughFlatForceQuadrature(benchmark::State& state) {
  run_history(state, std::make_shared<QuadratureBackbone>(flat(), separation()));
}
BENCHMARK(BM_RoughFlatForceQuadrature)->MinTime(0.5);

void BM_TanhCoulombForce(benchmark::State& state) {
  // F tanh(k v) with the velocity of the same history (finite differences).
  const auto& xs = history();
  const double F = 2e-3;
  const double k = 1e3;
  std::size_t i = 1;
  double sink = 0.0;
  for (auto _ : state) {
    const double v = xs[i] - xs[i - 1];
    sink += F * std::tanh(k * v);
    i = i + 1 < xs.size() ? i + 1 : 1;
  }
  benchmark::DoNotOptimize(sink);
}
BENCHMARK(BM_TanhCoulombForce);

void BM_TanhCoulombForceUnsaturated(benchmark::State& state) {
  const auto& xs = history();
  double v_max = 0.0;
  for (std::size_t i = 1; i < xs.size(); ++i) v_max = std::max(v_max, std::abs(xs[i] - xs[i - 1]));
  const double F = 2e-3;
  const double k = 2.0 / v_max;  // |k v| <= 2: tanh(2) = 0.964, never saturated
  std::size_t i = 1;
  double sink = 0.0;
  for (auto _ : state) {
    const double v = xs[i] - xs[i - 1];
    sink += F * std::tanh(k * v);
    i = i + 1 < xs.size() ? i + 1 : 1;
  }
  benchmark::DoNotOptimize(sink);
}
BENCHMARK(BM_TanhCoulombForceUnsaturated);

void BM_RoughFlatTableBuild(benchmark::State& state) {
  const double d = separation();
  for (auto _ : state) {
    auto table = flat().backbone(d);
    benchmark::DoNotOptimize(table);
  }
}
BENCHMARK(BM_RoughFlatTableBuild)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  asperity::bench::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto t = reporter.seconds();
  auto get = [&](const char* name) { return reporter.seconds_of(name); };
  const double table = get("BM_RoughFlatForce");
  const double quad = get("BM_RoughFlatForceQuadrature");
  const double tanh = get("BM_TanhCoulombForce");
  const double tanh_unsat = get("BM_TanhCoulombForceUnsaturated");
  const double build = get("BM_RoughFlatTableBuild");
  std::printf("\nRatios (same run, medians of %lld repetition(s)):\n",
              static_cast<long long>(reporter.repetitions()));
  if (table > 0 && tanh > 0) {
    std::printf("  RoughFlatForce / TanhCoulombForce       = %6.2f   (target <= 2)\n",
                table / tanh);
  }
  if (table > 0 && tanh_unsat > 0) {
    std::printf("  RoughFlatForce / TanhCoulombForceUnsaturated = %6.2f   (target <= 2)\n",
                table / tanh_unsat);
  }
  const double strided = get("BM_RoughFlatForceStrided") / static_cast<double>(history().size());
  if (table > 0 && strided > 0) {
    std::printf(
        "  RoughFlatForceStrided / RoughFlatForce  = %6.2f   (per sample: the batch path "
        "against update() one at a time)\n",
        strided / table);
  }
  if (table > 0 && quad > 0) {
    std::printf("  RoughFlatForceQuadrature / RoughFlatForce = %8.0f (target >= 300)\n",
                quad / table);
  }
  if (build > 0)
    std::printf("  table build                              = %6.2f ms (target < 5)\n",
                build * 1e3);
  // Issue 6: the physics-based law inside time integration at most 3x tanh-Coulomb
  // (bench/dynamics_bench.cpp: 1000 periods of the harmonic base motion, same options).
  const double dyn_tanh = get("BM_DynamicsHarmonic1000TanhCoulomb");
  const double dyn_phys = get("BM_DynamicsHarmonic1000Physics");
  if (dyn_tanh > 0 && dyn_phys > 0) {
    std::printf(
        "  Dynamics physics-based / tanh-Coulomb (1000 harmonic cycles) = %6.2f   (target <= 3)\n",
        dyn_phys / dyn_tanh);
  }
  const double dyn_tanh23 = get("BM_DynamicsHarmonic1000TanhCoulomb_BS23");
  const double dyn_phys23 = get("BM_DynamicsHarmonic1000Physics_BS23");
  if (dyn_tanh23 > 0 && dyn_phys23 > 0) {
    std::printf("  Dynamics physics-based / tanh-Coulomb (1000 harmonic cycles, BS23) = %6.2f\n",
                dyn_phys23 / dyn_tanh23);
  }
  // Issue 11 (bench/interface_bench.cpp): one ch. 5 load case under the bolt field (170
  // patches, one summed table) against the uniform one.
  const double uniform = get("BM_Ch5UniformLoad"), bolts = get("BM_Ch5BoltFieldLoad");
  if (uniform > 0 && bolts > 0) {
    std::printf("  Ch. 5 load case, bolt field / uniform = %6.1f   (%.0f ms against %.1f ms)\n",
                bolts / uniform, bolts * 1e3, uniform * 1e3);
  }
  for (const auto& [name, seconds] : t) {
    if (name.rfind("BM_Dynamics", 0) == 0) std::printf("  %s: %.3g s\n", name.c_str(), seconds);
  }
  // Issue 14 (bench/scale_bench.cpp): each against its same-run baseline.
  struct Ratio {
    std::string what, baseline, note;
  };
  std::vector<Ratio> ratios;
  for (const char* n : {"100000", "1000000"}) {
    const std::string s(n);
    ratios.push_back({"BM_ProfileRead/" + s, "BM_FileBytes/" + s, "parse / raw bytes"});
    ratios.push_back(
        {"BM_ProfileFilter/" + s, "BM_ProfileRead/" + s, "filter / read (target <= 2)"});
    ratios.push_back({"BM_ProfileFilterDirect/" + s, "BM_ProfileFilter/" + s,
                      "direct / FFT convolution (reference / fast path)"});
  }
  ratios.push_back(
      {"BM_ArealMomentsThreads", "BM_ArealMomentsOneThread", "all cores / one thread (wall time)"});
  ratios.push_back(
      {"BM_PredictThreads", "BM_PredictOneThread", "all cores / one thread (wall time)"});
  ratios.push_back(
      {"BM_DynamicsSummaryOnly", "BM_DynamicsFullRecord", "summary only / whole trajectory kept"});
  for (const auto& r : ratios) {
    const double a = get(r.what.c_str()), b = get(r.baseline.c_str());
    if (a > 0 && b > 0) {
      std::printf("  %s / %s = %6.3f   (%s)\n", r.what.c_str(), r.baseline.c_str(), a / b,
                  r.note.c_str());
    }
  }
  for (const char* n : {"BM_HistoryRead/1000000", "BM_HistoryWrite/1000000"}) {
    if (get(n) > 0) std::printf("  %s: %.1f ns per row\n", n, get(n) * 1e9 / 1e6);
  }
  benchmark::Shutdown();
  return 0;
}
