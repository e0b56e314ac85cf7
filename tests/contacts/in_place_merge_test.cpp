// The narrow phase's one array per step (contacts/in_place_merge.h): last step's records read in key
// order while this step's are written over them, against a reference merge with two arrays.
#include "contacts/in_place_merge.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

namespace collide::detail {
namespace {

// Trivially destructible, like a contact; `tag` tells last step's records from this step's.
struct Record {
  std::uint64_t key = 0;
  std::uint64_t tag = 0;
  bool operator==(const Record&) const = default;
};

// One walk: for each key of this step, in order, last step's records of smaller keys are read (and
// counted as ended), its own record (if last step had it) is read, and a record is written for it:
// kept as it was (keep), made anew from it or from nothing (emplace), or none. Returns the records
// read in order; `records` ends as this step's.
enum class Write { None, Keep, FromOld, Fresh };
struct Step {
  std::uint64_t key;
  Write write;
};

void walkSteps(InPlaceMerge<Record>& merge, std::span<const Step> steps, std::uint64_t tag,
               std::vector<Record>& read) {
  for (const Step& step : steps) {
    for (; merge.hasNext() && merge.next().key < step.key; merge.pop()) read.push_back(merge.next());
    const Record* old = nullptr;
    if (merge.hasNext() && merge.next().key == step.key) {
      old = &merge.next();
      read.push_back(*old);
      merge.pop();
    }
    switch (step.write) {
      case Write::None:
        break;
      case Write::Keep:
        if (old) {
          merge.keep(*old).tag = tag;  // updated where it lies, as a placed-again contact is
        } else {
          merge.emplace(Record{step.key, tag});
        }
        break;
      case Write::FromOld:
        if (old) {
          Record& made = merge.emplace(*old);  // `old` may lie where room is made
          made.tag = tag;
        } else {
          merge.emplace(Record{step.key, tag});
        }
        break;
      case Write::Fresh: {
        Record& made = merge.emplace();
        made = Record{step.key, tag};
        break;
      }
    }
  }
  for (; merge.hasNext(); merge.pop()) read.push_back(merge.next());
}

std::vector<Record> walk(Array<Record>& records, Array<Record>& spill, const std::vector<Step>& steps,
                         std::uint64_t tag) {
  std::vector<Record> read;
  InPlaceMerge<Record> merge(records, spill);
  walkSteps(merge, steps, tag, read);
  merge.finish();
  return read;
}

// The same walk cut into `blockCount` blocks of steps, each over the records of its keys (as the
// narrow phase's workers do), then the blocks joined (compactBlocks).
std::vector<Record> walkInBlocks(Array<Record>& records, const std::vector<Step>& steps, std::uint64_t tag,
                                 std::size_t blockCount) {
  std::vector<MergeBlock<Record>> blocks(blockCount);
  std::vector<std::size_t> firstStep(blockCount + 1);
  for (std::size_t b = 0; b <= blockCount; ++b) firstStep[b] = steps.size() * b / blockCount;
  for (std::size_t b = 0; b < blockCount; ++b) {
    MergeBlock<Record>& block = blocks[b];
    block.begin = b == 0 ? 0 : blocks[b - 1].end;
    block.end = b + 1 == blockCount || firstStep[b + 1] == steps.size()
                    ? records.size()
                    : firstAtOrAfter<Record>(records, steps[firstStep[b + 1]].key);
    if (block.end < block.begin) block.end = block.begin;
  }
  // In reverse, so that a block that wrote past its end would spoil a block already walked.
  std::vector<std::vector<Record>> readByBlock(blockCount);
  for (std::size_t b = blockCount; b-- > 0;) {
    InPlaceMerge<Record> merge(records, blocks[b]);
    walkSteps(merge, std::span<const Step>(steps).subspan(firstStep[b], firstStep[b + 1] - firstStep[b]), tag,
              readByBlock[b]);
    merge.finish();
  }
  compactBlocks<Record>(records, blocks);
  std::vector<Record> read;
  for (const std::vector<Record>& blockRead : readByBlock)
    read.insert(read.end(), blockRead.begin(), blockRead.end());
  return read;
}

// A step's keys below `keyCount`: each present as `present(key, had, draw)` says (`had`: last step
// held it, in `reference`; `draw` uniform in [0, 100)), written one of the three ways at random or,
// one in `apartOneIn`, not at all (a pair found apart). `expected` gets this step's records.
template <typename Present>
std::vector<Step> randomStep(std::mt19937& rng, const std::vector<Record>& reference, std::uint64_t keyCount,
                             unsigned apartOneIn, std::uint64_t tag, Present present,
                             std::vector<Record>& expected) {
  std::vector<Step> steps;
  expected.clear();
  for (std::uint64_t key = 0; key < keyCount; ++key) {
    const bool had = std::binary_search(reference.begin(), reference.end(), Record{key, 0},
                                        [](const Record& a, const Record& b) { return a.key < b.key; });
    if (!present(key, had, static_cast<int>(rng() % 100))) continue;
    const Write write = static_cast<Write>(1 + rng() % 3);
    const bool written = rng() % apartOneIn != 0;
    steps.push_back({key, written ? write : Write::None});
    if (written) expected.push_back({key, tag});
  }
  return steps;
}

TEST(InPlaceMerge, EveryOldRecordIsReadInOrderAndTheNewOnesWritten) {
  std::mt19937 rng(20261206);
  Array<Record> records;
  Array<Record> spill;
  std::vector<Record> reference;  // what the two-array merge would hold
  for (int stepIndex = 1; stepIndex <= 400; ++stepIndex) {
    const auto tag = static_cast<std::uint64_t>(stepIndex);
    // This step's keys: last step's, some dropped, some new ones anywhere (runs of them at times, so
    // that the written records run far ahead of the read ones, or fall far behind).
    const int mode = stepIndex % 5;
    std::vector<Record> expected;
    const std::vector<Step> steps = randomStep(
        rng, reference, 300, 10, tag,
        [&](std::uint64_t key, bool had, int draw) {
          if (mode == 4 && key < 40) return true;  // a run of new records at the front
          return had ? draw >= (mode == 1 ? 40 : 5) : draw < (mode == 2 ? 60 : mode == 3 ? 2 : 10);
        },
        expected);
    const std::vector<Record> read = walk(records, spill, steps, tag);
    ASSERT_EQ(read, reference) << "step " << stepIndex << ": last step's records, each once, in key order";
    ASSERT_EQ(std::vector<Record>(records.begin(), records.end()), expected) << "step " << stepIndex;
    reference = expected;
  }
  EXPECT_GT(spill.size(), 0u) << "the walks ran ahead of what they read";
}

TEST(InPlaceMerge, WalksInBlocksJoinedGiveTheOneWalksArray) {
  std::mt19937 rng(7);
  for (const std::size_t blockCount : {2u, 3u, 8u}) {
    Array<Record> records;
    std::vector<Record> reference;
    for (int stepIndex = 1; stepIndex <= 200; ++stepIndex) {
      const auto tag = static_cast<std::uint64_t>(stepIndex);
      // Some steps add records mostly in the first blocks (every later block then moves back), some
      // remove them there (every later block moves to the front).
      const int mode = stepIndex % 4;
      std::vector<Record> expected;
      const std::vector<Step> steps = randomStep(
          rng, reference, 400, 8, tag,
          [&](std::uint64_t key, bool had, int draw) {
            const bool front = key < 100;
            return had ? draw >= (mode == 1 && front ? 60 : 5) : draw < (mode == 2 && front ? 70 : 8);
          },
          expected);
      const std::vector<Record> read = walkInBlocks(records, steps, tag, blockCount);
      ASSERT_EQ(read, reference) << blockCount << " blocks, step " << stepIndex;
      ASSERT_EQ(std::vector<Record>(records.begin(), records.end()), expected)
          << blockCount << " blocks, step " << stepIndex;
      reference = expected;
    }
  }
}

TEST(InPlaceMerge, AStepOfOnlyNewRecordsGrowsTheArray) {
  Array<Record> records{{5, 0}};
  Array<Record> spill;
  const std::vector<Record> read =
      walk(records, spill, {{1, Write::Fresh}, {2, Write::Fresh}, {3, Write::Fresh}, {5, Write::Keep}}, 1);
  EXPECT_EQ(read, (std::vector<Record>{{5, 0}}));
  EXPECT_EQ(std::vector<Record>(records.begin(), records.end()),
            (std::vector<Record>{{1, 1}, {2, 1}, {3, 1}, {5, 1}}));
}

TEST(InPlaceMerge, KeepingARecordInItsOwnSlotCopiesNothing) {
  Array<Record> records{{1, 0}, {2, 0}, {3, 0}};
  Array<Record> spill;
  const Record* slots = records.data();
  InPlaceMerge<Record> merge(records, spill);
  for (int i = 0; i < 3; ++i) {
    const Record& old = merge.next();
    merge.pop();
    Record& kept = merge.keep(old);
    EXPECT_EQ(&kept, &slots[i]);
  }
  merge.finish();
  EXPECT_EQ(records.data(), slots);
  EXPECT_TRUE(spill.empty());
}

// A landing: every old record is preceded by new ones, and the spill ring holds most of last step's
// records at once (megabytes in a pile of thousands). The next, quiet walk spills nothing and the
// ring's block goes back; a walk that spills a little keeps what it used.
TEST(InPlaceMerge, ALandingsSpillIsNotKeptOnceTheWalksAreQuiet) {
  constexpr std::uint64_t kOld = 100000;  // 16 bytes each: 1.6 MB
  Array<Record> records, spill;
  for (std::uint64_t k = 0; k < kOld; ++k) records.push_back({2 * k + 1, 0});
  std::vector<Step> landing;
  for (std::uint64_t k = 0; k < 2 * kOld; ++k) landing.push_back({k, Write::FromOld});
  walk(records, spill, landing, 1);
  ASSERT_EQ(records.size(), 2 * kOld);
  // The ring held up to half the old records while the new ones went ahead of them; it was kept
  // for that walk, its last use.
  EXPECT_GE(spill.capacity() * sizeof(Record), std::size_t{1} << 20);
  std::vector<Step> quiet;
  for (std::uint64_t k = 0; k < 2 * kOld; ++k) quiet.push_back({k, Write::Keep});
  const std::vector<Record> read = walk(records, spill, quiet, 2);
  EXPECT_EQ(read.size(), 2 * kOld);
  EXPECT_EQ(spill.capacity(), 0u);
  EXPECT_EQ(records.size(), 2 * kOld);
}

}  // namespace
}  // namespace collide::detail
