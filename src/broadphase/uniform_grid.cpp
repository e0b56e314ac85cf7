// A uniform grid (spatial hash) broad phase, for many objects of similar size (Ericson, Real-Time
// Collision Detection, 7.1; Teschner et al., "Optimized spatial hashing for collision detection of
// deformable objects", 2003). Space is cut into cubic cells; each proxy is listed in every cell its box
// touches, cells are found through a hash map of their integer coordinates, and only proxies sharing
// a cell are tested. A pair sharing several cells is reported once, in the cell at the low corner of
// the intersection of their cell ranges (componentwise max of the two low corners), so no pair set is
// needed to remove duplicates.
//
// Proxies spanning more than gridMaxCellsPerAxis cells along an axis (the ground, a big wall) go to an
// "oversize" list tested against everything instead: one ground box would otherwise fill thousands
// of cells. The cell size defaults to twice the average movable box extent, measured at the first
// findPairs (until then proxies wait unbinned and queries scan them linearly).
#include "broadphase/broad_phase_internal.h"
#include "memory/heap_bytes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace collide {

namespace {

using Coord = glm::ivec3;

// Cell coordinates are packed in 21 bits each.
constexpr int kCoordLimit = 1 << 20;

std::uint64_t cellKey(const Coord& c) {
  return static_cast<std::uint64_t>(c.x + kCoordLimit) |
         (static_cast<std::uint64_t>(c.y + kCoordLimit) << 21) |
         (static_cast<std::uint64_t>(c.z + kCoordLimit) << 42);
}

bool inRange(const Coord& c, const Coord& lo, const Coord& hi) {
  return c.x >= lo.x && c.y >= lo.y && c.z >= lo.z && c.x <= hi.x && c.y <= hi.y && c.z <= hi.z;
}

class GridBroadPhase final : public BroadPhase {
 public:
  explicit GridBroadPhase(const BroadPhaseSettings& settings) : BroadPhase(settings) {
    if (settings.gridCellSize > 0.0f) setCellSize(settings.gridCellSize);
  }

  // The occupied cells (a cell is dropped when its last proxy leaves it); nothing before binning.
  std::size_t algorithmMemoryBytes() const override {
    std::size_t bytes = detail::heapBytes(cellIndex_) + detail::heapBytes(cells_) +
                        detail::heapBytes(oversize_) + detail::heapBytes(state_) + detail::heapBytes(lo_) +
                        detail::heapBytes(hi_) + detail::heapBytes(oversizeSlot_);
    for (const Cell& cell : cells_) bytes += detail::heapBytes(cell.members);
    return bytes;
  }

  void visitNodes(const NodeVisitor& visit) const override {
    for (const Cell& cell : cells_) {
      const Vec3 cellMin = Vec3(cell.coord) * cellSize_;
      visit(BroadPhaseNode{{cellMin, cellMin + Vec3(cellSize_)}, 0, true, MotionType::Movable});
    }
  }

 private:
  enum class State : std::uint8_t { Unbinned, Binned, Oversize };

  struct Cell {
    Coord coord;
    Array<std::uint32_t> members;
  };

  void setCellSize(float size) {
    cellSize_ = size;
    inverseCellSize_ = 1.0f / size;
    // Boxes are binned slightly enlarged, so that a ray walking the cells in floating point never
    // misses a box it touches exactly on a cell boundary.
    binSlack_ = 1e-4f * size;
    built_ = true;
  }

  // The cell range of a box, or false when it is too large (or too far out) for the grid.
  bool cellRange(const Aabb& box, float slack, Coord& outLo, Coord& outHi) const {
    const Vec3 lo = glm::floor((box.min - Vec3(slack)) * inverseCellSize_);
    const Vec3 hi = glm::floor((box.max + Vec3(slack)) * inverseCellSize_);
    const float limit = static_cast<float>(kCoordLimit - 1);
    for (int i = 0; i < 3; ++i) {
      if (!(lo[i] >= -limit) || !(hi[i] <= limit)) return false;
    }
    outLo = Coord(lo);
    outHi = Coord(hi);
    return true;
  }

  void growSlots(std::uint32_t index) {
    if (state_.size() <= index) {
      state_.resize(index + 1, State::Unbinned);
      lo_.resize(index + 1);
      hi_.resize(index + 1);
      oversizeSlot_.resize(index + 1, 0);
    }
  }

