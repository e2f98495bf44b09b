// Benchmarks of issue 14 (performance at scale), each with a baseline measured in the
// same run (main() in asperity_bench.cpp prints the ratios of the medians):
//   BM_FileBytes/N            reading the bytes of an N-point profile file (baseline)
//   BM_ProfileRead/N          parsing it into a profile (streamed, from_chars)
//   BM_ProfileFilter/N        the ISO 16610-21 band-pass (lc 0.8 mm, ls 20 um, FFT);
//                             target: at most 2x BM_ProfileRead
//   BM_ProfileFilterDirect/N  the same by direct convolution (the reference path)
//   BM_HistoryRead/N          an N-row displacement history CSV (streamed)
//   BM_HistoryWrite/N         writing N rows of two columns (chunked)
//   BM_ArealMomentsThreads    the rows and columns of a 650 x 650 X3P map on every core
//   BM_ArealMomentsOneThread  the same profiles one after another (baseline)
//   BM_PredictThreads         the four load cases of the steel 420 joint on every core
//   BM_PredictOneThread       the same load cases one after another (baseline)
//   BM_DynamicsSummaryOnly    1000 harmonic cycles keeping what the summary needs
//   BM_DynamicsFullRecord     the same run keeping the whole trajectory (baseline)
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "asperity/core/csv.hpp"
#include "asperity/dynamics/case.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/roughness.hpp"

#ifndef ASPERITY_SOURCE_DIR
#define ASPERITY_SOURCE_DIR "."
#endif

namespace {

using namespace asperity;

const std::filesystem::path& scratch() {
  static const auto dir = [] {
    auto d = std::filesystem::temp_directory_path() / fmt::format("asperity_bench_{}", ::getpid());
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

// A rough profile of n points at dx = 1 um (x[mm],z[um]), written once per n.
std::string profile_file(std::size_t n) {
  const auto path = (scratch() / fmt::format("profile_{}.csv", n)).string();
  if (std::filesystem::exists(path)) return path;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  fmt::memory_buffer buf;
  fmt::format_to(std::back_inserter(buf), "x[mm],z[um]\n");
  double a = 0.0, b = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    a = 0.95 * a + g(rng);  // correlated over ~20 points
    b = 0.999 * b + 0.05 * g(rng);
    fmt::format_to(std::back_inserter(buf), "{:.4f},{:.6f}\n", 1e-3 * static_cast<double>(i),
                   0.3 * a + b);
  }
  core::write_file_atomically(path, std::string(buf.data(), buf.size()));
  return path;
}

std::string history_file(std::size_t n) {
  const auto path = (scratch() / fmt::format("history_{}.csv", n)).string();
  if (std::filesystem::exists(path)) return path;
  fmt::memory_buffer buf;
  fmt::format_to(std::back_inserter(buf), "delta_star\n");
  for (std::size_t i = 0; i < n; ++i) {
    fmt::format_to(std::back_inserter(buf), "{:.9f}\n",
                   0.8 * std::sin(6.283185307179586 * static_cast<double>(i) / 1000.0));
  }
  core::write_file_atomically(path, std::string(buf.data(), buf.size()));
  return path;
}

void BM_FileBytes(benchmark::State& state) {
  const auto path = profile_file(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(surface::read_file_bytes(path));
}
void BM_ProfileRead(benchmark::State& state) {
  const auto path = profile_file(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(surface::read_profile_text(path));
}
void filter(benchmark::State& state, surface::Convolution conv) {
  const auto p = surface::level(
      surface::read_profile_text(profile_file(static_cast<std::size_t>(state.range(0)))),
      surface::Levelling::line);
  const surface::GaussianFilter f{.convolution = conv};
  for (auto _ : state) benchmark::DoNotOptimize(f.apply(p));
}
void BM_ProfileFilter(benchmark::State& state) {
  filter(state, surface::Convolution::fft);
}
void BM_ProfileFilterDirect(benchmark::State& state) {
  filter(state, surface::Convolution::direct);
}
BENCHMARK(BM_FileBytes)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProfileRead)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProfileFilter)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ProfileFilterDirect)->Arg(100000)->Unit(benchmark::kMillisecond);

void BM_HistoryRead(benchmark::State& state) {
  const auto path = history_file(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(core::read_csv_table(path));
}
void BM_HistoryWrite(benchmark::State& state) {
  const auto n = static_cast<std::size_t>(state.range(0));
  std::vector<std::vector<double>> cols(2, std::vector<double>(n));
  for (std::size_t i = 0; i < n; ++i) {
    cols[0][i] = std::sin(1e-3 * static_cast<double>(i));
    cols[1][i] = 1e-3 * std::cos(1e-3 * static_cast<double>(i));
  }
  const auto path = (scratch() / "forces.csv").string();
  for (auto _ : state) core::write_csv_table(path, {"delta_star", "Q_star"}, cols);
}
BENCHMARK(BM_HistoryRead)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_HistoryWrite)->Arg(1000000)->Unit(benchmark::kMillisecond);

const surface::HeightMap& areal_map() {
  static const auto m =
      surface::read_x3p(std::string(ASPERITY_SOURCE_DIR) + "/tests/data/mountainsmap-650x650.x3p");
  return m;
}
const surface::GaussianFilter kArealFilter{.lc = 20e-6, .ls = 2.5e-6};

void BM_ArealMomentsThreads(benchmark::State& state) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        surface::areal_moments(areal_map(), surface::Levelling::line, kArealFilter));
  }
}
void BM_ArealMomentsOneThread(benchmark::State& state) {
  const auto& map = areal_map();
  for (auto _ : state) {
    for (const auto& [profiles, spacing] :
         {std::pair{map.rows(), map.dx}, std::pair{map.columns(), map.dy}}) {
      for (const auto& p : profiles) {
        if (p.z.size() < kArealFilter.min_points(spacing)) continue;
        benchmark::DoNotOptimize(
            surface::profile_moments(p, surface::Levelling::line, kArealFilter));
      }
    }
  }
}
BENCHMARK(BM_ArealMomentsThreads)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ArealMomentsOneThread)->Unit(benchmark::kMillisecond)->UseRealTime();

