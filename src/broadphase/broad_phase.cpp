// The broad-phase interface: proxy storage with generational ids, validation of every input, the
// canonical pair list, the query wrappers, and the factory of the four algorithms.
#include "base/fail.h"
#include "broadphase/broad_phase_internal.h"
#include "memory/heap_bytes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace collide {

namespace {

std::string describe(const Vec3& v) {
  std::ostringstream out;
  out << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return out.str();
}

bool inverted(const Aabb& box) {
  return box.min.x > box.max.x || box.min.y > box.max.y || box.min.z > box.max.z;
}

bool validBox(const Aabb& box, const char* what) {
  if (!isFinite(box.min) || !isFinite(box.max)) {
    COLLIDE_FAIL(std::string("broad phase: ") + what + ": box must be finite, got min " + describe(box.min) +
                     " max " + describe(box.max),
                 false);
  }
  if (inverted(box)) {
    COLLIDE_FAIL(std::string("broad phase: ") + what + ": box is inverted (min > max), got min " +
                     describe(box.min) + " max " + describe(box.max),
                 false);
  }
  return true;
}

// What resolve returns for a bad id without exceptions.
constexpr std::uint32_t kBadProxy = 0xFFFFFFFFu;
const Aabb kNoBounds{};

}  // namespace

std::string_view toString(BroadPhaseType type) {
  switch (type) {
    case BroadPhaseType::Tree:
      return "tree";
    case BroadPhaseType::SweepAndPrune:
      return "sap";
    case BroadPhaseType::Grid:
      return "grid";
    case BroadPhaseType::BruteForce:
      return "brute";
  }
  return "unknown";
}

BroadPhaseType parseBroadPhaseType(std::string_view name) {
  for (int i = 0; i < kBroadPhaseTypeCount; ++i) {
    const auto type = static_cast<BroadPhaseType>(i);
    if (toString(type) == name) return type;
  }
  COLLIDE_FAIL("broad phase: unknown type \"" + std::string(name) + "\" (expected tree, sap, grid or brute)",
               BroadPhaseType::Tree);
}

BroadPhase::~BroadPhase() = default;

std::size_t BroadPhase::memoryBytes() const {
  return detail::heapBytes(proxies_) + detail::heapBytes(freeSlots_) + detail::heapBytes(keys_) +
         algorithmMemoryBytes();
}

std::uint32_t BroadPhase::resolve(ProxyId id, const char* operation) const {
  if (id.isNull()) COLLIDE_FAIL(std::string("broad phase: ") + operation + ": null proxy id", kBadProxy);
  if (id.index >= proxies_.size()) {
    COLLIDE_FAIL(std::string("broad phase: ") + operation + ": unknown proxy id (index " +
                     std::to_string(id.index) + ", generation " + std::to_string(id.generation) + "; only " +
                     std::to_string(proxies_.size()) + " slots exist)",
                 kBadProxy);
  }
  const ProxyRecord& record = proxies_[id.index];
  if (!record.alive || record.generation != id.generation) {
    COLLIDE_FAIL(std::string("broad phase: ") + operation + ": stale proxy id (index " +
                     std::to_string(id.index) + ", generation " + std::to_string(id.generation) +
                     "; the slot is now " +
                     (record.alive ? "generation " + std::to_string(record.generation) : "free") + ")",
                 kBadProxy);
  }
  return id.index;
}

ProxyId BroadPhase::add(const ProxyDef& def) {
  if (!validBox(def.bounds, "add")) return {};
  std::uint32_t index;
  if (!freeSlots_.empty()) {
    index = freeSlots_.back();
    freeSlots_.pop_back();
  } else {
    if (proxies_.size() >= ProxyId::kNullIndex) COLLIDE_FAIL("broad phase: add: too many proxies", {});
    index = static_cast<std::uint32_t>(proxies_.size());
    proxies_.emplace_back();
  }
  ProxyRecord& record = proxies_[index];
  record.bounds = def.bounds;
  record.userValue = def.userValue;
  record.layer = def.layer;
  record.mask = def.mask;
  record.motion = def.motion;
  record.alive = true;
  ++aliveCount_;
  onAdd(index);
  return {index, record.generation};
}

