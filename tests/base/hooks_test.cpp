// The engine's hooks (collide/hooks.h): every array of a stepping world takes its memory from the
// installed allocator and nothing in the step goes around it; the allocator cannot change under live
// arrays; assertions reach the handler; the log handler hears of frozen bodies and grown arrays; the
// profile hooks see each stage of the step when the build calls them.
#include <collide/collide.h>
#include <collide/hooks.h>

#include "dynamics/constraint_graph.h"
#include "support/collide_error.h"
#include "support/world_helpers.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <utility>
#include <vector>

// Global operator new, counted while a test asks: the step must not call it (its arrays go through
// the installed allocator). The count is atomic: the step's workers allocate too.
namespace {
std::atomic<bool> gCountGlobalNew{false};
std::atomic<long> gGlobalNews{0};
thread_local bool tInTestAllocator = false;  // the test's own allocator keeps its records with new
}  // namespace

// The replacements below pair malloc with free, which GCC cannot see through a replaced new.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t bytes) {
  if (gCountGlobalNew.load(std::memory_order_relaxed) && !tInTestAllocator) gGlobalNews.fetch_add(1);
  if (void* p = std::malloc(bytes ? bytes : 1)) return p;
#if COLLIDE_EXCEPTIONS
  throw std::bad_alloc();
#else
  std::abort();
