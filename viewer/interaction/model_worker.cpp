#include "hirsute/viewer/interaction/model_worker.h"

#include <exception>

namespace hirsute {

ModelWorker::ModelWorker(ModelBuilder builder, std::function<void()> wake)
    : builder_(std::move(builder)), wake_(std::move(wake)), thread_([this] { run(); }) {}

ModelWorker::~ModelWorker() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    pending_.reset();
  }
  changed_.notify_all();
  thread_.join();
}

std::uint64_t ModelWorker::request(ModelRequest request) {
  std::uint64_t serial;
  {
    std::lock_guard lock(mutex_);
    pending_ = std::move(request);
    serial = pendingSerial_ = ++lastSerial_;
  }
  changed_.notify_all();
  return serial;
}

std::optional<ModelBuild> ModelWorker::take() {
  std::lock_guard lock(mutex_);
  std::optional<ModelBuild> out = std::move(finished_);
  finished_.reset();
  return out;
}

bool ModelWorker::busy() const {
  std::lock_guard lock(mutex_);
  return running_ || pending_.has_value();
}

bool ModelWorker::settled() const {
  std::lock_guard lock(mutex_);
  return !running_ && !pending_.has_value() && !finished_.has_value();
}

double ModelWorker::runningSeconds() const {
  std::lock_guard lock(mutex_);
  if (!running_) return 0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

void ModelWorker::run() {
  for (;;) {
    ModelRequest request;
    std::uint64_t serial;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return stopping_ || pending_.has_value(); });
      if (stopping_) return;
      request = std::move(*pending_);
      pending_.reset();
      serial = pendingSerial_;
      running_ = true;
      started_ = std::chrono::steady_clock::now();
    }
    progress_.stepsDone = 0;
    progress_.totalSteps = 0;
    progress_.phase = 0;
    ModelBuild build;
    auto start = std::chrono::steady_clock::now();
    try {
      build = builder_(request, progress_);
    } catch (const std::bad_alloc&) {
      build.error =
          "hirsute: error: out of memory while building the model: it made more than this "
          "machine holds; lower its size or the limits (--max-modules, --max-vertices, "
          "--max-hairs, --max-feathers)";
    } catch (const std::exception& e) {
      build.error = std::string("hirsute: error: ") + e.what();
    }
    build.request = request;
    build.serial = serial;
    build.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    {
      std::lock_guard lock(mutex_);
      finished_ = std::move(build);
      running_ = false;
    }
    if (wake_) wake_();
  }
}

}  // namespace hirsute
