// The tree broad phase: two dynamic AABB trees, one for static and one for movable proxies, as in
// Box2D v3 (b2BroadPhase keeps a tree per body type) and Bullet's btDbvtBroadphase (two btDbvt).
//
// Movable proxies are stored with boxes fattened by a margin; a proxy whose tight box stays inside its
// fat box does not touch the tree at all. Only proxies whose fat box changed ("moved", re-inserted)
// are queried against both trees, and the pairs found join a persistent set of fat-box overlaps, so
// the pairs between proxies that did not move cost nothing to find again (a broad phase that touches
// only what moved). Each call then walks the persistent set once: pairs whose fat boxes separated are
// dropped, and pairs whose tight boxes overlap are reported, so the output is exact, like the others.
#include "base/fail.h"
#include "base/task_runner.h"
#include "broadphase/broad_phase_internal.h"
#include "broadphase/dynamic_tree.h"
#include "memory/heap_bytes.h"
#include "memory/scratch.h"

#include <algorithm>
#include <iterator>
#include <string>

namespace collide {

namespace {

class TreeBroadPhase final : public BroadPhase {
 public:
  explicit TreeBroadPhase(const BroadPhaseSettings& settings) : BroadPhase(settings) {}

  std::size_t algorithmMemoryBytes() const override {
    std::size_t bytes =
        staticTree_.memoryBytes() + movableTree_.memoryBytes() + detail::heapBytes(leaf_) +
        detail::heapBytes(moved_) + detail::heapBytes(moveBuffer_) + detail::heapBytes(pairs_) +
        detail::heapBytes(candidates_) + detail::heapBytes(queries_) + detail::heapBytes(workerCandidates_) +
        detail::heapBytes(chunks_) + detail::heapBytes(merged_) + detail::heapBytes(reported_);
    for (const WorkerCandidates& worker : workerCandidates_) bytes += detail::heapBytes(worker.keys);
    return bytes;
  }

  void validate() const override {
    const detail::ErrorScope scope;
    staticTree_.validate();
    COLLIDE_RETURN_IF_FAILED();
    movableTree_.validate();
    COLLIDE_RETURN_IF_FAILED();
    std::size_t statics = 0, movables = 0;
    for (std::uint32_t i = 0; i < proxies_.size(); ++i) {
      const ProxyRecord& p = proxies_[i];
      if (!p.alive) continue;
      const DynamicTree& tree = treeOf(i);
      (p.motion == MotionType::Static ? statics : movables) += 1;
      if (tree.proxy(leaf_[i]) != i)
        COLLIDE_FAIL("tree broad phase: leaf of proxy " + std::to_string(i) + " is wrong");
      if (!tree.box(leaf_[i]).contains(p.bounds)) {
        COLLIDE_FAIL("tree broad phase: fat box of proxy " + std::to_string(i) + " does not contain its box");
      }
    }
    if (statics != staticTree_.leafCount() || movables != movableTree_.leafCount()) {
      COLLIDE_FAIL("tree broad phase: leaf counts do not match the proxies");
    }
  }

  const DynamicTree& staticTree() const { return staticTree_; }
  const DynamicTree& movableTree() const { return movableTree_; }

  void visitNodes(const NodeVisitor& visit) const override {
    visitTree(staticTree_, MotionType::Static, visit);
    visitTree(movableTree_, MotionType::Movable, visit);
  }

 private:
  DynamicTree& treeOf(std::uint32_t index) {
    return proxies_[index].motion == MotionType::Static ? staticTree_ : movableTree_;
  }
  const DynamicTree& treeOf(std::uint32_t index) const {
    return proxies_[index].motion == MotionType::Static ? staticTree_ : movableTree_;
  }
  Aabb fatten(std::uint32_t index) const {
    const ProxyRecord& p = proxies_[index];
    return p.motion == MotionType::Static ? p.bounds : p.bounds.expanded(settings_.treeMargin);
  }
  const Aabb& fatBox(std::uint32_t index) const { return treeOf(index).box(leaf_[index]); }

