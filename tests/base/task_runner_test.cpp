// The step's parallel loops (src/base/task_runner.h): every item runs exactly once, in ranges of
// the size asked for, with worker indices that are in range and never shared by two ranges running
// at once; over the world's own threads and over an engine's job system.
#include "base/task_runner.h"

#include "support/test_job_system.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

namespace collide::detail {
namespace {

// Runs a loop of `count` items in ranges of `range` and checks what the ranges did.
void expectEveryItemOnce(TaskRunner& tasks, std::uint32_t count, std::uint32_t range) {
  std::vector<std::atomic<int>> visits(count);
  std::vector<std::atomic<int>> busy(static_cast<std::size_t>(kMaxWorkers));
  std::atomic<bool> shared{false}, outOfRange{false}, misaligned{false};
  tasks.parallelFor(count, range, [&](std::uint32_t begin, std::uint32_t end, std::uint32_t worker) {
    if (worker >= static_cast<std::uint32_t>(tasks.workerCount())) {
      outOfRange = true;
      return;
    }
    if (busy[worker].fetch_add(1) != 0) shared = true;
    if (begin % range != 0 && tasks.workerCount() > 1) misaligned = true;
    for (std::uint32_t i = begin; i < end; ++i) visits[i].fetch_add(1);
    busy[worker].fetch_sub(1);
  });
  EXPECT_FALSE(outOfRange);
  EXPECT_FALSE(shared) << "two ranges ran at once under one worker index";
  EXPECT_FALSE(misaligned);
  for (std::uint32_t i = 0; i < count; ++i) ASSERT_EQ(visits[i].load(), 1) << "item " << i;
}

TEST(TaskRunner, OneWorkerRunsTheWholeLoopAsOneRangeOnTheCaller) {
  TaskRunner tasks;
  int calls = 0;
  tasks.parallelFor(1000, 16, [&](std::uint32_t begin, std::uint32_t end, std::uint32_t worker) {
    ++calls;
    EXPECT_EQ(begin, 0u);
    EXPECT_EQ(end, 1000u);
    EXPECT_EQ(worker, 0u);
  });
  EXPECT_EQ(calls, 1);
}

TEST(TaskRunner, OwnThreadsRunEveryItemOnceAtEveryWorkerCount) {
  for (const int workers : {2, 3, 4, 8}) {
    SCOPED_TRACE(std::to_string(workers) + " workers");
    TaskRunner tasks;
    tasks.configure(workers, nullptr, nullptr, nullptr);
    for (const std::uint32_t count : {1u, 7u, 64u, 1000u, 100003u}) {
      for (const std::uint32_t range : {1u, 16u, 1000u}) expectEveryItemOnce(tasks, count, range);
    }
  }
}

TEST(TaskRunner, ManyLoopsInARowEachFinishBeforeTheNextStarts) {
  TaskRunner tasks;
  tasks.configure(4, nullptr, nullptr, nullptr);
  std::vector<int> values(4096, 0);
  for (int round = 0; round < 2000; ++round) {
    tasks.parallelFor(4096, 64, [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t i = begin; i < end; ++i) values[i] += 1;
    });
    // Reads the last loop's writes: a range still running would leave a value behind.
    ASSERT_EQ(values[round % 4096], round + 1);
    ASSERT_EQ(values[4095 - round % 4096], round + 1);
  }
}

TEST(TaskRunner, ResizingThePoolKeepsItWorking) {
  TaskRunner tasks;
  for (const int workers : {4, 1, 2, 8, 2}) {
    tasks.configure(workers, nullptr, nullptr, nullptr);
    EXPECT_EQ(tasks.workerCount(), workers);
    expectEveryItemOnce(tasks, 5000, 32);
  }
}

TEST(TaskRunner, AnEnginesJobSystemRunsTheRanges) {
  test::TestJobSystem jobs(3);
  TaskRunner tasks;
  tasks.configure(3, &test::TestJobSystem::enqueue, &test::TestJobSystem::finish, &jobs);
  for (int round = 0; round < 50; ++round) expectEveryItemOnce(tasks, 2000, 16);
  EXPECT_EQ(jobs.tasks(), 50);
}

// Two ranges that each wait until both have started: they finish only if two workers run them at
// once (a serial runner would wait for ever; the wait gives up after 10 s and fails).
bool rangesMeet(TaskRunner& tasks) {
  std::atomic<int> started{0};
  std::atomic<bool> met{true};
  tasks.parallelFor(2, 1, [&](std::uint32_t, std::uint32_t, std::uint32_t) {
    started.fetch_add(1);
    const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (started.load() < 2) {
      if (std::chrono::steady_clock::now() > giveUp) {
        met = false;
        return;
      }
    }
  });
  return met;
}

TEST(TaskRunner, RangesRunAtTheSameTimeOnTheOwnThreadsAndOnAJobSystem) {
  TaskRunner own;
  own.configure(2, nullptr, nullptr, nullptr);
  EXPECT_TRUE(rangesMeet(own));
  test::TestJobSystem jobs(2);
  TaskRunner engine;
  engine.configure(2, &test::TestJobSystem::enqueue, &test::TestJobSystem::finish, &jobs);
  EXPECT_TRUE(rangesMeet(engine));
  EXPECT_EQ(jobs.rangesRunByThreads(), 1);
}

TEST(TaskRunner, AJobSystemMayRunATaskOnTheCallerAndReturnNull) {
  test::TestJobSystem jobs(2);
  jobs.runEveryKthTaskInline(2);
  TaskRunner tasks;
  tasks.configure(2, &test::TestJobSystem::enqueue, &test::TestJobSystem::finish, &jobs);
  for (int round = 0; round < 10; ++round) expectEveryItemOnce(tasks, 500, 8);
  EXPECT_EQ(jobs.tasks(), 10);
}

}  // namespace
}  // namespace collide::detail
