// The solve's blocks of islands (solver_blocks.h).
#include "dynamics/solver_blocks.h"

#include "memory/heap_bytes.h"

#include <limits>

namespace collide::detail {

namespace {
constexpr std::uint32_t kNoBlock = std::numeric_limits<std::uint32_t>::max();
}  // namespace

std::uint32_t SolverBlocks::findRoot(std::uint32_t i) {
  while (parent_[i] != i) {
    parent_[i] = parent_[parent_[i]];  // path halving
    i = parent_[i];
  }
  return i;
}

void SolverBlocks::begin(std::uint32_t bodyCount) {
  parent_.resize(bodyCount);
  for (std::uint32_t i = 0; i < bodyCount; ++i) parent_[i] = i;
  rootContacts_.assign(bodyCount, 0);
  jointedBody_.assign(bodyCount, 0);
  withJoints_ = false;
}

void SolverBlocks::joinJoint(std::int32_t a, std::int32_t b) {
  if (a >= 0) jointedBody_[static_cast<std::uint32_t>(a)] = 1;
  if (b >= 0) jointedBody_[static_cast<std::uint32_t>(b)] = 1;
  if (a < 0 || b < 0) return;
  unite(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
}

void SolverBlocks::join(std::int32_t a, std::int32_t b) {
  if (a < 0 && b < 0) return;
  ++rootContacts_[static_cast<std::uint32_t>(a >= 0 ? a : b)];  // summed per island in finish()
  if (a < 0 || b < 0) return;
  unite(static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b));
}

void SolverBlocks::unite(std::uint32_t a, std::uint32_t b) {
  const std::uint32_t rootA = findRoot(a);
  const std::uint32_t rootB = findRoot(b);
  // The lower index is the root: the same islands whatever order the joins come in.
  if (rootA < rootB) {
    parent_[rootB] = rootA;
  } else if (rootB < rootA) {
    parent_[rootA] = rootB;
  }
}

void SolverBlocks::finish() {
  const std::uint32_t n = static_cast<std::uint32_t>(parent_.size());
  // Each body's root and its island's totals. A root has the lowest index of its island, so it is
  // met first and is its own root when met.
  rootBodies_.assign(n, 0);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t root = findRoot(i);
    parent_[i] = root;
    ++rootBodies_[root];
    if (root != i) {
      rootContacts_[root] += rootContacts_[i];
      rootContacts_[i] = 0;
      jointedBody_[root] |= jointedBody_[i];
    }
  }
  // The islands with joints into block 0, the others into blocks in the order of their first body.
  blockOfRoot_.assign(n, kNoBlock);
  contactCount_.clear();
  bodyStart_.assign(1, 0);  // each block's body count first, then the starts
  for (std::uint32_t i = 0; i < n; ++i) {
    if (parent_[i] != i || !jointedBody_[i]) continue;
    if (!withJoints_) {
      withJoints_ = true;
      contactCount_.push_back(0);
      bodyStart_.push_back(0);
    }
    blockOfRoot_[i] = 0;
    contactCount_[0] += rootContacts_[i];
    bodyStart_[1] += rootBodies_[i];
  }
  const std::size_t firstFree = contactCount_.size();  // blocks from here take islands without joints
  for (std::uint32_t i = 0; i < n; ++i) {
    if (parent_[i] != i || jointedBody_[i]) continue;
    const std::uint32_t contactsHere = rootContacts_[i];
    const std::uint32_t bodiesHere = rootBodies_[i];
    if (contactCount_.size() == firstFree ||
        (bodyStart_.back() > 0 && (contactCount_.back() + contactsHere > kBlockContacts ||
                                   bodyStart_.back() + bodiesHere > kBlockBodies))) {
      contactCount_.push_back(0);
      bodyStart_.push_back(0);
    }
    blockOfRoot_[i] = static_cast<std::uint32_t>(contactCount_.size() - 1);
    contactCount_.back() += contactsHere;
    bodyStart_.back() += bodiesHere;
  }
  if (contactCount_.empty()) {  // no solver bodies
    contactCount_.push_back(0);
    bodyStart_.push_back(0);
  }
  // Counts to starts, and the bodies placed block by block, ascending within each (a counting sort).
  for (std::size_t b = 1; b < bodyStart_.size(); ++b) bodyStart_[b] += bodyStart_[b - 1];
  bodyOrder_.resize(n);
  Array<std::uint32_t>& next = rootContacts_;  // the totals are used; their array holds the cursors
  next.assign(count(), 0);
  for (std::uint32_t b = 0; b < count(); ++b) next[b] = bodyStart_[b];
  for (std::uint32_t i = 0; i < n; ++i) bodyOrder_[next[blockOfRoot_[parent_[i]]]++] = i;
}

std::size_t SolverBlocks::memoryBytes() const {
  return heapBytes(parent_) + heapBytes(rootContacts_) + heapBytes(rootBodies_) + heapBytes(jointedBody_) +
         heapBytes(blockOfRoot_) + heapBytes(bodyOrder_) + heapBytes(contactCount_) + heapBytes(bodyStart_);
}

}  // namespace collide::detail