  void markMoved(std::uint32_t index) {
    if (!moved_[index]) {
      moved_[index] = 1;
      moveBuffer_.push_back(index);
    }
  }

  void onAdd(std::uint32_t index) override {
    if (leaf_.size() <= index) {
      leaf_.resize(index + 1, DynamicTree::kNull);
      moved_.resize(index + 1, 0);
    }
    leaf_[index] = treeOf(index).insert(fatten(index), index, proxies_[index].layer);
    markMoved(index);
  }

  // The nodes' layer unions take the new layer, and the proxy queries again: a pair its mask or a
  // partner's left out may be wanted now.
  void onFilterChange(std::uint32_t index) override {
    treeOf(index).setLayers(leaf_[index], proxies_[index].layer);
    markMoved(index);
  }

  void onRemove(std::uint32_t index) override {
    treeOf(index).remove(leaf_[index]);
    leaf_[index] = DynamicTree::kNull;
    // Its pairs leave the persistent set in the next findPairs (the record is no longer alive, or the
    // slot holds a new proxy, which is then in the move buffer and checked afresh).
    moved_[index] = 0;
  }

  // The whole point of the margin: a small motion leaves the tree and the pair set untouched.
  bool keepsInPlace(std::uint32_t index, const Aabb& bounds) const override {
    return proxies_[index].motion == MotionType::Movable && fatBox(index).contains(bounds);
  }
  void onUpdate(std::uint32_t index, const Aabb& oldBounds) override {
    const ProxyRecord& p = proxies_[index];
    DynamicTree& tree = treeOf(index);
    if (keepsInPlace(index, p.bounds)) return;
    Aabb fat = fatten(index);
    if (p.motion == MotionType::Movable) {
      // Stretched ahead along the motion, so that a body moving steadily stays inside for a few
      // steps (Box2D v2's b2_aabbMultiplier). The pairs are exact whatever the fat boxes. At most
      // by the box's own size: a body teleported far, or a bullet, would otherwise drag a box
      // across half the world that every pass over the pairs then tests.
      const Vec3 size = p.bounds.max - p.bounds.min;
      const float most = std::max(size.x, std::max(size.y, size.z));
      const Vec3 moved = glm::clamp(
          (kStretchAhead * 0.5f) * ((p.bounds.min + p.bounds.max) - (oldBounds.min + oldBounds.max)),
          Vec3(-most), Vec3(most));
      fat.min = glm::min(fat.min, fat.min + moved);
      fat.max = glm::max(fat.max, fat.max + moved);
    }
    tree.move(leaf_[index], fat);
    markMoved(index);
  }
  // Displacements of the last update a re-inserted fat box reaches ahead: four made the joint grid
  // and rain-jittered 6 % faster than none, eight rain-jittered 4 % slower than four.
  static constexpr float kStretchAhead = 4.0f;