void BroadPhase::remove(ProxyId id) {
  const std::uint32_t index = resolve(id, "remove");
  if (index == kBadProxy) return;
  onRemove(index);
  ProxyRecord& record = proxies_[index];
  record.alive = false;
  // A new generation on free, so the removed id (and copies of it) go stale at once.
  ++record.generation;
  --aliveCount_;
  freeSlots_.push_back(index);
}

void BroadPhase::adoptProxies(const BroadPhase& source) { adoptProxies(source.proxies_, source.freeSlots_); }

void BroadPhase::adoptProxies(std::span<const ProxyRecord> records,
                              std::span<const std::uint32_t> freeSlots) {
  if (!proxies_.empty()) COLLIDE_FAIL("broad phase: adoptProxies: this broad phase already has proxies");
  std::size_t alive = 0;
  for (std::uint32_t index = 0; index < records.size(); ++index) {
    if (!records[index].alive) continue;
    if (!validBox(records[index].bounds, "adoptProxies")) return;
    ++alive;
  }
  Array<std::uint8_t> free(records.size(), 0);
  for (const std::uint32_t slot : freeSlots) {
    if (slot >= records.size() || records[slot].alive || free[slot])
      COLLIDE_FAIL("broad phase: adoptProxies: free slot " + std::to_string(slot) +
                   " is out of range, alive or listed twice");
    free[slot] = 1;
  }
  proxies_.assign(records.begin(), records.end());
  freeSlots_.assign(freeSlots.begin(), freeSlots.end());
  aliveCount_ = alive;
  for (std::uint32_t index = 0; index < proxies_.size(); ++index) {
    if (proxies_[index].alive) onAdd(index);
  }
}

void BroadPhase::update(ProxyId id, const Aabb& bounds) {
  const std::uint32_t index = resolve(id, "update");
  if (index == kBadProxy || !validBox(bounds, "update")) return;
  const Aabb old = proxies_[index].bounds;
  proxies_[index].bounds = bounds;
  onUpdate(index, old);
}

bool BroadPhase::updateInPlace(ProxyId id, const Aabb& bounds) {
  // update()'s checks, without its errors: a refused id or box is left to update(), which names it.
  if (!contains(id) || !isFinite(bounds.min) || !isFinite(bounds.max) || inverted(bounds)) return false;
  if (!keepsInPlace(id.index, bounds)) return false;
  proxies_[id.index].bounds = bounds;
  return true;
}

bool BroadPhase::contains(ProxyId id) const {
  return !id.isNull() && id.index < proxies_.size() && proxies_[id.index].alive &&
         proxies_[id.index].generation == id.generation;
}

const Aabb& BroadPhase::bounds(ProxyId id) const {
  const std::uint32_t index = resolve(id, "bounds");
  return index == kBadProxy ? kNoBounds : proxies_[index].bounds;
}
MotionType BroadPhase::motion(ProxyId id) const {
  const std::uint32_t index = resolve(id, "motion");
  return index == kBadProxy ? MotionType::Static : proxies_[index].motion;
}
std::uint64_t BroadPhase::userValue(ProxyId id) const {
  const std::uint32_t index = resolve(id, "userValue");
  return index == kBadProxy ? 0 : proxies_[index].userValue;
}
std::uint32_t BroadPhase::layer(ProxyId id) const {
  const std::uint32_t index = resolve(id, "layer");
  return index == kBadProxy ? 0 : proxies_[index].layer;
}
void BroadPhase::setLayer(ProxyId id, std::uint32_t layer) {
  const std::uint32_t index = resolve(id, "setLayer");
  if (index == kBadProxy || proxies_[index].layer == layer) return;
  proxies_[index].layer = layer;
  onFilterChange(index);
}
LayerMask BroadPhase::mask(ProxyId id) const {
  const std::uint32_t index = resolve(id, "mask");
  return index == kBadProxy ? 0 : proxies_[index].mask;
}
void BroadPhase::setMask(ProxyId id, LayerMask mask) {
  const std::uint32_t index = resolve(id, "setMask");
  if (index == kBadProxy || proxies_[index].mask == mask) return;
  proxies_[index].mask = mask;
  onFilterChange(index);
}

