// The viewer's background builder: builds run off the caller's thread, and requests made while
// one runs are coalesced to the newest.
#include "hirsute/viewer/interaction/model_worker.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

namespace hirsute {
namespace {

using namespace std::chrono_literals;

std::optional<ModelBuild> waitFor(ModelWorker& worker) {
  for (int i = 0; i < 500; ++i) {
    if (auto b = worker.take()) return b;
    std::this_thread::sleep_for(5ms);
  }
  return std::nullopt;
}

TEST(ModelWorkerTest, BuildsOffTheCallersThreadAndWakesIt) {
  std::thread::id builderThread;
  std::atomic<int> wakes{0};
  ModelWorker worker(
      [&](const ModelRequest& r, BuildProgress&) {
        builderThread = std::this_thread::get_id();
        ModelBuild b;
        auto model = std::make_shared<ViewerModel>();
        model->steps = r.steps.value_or(-1);
        b.model = model;
        return b;
      },
      [&] { ++wakes; });
  std::uint64_t serial = worker.request({3, {}});
  auto build = waitFor(worker);
  ASSERT_TRUE(build && build->model);
  EXPECT_EQ(build->model->steps, 3);
  EXPECT_EQ(build->serial, serial);
  EXPECT_NE(builderThread, std::this_thread::get_id());
  for (int i = 0; i < 200 && wakes == 0; ++i) std::this_thread::sleep_for(5ms);
  EXPECT_EQ(wakes, 1);
  EXPECT_FALSE(worker.busy());
}

TEST(ModelWorkerTest, RequestsWhileBusyAreCoalescedToTheNewest) {
  std::mutex gate;
  gate.lock();
  std::vector<int> built;
  std::mutex builtMutex;
  ModelWorker worker([&](const ModelRequest& r, BuildProgress&) {
    if (r.steps == 0) std::lock_guard wait(gate);  // the first build waits for the gate
    std::lock_guard lock(builtMutex);
    built.push_back(*r.steps);
    return ModelBuild{};
  });
  worker.request({0, {}});
  std::this_thread::sleep_for(20ms);
  for (int s = 1; s <= 5; ++s) worker.request({s, {}});
  EXPECT_TRUE(worker.busy());
  gate.unlock();
  for (int i = 0; i < 500 && worker.busy(); ++i) std::this_thread::sleep_for(5ms);
  std::lock_guard lock(builtMutex);
  EXPECT_EQ(built, (std::vector<int>{0, 5}));
}

TEST(ModelWorkerTest, AFinishedBuildNotYetTakenIsNotSettled) {
  ModelWorker worker([](const ModelRequest&, BuildProgress&) { return ModelBuild{}; });
  EXPECT_TRUE(worker.settled());
  worker.request({});
  for (int i = 0; i < 500 && worker.busy(); ++i) std::this_thread::sleep_for(5ms);
  ASSERT_FALSE(worker.busy());
  // Built, but the window has not shown it yet: a script must not take a picture now.
  EXPECT_FALSE(worker.settled());
  EXPECT_TRUE(worker.take().has_value());
  EXPECT_TRUE(worker.settled());
}

TEST(ModelWorkerTest, AnErrorIsABuildWithoutAModel) {
  ModelWorker worker(
      [](const ModelRequest&, BuildProgress&) -> ModelBuild { throw std::runtime_error("boom"); });
  worker.request({});
  auto build = waitFor(worker);
  ASSERT_TRUE(build);
  EXPECT_FALSE(build->model);
  EXPECT_EQ(build->error, "hirsute: error: boom");
}

}  // namespace
}  // namespace hirsute
