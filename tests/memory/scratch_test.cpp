// Per-step scratch arrays (memory/scratch.h): resizeScratch grows to an eighth beyond the count
// asked for and keeps its block while the count fits; releaseOversizedScratch frees an array of a
// megabyte or more only once its last use needed less than a quarter of it.
#include "memory/scratch.h"

#include <collide/hooks.h>

#include <gtest/gtest.h>

#include <cstdint>

namespace collide::detail {
namespace {

TEST(Scratch, ResizeGrowsByAnEighthAndKeepsItsBlockWhileTheCountFits) {
  Array<std::uint32_t> v;
  resizeScratch(v, 800);
  EXPECT_EQ(v.size(), 800u);
  EXPECT_EQ(v.capacity(), 900u);  // 800 + 800 / 8
  const std::uint32_t* block = v.data();
  resizeScratch(v, 900);
  EXPECT_EQ(v.data(), block);
  resizeScratch(v, 10);
  EXPECT_EQ(v.data(), block);
  EXPECT_EQ(v.capacity(), 900u);
  resizeScratch(v, 901);
  EXPECT_EQ(v.size(), 901u);
  EXPECT_EQ(v.capacity(), 901u + 901u / 8);
}

TEST(Scratch, OnlyALargeArrayUsedBelowAQuarterIsReleased) {
  constexpr std::size_t kMegabyteOfWords = (std::size_t{1} << 20) / sizeof(std::uint64_t);
  Array<std::uint64_t> large;
  large.reserve(4 * kMegabyteOfWords);               // 4 MiB
  releaseOversizedScratch(large, kMegabyteOfWords);  // a quarter: kept
  EXPECT_EQ(large.capacity(), 4 * kMegabyteOfWords);
  releaseOversizedScratch(large, kMegabyteOfWords - 1);  // below a quarter: released
  EXPECT_EQ(large.capacity(), 0u);

  Array<std::uint64_t> small;
  small.reserve(kMegabyteOfWords / 2);  // half a megabyte: kept however little it was used
  releaseOversizedScratch(small, 0);
  EXPECT_EQ(small.capacity(), kMegabyteOfWords / 2);
}

}  // namespace
}  // namespace collide::detail

namespace collide {
namespace {

struct Record {
  std::uint64_t key;
  float values[30];
};

// A kept array grown by stretches holds what it held, in order, with the capacity asked for: small
// (from the heap) and large (mapped by the default allocator, whose copied stretches go back to the
// system as they are copied).
TEST(Scratch, GrowingByStretchesKeepsEveryRecord) {
  for (const std::size_t count : {std::size_t{10}, std::size_t{40000}}) {
    Array<Record> records(count);
    for (std::size_t i = 0; i < count; ++i) {
      records[i].key = i * 7919;
      for (int k = 0; k < 30; ++k) records[i].values[k] = float(i) + 0.5f * float(k);
    }
    detail::growByStretches(records, 2 * count + 3);
    ASSERT_EQ(records.size(), count);
    EXPECT_EQ(records.capacity(), 2 * count + 3);
    for (std::size_t i = 0; i < count; ++i) {
      ASSERT_EQ(records[i].key, i * 7919) << i;
      for (int k = 0; k < 30; ++k) ASSERT_EQ(records[i].values[k], float(i) + 0.5f * float(k)) << i;
    }
    // Asking for less than it has changes nothing.
    detail::growByStretches(records, count);
    EXPECT_EQ(records.capacity(), 2 * count + 3);
  }
}

}  // namespace
}  // namespace collide
