// A program run by runChild (hirsute/core/child_process.h) while its caller shows how far it has
// got: whileRunning is called as it runs, and its time limit holds all the same.
#include "hirsute/core/child_process.h"

#include <gtest/gtest.h>

#include <chrono>

namespace hirsute {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

ChildRequest sleeping(const char* seconds) {
  ChildRequest request;
  request.program = "/bin/sleep";
  request.arguments = {"sleep", seconds};
  request.environment = environmentWith({});
  return request;
}

TEST(ChildProcess, WhileRunningIsCalledAsTheChildRuns) {
  ChildRequest request = sleeping("1");
  int calls = 0;
  request.whileRunning = [&calls] { ++calls; };
  const ChildResult result = runChild(request);
  ASSERT_TRUE(result.started) << result.failure;
  EXPECT_EQ(result.exitStatus, 0);
  // A second at a call every quarter of one.
  EXPECT_GE(calls, 3);
  EXPECT_LE(calls, 5);
}

TEST(ChildProcess, TheTimeLimitHoldsWhileItIsCalled) {
  ChildRequest request = sleeping("30");
  request.timeLimit = 500ms;
  int calls = 0;
  request.whileRunning = [&calls] { ++calls; };
  const auto started = Clock::now();
  const ChildResult result = runChild(request);
  EXPECT_TRUE(result.timedOut);
  EXPECT_LT(Clock::now() - started, 5s);
  EXPECT_GE(calls, 1);
}

}  // namespace
}  // namespace hirsute
