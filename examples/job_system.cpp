// A world stepped by an engine's own job system (WorldDef::enqueueTask / finishTask, docs/threads.md):
// a minimal one here, a few threads that take the ranges of one task at a time from a counter, the
// thread that waits in finishTask taking ranges too. The same pile is stepped on one worker and on
// the job system, and the program checks that both end in the same state, bit for bit.
#include <collide/collide.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

namespace {

class JobSystem {
 public:
  explicit JobSystem(int workers) {
    for (int w = 1; w < workers; ++w) threads_.emplace_back([this, w] { loop(std::uint32_t(w)); });
  }
  ~JobSystem() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  // WorldDef::enqueueTask: publish the task and wake the threads. The world waits for it in
  // finishTask before it enqueues the next, so one task at a time is enough here.
  static void* enqueue(collide::TaskFunction* task, std::uint32_t count, std::uint32_t minRange,
                       void* taskContext, void* user) {
    JobSystem& self = *static_cast<JobSystem*>(user);
    {
      std::unique_lock lock(self.mutex_);
      self.idle_.wait(lock, [&] { return self.active_ == 0; });  // no thread still reads the last one
      self.task_ = task;
      self.context_ = taskContext;
      self.count_ = count;
      self.range_ = std::max<std::uint32_t>(minRange, 1);
      self.next_ = 0;
      self.done_ = 0;
      ++self.generation_;
    }
    self.wake_.notify_all();
    return &self;
  }

  // WorldDef::finishTask: help with the ranges (as worker 0), then wait for the rest.
  static void finish(void* handle, void*) {
    JobSystem& self = *static_cast<JobSystem*>(handle);
    self.work(0);
    std::unique_lock lock(self.mutex_);
    self.finished_.wait(lock, [&] { return self.done_ == self.ranges(); });
  }

 private:
  std::uint32_t ranges() const { return (count_ + range_ - 1) / range_; }

  void work(std::uint32_t worker) {
    for (std::uint32_t index = next_++; index < ranges(); index = next_++) {
      const std::uint32_t begin = index * range_;
      task_(begin, std::min(begin + range_, count_), worker, context_);
      if (++done_ == ranges()) {
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
  collide::TaskFunction* task_ = nullptr;
  void* context_ = nullptr;
  std::uint32_t count_ = 0, range_ = 1;
  std::atomic<std::uint32_t> next_{0}, done_{0};
  std::uint64_t generation_ = 0;
  int active_ = 0;
  bool stop_ = false;
};

// A pile of 1,000 boxes on a ground box; returns every body's final position.
std::vector<collide::Vec3> runPile(const collide::WorldDef& def) {
  using namespace collide;
  World world(def);
  BodyDef ground;
  ground.type = BodyType::Static;
  ground.shape = Box{Vec3(20.0f, 0.5f, 20.0f)};
  ground.position = Vec3(0.0f, -0.5f, 0.0f);
  world.createBody(ground);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 1000; ++i) {
    BodyDef box;
    box.shape = Box{Vec3(0.25f)};
    box.position = Vec3(0.6f * float(i % 10), 0.3f + 0.6f * float(i / 100), 0.6f * float(i / 10 % 10));
    boxes.push_back(world.createBody(box));
  }
  for (int step = 0; step < 180; ++step) world.step(1.0f / 60.0f);
  std::vector<Vec3> positions;
  for (const BodyId b : boxes) positions.push_back(world.transform(b).position);
  return positions;
}

}  // namespace

int main() {
  const std::vector<collide::Vec3> alone = runPile(collide::WorldDef{});

  JobSystem jobs(4);
  collide::WorldDef def;
  def.workerCount = 4;  // worker indices 0..3: the waiting thread and the job system's three
  def.enqueueTask = &JobSystem::enqueue;
  def.finishTask = &JobSystem::finish;
  def.userTaskContext = &jobs;
  const std::vector<collide::Vec3> threaded = runPile(def);

  const bool same = std::memcmp(alone.data(), threaded.data(), alone.size() * sizeof(collide::Vec3)) == 0;
  std::printf("1,000 boxes, 180 steps: one worker and the job system's four end %s\n",
              same ? "bit for bit in the same state" : "in different states");
  return same ? 0 : 1;
}
