// core::parallel_for: every item runs once, the exception of the lowest index wins
// (what the sequential loop throws first), nested calls run on the calling thread; and
// the parallel load cases of joint::predict equal predict_load called one by one, the
// parallel rows and columns of areal_moments equal the profiles processed in order.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include "asperity/core/error.hpp"
#include "asperity/core/parallel.hpp"
#include "asperity/joint/case.hpp"
#include "asperity/joint/predict.hpp"
#include "asperity/surface/profile_io.hpp"
#include "asperity/surface/roughness.hpp"

namespace asperity::core {
namespace {

TEST(ParallelFor, EveryItemOnceInItsSlot) {
  EXPECT_GE(worker_count(), 1u);
  std::vector<int> hits(1000, 0);
  parallel_for(hits.size(), [&](std::size_t i) { hits[i] += static_cast<int>(i) + 1; });
  for (std::size_t i = 0; i < hits.size(); ++i) EXPECT_EQ(hits[i], static_cast<int>(i) + 1);
  parallel_for(0, [](std::size_t) { FAIL() << "no item for n = 0"; });
}

TEST(ParallelFor, LowestIndexExceptionWinsAndEveryItemStillRuns) {
  std::atomic<int> ran{0};
  try {
    parallel_for(64, [&](std::size_t i) {
      ++ran;
      if (i == 41) throw std::runtime_error("41");
      if (i == 7) throw InvalidInput("7");
    });
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_STREQ(e.what(), "7");
  }
  EXPECT_EQ(ran.load(), 64);
}

TEST(ParallelFor, NestedCallsComplete) {
  std::vector<std::vector<int>> out(8, std::vector<int>(8, 0));
  parallel_for(8, [&](std::size_t i) {
    parallel_for(8, [&](std::size_t j) { out[i][j] = static_cast<int>(i * 8 + j); });
  });
  for (std::size_t i = 0; i < 8; ++i) {
    for (std::size_t j = 0; j < 8; ++j) EXPECT_EQ(out[i][j], static_cast<int>(i * 8 + j));
  }
}

TEST(ParallelFor, SetWorkerCountIsValidatedAndHonoured) {
  const std::size_t before = worker_count();
  EXPECT_THROW(set_worker_count(0), InvalidInput);
  EXPECT_THROW(set_worker_count(257), InvalidInput);
  EXPECT_EQ(worker_count(), before);  // a refused value changes nothing
  set_worker_count(1);
  EXPECT_EQ(worker_count(), 1u);
  // One thread: every item runs on the calling thread, in index order.
  std::vector<std::size_t> order;
  parallel_for(100, [&](std::size_t i) { order.push_back(i); });
  ASSERT_EQ(order.size(), 100u);
  for (std::size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
  set_worker_count(before);
  EXPECT_EQ(worker_count(), before);
}

const std::string kData = ASPERITY_TEST_DATA_DIR;

TEST(ParallelFor, PredictEqualsTheLoadCasesOneByOne) {
  const auto c = joint::read_case_file(kData + "/../../examples/joints/steel420_two_bolts.toml");
  const auto p = joint::predict(c);
  const auto flat = c.rough_flat();
  ASSERT_EQ(p.loads.size(), c.preloads.size());
  for (std::size_t i = 0; i < c.preloads.size(); ++i) {
    const auto ref =
        joint::predict_load(flat, c.preloads[i], c.amplitudes, c.imposed, c.apparatus.compliance());
    EXPECT_EQ(p.loads[i].preload, ref.preload);
    EXPECT_EQ(p.loads[i].mu, ref.mu);
    EXPECT_EQ(p.loads[i].stiffness, ref.stiffness);
    ASSERT_EQ(p.loads[i].amplitudes.size(), ref.amplitudes.size());
    for (std::size_t k = 0; k < ref.amplitudes.size(); ++k) {
      EXPECT_EQ(p.loads[i].amplitudes[k].energy, ref.amplitudes[k].energy);
      EXPECT_EQ(p.loads[i].amplitudes[k].Q_peak, ref.amplitudes[k].Q_peak);
    }
  }
}

TEST(ParallelFor, ArealMomentsEqualTheRowsAndColumnsInOrder) {
  const auto map = surface::read_x3p(kData + "/mountainsmap-650x650.x3p");
  const surface::GaussianFilter f{.lc = 20e-6, .ls = 2.5e-6};
  const auto d = surface::areal_moments(map, surface::Levelling::line, f);
  for (const auto& [profiles, spacing, m, count] :
       {std::tuple{map.rows(), map.dx, d.x, d.x_profiles},
        std::tuple{map.columns(), map.dy, d.y, d.y_profiles}}) {
    std::vector<surface::SpectralMoments> ms;
    std::vector<double> ws;
    for (const auto& p : profiles) {
      if (p.z.size() < f.min_points(spacing)) continue;
      const auto r = surface::process_profile(p, surface::Levelling::line, f);
      ms.push_back(r.moments);
      ws.push_back(static_cast<double>(r.filtered.z.size()));
    }
    EXPECT_EQ(count, ms.size());
    const auto ref = surface::average_moments(ms, ws);
    EXPECT_EQ(m.m0, ref.m0);
    EXPECT_EQ(m.m2, ref.m2);
    EXPECT_EQ(m.m4, ref.m4);
  }
}

}  // namespace
}  // namespace asperity::core
