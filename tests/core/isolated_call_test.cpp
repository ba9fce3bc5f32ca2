// Work run in a child process with limits (isolated_call.h): its bytes come back whole, and a
// crash, a spin, an appetite for memory or an early end becomes a result the caller can report,
// within the time limit, with no process left behind.
#include "hirsute/core/isolated_call.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

namespace hirsute {
namespace {

using End = IsolatedCallResult::End;
using Clock = std::chrono::steady_clock;

IsolatedCallLimits shortLimits() {
  IsolatedCallLimits limits;
  limits.time = std::chrono::milliseconds(1500);
  limits.memoryBytes = std::size_t(256) << 20;
  return limits;
}

TEST(IsolatedCall, TheWorksBytesComeBackWhole) {
  // More than a pipe holds at once, with every byte value.
  std::string expected;
  for (int i = 0; i < 300'000; ++i) expected += static_cast<char>(i * 7);
  const IsolatedCallResult result = callIsolated([&] { return expected; }, shortLimits());
  ASSERT_EQ(result.end, End::Finished) << result.why;
  EXPECT_EQ(result.output, expected);
}

TEST(IsolatedCall, ACrashIsReportedWithItsSignal) {
  const IsolatedCallResult result = callIsolated(
      []() -> std::string {
        raise(SIGSEGV);
        return "not reached";
      },
      shortLimits());
  EXPECT_EQ(result.end, End::Crashed);
  EXPECT_EQ(result.signal, SIGSEGV);
  EXPECT_EQ(signalDescription(result.signal), "a segmentation fault");
  const IsolatedCallResult aborted =
      callIsolated([]() -> std::string { std::abort(); }, shortLimits());
  EXPECT_EQ(aborted.end, End::Crashed);
  EXPECT_EQ(aborted.signal, SIGABRT);
}

TEST(IsolatedCall, ASpinIsStoppedAtTheTimeLimit) {
  const auto start = Clock::now();
  const IsolatedCallResult result = callIsolated(
      []() -> std::string {
        for (;;) __asm__ volatile("" ::: "memory");  // a loop the compiler keeps
      },
      shortLimits());
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  EXPECT_EQ(result.end, End::TimedOut);
  EXPECT_GE(seconds, 1.4);
  EXPECT_LT(seconds, 5.0);
}

TEST(IsolatedCall, AChildThatSleepsIsStoppedWithItsGroup) {
  // A child blocked, not spinning (no processor time used): the wall clock stops it.
  const auto start = Clock::now();
  const IsolatedCallResult result = callIsolated(
      []() -> std::string {
        pause();
        return {};
      },
      shortLimits());
  EXPECT_EQ(result.end, End::TimedOut);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 5.0);
}

#if !defined(__SANITIZE_ADDRESS__)
#if !defined(__has_feature)
#define HIRSUTE_TEST_MEMORY_LIMIT 1
#elif !__has_feature(address_sanitizer)
#define HIRSUTE_TEST_MEMORY_LIMIT 1
#endif
#endif

#ifdef HIRSUTE_TEST_MEMORY_LIMIT
TEST(IsolatedCall, MemoryPastTheLimitIsReported) {
  const IsolatedCallResult result = callIsolated(
      []() -> std::string {
        std::vector<std::vector<char>> blocks;
        for (int i = 0; i < 64; ++i) blocks.emplace_back(std::size_t(16) << 20, 'x');  // 1 GB
        return "not reached";
      },
      shortLimits());
  EXPECT_EQ(result.end, End::OutOfMemory);
}
#endif

TEST(IsolatedCall, AnEndWithoutTheWholeAnswerIsAFailure) {
  const IsolatedCallResult result = callIsolated([]() -> std::string { _exit(0); }, shortLimits());
  EXPECT_EQ(result.end, End::Failed);
  EXPECT_NE(result.why.find("whole answer"), std::string::npos) << result.why;
  const IsolatedCallResult threw = callIsolated([]() -> std::string { throw 7; }, shortLimits());
  EXPECT_EQ(threw.end, End::Failed);
  EXPECT_NE(threw.why.find("exception"), std::string::npos) << threw.why;
}

TEST(IsolatedCall, AnAnswerPastItsLimitIsAFailure) {
  IsolatedCallLimits limits = shortLimits();
  limits.maxOutputBytes = 1000;
  const IsolatedCallResult result = callIsolated([] { return std::string(5000, 'x'); }, limits);
  EXPECT_EQ(result.end, End::Failed);
  EXPECT_TRUE(result.output.empty());
}

}  // namespace
}  // namespace hirsute
