// A run that keeps only what its summary needs (run_case summary_only: a harmonic
// response keeps its last loop_cycles + 1 periods, the running totals cover the rest)
// and streams its samples through a sink gives the same summary, to the bit, as the
// run that keeps the whole trajectory; the streamed rows are the rows of
// time_history_columns() of the whole trajectory.
#include <gtest/gtest.h>

#include <string>
#include <variant>
#include <vector>

#include "asperity/dynamics/case.hpp"

namespace asperity::dynamics {
namespace {

const std::string kExamples = std::string(ASPERITY_TEST_DATA_DIR) + "/../../examples/dynamics/";

// Exact equality of two summaries (same keys in the same order, same values).
void expect_same(const SummaryValue& a, const SummaryValue& b, const std::string& path) {
  ASSERT_EQ(a.data.index(), b.data.index()) << path;
  if (const auto* o = std::get_if<SummaryObject>(&a.data)) {
    const auto& p = std::get<SummaryObject>(b.data);
    ASSERT_EQ(o->size(), p.size()) << path;
    for (std::size_t i = 0; i < o->size(); ++i) {
      ASSERT_EQ((*o)[i].first, p[i].first) << path;
      expect_same((*o)[i].second, p[i].second, path + "." + (*o)[i].first);
    }
  } else if (const auto* v = std::get_if<SummaryArray>(&a.data)) {
    const auto& w = std::get<SummaryArray>(b.data);
    ASSERT_EQ(v->size(), w.size()) << path;
    for (std::size_t i = 0; i < v->size(); ++i) {
      expect_same((*v)[i], w[i], path + "[" + std::to_string(i) + "]");
    }
  } else if (const auto* d = std::get_if<double>(&a.data)) {
    EXPECT_EQ(*d, std::get<double>(b.data)) << path;
  } else if (const auto* s = std::get_if<std::string>(&a.data)) {
    EXPECT_EQ(*s, std::get<std::string>(b.data)) << path;
  } else if (const auto* i = std::get_if<std::int64_t>(&a.data)) {
    EXPECT_EQ(*i, std::get<std::int64_t>(b.data)) << path;
  } else if (const auto* f = std::get_if<bool>(&a.data)) {
    EXPECT_EQ(*f, std::get<bool>(b.data)) << path;
  }
}

TEST(DynamicsStreaming, SummaryOnlyRunEqualsTheFullRunAndStreamsEveryRow) {
  for (const char* name : {"harmonic_coulomb", "harmonic_dankowicz", "harmonic_mindlin",
                           "impulse_dankowicz", "ramp_coulomb_soft"}) {
    SCOPED_TRACE(name);
    const DynamicsCase c = read_case_file(kExamples + name + ".toml");
    const CaseResult full = run_case(c);
    std::vector<std::vector<double>> rows;
    std::vector<double> row;
    RunOptions lean{.summary_only = true};
    lean.sink = [&](const TrajectorySample& x) {
      time_history_row(c, x, row);
      rows.push_back(row);
    };
    const CaseResult kept = run_case(c, lean);
    expect_same(SummaryValue(full.summary), SummaryValue(kept.summary), "summary");
    EXPECT_EQ(full.trajectory.energy_balance_error(), kept.trajectory.energy_balance_error());
    // A harmonic run keeps (loop_cycles + 1) / frequency of its duration (60 tau).
    if (c.excitation_name == "harmonic") {
      EXPECT_LT(kept.trajectory.size(), full.trajectory.size() / 5);
    } else {
      EXPECT_EQ(kept.trajectory.size(), full.trajectory.size());
    }
    const auto cols = time_history_columns(c, full.trajectory);
    const auto names = time_history_names(c);
    ASSERT_EQ(names.size(), cols.size());
    for (std::size_t j = 0; j < cols.size(); ++j) EXPECT_EQ(names[j], cols[j].name);
    ASSERT_EQ(rows.size(), full.trajectory.size());
    EXPECT_EQ(kept.trajectory.samples, rows.size());
    for (std::size_t k = 0; k < rows.size(); ++k) {
      ASSERT_EQ(rows[k].size(), cols.size());
      for (std::size_t j = 0; j < cols.size(); ++j) {
        ASSERT_EQ(rows[k][j], cols[j].values[k]) << cols[j].name << " sample " << k;
      }
    }
  }
}

}  // namespace
}  // namespace asperity::dynamics