  bool findPairKeys(Array<std::uint64_t>& outKeys, std::uint64_t& outBoxTests) override {
    // 1. New fat-box overlaps of the moved proxies, against both trees (a static one only against
    //    the movable tree: static-static pairs are never wanted).
    //    The queries only read the trees: with workers, ranges of them run in parallel, each
    //    worker collecting into its own list; the sort below makes the order of the lists moot.
    candidates_.clear();
    queries_.clear();
    // moved_ stays set through the queries (2: queued once, though a slot removed and added again
    // is in the buffer twice); 0 is a proxy removed since it was buffered.
    for (const std::uint32_t i : moveBuffer_) {
      if (moved_[i] != 1) continue;
      moved_[i] = 2;
      queries_.push_back(i);
    }
    moveBuffer_.clear();
    const std::uint32_t queryCount = static_cast<std::uint32_t>(queries_.size());
    if (tasks_ != nullptr && tasks_->workerCount() > 1 && queryCount > kQueriesPerRange) {
      const std::size_t workers = static_cast<std::size_t>(tasks_->workerCount());
      if (workerCandidates_.size() < workers) workerCandidates_.resize(workers);
      for (WorkerCandidates& w : workerCandidates_) {
        w.keys.clear();
        w.boxTests = 0;
      }
      tasks_->parallelFor(queryCount, kQueriesPerRange,
                          [&](std::uint32_t begin, std::uint32_t end, std::uint32_t worker) {
                            WorkerCandidates& w = workerCandidates_[worker];
                            for (std::uint32_t k = begin; k < end; ++k)
                              queryMoved(queries_[k], w.keys, w.boxTests);
                          });
      for (WorkerCandidates& w : workerCandidates_) {
        candidates_.insert(candidates_.end(), w.keys.begin(), w.keys.end());
        outBoxTests += w.boxTests;
        // As candidates_ below: a worker's share of the first step's burst is not kept.
        detail::releaseOversizedScratch(w.keys, w.keys.size());
      }
    } else {
      for (const std::uint32_t i : queries_) queryMoved(i, candidates_, outBoxTests);
      for (WorkerCandidates& w : workerCandidates_)
        detail::releaseOversizedScratch(w.keys, 0);  // unused this step
    }
    for (const std::uint32_t i : queries_) moved_[i] = 0;
    const std::size_t candidateCount = candidates_.size();
    std::sort(candidates_.begin(), candidates_.end());
    candidates_.erase(std::unique(candidates_.begin(), candidates_.end()), candidates_.end());

    // 2. Merge them into the persistent set (both sorted): each key of the union gets its verdict
    //    (pairVerdict: dropped, kept, or kept and reported), and the kept and the reported keys are
    //    written in key order, so the output stays sorted. The union is cut into chunks of keys
    //    (at keys of the longer list, the other split where they fall in it); a chunk's merge only
    //    reads boxes and writes its own part of the two lists, so chunks run in parallel, and the
    //    lists are then closed up chunk by chunk: the same keys in the same order at any count.
    const std::size_t pairCount = pairs_.size();
    const std::size_t total = pairCount + candidates_.size();
    const bool byPairs = pairCount >= candidates_.size();
    const Array<std::uint64_t>& longer = byPairs ? pairs_ : candidates_;
    const Array<std::uint64_t>& shorter = byPairs ? candidates_ : pairs_;
    const std::uint32_t chunkCount = static_cast<std::uint32_t>(
        std::max<std::size_t>(1, (longer.size() + kKeysPerChunk - 1) / kKeysPerChunk));
    chunks_.resize(chunkCount + 1);
    for (std::uint32_t c = 0; c <= chunkCount; ++c) {
      MergeChunk& chunk = chunks_[c];
      chunk.longerBegin = longer.size() * c / chunkCount;
      // The shorter list's keys below the chunk's first key of the longer one are the chunk before's.
      chunk.shorterBegin = c == 0 ? 0
                           : c == chunkCount
                               ? shorter.size()
                               : static_cast<std::size_t>(std::lower_bound(shorter.begin(), shorter.end(),
                                                                           longer[chunk.longerBegin]) -
                                                          shorter.begin());
    }
    // Each chunk writes at its first keys' offset in both lists (a union is no longer than them).
    if (merged_.capacity() < total) {
      merged_.clear();
      merged_.reserve(total);  // exactly: resize alone would double last step's pairs
    }
    merged_.resize(total);
    reported_.resize(total);
    auto mergeChunks = [&](std::uint32_t begin, std::uint32_t end, std::uint32_t) {
      for (std::uint32_t c = begin; c < end; ++c) {
        MergeChunk& chunk = chunks_[c];
        const MergeChunk& next = chunks_[c + 1];
        const std::size_t at = chunk.longerBegin + chunk.shorterBegin;
        mergeChunk(
            byPairs ? chunk.longerBegin : chunk.shorterBegin, byPairs ? next.longerBegin : next.shorterBegin,
            byPairs ? chunk.shorterBegin : chunk.longerBegin, byPairs ? next.shorterBegin : next.longerBegin,
            merged_.data() + at, reported_.data() + at, chunk);
      }
    };
    if (tasks_ != nullptr) {
      tasks_->parallelFor(chunkCount, 1, mergeChunks);
    } else {
      mergeChunks(0, chunkCount, 0);
    }
    std::size_t kept = 0, reported = 0;
    for (std::uint32_t c = 0; c < chunkCount; ++c) {
      const MergeChunk& chunk = chunks_[c];
      reported += chunk.reported;
      outBoxTests += chunk.boxTests;
    }
    // Grown as push_back would grow it (insert would take the exact size, and grow again next step).
    const std::size_t needed = outKeys.size() + reported;
    if (outKeys.capacity() < needed) outKeys.reserve(std::max(needed, 2 * outKeys.capacity()));
    for (std::uint32_t c = 0; c < chunkCount; ++c) {
      const MergeChunk& chunk = chunks_[c];
      const std::size_t at = chunk.longerBegin + chunk.shorterBegin;
      outKeys.insert(outKeys.end(), reported_.begin() + static_cast<std::ptrdiff_t>(at),
                     reported_.begin() + static_cast<std::ptrdiff_t>(at + chunk.reported));
      // Never ahead of its own place: kept keys of earlier chunks are at most their chunks' size.
      if (kept != at)
        std::copy_n(merged_.begin() + static_cast<std::ptrdiff_t>(at), chunk.kept,
                    merged_.begin() + static_cast<std::ptrdiff_t>(kept));
      kept += chunk.kept;
    }
    merged_.resize(kept);
    pairs_.swap(merged_);
    // The first step queries every proxy, a later one those that moved out of their fat boxes: the
    // candidates of the first (2 MB in a heap of 8,000 spheres) are not kept for the rest.
    detail::releaseOversizedScratch(candidates_, candidateCount);
    return true;
  }

