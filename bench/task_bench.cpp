// The cost of one parallel loop of the world's own pool (src/base/task_runner.h), apart from its
// work: the solver issues one loop per colour and pass, a few hundred a step, so the time from a
// loop's start to the caller's return over items that do almost nothing is what each of them adds
// to a step at two workers (docs/threads.md). Arg: the loop's items, in ranges of four.
#include "base/task_runner.h"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

namespace {

void BM_ParallelLoopRoundTrip(benchmark::State& state) {
  const auto items = static_cast<std::uint32_t>(state.range(0));
  collide::detail::TaskRunner tasks;
  tasks.configure(2, nullptr, nullptr, nullptr);
  // Each item writes its own slot, a cache line apart, as a colour's batches write their bodies.
  std::vector<std::uint64_t> slots(static_cast<std::size_t>(items) * 8, 0);
  for (auto _ : state) {
    tasks.parallelFor(items, 4, [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t i = begin; i < end; ++i) slots[static_cast<std::size_t>(i) * 8] += 1;
    });
  }
  benchmark::DoNotOptimize(slots.data());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

}  // namespace

BENCHMARK(BM_ParallelLoopRoundTrip)->Arg(8)->Arg(16)->Arg(64)->Unit(benchmark::kNanosecond);
