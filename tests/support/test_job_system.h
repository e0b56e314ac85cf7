// A minimal job system of the kind an engine plugs into WorldDef::enqueueTask / finishTask
// (include/collide/tasks.h), for the tests: its own threads take the ranges of one task at a time
// from a shared counter, and finishTask's caller takes ranges too, as worker 0.
#pragma once

#include <collide/tasks.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace collide::test {

class TestJobSystem {
 public:
  explicit TestJobSystem(int workers) {
    for (int w = 1; w < workers; ++w)
      threads_.emplace_back([this, w] { loop(static_cast<std::uint32_t>(w)); });
  }
  ~TestJobSystem() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  static void* enqueue(TaskFunction* task, std::uint32_t count, std::uint32_t minRange, void* taskContext,
                       void* user) {
    auto& self = *static_cast<TestJobSystem*>(user);
    self.tasks_.fetch_add(1);
    if (self.serialEvery_ > 0 && self.tasks_.load() % self.serialEvery_ == 0) {
      task(0, count, 0, taskContext);  // run here: nullptr tells the world it is done
      return nullptr;
    }
    {
      std::unique_lock lock(self.mutex_);
      // A thread still inside the last task's work() reads the job: it must be out first.
      self.idle_.wait(lock, [&] { return self.active_ == 0; });
      self.job_ = Job{task, taskContext, count, std::max<std::uint32_t>(minRange, 1)};
      self.next_.store(0);
      self.done_.store(0);
      ++self.generation_;
    }
    self.wake_.notify_all();
    return &self;
  }

  static void finish(void* handle, void*) {
    auto& self = *static_cast<TestJobSystem*>(handle);
    self.work(0);
    std::unique_lock lock(self.mutex_);
    self.finished_.wait(lock, [&] { return self.done_.load() == self.ranges(); });
  }

  // Every k-th task runs on the caller and enqueue returns nullptr (0: never).
  void runEveryKthTaskInline(int k) { serialEvery_ = k; }
  int tasks() const { return tasks_.load(); }
  int rangesRunByThreads() const { return byThreads_.load(); }

 private:
  struct Job {
    TaskFunction* task = nullptr;
    void* context = nullptr;
    std::uint32_t count = 0;
    std::uint32_t range = 1;
  };
  std::uint32_t ranges() const { return (job_.count + job_.range - 1) / job_.range; }

  void work(std::uint32_t worker) {
    for (;;) {
      const std::uint32_t index = next_.fetch_add(1);
      if (index >= ranges()) return;
      const std::uint32_t begin = index * job_.range;
      job_.task(begin, std::min(begin + job_.range, job_.count), worker, job_.context);
      if (worker != 0) byThreads_.fetch_add(1);
      if (done_.fetch_add(1) + 1 == ranges()) {
        std::lock_guard lock(mutex_);
        finished_.notify_all();
      }
    }
  }

  void loop(std::uint32_t worker) {
    std::uint64_t seen = 0;
    for (;;) {
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
        ++active_;
      }
      work(worker);
      std::lock_guard lock(mutex_);
      if (--active_ == 0) idle_.notify_all();
    }
  }

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, finished_, idle_;
  int active_ = 0;  // threads inside work()
  Job job_;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
  std::atomic<std::uint32_t> next_{0}, done_{0};
  std::atomic<int> tasks_{0}, byThreads_{0};
  int serialEvery_ = 0;
};

}  // namespace collide::test