  // One chunk of the merge: where it starts in the longer and the shorter list, and what it wrote.
  struct MergeChunk {
    std::size_t longerBegin = 0;
    std::size_t shorterBegin = 0;
    std::size_t kept = 0;
    std::size_t reported = 0;
    std::uint64_t boxTests = 0;
  };

  // The union of pairs_[p, pEnd) and candidates_[q, qEnd), each key judged once: the kept keys to
  // kept, the reported ones to reported, in key order. A step's candidates are few beside the
  // persistent set: the walk runs through the pairs between two candidates without a comparison.
  void mergeChunk(std::size_t p, std::size_t pEnd, std::size_t q, std::size_t qEnd, std::uint64_t* kept,
                  std::uint64_t* reported, MergeChunk& out) const {
    std::size_t keptCount = 0, reportedCount = 0;
    std::uint64_t boxTests = 0;
    // Without branches on the verdict: in a heap a key is about as often kept as reported, and a
    // branch on it would be mispredicted every other key. Each key is written to both lists, and
    // each list's end moves past it when the verdict keeps it there.
    const auto judge = [&](std::uint64_t key) {
      const PairVerdict v = pairVerdict(key);
      boxTests += (v >= PairVerdict::FatApart ? 1 : 0) + (v >= PairVerdict::Kept ? 1 : 0);
      kept[keptCount] = key;
      keptCount += v >= PairVerdict::Kept ? 1 : 0;
      reported[reportedCount] = key;
      reportedCount += v == PairVerdict::Reported ? 1 : 0;
    };
    for (; q < qEnd; ++q) {
      const std::uint64_t candidate = candidates_[q];
      for (; p < pEnd && pairs_[p] < candidate; ++p) judge(pairs_[p]);
      if (p < pEnd && pairs_[p] == candidate) ++p;  // already in the set: judged once
      judge(candidate);
    }
    for (; p < pEnd; ++p) judge(pairs_[p]);
    out.kept = keptCount;
    out.reported = reportedCount;
    out.boxTests = boxTests;
  }

