// The solve's islands and their blocks (solver_blocks.h): who is joined, how islands are packed,
// and that the blocks do not depend on the order the contacts came in.
#include "dynamics/solver_blocks.h"
#include "dynamics/solver_body.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

namespace collide::detail {
namespace {

using Contacts = std::vector<std::pair<std::int32_t, std::int32_t>>;

SolverBlocks blocksOf(std::uint32_t bodies, const Contacts& contacts) {
  SolverBlocks blocks;
  blocks.begin(bodies);
  for (const auto& [a, b] : contacts) blocks.join(a, b);
  blocks.finish();
  return blocks;
}

// Every body once, in some block, ascending within it.
void expectAPartition(const SolverBlocks& blocks, std::uint32_t bodies) {
  std::vector<int> seen(bodies, 0);
  for (std::uint32_t b = 0; b < blocks.count(); ++b) {
    const auto list = blocks.bodies(b);
    EXPECT_TRUE(std::is_sorted(list.begin(), list.end()));
    for (const std::uint32_t body : list) {
      ++seen[body];
      EXPECT_EQ(blocks.blockOf(body), b);
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(bodies));
}

TEST(SolverBlocks, ContactsBetweenSolverBodiesJoinTheirIslandsAndAStaticSideJoinsNone) {
  // 0-1-2 a chain; 5-6; 3 and 7 touch a static body (kNoSolverBody); 4, 8 and 9 touch nothing.
  const SolverBlocks blocks = blocksOf(
      10, {{0, 1}, {2, 1}, {5, 6}, {3, kNoSolverBody}, {kNoSolverBody, 7}, {kNoSolverBody, kNoSolverBody}});
  expectAPartition(blocks, 10);
  ASSERT_EQ(blocks.count(), 1u);  // small islands share a block
  EXPECT_EQ(blocks.contactCount(0), 5u);
  EXPECT_FALSE(blocks.large(0));
}

TEST(SolverBlocks, IslandsFillBlocksInTheOrderOfTheirFirstBodyAndAreNeverSplit) {
  // 600 pairs of bodies, each joined by one contact; pair i is bodies i and 1199 - i, so that an
  // island's bodies lie far apart in body order.
  Contacts contacts;
  for (std::int32_t i = 0; i < 600; ++i) contacts.push_back({i, 1199 - i});
  const SolverBlocks blocks = blocksOf(1200, contacts);
  expectAPartition(blocks, 1200);
  ASSERT_EQ(blocks.count(), 2u);
  EXPECT_EQ(blocks.contactCount(0), kBlockContacts);
  EXPECT_EQ(blocks.contactCount(1), 600u - kBlockContacts);
  for (std::int32_t i = 0; i < 600; ++i) {
    EXPECT_EQ(blocks.blockOf(static_cast<std::uint32_t>(i)),
              blocks.blockOf(static_cast<std::uint32_t>(1199 - i)));
    EXPECT_EQ(blocks.blockOf(static_cast<std::uint32_t>(i)),
              static_cast<std::uint32_t>(i) < kBlockContacts ? 0u : 1u);
  }
}

TEST(SolverBlocks, AnIslandLargerThanABlockIsABlockOfItsOwn) {
  // Bodies 0..99 alone, then a chain of 1,000 bodies, then 100 alone.
  Contacts contacts;
  for (std::int32_t i = 100; i < 1099; ++i) contacts.push_back({i, i + 1});
  const SolverBlocks blocks = blocksOf(1200, contacts);
  expectAPartition(blocks, 1200);
  ASSERT_EQ(blocks.count(), 3u);
  EXPECT_FALSE(blocks.large(0));
  EXPECT_TRUE(blocks.large(1));
  EXPECT_FALSE(blocks.large(2));
  EXPECT_EQ(blocks.contactCount(1), 999u);
  EXPECT_EQ(blocks.bodies(1).size(), 1000u);
  EXPECT_EQ(blocks.bodies(0).size(), 100u);
}

TEST(SolverBlocks, BodiesFallingFreeFillBlocksOfAtMostKBlockBodies) {
  const SolverBlocks blocks = blocksOf(5000, {});
  expectAPartition(blocks, 5000);
  ASSERT_EQ(blocks.count(), (5000 + kBlockBodies - 1) / kBlockBodies);
  for (std::uint32_t b = 0; b < blocks.count(); ++b) EXPECT_LE(blocks.bodies(b).size(), kBlockBodies);
}

TEST(SolverBlocks, TheIslandsWithJointsAreTheFirstBlockWhateverTheirSize) {
  // 600 pairs as above; pair 300 has a joint between its bodies, body 700's island (pair 499) a
  // joint to a static body, and bodies 5 and 1150 (pairs 5 and 49) are joined by a joint.
  SolverBlocks blocks;
  blocks.begin(1200);
  blocks.joinJoint(300, 899);
  blocks.joinJoint(kNoSolverBody, 700);
  blocks.joinJoint(5, 1150);
  for (std::int32_t i = 0; i < 600; ++i) blocks.join(i, 1199 - i);
  blocks.finish();
  expectAPartition(blocks, 1200);
  ASSERT_GE(blocks.count(), 2u);
  EXPECT_TRUE(blocks.jointed(0));
  EXPECT_FALSE(blocks.jointed(1));
  const std::set<std::uint32_t> jointed{5, 1194, 49, 1150, 300, 899, 499, 700};
  const auto first = blocks.bodies(0);
  EXPECT_EQ(std::set<std::uint32_t>(first.begin(), first.end()), jointed);
  EXPECT_EQ(blocks.contactCount(0), 4u);
  // The other 596 pairs fill blocks from block 1 on.
  EXPECT_EQ(blocks.contactCount(1), kBlockContacts);
  // Without joints there is no joints' block.
  EXPECT_FALSE(blocksOf(10, {{0, 1}}).jointed(0));
}

TEST(SolverBlocks, TheBlocksDoNotDependOnTheContactsOrder) {
  Contacts contacts;
  for (std::int32_t i = 0; i < 400; ++i) contacts.push_back({(i * 7) % 900, (i * 13 + 5) % 900});
  const SolverBlocks forwards = blocksOf(900, contacts);
  std::reverse(contacts.begin(), contacts.end());
  for (auto& [a, b] : contacts) std::swap(a, b);
  const SolverBlocks backwards = blocksOf(900, contacts);
  ASSERT_EQ(forwards.count(), backwards.count());
  for (std::uint32_t b = 0; b < forwards.count(); ++b) {
    const auto f = forwards.bodies(b);
    const auto r = backwards.bodies(b);
    EXPECT_TRUE(std::equal(f.begin(), f.end(), r.begin(), r.end())) << "block " << b;
    EXPECT_EQ(forwards.contactCount(b), backwards.contactCount(b));
  }
}

}  // namespace
}  // namespace collide::detail
