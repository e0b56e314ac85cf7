// Sweep and prune, in its sort-and-sweep form (Baraff 1992; Cohen et al., I-COLLIDE 1995; Terdiman,
// "Sweep-and-prune", 2007): keep the boxes sorted by their minimum on one axis, then sweep: a box can
// only overlap the boxes that start before it ends. The other two axes are checked on the candidates.
//
// The sort is incremental: an insertion sort of last step's order, which is near linear when motion
// is coherent (few boxes swap places between steps). When many boxes were added or the motion was
// incoherent (the insertion sort exceeds its budget of moves) a full sort takes over, and the sweep
// axis is then re-chosen as the one along which the movable boxes are spread the most.
//
// Static and movable boxes are kept in two sorted lists: movable-movable pairs come from a sweep of
// one list, movable-static pairs from a two-list sweep, and static-static pairs are never looked at.
#include "broadphase/broad_phase_internal.h"
#include "memory/heap_bytes.h"

#include <algorithm>

namespace collide {

namespace {

class SweepAndPruneBroadPhase final : public LinearScanBroadPhase {
 public:
  explicit SweepAndPruneBroadPhase(const BroadPhaseSettings& settings) : LinearScanBroadPhase(settings) {}

 private:
  struct Entry {
    Aabb box;
    std::uint32_t index;
    std::uint32_t generation;  // a removed (or removed and reused) slot is recognised by it
  };

  struct List {
    Array<Entry> entries;
    std::size_t appended = 0;  // entries pushed at the end since the last sort
    bool dirty = true;         // boxes changed since the last refresh
  };

  List& listOf(std::uint32_t index) {
    return proxies_[index].motion == MotionType::Static ? statics_ : movables_;
  }

  void onAdd(std::uint32_t index) override {
    List& list = listOf(index);
    list.entries.push_back({proxies_[index].bounds, index, proxies_[index].generation});
    ++list.appended;
    list.dirty = true;
  }
  // Removed entries are dropped at the next refresh: their generation no longer matches.
  void onRemove(std::uint32_t index) override { listOf(index).dirty = true; }
  void onUpdate(std::uint32_t index, const Aabb&) override { listOf(index).dirty = true; }

  // Copies the current boxes into the list (so the sweep reads contiguous memory) and drops the
  // entries of removed proxies.
  void refresh(List& list) {
    if (!list.dirty) return;
    std::size_t kept = 0;
    for (const Entry& e : list.entries) {
      const ProxyRecord& p = proxies_[e.index];
      if (!p.alive || p.generation != e.generation) continue;
      list.entries[kept++] = {p.bounds, e.index, e.generation};
    }
    list.entries.resize(kept);
    list.appended = std::min(list.appended, kept);
    list.dirty = false;
  }

  void fullSort(List& list) {
    const int axis = axis_;
    std::sort(list.entries.begin(), list.entries.end(),
              [axis](const Entry& x, const Entry& y) { return x.box.min[axis] < y.box.min[axis]; });
    list.appended = 0;
  }

  // Insertion sort with a budget of moves; returns false (the list still a permutation) when the
  // motion was too incoherent for it to pay.
  bool insertionSort(List& list) {
    const int axis = axis_;
    Array<Entry>& v = list.entries;
    const std::size_t budget = 8 * v.size() + 64;
    std::size_t moves = 0;
    for (std::size_t i = 1; i < v.size(); ++i) {
      const float key = v[i].box.min[axis];
      if (v[i - 1].box.min[axis] <= key) continue;
      const Entry e = v[i];
      std::size_t j = i;
      while (j > 0 && v[j - 1].box.min[axis] > key) {
        v[j] = v[j - 1];
        --j;
      }
      v[j] = e;
      moves += i - j;
      if (moves > budget) return false;
    }
    list.appended = 0;
    return true;
  }

  // The axis of largest variance of the movable box centres (Ericson, Real-Time Collision Detection,
  // 7.5.2): the sweep prunes best along it.
  int chooseAxis() const {
    if (movables_.entries.size() < 2) return axis_;
    Vec3 sum(0.0f), sumSquares(0.0f);
    for (const Entry& e : movables_.entries) {
      const Vec3 c = e.box.center();
      sum += c;
      sumSquares += c * c;
    }
    const float n = static_cast<float>(movables_.entries.size());
    const Vec3 variance = sumSquares / n - (sum / n) * (sum / n);
    int axis = 0;
    if (variance.y > variance[axis]) axis = 1;
    if (variance.z > variance[axis]) axis = 2;
    return axis;
  }

  void sortLists() {
    bool resort = movables_.appended > movables_.entries.size() / 8 + 16;
    if (!resort && !insertionSort(movables_)) resort = true;
    if (resort) {
      const int axis = chooseAxis();
      if (axis != axis_) {
        axis_ = axis;
        fullSort(statics_);
      }
      fullSort(movables_);
    }
    if (statics_.appended > statics_.entries.size() / 8 + 16 || !insertionSort(statics_)) fullSort(statics_);
  }

  std::size_t algorithmMemoryBytes() const override {
    return detail::heapBytes(movables_.entries) + detail::heapBytes(statics_.entries);
  }

  bool findPairKeys(Array<std::uint64_t>& outKeys, std::uint64_t& outBoxTests) override {
    refresh(movables_);
    refresh(statics_);
    sortLists();
    const int axis = axis_;
    const Array<Entry>& m = movables_.entries;
    const Array<Entry>& s = statics_.entries;

    // Movable against movable: every box that starts before box i ends, and after it starts.
    for (std::size_t i = 0; i < m.size(); ++i) {
      const Entry& a = m[i];
      const float end = a.box.max[axis];
      for (std::size_t j = i + 1; j < m.size() && m[j].box.min[axis] <= end; ++j) {
        ++outBoxTests;
        if (a.box.overlaps(m[j].box)) outKeys.push_back(pairKey(a.index, m[j].index));
      }
    }

    // Movable against static: two boxes overlap on the axis exactly when the static one starts within
    // the movable one ([m.min, m.max]) or the movable one starts within the static one ((s.min, s.max]).
    // The two sweeps below find the two cases, disjointly.
    std::size_t first = 0;
    for (const Entry& a : m) {
      while (first < s.size() && s[first].box.min[axis] < a.box.min[axis]) ++first;
      const float end = a.box.max[axis];
      for (std::size_t j = first; j < s.size() && s[j].box.min[axis] <= end; ++j) {
        ++outBoxTests;
        if (a.box.overlaps(s[j].box)) outKeys.push_back(pairKey(a.index, s[j].index));
      }
    }
    first = 0;
    for (const Entry& b : s) {
      while (first < m.size() && m[first].box.min[axis] <= b.box.min[axis]) ++first;
      const float end = b.box.max[axis];
      for (std::size_t i = first; i < m.size() && m[i].box.min[axis] <= end; ++i) {
        ++outBoxTests;
        if (b.box.overlaps(m[i].box)) outKeys.push_back(pairKey(b.index, m[i].index));
      }
    }
    return false;
  }

  List movables_;
  List statics_;
  int axis_ = 0;
};

}  // namespace

std::unique_ptr<BroadPhase> makeSweepAndPruneBroadPhase(const BroadPhaseSettings& settings) {
  return std::make_unique<SweepAndPruneBroadPhase>(settings);
}

}  // namespace collide