#endif
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace collide {
namespace {

using test::kDt;

// An allocator that keeps every block it gave with its size and alignment, and checks that each
// comes back with the same.
struct CountingAllocator {
  std::mutex mutex;
  std::map<void*, std::pair<std::size_t, std::size_t>> live;
  long allocations = 0;
  long frees = 0;
  bool mismatched = false;

  static void* allocate(std::size_t bytes, std::size_t alignment, void* context) {
    auto& self = *static_cast<CountingAllocator*>(context);
    tInTestAllocator = true;
    void* p = std::aligned_alloc(std::max(alignment, sizeof(void*)),
                                 (bytes + alignment - 1) / alignment * alignment);
    const std::lock_guard lock(self.mutex);
    ++self.allocations;
    self.live[p] = {bytes, alignment};
    tInTestAllocator = false;
    return p;
  }
  static void free(void* memory, std::size_t bytes, std::size_t alignment, void* context) {
    auto& self = *static_cast<CountingAllocator*>(context);
    {
      const std::lock_guard lock(self.mutex);
      ++self.frees;
      const auto it = self.live.find(memory);
      if (it == self.live.end() || it->second != std::pair{bytes, alignment}) {
        self.mismatched = true;
      } else {
        self.live.erase(it);
      }
    }
    std::free(memory);
  }
  Allocator hooks() { return {&allocate, &free, this}; }
};

// A pile of boxes and spheres on the ground, a chain of ball joints and a hinged door: contacts,
// joint trees, islands, on `workers` workers.
void buildScene(World& world) {
  world.createBody(test::groundBox());
  for (int i = 0; i < 125; ++i) {
    const Vec3 at(float(i % 5) * 1.1f - 2.2f, 0.5f + float(i / 25) * 1.1f, float((i / 5) % 5) * 1.1f - 2.2f);
    world.createBody(i % 3 == 0 ? test::sphereBody(at, 0.5f, 1.0f) : test::boxBody(at, Vec3(0.5f), 1.0f));
  }
  BodyId previous = test::staticAnchor(world, Vec3(10.0f, 8.0f, 0.0f));
  for (int i = 0; i < 10; ++i) {
    const BodyId link = world.createBody(test::sphereBody(Vec3(10.5f + float(i), 8.0f, 0.0f), 0.2f, 0.5f));
    BallJointDef joint;
    joint.a = previous;
    joint.b = link;
    joint.anchor = Vec3(10.0f + float(i), 8.0f, 0.0f);
    world.createBallJoint(joint);
    previous = link;
  }
}

// Each scenario runs on a thread of its own, so that the narrow phase's per-thread scratch (grown
// through the allocator like every array) is given back when the thread ends.
template <typename F>
void onItsOwnThread(F&& f) {
  std::thread thread(std::forward<F>(f));
  thread.join();
}

TEST(AllocatorHook, EveryArrayOfASteppingWorldGoesThroughTheAllocator) {
  for (const int workers : {1, 2}) {
    static CountingAllocator counting;  // outlives every block it gives
    const std::size_t liveBefore = liveAllocations();
    const long allocationsBefore = counting.allocations;
    long allocationsInSteps = 0;
    long globalNews = 0;
    onItsOwnThread([&] {
      setAllocator(counting.hooks());
      WorldDef def;
      def.workerCount = workers;
      World world(def);
      buildScene(world);
      const long beforeSteps = counting.allocations;
      gGlobalNews = 0;
      gCountGlobalNew = true;
      for (int i = 0; i < 120; ++i) world.step(kDt);
      gCountGlobalNew = false;
      globalNews = gGlobalNews.load();
      allocationsInSteps = counting.allocations - beforeSteps;
      setAllocator(Allocator{});
    });
    EXPECT_EQ(globalNews, 0) << workers << " workers: the step allocated around the allocator";
    EXPECT_GT(allocationsInSteps, 0) << "the first steps grow the contact and pair arrays";
    EXPECT_GT(counting.allocations, allocationsBefore);
    EXPECT_TRUE(counting.live.empty()) << counting.live.size() << " blocks never came back";
    EXPECT_EQ(liveAllocations(), liveBefore);
    EXPECT_FALSE(counting.mismatched) << "a block came back with another size or alignment";
  }
}

TEST(AllocatorHook, BlocksGoBackToTheAllocatorThatGaveThem) {
  static CountingAllocator first;
  static CountingAllocator second;
  onItsOwnThread([&] {
    setAllocator(first.hooks());
    World world;
    buildScene(world);
    for (int i = 0; i < 10; ++i) world.step(kDt);
    setAllocator(second.hooks());  // with the world alive: what grows now comes from the second
    for (int i = 0; i < 4; ++i) buildScene(world);
    for (int i = 0; i < 10; ++i) world.step(kDt);
    setAllocator(Allocator{});
  });
  EXPECT_GT(first.allocations, 0);
  EXPECT_GT(second.allocations, 0);
  EXPECT_TRUE(first.live.empty());
  EXPECT_TRUE(second.live.empty());
  EXPECT_FALSE(first.mismatched || second.mismatched);
  EXPECT_EQ(first.allocations, first.frees);
  EXPECT_EQ(second.allocations, second.frees);
}

// The default allocator maps a block of 1 MiB or more from the system (collide/hooks.h): the block
// is the start of a mapping of its own, after its header, while it lives; its contents move with
// the array when it grows into another such block; the bytes it counts come back when it is freed.
// Sanitized builds keep every block in the heap, where AddressSanitizer checks its bounds.
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define COLLIDE_TEST_ADDRESS_SANITIZER 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define COLLIDE_TEST_ADDRESS_SANITIZER 1
#endif
#if defined(__linux__) && !defined(COLLIDE_TEST_ADDRESS_SANITIZER)
bool startsAMapping(const void* address) {
  std::FILE* maps = std::fopen("/proc/self/maps", "r");
  if (maps == nullptr) return false;
  bool found = false;
  unsigned long start = 0, end = 0;
  char line[512];
  while (!found && std::fgets(line, sizeof line, maps) != nullptr)
    found =
        std::sscanf(line, "%lx-%lx", &start, &end) == 2 && start == reinterpret_cast<std::uintptr_t>(address);
  std::fclose(maps);
  return found;
}

TEST(AllocatorHook, TheDefaultMapsALargeBlockAndGivesItBack) {
  const std::size_t bytesBefore = liveAllocatedBytes();
  {
    Array<std::uint32_t> large(std::size_t{1} << 19);  // 2 MiB
    for (std::size_t i = 0; i < large.size(); ++i) large[i] = static_cast<std::uint32_t>(i * 2654435761u);
    // The header before the block is the size of its alignment, at least max_align_t's.
    const auto* mapping = reinterpret_cast<const unsigned char*>(large.data()) - alignof(std::max_align_t);
    EXPECT_TRUE(startsAMapping(mapping)) << "a 2 MiB block is not a mapping of its own";
    EXPECT_EQ(liveAllocatedBytes(), bytesBefore + large.capacity() * sizeof(std::uint32_t));
    large.resize(std::size_t{1} << 21);  // 8 MiB: a new mapping, the contents copied over
    bool kept = true;
    for (std::size_t i = 0; i < (std::size_t{1} << 19); ++i)
      kept = kept && large[i] == static_cast<std::uint32_t>(i * 2654435761u);
    EXPECT_TRUE(kept);
    Array<std::uint32_t> small(1024);  // 4 KiB: from the heap
    const auto* smallBlock = reinterpret_cast<const unsigned char*>(small.data()) - alignof(std::max_align_t);
    EXPECT_FALSE(startsAMapping(smallBlock));
  }
  EXPECT_EQ(liveAllocatedBytes(), bytesBefore);
}
#endif

TEST(AllocatorHook, HalfAnAllocatorIsRefused) {
  Allocator half;
  half.allocate = [](std::size_t, std::size_t, void*) -> void* { return nullptr; };
  EXPECT_THAT([&] { setAllocator(half); },
              ::collide::test::ReportsError(::testing::HasSubstr("both be set")));
}

#if COLLIDE_EXCEPTIONS
TEST(AllocatorHook, AnAllocatorWithoutMemoryIsBadAlloc) {
  const std::size_t liveBefore = liveAllocations();
  setAllocator({[](std::size_t, std::size_t, void*) -> void* { return nullptr; },
                [](void*, std::size_t, std::size_t, void*) {}, nullptr});
  World world;
  EXPECT_THROW(world.createBody(test::groundBox()), std::bad_alloc);
  setAllocator(Allocator{});
  EXPECT_EQ(liveAllocations(), liveBefore);
}
#else
// Without exceptions an allocator with no memory left is fatal, as operator new is: the error
// handler hears of it, then the process aborts.
TEST(AllocatorHookDeathTest, AnAllocatorWithoutMemoryAbortsAfterTellingTheHandler) {
  EXPECT_DEATH(
      {
        setErrorHandler([](const char* message, void*) { std::fprintf(stderr, "handler: %s\n", message); });
        setAllocator({[](std::size_t, std::size_t, void*) -> void* { return nullptr; },
                      [](void*, std::size_t, std::size_t, void*) {}, nullptr});
        World world;
        world.createBody(test::groundBox());
      },
      "handler: out of memory");
}
#endif

// The handler gets the failed condition with its file and line, in builds that check assertions.
struct AssertRecord {
  int calls = 0;
  std::string condition;
  std::string file;
};
AssertRecord gAssertRecord;

TEST(AssertHook, AFailedInvariantReachesTheHandler) {
  if (!assertionsEnabled()) GTEST_SKIP() << "this build compiles the library's assertions out (NDEBUG)";
  gAssertRecord = {};
  setAssertHandler([](const char* condition, const char* file, int) {
    ++gAssertRecord.calls;
    gAssertRecord.condition = condition;
    gAssertRecord.file = file;
    return false;  // go on: the colouring below stays in bounds
  });
  // Colouring a constraint on a body the graph does not have breaks the solver's invariant.
  Array<std::array<std::int32_t, 2>> constraints = {{0, 1}, {1, 2}};
  Array<std::uint8_t> colors;
  Array<std::uint64_t> bits;
  detail::colorConstraints(constraints, 2, colors, bits);
  setAssertHandler(nullptr);
  EXPECT_EQ(gAssertRecord.calls, 1);
  EXPECT_THAT(gAssertRecord.condition, ::testing::HasSubstr("bodyCount"));
  EXPECT_THAT(gAssertRecord.file, ::testing::HasSubstr("constraint_graph.cpp"));
}

struct LogRecord {
  std::vector<std::pair<LogLevel, std::string>> lines;
};

TEST(LogHook, AFrozenBodyAndGrownArraysAreReported) {
  LogRecord record;
  setLogHandler([](LogLevel level, const char* message,
                   void* context) { static_cast<LogRecord*>(context)->lines.emplace_back(level, message); },
                &record);
  {
    World world;
    world.createBody(test::groundBox());
    BodyDef def = test::boxBody(Vec3(0.0f, 3.0f, 0.0f), Vec3(0.5f), 1.0f);
    def.name = "runaway";
    const BodyId runaway = world.createBody(def);
    world.step(kDt);
    ASSERT_FALSE(record.lines.empty());
    EXPECT_EQ(record.lines.front().first, LogLevel::Info);
    EXPECT_THAT(record.lines.front().second, ::testing::HasSubstr("grew the world's arrays"));
    record.lines.clear();
    // Two finite forces whose sum overflows: the velocity stops being finite in the step.
    world.applyForce(runaway, Vec3(3.0e38f, 0.0f, 0.0f), world.transform(runaway).position);
    world.applyForce(runaway, Vec3(3.0e38f, 0.0f, 0.0f), world.transform(runaway).position);
    world.step(kDt);
    ASSERT_EQ(world.faultEvents().size(), 1u);
    const auto warning = std::find_if(record.lines.begin(), record.lines.end(),
                                      [](const auto& line) { return line.first == LogLevel::Warning; });
    ASSERT_NE(warning, record.lines.end());
    EXPECT_THAT(warning->second, ::testing::HasSubstr("body 1 (runaway) frozen by the fault guard"));
    EXPECT_THAT(warning->second, ::testing::HasSubstr("linear velocity"));
  }
  setLogHandler(nullptr);
}

struct ZoneRecord {
  std::atomic<int> begins{0};
  std::atomic<int> ends{0};
  std::mutex mutex;
  std::vector<std::string> names;
};

TEST(ProfileHook, EveryStageOfTheStepIsAZoneWhenTheBuildCallsTheHooks) {
  ZoneRecord record;
  setProfileHooks({[](const char* name, void* context) {
                     auto& r = *static_cast<ZoneRecord*>(context);
                     ++r.begins;
                     const std::lock_guard lock(r.mutex);
                     r.names.emplace_back(name);
                   },
                   [](void* context) { ++static_cast<ZoneRecord*>(context)->ends; }, &record});
  {
    World world;
    buildScene(world);
    for (int i = 0; i < 3; ++i) world.step(kDt);
  }
  setProfileHooks({});
  EXPECT_EQ(record.begins.load(), record.ends.load());
  if (!profileZonesEnabled()) {
    EXPECT_EQ(record.begins.load(), 0) << "a build without COLLIDE_PROFILE_ZONES calls no hook";
    return;
  }
  for (const char* stage : {"collide: broad phase", "collide: narrow phase", "collide: solve",
                            "collide: continuous", "collide: events", "collide: islands and sleep"}) {
    EXPECT_EQ(std::count(record.names.begin(), record.names.end(), stage), 3) << stage;
  }
}

}  // namespace
}  // namespace collide
