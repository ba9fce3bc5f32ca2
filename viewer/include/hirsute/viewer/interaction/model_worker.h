// The viewer's background builder: derivation, interpretation and the organs' stages run on a
// thread of their own, so that the window keeps drawing (and the camera keeps moving) while a big
// plant is built. Requests are coalesced: while one build runs, only the newest request waits, and the
// ones before it are dropped. No GL here; the window uploads what comes back.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hirsute/interpreter/scene.h"
#include "hirsute/interpreter/view_settings.h"

namespace hirsute {

// What to build: the derivation step to show, and `#define` constants to change.
struct ModelRequest {
  std::optional<int> steps;  // none: the file's derivation length
  std::map<std::string, std::string> defines;
  bool operator==(const ModelRequest&) const = default;
};

// How far a build has got, written by the builder and read by the window.
struct BuildProgress {
  std::atomic<int> stepsDone{0};
  std::atomic<int> totalSteps{0};
  // 0 reading, 1 deriving, 2 interpreting, 3 + k the stage of organStages()[k]
  std::atomic<int> phase{0};
};

// A built model, ready for upload.
struct ViewerModel {
  Scene scene;
  Bounds bounds;
  ViewSettings view;
  bool materialMode = false;
  int steps = 0;             // the derivation step shown
  int derivationLength = 0;  // the file's
  // The `function:`/`function set:` and `curve:` files the derivation read (the editors').
  std::vector<std::filesystem::path> functionFiles, curveFiles;
  std::vector<int> functionSamples;  // the count on each `function:` line (0: none)
};

struct ModelBuild {
  std::shared_ptr<const ViewerModel> model;  // null after an error
  std::string error;                         // "file:line:col: error: …" after an error
  ModelRequest request;
  std::uint64_t serial = 0;  // as request() returned it
  double seconds = 0;        // how long the build took
};

using ModelBuilder = std::function<ModelBuild(const ModelRequest&, BuildProgress&)>;

class ModelWorker {
 public:
  // `wake` is called (from the worker's thread) when a build has finished, to wake the window.
  ModelWorker(ModelBuilder builder, std::function<void()> wake = {});
  ~ModelWorker();
  ModelWorker(const ModelWorker&) = delete;
  ModelWorker& operator=(const ModelWorker&) = delete;

  // Asks for a build; replaces a request that has not started yet. Returns the request's serial
  // number (1, 2, …), which its build carries.
  std::uint64_t request(ModelRequest request);
  // The newest finished build not yet taken.
  std::optional<ModelBuild> take();
  // A build is running or waiting.
  bool busy() const;
  // Nothing is running, waiting, or finished and not yet taken: what was asked for is shown.
  bool settled() const;
  // While busy: seconds since the running build started, and its progress.
  double runningSeconds() const;
  const BuildProgress& progress() const { return progress_; }

 private:
  void run();

  ModelBuilder builder_;
  std::function<void()> wake_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<ModelRequest> pending_;
  std::uint64_t pendingSerial_ = 0, lastSerial_ = 0;
  std::optional<ModelBuild> finished_;
  bool running_ = false, stopping_ = false;
  std::chrono::steady_clock::time_point started_;
  BuildProgress progress_;
  std::thread thread_;
};

}  // namespace hirsute