  void bin(std::uint32_t index) {
    const Aabb& box = proxies_[index].bounds;
    Coord lo, hi;
    const bool fits = cellRange(box, binSlack_, lo, hi);
    const auto maxCells = static_cast<int>(settings_.gridMaxCellsPerAxis);
    if (!fits || hi.x - lo.x >= maxCells || hi.y - lo.y >= maxCells || hi.z - lo.z >= maxCells) {
      state_[index] = State::Oversize;
      oversizeSlot_[index] = static_cast<std::uint32_t>(oversize_.size());
      oversize_.push_back(index);
      return;
    }
    state_[index] = State::Binned;
    lo_[index] = lo;
    hi_[index] = hi;
    if (cells_.empty() && !occupied_) {
      occupiedLo_ = lo;
      occupiedHi_ = hi;
    }
    occupied_ = true;
    occupiedLo_ = glm::min(occupiedLo_, lo);
    occupiedHi_ = glm::max(occupiedHi_, hi);
    const Vec3 extent = box.max - box.min;
    maxExtent_ = std::max(maxExtent_, std::max(extent.x, std::max(extent.y, extent.z)) + 2.0f * binSlack_);
    for (int z = lo.z; z <= hi.z; ++z) {
      for (int y = lo.y; y <= hi.y; ++y) {
        for (int x = lo.x; x <= hi.x; ++x) {
          const Coord c(x, y, z);
          auto [it, inserted] = cellIndex_.try_emplace(cellKey(c), static_cast<std::uint32_t>(cells_.size()));
          if (inserted) cells_.push_back({c, {}});
          cells_[it->second].members.push_back(index);
        }
      }
    }
  }

  void unbin(std::uint32_t index) {
    if (state_[index] == State::Oversize) {
      const std::uint32_t slot = oversizeSlot_[index];
      oversize_[slot] = oversize_.back();
      oversizeSlot_[oversize_[slot]] = slot;
      oversize_.pop_back();
    } else if (state_[index] == State::Binned) {
      const Coord lo = lo_[index], hi = hi_[index];
      for (int z = lo.z; z <= hi.z; ++z) {
        for (int y = lo.y; y <= hi.y; ++y) {
          for (int x = lo.x; x <= hi.x; ++x) removeFromCell(Coord(x, y, z), index);
        }
      }
    }
    state_[index] = State::Unbinned;
  }

  void removeFromCell(const Coord& c, std::uint32_t index) {
    const auto it = cellIndex_.find(cellKey(c));
    const std::uint32_t cellSlot = it->second;
    Array<std::uint32_t>& members = cells_[cellSlot].members;
    auto m = std::find(members.begin(), members.end(), index);
    *m = members.back();
    members.pop_back();
    if (!members.empty()) return;
    // An empty cell leaves: the last cell takes its slot, so the cell array stays dense.
    cellIndex_.erase(it);
    if (cellSlot + 1 != cells_.size()) {
      cells_[cellSlot] = std::move(cells_.back());
      cellIndex_[cellKey(cells_[cellSlot].coord)] = cellSlot;
    }
    cells_.pop_back();
  }

  void build() {
    // Twice the average movable extent: most boxes then touch one or two cells per axis.
    double sum = 0.0;
    std::size_t count = 0;
    for (int pass = 0; pass < 2 && count == 0; ++pass) {
      const MotionType wanted = pass == 0 ? MotionType::Movable : MotionType::Static;
      for (const ProxyRecord& p : proxies_) {
        if (!p.alive || p.motion != wanted) continue;
        const Vec3 d = p.bounds.max - p.bounds.min;
        sum += std::max(d.x, std::max(d.y, d.z));
        ++count;
      }
    }
    const double average = count == 0 ? 0.0 : sum / static_cast<double>(count);
    setCellSize(average > 0.0 ? static_cast<float>(2.0 * average) : 1.0f);
    for (std::uint32_t i = 0; i < proxies_.size(); ++i) {
      if (proxies_[i].alive) bin(i);
    }
  }

  void onAdd(std::uint32_t index) override {
    growSlots(index);
    state_[index] = State::Unbinned;
    if (built_) bin(index);
  }
  void onRemove(std::uint32_t index) override {
    if (built_) unbin(index);
  }
  void onUpdate(std::uint32_t index, const Aabb&) override {
    if (!built_) return;
    if (state_[index] == State::Binned) {
      Coord lo, hi;
      // Most steps a box stays within the same cells: nothing to do.
      if (cellRange(proxies_[index].bounds, binSlack_, lo, hi) && lo == lo_[index] && hi == hi_[index])
        return;
    }
    unbin(index);
    bin(index);
  }