const joint::JointCase& joint_case() {
  static const auto c = joint::read_case_file(std::string(ASPERITY_SOURCE_DIR) +
                                              "/examples/joints/steel420_two_bolts.toml");
  return c;
}
void BM_PredictThreads(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(joint::predict(joint_case()));
}
void BM_PredictOneThread(benchmark::State& state) {
  const auto& c = joint_case();
  for (auto _ : state) {
    const auto flat = c.rough_flat();
    for (double P : c.preloads) {
      benchmark::DoNotOptimize(
          joint::predict_load(flat, P, c.amplitudes, c.imposed, c.apparatus.compliance()));
    }
  }
}
BENCHMARK(BM_PredictThreads)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PredictOneThread)->Unit(benchmark::kMillisecond)->UseRealTime();

dynamics::DynamicsCase harmonic_case() {
  auto c = dynamics::read_case_file(std::string(ASPERITY_SOURCE_DIR) +
                                    "/examples/dynamics/harmonic_coulomb.toml");
  c.simulation.duration = 1000.0;  // 1000 cycles at frequency 1
  return c;
}
void BM_DynamicsSummaryOnly(benchmark::State& state) {
  const auto c = harmonic_case();
  for (auto _ : state) benchmark::DoNotOptimize(dynamics::run_case(c, {.summary_only = true}));
}
void BM_DynamicsFullRecord(benchmark::State& state) {
  const auto c = harmonic_case();
  for (auto _ : state) benchmark::DoNotOptimize(dynamics::run_case(c));
}
BENCHMARK(BM_DynamicsSummaryOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DynamicsFullRecord)->Unit(benchmark::kMillisecond);

}  // namespace
