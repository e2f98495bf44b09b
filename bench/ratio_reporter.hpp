#pragma once
// A console reporter that also remembers each benchmark's time per iteration, so that
// main() can print ratios against references measured in the same run. The time kept
// is the median over repetitions (--benchmark_repetitions), in every reporting mode:
// the "median" aggregate when Google Benchmark reports one (always so with
// --benchmark_report_aggregates_only, where no single repetition reaches a reporter),
// else the median of the repetitions seen. CPU time, or wall time for benchmarks
// that use real time (the multi-threaded ones: their CPU time is the main thread's).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace asperity::bench {

class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& run : runs) {
      if (run.error_occurred || run.iterations == 0) continue;
      repetitions_ = std::max<std::int64_t>(repetitions_, run.repetitions);
      const std::string key =
          run.run_name.function_name + (run.run_name.args.empty() ? "" : "/" + run.run_name.args);
      const bool real = run.run_name.time_type.find("real_time") != std::string::npos;
      const double t = (real ? run.GetAdjustedRealTime() : run.GetAdjustedCPUTime()) /
                       benchmark::GetTimeUnitMultiplier(run.time_unit);
      if (run.run_type == Run::RT_Iteration) {
        samples_[key].push_back(t);
      } else if (run.aggregate_name == "median") {
        medians_[key] = t;
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }

  /// Seconds per iteration, median over repetitions, by "name" or "name/args".
  [[nodiscard]] std::map<std::string, double> seconds() const {
    std::map<std::string, double> out = medians_;
    for (auto [key, v] : samples_) {
      if (out.count(key) != 0 || v.empty()) continue;
      std::sort(v.begin(), v.end());
      const std::size_t m = v.size() / 2;
      out[key] = v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
    }
    return out;
  }

  /// seconds() of one benchmark, 0 when it did not run (filtered out).
  [[nodiscard]] double seconds_of(const std::string& name) const {
    const auto t = seconds();
    const auto it = t.find(name);
    return it == t.end() ? 0.0 : it->second;
  }

  /// Repetitions per benchmark (--benchmark_repetitions; 1 by default).
  [[nodiscard]] std::int64_t repetitions() const { return repetitions_; }

 private:
  std::map<std::string, std::vector<double>> samples_;
  std::map<std::string, double> medians_;
  std::int64_t repetitions_ = 1;
};

}  // namespace asperity::bench
