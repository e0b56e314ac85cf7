// The step's solve in blocks of islands. Bodies that no chain of contacts or joints joins never act
// on each other within a step, so each such group (an island, found by union-find over the joints
// and the contacts the solver takes) may run its whole substep loop on its own, before or beside
// the others, and end exactly where the solve over the whole world would have left it: each body
// meets its contacts in the same order (by colour, constraint_graph.h), and every other step of the
// loop is per body.
//
// Why: the solver streams every contact's batch several times a substep. Over a world of tens of
// thousands of contacts that is tens of megabytes a pass, more than the caches hold; a block of
// islands with a few hundred contacts stays in the core's own cache through all its substeps.
// And blocks need no barrier between them, where each colour of a pass is one (threads.md).
//
// Islands are packed into blocks of about kBlockContacts contacts, in the order of their first
// body, so that the batches of a block fill their SIMD lanes. An island larger than that is a
// block of its own, solved colour by colour on every worker, as the whole world is otherwise.
// Kinematic bodies join the islands they touch (their pose moves each substep, and the islands
// that read it must run with it); static bodies, which are not solver bodies, join none. The
// joints' passes go over every joint of the world, so the islands with joints are one block, the
// first, whatever its size.
#pragma once

#include <collide/hooks.h>

#include <cstdint>
#include <span>
#include <vector>

namespace collide::detail {

// Contacts a block of islands is filled up to, and bodies (a block of bodies falling free is only
// integrated, but one block of all of them would run on one worker).
inline constexpr std::uint32_t kBlockContacts = 512;
inline constexpr std::uint32_t kBlockBodies = 2048;

class SolverBlocks {
 public:
  // Per step, over the solver bodies: begin, join each active joint and each contact the solver
  // takes, finish.
  void begin(std::uint32_t bodyCount);
  // A joint between solver bodies a and b (kNoSolverBody for a side not in the solve).
  void joinJoint(std::int32_t a, std::int32_t b);
  // A contact between solver bodies a and b (kNoSolverBody for a static side): joins their
  // islands, and counts on the island.
  void join(std::int32_t a, std::int32_t b);
  // The islands into blocks, and each block's bodies.
  void finish();

  std::uint32_t count() const { return static_cast<std::uint32_t>(contactCount_.size()); }
  std::uint32_t contactCount(std::uint32_t block) const { return contactCount_[block]; }
  // A block of one island larger than a block: solved with every worker, colour by colour.
  bool large(std::uint32_t block) const { return contactCount_[block] > kBlockContacts; }
  // The block of the islands with joints (block 0, where there are joints).
  bool jointed(std::uint32_t block) const { return block == 0 && withJoints_; }
  // Block b's solver bodies, ascending (with one block: every solver body).
  std::span<const std::uint32_t> bodies(std::uint32_t block) const {
    return {bodyOrder_.data() + bodyStart_[block], bodyOrder_.data() + bodyStart_[block + 1]};
  }
  std::uint32_t blockOf(std::uint32_t solverBody) const { return blockOfRoot_[parent_[solverBody]]; }

  std::size_t memoryBytes() const;  // World::memoryUse

 private:
  std::uint32_t findRoot(std::uint32_t i);
  void unite(std::uint32_t a, std::uint32_t b);

  Array<std::uint32_t> parent_;        // union-find over the solver bodies; each body's root after finish
  Array<std::uint32_t> rootContacts_;  // per root: its island's contacts
  Array<std::uint32_t> rootBodies_;    // per root: its island's bodies
  Array<std::uint32_t> blockOfRoot_;   // per root: its block
  Array<std::uint32_t> bodyOrder_;
  Array<std::uint32_t> bodyStart_;
  Array<std::uint32_t> contactCount_;
  Array<std::uint8_t> jointedBody_;  // per body, then per root: a joint holds it (its island)
  bool withJoints_ = false;
};

}  // namespace collide::detail
