// run_guarded (src/cli/common.cpp): every exception becomes a one-line message and an exit
// code; none escapes to abort the CLI (exit 134).
#include <gtest/gtest.h>

#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "asperity/core/error.hpp"
#include "common.hpp"

namespace asperity::cli {
namespace {

struct Outcome {
  int code;
  std::string out, err;
};

template <class Body>
Outcome guarded(Body body) {
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const int code = run_guarded([&](std::string& out) {
    out = "result\n";
    body();
  });
  Outcome o{code, testing::internal::GetCapturedStdout(), testing::internal::GetCapturedStderr()};
  return o;
}

TEST(RunGuarded, ExitCodesAndMessages) {
  auto o = guarded([] {});
  EXPECT_EQ(o.code, 0);
  EXPECT_EQ(o.out, "result\n");
  o = guarded([] { throw InvalidInput("--x = 1: must be > 2"); });
  EXPECT_EQ(o.code, 2);
  EXPECT_EQ(o.err, "asperity: error: --x = 1: must be > 2\n");
  EXPECT_EQ(o.out, "");  // nothing printed on failure
  o = guarded([] { throw NumericalError("no root"); });
  EXPECT_EQ(o.code, 3);
  o = guarded([] { throw Error("gnuplot failed"); });
  EXPECT_EQ(o.code, 1);
}

TEST(RunGuarded, MemoryExhaustionIsAnErrorNotAnAbort) {
  // std::bad_alloc: the input asked for too much (README: exit 2, like bad input).
  auto o = guarded([] { throw std::bad_alloc(); });
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("out of memory"), std::string::npos) << o.err;
  EXPECT_EQ(o.out, "");
  // A container asked for more elements than it can hold: the same cause.
  o = guarded([] {
    std::vector<double> v;
    v.resize(v.max_size() + 1);
  });
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.err.find("make the problem smaller"), std::string::npos) << o.err;
}

TEST(RunGuarded, AnyOtherExceptionGivesExit1WithItsMessage) {
  auto o = guarded([] { throw std::out_of_range("map::at"); });
  EXPECT_EQ(o.code, 1);
  EXPECT_EQ(o.err, "asperity: error: unexpected failure: map::at\n");
  o = guarded([] { throw std::runtime_error("boom"); });
  EXPECT_EQ(o.code, 1);
  EXPECT_NE(o.err.find("boom"), std::string::npos);
}

}  // namespace
}  // namespace asperity::cli
