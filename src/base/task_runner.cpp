// The world's own thread pool and the dispatch to an engine's job system (task_runner.h).
//
// A loop is a job: its ranges are claimed from one 64-bit counter that holds the job's generation,
// its next range and its number of ranges, so a worker that wakes late, after its job is over,
// cannot claim a range of the next one. Workers spin for a while after a job (the solver's
// loops come microseconds apart, one per colour and pass) and then sleep on the generation.
#include "base/task_runner.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__)
#include <immintrin.h>
#endif

namespace collide::detail {

namespace {

inline void pause() {
#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

// How long a worker spins between jobs before it sleeps: the stages of a step come a few
// microseconds to a few hundred apart, and waking a sleeping thread costs a system call on one
// side and tens of microseconds on the other.
constexpr auto kSpinBeforeSleep = std::chrono::microseconds(1000);
constexpr int kSpinsPerClockRead = 64;

}  // namespace

class ThreadPool {
 public:
  explicit ThreadPool(int workerCount) {
    for (int worker = 1; worker < workerCount; ++worker)
      threads_.emplace_back([this, worker] { workerLoop(static_cast<std::uint32_t>(worker)); });
  }

  ~ThreadPool() {
    stop_.store(true);
    generation_.fetch_add(1);
    generation_.notify_all();
    for (std::thread& thread : threads_) thread.join();
  }

  // On the calling thread as worker 0, with the pool's threads.
  void run(std::uint32_t count, std::uint32_t range, TaskFunction* task, void* context) {
    // The claim counter holds at most kMaxRanges ranges: longer ones if need be.
    range = std::max(range, (count + kMaxRanges - 1) / kMaxRanges);
    const std::uint32_t ranges = (count + range - 1) / range;
    const std::uint32_t generation = generation_.load(std::memory_order_relaxed) + 1;
    task_.store(task, std::memory_order_relaxed);
    context_.store(context, std::memory_order_relaxed);
    count_.store(count, std::memory_order_relaxed);
    range_.store(range, std::memory_order_relaxed);
    done_.store(0, std::memory_order_relaxed);
    claim_.store(packClaim(generation, 0, ranges), std::memory_order_release);
    generation_.store(generation);
    if (sleepers_.load() > 0) generation_.notify_all();
    work(generation, 0);
    while (done_.load(std::memory_order_acquire) != ranges) pause();
  }

 private:
  static constexpr std::uint32_t kMaxRanges = 0xFFFF;
  // generation (32 bits), the next range (16), the job's ranges (16).
  static std::uint64_t packClaim(std::uint32_t generation, std::uint32_t next, std::uint32_t ranges) {
    return std::uint64_t{generation} << 32 | std::uint64_t{next} << 16 | ranges;
  }

  void workerLoop(std::uint32_t worker) {
    std::uint32_t seen = 0;
    for (;;) {
      int spins = 0;
      auto spinStart = std::chrono::steady_clock::now();
      while (generation_.load(std::memory_order_acquire) == seen && !stop_.load(std::memory_order_relaxed)) {
        pause();
        if (++spins % kSpinsPerClockRead != 0) continue;
        // Now and then the core goes to whoever else waits for it: with more workers than cores,
        // a spinning worker would hold up the one with a range in hand.
        std::this_thread::yield();
        if (std::chrono::steady_clock::now() - spinStart < kSpinBeforeSleep) continue;
        sleepers_.fetch_add(1);
        generation_.wait(seen);
        sleepers_.fetch_sub(1);
        spinStart = std::chrono::steady_clock::now();
      }
      if (stop_.load()) return;
      seen = generation_.load(std::memory_order_acquire);
      work(seen, worker);
    }
  }

  // Claims and runs the ranges of job `generation` until none is left (or the job is over). The
  // job's fields are read only after a claim succeeded: until that range is done, the caller
  // cannot start the next job and overwrite them.
  void work(std::uint32_t generation, std::uint32_t worker) {
    std::uint64_t claim = claim_.load(std::memory_order_acquire);
    for (;;) {
      if (static_cast<std::uint32_t>(claim >> 32) != generation) return;
      const std::uint32_t next = static_cast<std::uint32_t>(claim >> 16) & 0xFFFF;
      const std::uint32_t ranges = static_cast<std::uint32_t>(claim) & 0xFFFF;
      if (next >= ranges) return;
      if (!claim_.compare_exchange_weak(claim, packClaim(generation, next + 1, ranges),
                                        std::memory_order_acq_rel, std::memory_order_acquire))
        continue;
      const std::uint32_t count = count_.load(std::memory_order_relaxed);
      const std::uint32_t range = range_.load(std::memory_order_relaxed);
      const std::uint32_t begin = next * range;
      task_.load(std::memory_order_relaxed)(begin, std::min(begin + range, count), worker,
                                            context_.load(std::memory_order_relaxed));
      done_.fetch_add(1, std::memory_order_acq_rel);
      claim = claim_.load(std::memory_order_acquire);
    }
  }

  std::vector<std::thread> threads_;
  // The job, written before its claim counter is published.
  std::atomic<TaskFunction*> task_{nullptr};
  std::atomic<void*> context_{nullptr};
  std::atomic<std::uint32_t> count_{0};
  std::atomic<std::uint32_t> range_{1};
  alignas(64) std::atomic<std::uint64_t> claim_{0};
  alignas(64) std::atomic<std::uint32_t> done_{0};
  alignas(64) std::atomic<std::uint32_t> generation_{0};
  std::atomic<int> sleepers_{0};
  std::atomic<bool> stop_{false};
};

TaskRunner::TaskRunner() = default;
TaskRunner::~TaskRunner() = default;

void TaskRunner::configure(int workerCount, EnqueueTaskCallback* enqueue, FinishTaskCallback* finish,
                           void* userContext) {
  const bool ownThreads = workerCount > 1 && enqueue == nullptr;
  const bool samePool = pool_ != nullptr && ownThreads && workerCount == workerCount_;
  if (!samePool) pool_.reset();
  workerCount_ = workerCount;
  enqueue_ = enqueue;
  finish_ = finish;
  userContext_ = userContext;
  if (ownThreads && !pool_) pool_ = std::make_unique<ThreadPool>(workerCount);
}

void TaskRunner::run(std::uint32_t count, std::uint32_t minRange, TaskFunction* task, void* context) {
  if (enqueue_ != nullptr) {
    void* handle = enqueue_(task, count, minRange, context, userContext_);
    if (handle != nullptr) finish_(handle, userContext_);
    return;
  }
  pool_->run(count, minRange, task, context);
}

}  // namespace collide::detail
