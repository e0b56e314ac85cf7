// Private helpers shared by the four broad-phase algorithms: the exact per-proxy tests (the same
// floating-point code in every algorithm, so that their answers are bit-for-bit equal), pair keys,
// and the ray-query state with its clip-or-stop protocol.
#pragma once

#include <collide/broadphase.h>

#include <cmath>
#include <cstdint>
#include <memory>

namespace collide {

namespace detail {
// Reports Error naming the field for bad settings (createBroadPhase refuses them); false then.
bool validateBroadPhaseSettings(const BroadPhaseSettings& settings);
}  // namespace detail

// (a, b) with a < b packed so that sorting keys sorts pairs by (a, b).
inline std::uint64_t pairKey(std::uint32_t a, std::uint32_t b) {
  return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
}
inline std::uint32_t pairKeyFirst(std::uint64_t key) { return static_cast<std::uint32_t>(key >> 32); }
inline std::uint32_t pairKeySecond(std::uint64_t key) { return static_cast<std::uint32_t>(key); }

inline bool sphereTouchesBox(const BoundingSphere& sphere, const Aabb& box) {
  const Vec3 closest = glm::clamp(sphere.center, box.min, box.max);
  const Vec3 d = closest - sphere.center;
  return glm::dot(d, d) <= sphere.radius * sphere.radius;
}

inline bool passesMask(const BroadPhase::ProxyRecord& record, LayerMask mask) {
  return (record.layer & mask) != 0;
}
// Whether two proxies pair: each one's mask is kAllLayers (no filter: any layer, 0 too) or holds
// the other's layer.
inline bool maskTakes(const BroadPhase::ProxyRecord& self, const BroadPhase::ProxyRecord& other) {
  return self.mask == kAllLayers || (other.layer & self.mask) != 0;
}
inline bool masksAccept(const BroadPhase::ProxyRecord& a, const BroadPhase::ProxyRecord& b) {
  return maskTakes(a, b) && maskTakes(b, a);
}

// The state of one ray cast. The slab test uses a precomputed inverse direction (Williams et al.,
// "An efficient and robust ray-box intersection algorithm", JGT 2005); axes along which the ray does
// not move are handled by a containment test, as math.h's rayAabbEntry does, so 0 * inf never occurs.
struct BroadPhase::RayQuery {
  Vec3 origin{0.0f};
  Vec3 direction{0.0f};
  Vec3 inverse{0.0f};
  bool parallel[3] = {false, false, false};
  float maxDistance = 0.0f;
  // A box cast's half extents: each box is grown by them, so the ray from the moving box's centre
  // enters it when the moving box first touches it (0 for a ray).
  Vec3 extent{0.0f};
  LayerMask mask = kAllLayers;
  const RayCastCallback* callback = nullptr;
  const Array<ProxyRecord>* proxies = nullptr;
  bool stopped = false;

  // Points the query from `from` along the unit `unitDirection` for `reach`, its inverse direction
  // and parallel axes with it.
  void aim(const Vec3& from, const Vec3& unitDirection, float reach) {
    origin = from;
    direction = unitDirection;
    for (int i = 0; i < 3; ++i) {
      parallel[i] = std::abs(direction[i]) < 1e-12f;
      inverse[i] = parallel[i] ? 0.0f : 1.0f / direction[i];
    }
    maxDistance = reach;
  }

  // Entry distance into the box within [0, maxDistance], or a negative value on a miss. Monotone in
  // the box: a box containing another is entered no later, which keeps tree and grid pruning exact.
  float entry(const Aabb& box) const {
    float tMin = 0.0f;
    float tMax = maxDistance;
    for (int i = 0; i < 3; ++i) {
      const float lo = box.min[i] - extent[i], hi = box.max[i] + extent[i];
      if (parallel[i]) {
        if (origin[i] < lo || origin[i] > hi) return -1.0f;
        continue;
      }
      float t0 = (lo - origin[i]) * inverse[i];
      float t1 = (hi - origin[i]) * inverse[i];
      if (t0 > t1) std::swap(t0, t1);
      tMin = t0 > tMin ? t0 : tMin;
      tMax = t1 < tMax ? t1 : tMax;
      if (tMin > tMax) return -1.0f;
    }
    return tMin;
  }

  // Tests one proxy exactly and, on a hit, hands it to the callback. Returns false once stopped.
  bool report(std::uint32_t index) {
    const ProxyRecord& record = (*proxies)[index];
    if (!passesMask(record, mask)) return true;
    const float t = entry(record.bounds);
    if (t < 0.0f) return true;
    const float next = (*callback)(ProxyId{index, record.generation}, t);
    if (next < 0.0f) {
      stopped = true;
      return false;
    }
    if (next < maxDistance) maxDistance = next;
    return true;
  }
};

// Queries by a linear scan over every proxy: exact, and all that brute force has; sweep and prune
// uses them too, since its lists are sorted only inside findPairs.
class LinearScanBroadPhase : public BroadPhase {
 protected:
  explicit LinearScanBroadPhase(const BroadPhaseSettings& settings) : BroadPhase(settings) {}

  void rayCastImpl(RayQuery& query) const override {
    const auto count = static_cast<std::uint32_t>(proxies_.size());
    for (std::uint32_t i = 0; i < count; ++i) {
      if (proxies_[i].alive && !query.report(i)) return;
    }
  }
  void queryAabbImpl(const Aabb& box, LayerMask mask, const OverlapCallback& callback) const override {
    scan(mask, callback, [&](const Aabb& b) { return b.overlaps(box); });
  }
  void querySphereImpl(const BoundingSphere& sphere, LayerMask mask,
                       const OverlapCallback& callback) const override {
    scan(mask, callback, [&](const Aabb& b) { return sphereTouchesBox(sphere, b); });
  }
  void queryFrustumImpl(const Frustum& frustum, LayerMask mask,
                        const OverlapCallback& callback) const override {
    scan(mask, callback, [&](const Aabb& b) { return frustum.intersects(b); });
  }

 private:
  template <typename Test>
  void scan(LayerMask mask, const OverlapCallback& callback, Test&& test) const {
    const auto count = static_cast<std::uint32_t>(proxies_.size());
    for (std::uint32_t i = 0; i < count; ++i) {
      const ProxyRecord& p = proxies_[i];
      if (p.alive && passesMask(p, mask) && test(p.bounds) && !callback(idOf(i))) return;
    }
  }
};

// Factories of the four algorithms (one file each).
std::unique_ptr<BroadPhase> makeTreeBroadPhase(const BroadPhaseSettings& settings);
std::unique_ptr<BroadPhase> makeSweepAndPruneBroadPhase(const BroadPhaseSettings& settings);
std::unique_ptr<BroadPhase> makeGridBroadPhase(const BroadPhaseSettings& settings);
std::unique_ptr<BroadPhase> makeBruteForceBroadPhase(const BroadPhaseSettings& settings);

// For tests: the static or movable tree of a Tree broad phase (nullptr for the other algorithms).
class DynamicTree;
const DynamicTree* treeOfBroadPhase(const BroadPhase& broadPhase, MotionType motion);

}  // namespace collide