  bool findPairKeys(Array<std::uint64_t>& outKeys, std::uint64_t& outBoxTests) override {
    if (!built_) build();
    for (const Cell& cell : cells_) {
      const Array<std::uint32_t>& members = cell.members;
      for (std::size_t i = 0; i < members.size(); ++i) {
        const std::uint32_t a = members[i];
        const ProxyRecord& pa = proxies_[a];
        for (std::size_t j = i + 1; j < members.size(); ++j) {
          const std::uint32_t b = members[j];
          const ProxyRecord& pb = proxies_[b];
          if (pa.motion == MotionType::Static && pb.motion == MotionType::Static) continue;
          if (glm::max(lo_[a], lo_[b]) != cell.coord) continue;  // reported in another shared cell
          ++outBoxTests;
          if (pa.bounds.overlaps(pb.bounds)) outKeys.push_back(pairKey(a, b));
        }
      }
    }
    // The oversize proxies against all others (an oversize pair once, from its higher index).
    for (const std::uint32_t o : oversize_) {
      const ProxyRecord& po = proxies_[o];
      for (std::uint32_t i = 0; i < proxies_.size(); ++i) {
        const ProxyRecord& p = proxies_[i];
        if (!p.alive || i == o) continue;
        if (po.motion == MotionType::Static && p.motion == MotionType::Static) continue;
        if (state_[i] == State::Oversize && i > o) continue;
        ++outBoxTests;
        if (po.bounds.overlaps(p.bounds)) outKeys.push_back(pairKey(o, i));
      }
    }
    return false;
  }

  template <typename Test>
  bool scanAll(LayerMask mask, const OverlapCallback& callback, Test&& test) const {
    const auto count = static_cast<std::uint32_t>(proxies_.size());
    for (std::uint32_t i = 0; i < count; ++i) {
      const ProxyRecord& p = proxies_[i];
      if (p.alive && passesMask(p, mask) && test(p.bounds) && !callback(idOf(i))) return false;
    }
    return true;
  }

  template <typename Test>
  bool scanOversize(LayerMask mask, const OverlapCallback& callback, Test&& test) const {
    for (const std::uint32_t i : oversize_) {
      const ProxyRecord& p = proxies_[i];
      if (passesMask(p, mask) && test(p.bounds) && !callback(idOf(i))) return false;
    }
    return true;
  }

  // Proxies in the cells of `region` that pass `test`; each reported once, from the low corner of
  // the intersection of its cell range with the region's.
  template <typename Test>
  void queryRegion(const Aabb& region, LayerMask mask, const OverlapCallback& callback, Test&& test) const {
    if (!built_) {
      scanAll(mask, callback, test);
      return;
    }
    if (!scanOversize(mask, callback, test) || !occupied_) return;
    // The region's cells, clipped to the occupied part of the grid (computed in float first, so a
    // huge region cannot overflow the integer coordinates).
    const Vec3 loF = glm::floor(region.min * inverseCellSize_);
    const Vec3 hiF = glm::floor(region.max * inverseCellSize_);
    const Coord lo(glm::clamp(loF, Vec3(occupiedLo_), Vec3(occupiedHi_) + 1.0f));
    const Coord hi(glm::clamp(hiF, Vec3(occupiedLo_) - 1.0f, Vec3(occupiedHi_)));
    if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) return;
    auto visitCell = [&](const Cell& cell) {
      for (const std::uint32_t i : cell.members) {
        if (glm::max(lo_[i], lo) != cell.coord) continue;
        const ProxyRecord& p = proxies_[i];
        if (passesMask(p, mask) && test(p.bounds) && !callback(idOf(i))) return false;
      }
      return true;
    };
    const double regionCells = double(hi.x - lo.x + 1) * double(hi.y - lo.y + 1) * double(hi.z - lo.z + 1);
    if (regionCells > static_cast<double>(cells_.size())) {
      for (const Cell& cell : cells_) {
        if (inRange(cell.coord, lo, hi) && !visitCell(cell)) return;
      }
      return;
    }
    for (int z = lo.z; z <= hi.z; ++z) {
      for (int y = lo.y; y <= hi.y; ++y) {
        for (int x = lo.x; x <= hi.x; ++x) {
          const auto it = cellIndex_.find(cellKey(Coord(x, y, z)));
          if (it != cellIndex_.end() && !visitCell(cells_[it->second])) return;
        }
      }
    }
  }

  void queryAabbImpl(const Aabb& box, LayerMask mask, const OverlapCallback& callback) const override {
    queryRegion(box, mask, callback, [&](const Aabb& b) { return b.overlaps(box); });
  }
  void querySphereImpl(const BoundingSphere& sphere, LayerMask mask,
                       const OverlapCallback& callback) const override {
    const Aabb region = Aabb::fromCenterHalfExtents(sphere.center, Vec3(sphere.radius));
    queryRegion(region, mask, callback, [&](const Aabb& b) { return sphereTouchesBox(sphere, b); });
  }