const BroadPhaseStats& BroadPhase::findPairs(Array<ProxyPair>& outPairs, detail::TaskRunner& tasks) {
  tasks_ = &tasks;
  struct Clear {
    detail::TaskRunner*& tasks;
    ~Clear() { tasks = nullptr; }
  } clear{tasks_};
  return findPairs(outPairs);
}

const BroadPhaseStats& BroadPhase::findPairs(Array<ProxyPair>& outPairs) {
  keys_.clear();
  std::uint64_t boxTests = 0;
  const bool sorted = findPairKeys(keys_, boxTests);
  // The canonical order makes every algorithm's output identical and the simulation deterministic.
  if (!sorted) std::sort(keys_.begin(), keys_.end());
  outPairs.clear();
  outPairs.reserve(keys_.size());
  for (const std::uint64_t key : keys_) {
    const std::uint32_t a = pairKeyFirst(key), b = pairKeySecond(key);
    if (!masksAccept(proxies_[a], proxies_[b])) continue;
    const bool oneWay = proxies_[a].motion == MotionType::Static || proxies_[b].motion == MotionType::Static;
    outPairs.push_back({idOf(a), idOf(b), oneWay ? PairKind::OneWay : PairKind::TwoWay});
  }
  const std::uint64_t n = aliveCount_;
  stats_ = {};
  stats_.proxies = n;
  stats_.potentialPairs = n < 2 ? 0 : n * (n - 1) / 2;
  stats_.keptPairs = outPairs.size();
  stats_.boxTests = boxTests;
  return stats_;
}

void BroadPhase::rayCast(const Ray& ray, LayerMask mask, const RayCastCallback& callback) const {
  if (!isFinite(ray.origin))
    COLLIDE_FAIL("broad phase: ray cast: origin must be finite, got " + describe(ray.origin));
  if (!isFinite(ray.direction)) {
    COLLIDE_FAIL("broad phase: ray cast: direction must be finite, got " + describe(ray.direction));
  }
  const float length = glm::length(ray.direction);
  if (!(length > 0.0f) || !std::isfinite(length)) {
    COLLIDE_FAIL("broad phase: ray cast: direction must be non-zero, got " + describe(ray.direction));
  }
  if (std::isnan(ray.maxDistance) || ray.maxDistance < 0.0f) {
    COLLIDE_FAIL("broad phase: ray cast: maxDistance must be >= 0, got " + std::to_string(ray.maxDistance));
  }
  if (!callback) COLLIDE_FAIL("broad phase: ray cast: empty callback");
  RayQuery query;
  query.aim(ray.origin, ray.direction / length, ray.maxDistance);
  query.mask = mask;
  query.callback = &callback;
  query.proxies = &proxies_;
  rayCastImpl(query);
}

void BroadPhase::boxCast(const Aabb& box, const Vec3& translation, LayerMask mask,
                         const RayCastCallback& callback) const {
  if (!isFinite(box.min) || !isFinite(box.max) || !isFinite(translation)) {
    COLLIDE_FAIL("broad phase: box cast: box and translation must be finite, got box " + describe(box.min) +
                 " to " + describe(box.max) + ", translation " + describe(translation));
  }
  if (!callback) COLLIDE_FAIL("broad phase: box cast: empty callback");
  const float length = glm::length(translation);
  if (!(length > 0.0f) || !std::isfinite(length)) {
    queryAabb(box, mask, [&](ProxyId id) { return callback(id, 0.0f) >= 0.0f; });
    return;
  }
  RayQuery query;
  query.aim(box.center(), translation / length, length);
  query.extent = box.halfExtents();
  query.mask = mask;
  query.callback = &callback;
  query.proxies = &proxies_;
  rayCastImpl(query);
}

