// Issue 11: one load case of the chapter 5 joint under its two bolts' pressure cones
// (170 patches, examples/joints/steel420_bolt_field.toml's geometry) against the same
// load case with the uniform pressure, in the same run: patches, separations, the summed
// table. Ratio printed by asperity_bench.cpp's main.
#include <benchmark/benchmark.h>

#include "asperity/joint/predict.hpp"
#include "asperity/joint/validation.hpp"

namespace {

using namespace asperity;

void BM_Ch5UniformLoad(benchmark::State& state) {
  const auto c = joint::chapter5_joint();
  for (auto _ : state) {
    auto lp = joint::predict_case_load(c, c.preloads[2]);
    benchmark::DoNotOptimize(lp);
  }
}
BENCHMARK(BM_Ch5UniformLoad)->Unit(benchmark::kMillisecond);

void BM_Ch5BoltFieldLoad(benchmark::State& state) {
  const auto c = joint::with_assumed_bolt_field(joint::chapter5_joint());
  for (auto _ : state) {
    auto lp = joint::predict_case_load(c, c.preloads[2]);
    benchmark::DoNotOptimize(lp);
  }
}
BENCHMARK(BM_Ch5BoltFieldLoad)->Unit(benchmark::kMillisecond);

}  // namespace