  // What the merge does with a key of the persistent set or the candidates, in order: its box tests
  // are one for FatApart and two for Kept and Reported.
  enum class PairVerdict : std::uint8_t {
    Gone,      // a proxy was removed (or its slot holds a static proxy now, beside a static one)
    FatApart,  // the fat boxes no longer overlap: the pair leaves the persistent set
    Kept,      // the fat boxes overlap: the pair stays, unreported
    Reported,  // and the tight boxes overlap too: the pair is found
  };
  PairVerdict pairVerdict(std::uint64_t key) const {
    const std::uint32_t a = pairKeyFirst(key), b = pairKeySecond(key);
    const ProxyRecord& pa = proxies_[a];
    const ProxyRecord& pb = proxies_[b];
    if (!pa.alive || !pb.alive) return PairVerdict::Gone;
    if (pa.motion == MotionType::Static && pb.motion == MotionType::Static) return PairVerdict::Gone;
    if (!masksAccept(pa, pb)) return PairVerdict::Gone;  // a layer or mask changed since it was found
    if (!fatBox(a).overlaps(fatBox(b))) return PairVerdict::FatApart;
    return pa.bounds.overlaps(pb.bounds) ? PairVerdict::Reported : PairVerdict::Kept;
  }

  // The new fat-box overlaps of moved proxy i, against both trees (a static one only against the
  // movable tree: static-static pairs are never wanted), among the proxies its mask and theirs
  // accept: the subtrees of layers outside its mask are skipped whole. Two moved proxies find each
  // other from both sides; the lower index keeps the pair (Box2D's rule), so each is a candidate once.
  void queryMoved(std::uint32_t i, Array<std::uint64_t>& keys, std::uint64_t& boxTests) const {
    const Aabb query = fatBox(i);
    const ProxyRecord& self = proxies_[i];
    auto collect = [&](const DynamicTree::Node& leaf) {
      const std::uint32_t j = leaf.proxy;
      if (j != i && (j > i || !moved_[j]) && masksAccept(self, proxies_[j])) keys.push_back(pairKey(i, j));
      return true;
    };
    auto overlapsQuery = [&](const Aabb& box) { return box.overlaps(query); };
    movableTree_.traverse(overlapsQuery, collect, boxTests, self.mask);
    if (self.motion == MotionType::Movable) staticTree_.traverse(overlapsQuery, collect, boxTests, self.mask);
  }

  void rayCastImpl(RayQuery& query) const override {
    rayCastTree(staticTree_, query);
    if (!query.stopped) rayCastTree(movableTree_, query);
  }

  static void visitTree(const DynamicTree& tree, MotionType motion, const NodeVisitor& visit) {
    if (tree.root() == DynamicTree::kNull) return;
    Array<std::pair<std::int32_t, int>> stack{{tree.root(), 0}};  // node, depth
    while (!stack.empty()) {
      const auto [index, depth] = stack.back();
      stack.pop_back();
      const DynamicTree::Node& n = tree.node(index);
      visit(BroadPhaseNode{n.box, depth, n.isLeaf(), motion});
      if (n.isLeaf()) continue;
      stack.push_back({n.child1, depth + 1});
      stack.push_back({n.child2, depth + 1});
    }
  }

  // Depth first, nearer child first, so that a closest-hit callback clips the ray early. Subtrees
  // with no layer in the query's mask are not entered.
  static void rayCastTree(const DynamicTree& tree, RayQuery& query) {
    if (tree.root() == DynamicTree::kNull) return;
    const auto entry = [&](std::int32_t index) {
      const DynamicTree::Node& n = tree.node(index);
      return (n.layers & query.mask) == 0 ? -1.0f : query.entry(n.box);
    };
    if (entry(tree.root()) < 0.0f) return;
    NodeStack stack;
    stack.push(tree.root());
    while (!stack.empty()) {
      const DynamicTree::Node& n = tree.node(stack.pop());
      // Pushed nodes were hit when pushed; the ray may have been clipped since.
      if (n.isLeaf()) {
        if (!query.report(n.proxy)) return;
        continue;
      }
      const float t1 = entry(n.child1);
      const float t2 = entry(n.child2);
      if (t1 >= 0.0f && t2 >= 0.0f) {
        if (t1 <= t2) {
          stack.push(n.child2);
          stack.push(n.child1);
        } else {
          stack.push(n.child1);
          stack.push(n.child2);
        }
      } else if (t1 >= 0.0f) {
        stack.push(n.child1);
      } else if (t2 >= 0.0f) {
        stack.push(n.child2);
      }
    }
  }