std::optional<ProxyRayHit> BroadPhase::rayCastClosest(const Ray& ray, LayerMask mask) const {
  std::optional<ProxyRayHit> best;
  rayCast(ray, mask, [&](ProxyId id, float distance) {
    // Ties go to the lowest index, so the answer does not depend on the traversal order. Clipping
    // to the hit distance (not below it) lets equally close boxes still be reported.
    if (!best || distance < best->distance || (distance == best->distance && id.index < best->id.index)) {
      best = ProxyRayHit{id, distance};
    }
    return best->distance;
  });
  return best;
}

std::vector<ProxyRayHit> BroadPhase::rayCastAll(const Ray& ray, LayerMask mask) const {
  std::vector<ProxyRayHit> hits;
  rayCast(ray, mask, [&](ProxyId id, float distance) {
    hits.push_back({id, distance});
    return std::numeric_limits<float>::infinity();
  });
  std::sort(hits.begin(), hits.end(), [](const ProxyRayHit& x, const ProxyRayHit& y) {
    return x.distance < y.distance || (x.distance == y.distance && x.id.index < y.id.index);
  });
  return hits;
}

void BroadPhase::queryAabb(const Aabb& box, LayerMask mask, const OverlapCallback& callback) const {
  queryAabb(box, mask, MotionFilter::All, callback);
}

void BroadPhase::queryAabb(const Aabb& box, LayerMask mask, MotionFilter motions,
                           const OverlapCallback& callback) const {
  if (!validBox(box, "AABB query")) return;
  if (!callback) COLLIDE_FAIL("broad phase: AABB query: empty callback");
  if (motions == MotionFilter::All) return queryAabbImpl(box, mask, callback);
  queryAabbByMotionImpl(box, mask, motions, callback);
}

void BroadPhase::queryAabbByMotionImpl(const Aabb& box, LayerMask mask, MotionFilter motions,
                                       const OverlapCallback& callback) const {
  const MotionType wanted = motions == MotionFilter::StaticOnly ? MotionType::Static : MotionType::Movable;
  queryAabbImpl(box, mask, [&](ProxyId id) { return proxies_[id.index].motion != wanted || callback(id); });
}

void BroadPhase::querySphere(const BoundingSphere& sphere, LayerMask mask,
                             const OverlapCallback& callback) const {
  if (!isFinite(sphere.center) || !std::isfinite(sphere.radius) || sphere.radius < 0.0f) {
    COLLIDE_FAIL("broad phase: sphere query: centre must be finite and radius finite and >= 0, got centre " +
                 describe(sphere.center) + " radius " + std::to_string(sphere.radius));
  }
  if (!callback) COLLIDE_FAIL("broad phase: sphere query: empty callback");
  querySphereImpl(sphere, mask, callback);
}

void BroadPhase::queryFrustum(const Frustum& frustum, LayerMask mask, const OverlapCallback& callback) const {
  for (const Plane& plane : frustum.planes) {
    const float length = glm::length(plane.normal);
    if (!isFinite(plane.normal) || !std::isfinite(plane.distance) || std::abs(length - 1.0f) > 1e-3f) {
      COLLIDE_FAIL(
          "broad phase: frustum query: planes need finite unit normals and finite distances, got normal " +
          describe(plane.normal) + " distance " + std::to_string(plane.distance));
    }
  }
  if (!callback) COLLIDE_FAIL("broad phase: frustum query: empty callback");
  queryFrustumImpl(frustum, mask, callback);
}