  void queryFrustumImpl(const Frustum& frustum, LayerMask mask,
                        const OverlapCallback& callback) const override {
    auto test = [&](const Aabb& b) { return frustum.intersects(b); };
    if (!built_) {
      scanAll(mask, callback, test);
      return;
    }
    if (!scanOversize(mask, callback, test)) return;
    // The per-box plane test is conservative, so a box may pass while each of its cells fails a
    // different plane. Testing "loose" cells (grown by the largest binned box) keeps the pruning
    // exact: a loose cell contains every member's box, and a box containing a passing box passes.
    Array<std::uint8_t> seen(proxies_.size(), 0);
    const Vec3 grow(maxExtent_);
    for (const Cell& cell : cells_) {
      const Vec3 cellMin = Vec3(cell.coord) * cellSize_;
      const Aabb loose{cellMin - grow, cellMin + Vec3(cellSize_) + grow};
      if (!frustum.intersects(loose)) continue;
      for (const std::uint32_t i : cell.members) {
        if (seen[i]) continue;
        seen[i] = 1;
        const ProxyRecord& p = proxies_[i];
        if (passesMask(p, mask) && test(p.bounds) && !callback(idOf(i))) return;
      }
    }
  }

  // A 3D digital differential analyser through the cells (Amanatides and Woo, "A fast voxel
  // traversal algorithm for ray tracing", 1987), stopping once the next cell starts beyond the
  // (possibly clipped) ray. A proxy is reported in the first cell of its range the ray visits: the
  // cells of a box that a straight ray crosses come one after another.
  void rayCastImpl(RayQuery& query) const override {
    // A box cast visits more than the cells the centre's ray crosses: scanned, exactly.
    if (!built_ || query.extent != Vec3(0.0f)) {
      const auto count = static_cast<std::uint32_t>(proxies_.size());
      for (std::uint32_t i = 0; i < count; ++i) {
        if (proxies_[i].alive && !query.report(i)) return;
      }
      return;
    }
    for (const std::uint32_t i : oversize_) {
      if (!query.report(i)) return;
    }
    if (!occupied_ || cells_.empty()) return;
    const Aabb region{Vec3(occupiedLo_) * cellSize_, (Vec3(occupiedHi_) + 1.0f) * cellSize_};
    const float tEnter = query.entry(region);
    if (tEnter < 0.0f) return;

    const Vec3 start = query.origin + tEnter * query.direction;
    Coord cell(glm::clamp(glm::floor(start * inverseCellSize_), Vec3(occupiedLo_), Vec3(occupiedHi_)));
    Coord step(0);
    Vec3 tNext(std::numeric_limits<float>::infinity());
    Vec3 tDelta(std::numeric_limits<float>::infinity());
    for (int i = 0; i < 3; ++i) {
      if (query.parallel[i]) continue;
      step[i] = query.direction[i] > 0.0f ? 1 : -1;
      const float boundary = (static_cast<float>(cell[i]) + (step[i] > 0 ? 1.0f : 0.0f)) * cellSize_;
      tNext[i] = std::max((boundary - query.origin[i]) * query.inverse[i], tEnter);
      tDelta[i] = cellSize_ * std::abs(query.inverse[i]);
    }
    const Coord extent = occupiedHi_ - occupiedLo_;
    std::int64_t remaining = std::int64_t(extent.x) + extent.y + extent.z + 4;
    float tCell = tEnter;
    bool hasPrevious = false;
    Coord previous(0);
    while (inRange(cell, occupiedLo_, occupiedHi_) && tCell <= query.maxDistance && remaining-- > 0) {
      const auto it = cellIndex_.find(cellKey(cell));
      if (it != cellIndex_.end()) {
        for (const std::uint32_t i : cells_[it->second].members) {
          if (hasPrevious && inRange(previous, lo_[i], hi_[i])) continue;  // already seen
          if (!query.report(i)) return;
        }
      }
      int axis = 0;
      if (tNext.y < tNext[axis]) axis = 1;
      if (tNext.z < tNext[axis]) axis = 2;
      previous = cell;
      hasPrevious = true;
      tCell = tNext[axis];
      cell[axis] += step[axis];
      tNext[axis] += tDelta[axis];
    }
  }

  float cellSize_ = 0.0f;
  float inverseCellSize_ = 0.0f;
  float binSlack_ = 0.0f;
  bool built_ = false;
  bool occupied_ = false;
  Coord occupiedLo_{0};
  Coord occupiedHi_{0};
  float maxExtent_ = 0.0f;

  std::unordered_map<std::uint64_t, std::uint32_t> cellIndex_;
  Array<Cell> cells_;
  Array<std::uint32_t> oversize_;

  Array<State> state_;
  Array<Coord> lo_;
  Array<Coord> hi_;
  Array<std::uint32_t> oversizeSlot_;
};

}  // namespace

std::unique_ptr<BroadPhase> makeGridBroadPhase(const BroadPhaseSettings& settings) {
  return std::make_unique<GridBroadPhase>(settings);
}

}  // namespace collide
