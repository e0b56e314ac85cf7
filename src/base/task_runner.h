// The step's parallel loops (include/collide/tasks.h): over the engine's job system when it gives
// one, else over a pool of the world's own threads, else on the calling thread. A loop's items
// must not depend on one another within the loop; then the result is the same for every split.
#pragma once

#include <collide/tasks.h>

#include <cstdint>
#include <memory>
#include <type_traits>

namespace collide::detail {

class ThreadPool;

class TaskRunner {
 public:
  TaskRunner();
  ~TaskRunner();
  TaskRunner(const TaskRunner&) = delete;
  TaskRunner& operator=(const TaskRunner&) = delete;
  // Moved whole, threads and all (a world that loads a snapshot keeps its own).
  TaskRunner(TaskRunner&&) noexcept;
  TaskRunner& operator=(TaskRunner&&) noexcept;

  // Joins the old threads and starts new ones when the pool's size changes; one worker or the
  // engine's callbacks start none.
  void configure(int workerCount, EnqueueTaskCallback* enqueue, FinishTaskCallback* finish,
                 void* userContext);
  int workerCount() const { return workerCount_; }

  // fn(begin, end, worker) over [0, count) in ranges of minRange items (the engine's job system
  // may make them longer); returns when every range has run. One range runs on the caller.
  template <typename F>
  void parallelFor(std::uint32_t count, std::uint32_t minRange, F&& fn) {
    if (count == 0) return;
    if (workerCount_ <= 1 || count <= minRange) {
      fn(std::uint32_t{0}, count, std::uint32_t{0});
      return;
    }
    using Fn = std::remove_reference_t<F>;
    run(count, minRange, &trampoline<Fn>, static_cast<void*>(&fn));
  }

 private:
  template <typename Fn>
  static void trampoline(std::uint32_t begin, std::uint32_t end, std::uint32_t worker, void* context) {
    (*static_cast<Fn*>(context))(begin, end, worker);
  }
  void run(std::uint32_t count, std::uint32_t minRange, TaskFunction* task, void* context);

  int workerCount_ = 1;
  EnqueueTaskCallback* enqueue_ = nullptr;
  FinishTaskCallback* finish_ = nullptr;
  void* userContext_ = nullptr;
  std::unique_ptr<ThreadPool> pool_;
};

}  // namespace collide::detail
