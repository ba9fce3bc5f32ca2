// A few threads kept for the simulation's parallel loops (the narrow phase over candidate pairs,
// the broad phase's queries, the stems' internal dynamics): started once, woken for each loop,
// so that the 60-odd loops of a frame do not each pay for starting threads. A loop's work is
// split into chunks that the threads take in turn; what a chunk computes is written to places of
// its own (one slot per item), so that results never depend on the number of threads.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace hirsute::dynamics {

class WorkerPool {
 public:
  // `threads` threads in all, the caller's among them (0: one per core the machine reports;
  // 1: every loop runs on the caller's thread alone).
  explicit WorkerPool(int threads = 0);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }

  // Calls `body(begin, end)` over chunks of [0, count) of at most `grain` items, spread over the
  // threads, and returns when all are done. The chunks are disjoint and cover the range; which
  // thread runs which is not fixed. An exception in a chunk is thrown again here, after the rest.
  void forEach(std::size_t count, std::size_t grain,
               const std::function<void(std::size_t, std::size_t)>& body);

 private:
  void work();
  void runChunks();

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::uint64_t generation_ = 0;
  bool stopping_ = false;
  // The loop under way.
  const std::function<void(std::size_t, std::size_t)>* body_ = nullptr;
  std::size_t count_ = 0, grain_ = 1, next_ = 0;
  int busy_ = 0;  // workers still in the loop
  std::exception_ptr error_;
};

// `pool->forEach`, or the whole range on this thread where there is no pool.
inline void forEach(WorkerPool* pool, std::size_t count, std::size_t grain,
                    const std::function<void(std::size_t, std::size_t)>& body) {
  if (pool != nullptr)
    pool->forEach(count, grain, body);
  else if (count > 0)
    body(0, count);
}

}  // namespace hirsute::dynamics