namespace {

std::vector<ProxyId> sortedByIndex(std::vector<ProxyId> ids) {
  std::sort(ids.begin(), ids.end(), [](ProxyId x, ProxyId y) { return x.index < y.index; });
  return ids;
}

}  // namespace

std::vector<ProxyId> BroadPhase::overlapAabb(const Aabb& box, LayerMask mask) const {
  std::vector<ProxyId> ids;
  queryAabb(box, mask, [&](ProxyId id) {
    ids.push_back(id);
    return true;
  });
  return sortedByIndex(std::move(ids));
}

std::vector<ProxyId> BroadPhase::overlapSphere(const BoundingSphere& sphere, LayerMask mask) const {
  std::vector<ProxyId> ids;
  querySphere(sphere, mask, [&](ProxyId id) {
    ids.push_back(id);
    return true;
  });
  return sortedByIndex(std::move(ids));
}

std::vector<ProxyId> BroadPhase::cullFrustum(const Frustum& frustum, LayerMask mask) const {
  std::vector<ProxyId> ids;
  queryFrustum(frustum, mask, [&](ProxyId id) {
    ids.push_back(id);
    return true;
  });
  return sortedByIndex(std::move(ids));
}

bool BroadPhase::isSegmentBlocked(const Vec3& from, const Vec3& to, LayerMask mask) const {
  if (!isFinite(from) || !isFinite(to)) {
    COLLIDE_FAIL("broad phase: line of sight: end points must be finite, got " + describe(from) + " and " +
                     describe(to),
                 false);
  }
  const Vec3 d = to - from;
  const float length = glm::length(d);
  bool blocked = false;
  if (length == 0.0f) {
    // A point: blocked when a box holds it. The AABB query with a degenerate box is that test.
    queryAabb({from, from}, mask, [&](ProxyId) {
      blocked = true;
      return false;
    });
    return blocked;
  }
  rayCast(Ray{from, d / length, length}, mask, [&](ProxyId, float) {
    blocked = true;
    return -1.0f;  // any blocker will do: stop at the first
  });
  return blocked;
}

bool detail::validateBroadPhaseSettings(const BroadPhaseSettings& settings) {
  if (!std::isfinite(settings.treeMargin) || settings.treeMargin < 0.0f) {
    COLLIDE_FAIL(
        "broad phase: treeMargin must be finite and >= 0, got " + std::to_string(settings.treeMargin), false);
  }
  if (!std::isfinite(settings.gridCellSize) || settings.gridCellSize < 0.0f) {
    COLLIDE_FAIL("broad phase: gridCellSize must be finite and >= 0 (0: automatic), got " +
                     std::to_string(settings.gridCellSize),
                 false);
  }
  if (settings.gridMaxCellsPerAxis == 0)
    COLLIDE_FAIL("broad phase: gridMaxCellsPerAxis must be >= 1, got 0", false);
  if (static_cast<int>(settings.type) >= kBroadPhaseTypeCount)
    COLLIDE_FAIL("broad phase: unknown type " + std::to_string(static_cast<int>(settings.type)), false);
  return true;
}

std::unique_ptr<BroadPhase> createBroadPhase(const BroadPhaseSettings& settings) {
  if (!detail::validateBroadPhaseSettings(settings)) return nullptr;
  switch (settings.type) {
    case BroadPhaseType::Tree:
      return makeTreeBroadPhase(settings);
    case BroadPhaseType::SweepAndPrune:
      return makeSweepAndPruneBroadPhase(settings);
    case BroadPhaseType::Grid:
      return makeGridBroadPhase(settings);
    case BroadPhaseType::BruteForce:
      return makeBruteForceBroadPhase(settings);
  }
  COLLIDE_FAIL("broad phase: unknown type " + std::to_string(static_cast<int>(settings.type)), nullptr);
}

}  // namespace collide
