// The world's own thread pool and the dispatch to an engine's job system (task_runner.h).
//
// A loop is a job: its ranges are split in one block per worker, each claimed from a 64-bit counter
// that holds the job's generation, the block's next range and its end, so a worker that wakes
// late, after its job is over, cannot claim a range of the next one. Workers spin for a while after a job
// (the solver's loops come microseconds apart, one per colour and pass) and then sleep on the generation.
#include "base/task_runner.h"
#include "base/profile.h"

#include <collide/hooks.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
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
  explicit ThreadPool(int workerCount)
      : workers_(static_cast<std::uint32_t>(workerCount)),
        oversubscribed_(static_cast<unsigned>(workerCount) >
                        std::max(1u, std::thread::hardware_concurrency())),
        blocks_(std::make_unique<Block[]>(static_cast<std::size_t>(workerCount))) {
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
    // A claim and a completion each move a cache line between cores (a hundred nanoseconds or
    // more): a few ranges per worker balance the load, more only pay that toll.
    const std::uint32_t wanted = std::min(kMaxRanges, workers_ * kRangesPerWorker);
    // Ranges stay multiples of the one asked for (a caller may align its items' lanes to it).
    const std::uint32_t even = (count + wanted - 1) / wanted;
    range *= std::max(1u, (even + range - 1) / range);
    const std::uint32_t rangeCount = (count + range - 1) / range;
    const std::uint32_t generation = generation_.load(std::memory_order_relaxed) + 1;
    task_.store(task, std::memory_order_relaxed);
    context_.store(context, std::memory_order_relaxed);
    count_.store(count, std::memory_order_relaxed);
    range_.store(range, std::memory_order_relaxed);
    done_.store(0, std::memory_order_relaxed);
    // Worker w owns the w-th block of ranges. The solver's loops, one per colour, are split the
    // same way each time, so a worker meets mostly the same bodies colour after colour and finds
    // them in its own cache; a worker done with its block takes ranges of the others'.
    for (std::uint32_t w = 0; w < workers_; ++w) {
      const std::uint32_t first = rangeCount * w / workers_;
      const std::uint32_t last = rangeCount * (w + 1) / workers_;
      blocks_[w].claim.store(packClaim(generation, first, last), std::memory_order_release);
    }
    generation_.store(generation);
    if (sleepers_.load() > 0) generation_.notify_all();
    work(generation, 0);
    while (done_.load(std::memory_order_acquire) != rangeCount) pause();
  }

 private:
  static constexpr std::uint32_t kMaxRanges = 0xFFFF;
  static constexpr std::uint32_t kRangesPerWorker = 2;
  // generation (32 bits), the block's next range (16), its end (16).
  static std::uint64_t packClaim(std::uint32_t generation, std::uint32_t next, std::uint32_t end) {
    return std::uint64_t{generation} << 32 | std::uint64_t{next} << 16 | end;
  }

  void workerLoop(std::uint32_t worker) {
    std::uint32_t seen = 0;
    for (;;) {
      int spins = 0;
      auto spinStart = std::chrono::steady_clock::now();
      while (generation_.load(std::memory_order_acquire) == seen && !stop_.load(std::memory_order_relaxed)) {
        pause();
        if (++spins % kSpinsPerClockRead != 0) continue;
        // With more workers than cores, a spinning worker would hold up the one with a range in
        // hand: now and then the core goes to whoever else waits for it. Only then: a yield is a
        // system call, and on a virtual machine one costs microseconds of the next job's start.
        if (oversubscribed_) std::this_thread::yield();
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

  // Runs the ranges of job `generation` that are left: its own block's, then the other blocks'.
  void work(std::uint32_t generation, std::uint32_t worker) {
    for (std::uint32_t k = 0; k < workers_; ++k) {
      const std::uint32_t block = worker + k < workers_ ? worker + k : worker + k - workers_;
      workBlock(generation, worker, blocks_[block].claim);
    }
  }

  // Claims and runs the ranges of one block until none is left (or the job is over). The job's
  // fields are read only after a claim succeeded: until that range is done, the caller cannot
  // start the next job and overwrite them.
  void workBlock(std::uint32_t generation, std::uint32_t worker, std::atomic<std::uint64_t>& claimOfBlock) {
    std::uint64_t claim = claimOfBlock.load(std::memory_order_acquire);
    for (;;) {
      if (static_cast<std::uint32_t>(claim >> 32) != generation) return;
      const std::uint32_t next = static_cast<std::uint32_t>(claim >> 16) & 0xFFFF;
      const std::uint32_t end = static_cast<std::uint32_t>(claim) & 0xFFFF;
      if (next >= end) return;
      if (!claimOfBlock.compare_exchange_weak(claim, packClaim(generation, next + 1, end),
                                              std::memory_order_acq_rel, std::memory_order_acquire))
        continue;
      const std::uint32_t count = count_.load(std::memory_order_relaxed);
      const std::uint32_t range = range_.load(std::memory_order_relaxed);
      const std::uint32_t begin = next * range;
      {
        COLLIDE_PROFILE_ZONE("collide: task range");
        task_.load(std::memory_order_relaxed)(begin, std::min(begin + range, count), worker,
                                              context_.load(std::memory_order_relaxed));
      }
      done_.fetch_add(1, std::memory_order_acq_rel);
      claim = claimOfBlock.load(std::memory_order_acquire);
    }
  }

  struct alignas(64) Block {
    std::atomic<std::uint64_t> claim{0};
  };

  const std::uint32_t workers_;
  const bool oversubscribed_;  // more workers than the machine has cores
  std::unique_ptr<Block[]> blocks_;
  Array<std::thread> threads_;
  // The job, written before its claim counter is published.
  std::atomic<TaskFunction*> task_{nullptr};
  std::atomic<void*> context_{nullptr};
  std::atomic<std::uint32_t> count_{0};
  std::atomic<std::uint32_t> range_{1};
  alignas(64) std::atomic<std::uint32_t> done_{0};
  alignas(64) std::atomic<std::uint32_t> generation_{0};
  std::atomic<int> sleepers_{0};
  std::atomic<bool> stop_{false};
};

TaskRunner::TaskRunner() = default;
TaskRunner::~TaskRunner() = default;
TaskRunner::TaskRunner(TaskRunner&&) noexcept = default;
TaskRunner& TaskRunner::operator=(TaskRunner&&) noexcept = default;

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
