#pragma once
// A console reporter that also remembers each benchmark's time per iteration, so that
// main() can print ratios against references measured in the same run.
#include <benchmark/benchmark.h>

#include <map>
#include <string>

namespace asperity::bench {

class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.iterations == 0) continue;
      // Seconds of CPU time per iteration.
      // Keyed by the name before any "/argument" suffix.
      const std::string name = run.benchmark_name();
      seconds_[name.substr(0, name.find('/'))] =
          run.GetAdjustedCPUTime() / benchmark::GetTimeUnitMultiplier(run.time_unit);
    }
    ConsoleReporter::ReportRuns(runs);
  }
  [[nodiscard]] const std::map<std::string, double>& seconds() const { return seconds_; }

 private:
  std::map<std::string, double> seconds_;
};

}  // namespace asperity::bench
