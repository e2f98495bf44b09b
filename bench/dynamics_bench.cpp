// Benchmarks of the dynamics layer (issue 6): a harmonic run of 1000 cycles with the
// physics-based law (the rough flat of Table 7.2, rough contact, through the Masing
// engine) against the same run with the tanh-Coulomb law (Eq. 7.2). Target: the
// physics-based run costs at most 3x the Coulomb run (compare the two BM_Dynamics
// lines of the same run; main() in asperity_bench.cpp prints them).
//
// Each iteration integrates 1000 non-dimensional periods of sin(2 pi tau) with the
// default Dormand-Prince 5(4) (and, for the _BS23 variants, MATLAB ode23's method) at
// rtol 1e-6, atol 1e-7, recording every 0.05 tau.
#include <benchmark/benchmark.h>

#include "asperity/dynamics/epb.hpp"
#include "asperity/dynamics/system.hpp"

namespace {

using namespace asperity::dynamics;

SimulationOptions options(Method m) {
  SimulationOptions o;
  o.duration = 1000.0;
  o.integrator.method = m;
  o.output_interval = 0.05;
  return o;
}

void run(benchmark::State& state, const FrictionModel& model, Method m) {
  std::size_t steps = 0, evals = 0;
  for (auto _ : state) {
    const auto tr = simulate({.epsilon = 0.032}, HarmonicExcitation{}, model, options(m));
    steps = tr.stats.steps;
    evals = tr.force_evaluations;
    benchmark::DoNotOptimize(tr.u.back());
  }
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["force_evaluations"] = static_cast<double>(evals);
}

const FrictionModel& physics() {
  // Table 7.2 rough contact; A0 = 1 cm^2, A = 18 um, P = 5 k A (examples/dynamics/README.md).
  static const auto model = [] {
    auto c = table_7_2_rough();
    c.A0 = 1e-4;
    c.P = 5.0 * 1e5 * 18e-6;
    return make_physics_based(epb_backbone(c), 1e5, 18e-6);
  }();
  return *model;
}

void BM_DynamicsHarmonic1000TanhCoulomb(benchmark::State& state) {
  run(state, RegularizedCoulomb({}), Method::dormand_prince_54);
}
void BM_DynamicsHarmonic1000Physics(benchmark::State& state) {
  run(state, physics(), Method::dormand_prince_54);
}
void BM_DynamicsHarmonic1000Dankowicz(benchmark::State& state) {
  run(state, Dankowicz({}), Method::dormand_prince_54);
}
void BM_DynamicsHarmonic1000TanhCoulomb_BS23(benchmark::State& state) {
  run(state, RegularizedCoulomb({}), Method::bogacki_shampine_32);
}
void BM_DynamicsHarmonic1000Physics_BS23(benchmark::State& state) {
  run(state, physics(), Method::bogacki_shampine_32);
}

BENCHMARK(BM_DynamicsHarmonic1000TanhCoulomb)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DynamicsHarmonic1000Physics)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DynamicsHarmonic1000Dankowicz)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DynamicsHarmonic1000TanhCoulomb_BS23)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DynamicsHarmonic1000Physics_BS23)->Unit(benchmark::kMillisecond);

}  // namespace