  template <typename Test>
  void query(LayerMask mask, const OverlapCallback& callback, Test&& test,
             MotionFilter motions = MotionFilter::All) const {
    std::uint64_t tests = 0;
    auto visit = [&](const DynamicTree::Node& leaf) {
      const ProxyRecord& p = proxies_[leaf.proxy];
      if (!passesMask(p, mask) || !test(p.bounds)) return true;
      return callback(idOf(leaf.proxy));
    };
    if (motions != MotionFilter::MovableOnly && !staticTree_.traverse(test, visit, tests, mask)) return;
    if (motions != MotionFilter::StaticOnly) movableTree_.traverse(test, visit, tests, mask);
  }

  void queryAabbImpl(const Aabb& box, LayerMask mask, const OverlapCallback& callback) const override {
    query(mask, callback, [&](const Aabb& b) { return b.overlaps(box); });
  }
  // One tree alone.
  void queryAabbByMotionImpl(const Aabb& box, LayerMask mask, MotionFilter motions,
                             const OverlapCallback& callback) const override {
    query(
        mask, callback, [&](const Aabb& b) { return b.overlaps(box); }, motions);
  }
  void querySphereImpl(const BoundingSphere& sphere, LayerMask mask,
                       const OverlapCallback& callback) const override {
    query(mask, callback, [&](const Aabb& b) { return sphereTouchesBox(sphere, b); });
  }
  void queryFrustumImpl(const Frustum& frustum, LayerMask mask,
                        const OverlapCallback& callback) const override {
    query(mask, callback, [&](const Aabb& b) { return frustum.intersects(b); });
  }

  DynamicTree staticTree_;
  DynamicTree movableTree_;
  Array<std::int32_t> leaf_;   // per proxy: its leaf in its tree
  Array<std::uint8_t> moved_;  // per proxy: in the move buffer (2 while its query is queued)
  Array<std::uint32_t> moveBuffer_;
  Array<std::uint64_t> pairs_;  // sorted keys of all fat-box overlaps (persistent)
  Array<std::uint64_t> candidates_;
  Array<std::uint32_t> queries_;  // the moved proxies still alive, in move-buffer order
  // Per worker, on its own cache lines: the keys and box tests of its queries.
  struct alignas(64) WorkerCandidates {
    Array<std::uint64_t> keys;
    std::uint64_t boxTests = 0;
  };
  Array<WorkerCandidates> workerCandidates_;
  static constexpr std::uint32_t kQueriesPerRange = 128;
  // The merge's scratch: its chunks, the kept keys (the next persistent set) and the reported ones.
  static constexpr std::size_t kKeysPerChunk = 8192;
  Array<MergeChunk> chunks_;
  Array<std::uint64_t> merged_;
  Array<std::uint64_t> reported_;
};

}  // namespace

std::unique_ptr<BroadPhase> makeTreeBroadPhase(const BroadPhaseSettings& settings) {
  return std::make_unique<TreeBroadPhase>(settings);
}

// For tests: the trees' own invariants and heights.
const DynamicTree* treeOfBroadPhase(const BroadPhase& broadPhase, MotionType motion) {
  // The type tells the class (createBroadPhase makes a TreeBroadPhase for Tree alone): no RTTI needed.
  if (broadPhase.type() != BroadPhaseType::Tree) return nullptr;
  const auto* tree = static_cast<const TreeBroadPhase*>(&broadPhase);
  return motion == MotionType::Static ? &tree->staticTree() : &tree->movableTree();
}

}  // namespace collide
