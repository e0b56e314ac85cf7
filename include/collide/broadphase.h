// The broad phase (lecture, "a preliminary observation"): almost all pairs of objects, almost all of
// the time, do not collide (the billiard shot: under 0.02% of the potential tests are contacts), so n
// objects must not cost n² narrow-phase tests. The broad phase keeps one AABB per proxy and reports
// only the pairs whose boxes overlap; it also answers the spatial queries (rays, overlaps, frustum
// culling, line of sight) over the same structure.
//
// Four algorithms sit behind one interface and give exactly the same answers:
//   Tree           dynamic AABB tree (as Box2D's b2DynamicTree and Bullet's btDbvt), the default;
//   SweepAndPrune  sort-and-sweep on one axis with an incremental (insertion) sort;
//   Grid           uniform grid / spatial hash, for many similar-sized objects;
//   BruteForce     the n² reference.
// See docs/broadphase.md for the semantics and when to choose which.
#pragma once

#include <collide/error.h>
#include <collide/function_ref.h>
#include <collide/math.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace collide {

namespace detail {
class TaskRunner;  // the world's parallel loops (src/base/task_runner.h)
}

enum class BroadPhaseType : std::uint8_t { Tree, SweepAndPrune, Grid, BruteForce };
inline constexpr int kBroadPhaseTypeCount = 4;

// The names used in scene files: "tree", "sap", "grid", "brute".
std::string_view toString(BroadPhaseType type);
// Throws collide::Error on an unknown name.
BroadPhaseType parseBroadPhaseType(std::string_view name);

// Static proxies never move (or move rarely, e.g. a door): static-static pairs are never produced,
// which is a feature, not a limitation (lecture: walls may interpenetrate).
enum class MotionType : std::uint8_t { Static, Movable };

// A handle to a proxy (Box2D v3 style): a slot index plus a generation that changes whenever the
// slot is freed, so a stale id is detected and reported rather than silently aliasing a new proxy.
struct ProxyId {
  static constexpr std::uint32_t kNullIndex = 0xFFFFFFFFu;
  std::uint32_t index = kNullIndex;
  std::uint32_t generation = 0;

  bool isNull() const { return index == kNullIndex; }
  friend bool operator==(const ProxyId&, const ProxyId&) = default;
};

using LayerMask = std::uint32_t;
inline constexpr LayerMask kAllLayers = 0xFFFFFFFFu;

struct ProxyDef {
  Aabb bounds{Vec3(0.0f), Vec3(0.0f)};  // finite, min <= max on every axis
  MotionType motion = MotionType::Movable;
  std::uint64_t userValue = 0;
  std::uint32_t layer = 1;  // the bits a query mask is tested against
  // The layers it pairs with: findPairs reports a pair only when each proxy's mask is kAllLayers
  // (no filter, the default) or shares a bit with the other's layer (the world's collision filter).
  // The tree skips whole subtrees of layers the mask leaves out, as it does for a query's mask.
  LayerMask mask = kAllLayers;
};

// Which proxies a query takes by their motion type (BroadPhase::queryAabb).
enum class MotionFilter : std::uint8_t { All, StaticOnly, MovableOnly };

// Lecture vocabulary: a one-way pair is a movable proxy against a static one (only the movable one
// responds), a two-way pair is two movable proxies.
enum class PairKind : std::uint8_t { OneWay, TwoWay };

// A pair of proxies whose (tight) boxes overlap, with a.index < b.index.
struct ProxyPair {
  ProxyId a;
  ProxyId b;
  PairKind kind = PairKind::TwoWay;
  friend bool operator==(const ProxyPair&, const ProxyPair&) = default;
};

// Counters of one findPairs call. The broad phase fills the first four; the caller fills the last
// three after its narrow phase, so that one struct tells the whole funnel of the lecture's argument.
struct BroadPhaseStats {
  std::uint64_t proxies = 0;
  std::uint64_t potentialPairs = 0;  // n (n - 1) / 2 over all proxies, static ones included
  std::uint64_t keptPairs = 0;       // the pairs reported (box overlaps, static-static excluded)
  std::uint64_t boxTests = 0;        // AABB-vs-AABB tests the algorithm performed to find them

  // The fraction of potential pairs the broad phase kept (0 when there are none).
  double keptFraction() const {
    return potentialPairs == 0 ? 0.0 : static_cast<double>(keptPairs) / static_cast<double>(potentialPairs);
  }
};

struct BroadPhaseSettings {
  BroadPhaseType type = BroadPhaseType::Tree;
  // Tree: movable proxies are stored with boxes fattened by this margin, so that small motions do
  // not touch the tree (Box2D's aabbMargin; Bullet's dbvt margin).
  float treeMargin = 0.1f;
  // Grid: the cell edge length; 0 picks twice the average movable box extent at the first findPairs.
  float gridCellSize = 0.0f;
  // Grid: proxies spanning more cells than this along any axis (the ground) are kept in a separate
  // list tested against all, so that they do not fill thousands of cells.
  std::uint32_t gridMaxCellsPerAxis = 4;

  bool operator==(const BroadPhaseSettings&) const = default;
};

struct ProxyRayHit {
  ProxyId id;
  float distance = 0.0f;  // where the ray enters the proxy's box; 0 when it starts inside
};

// Called for each proxy whose box the ray hits within the current maximum distance, in no particular
// order. Return the new maximum distance: the hit distance to clip (closest-hit search), infinity to
// keep going unclipped (all hits), or a negative number to stop the cast (any hit). As b2RayCast.
// The callbacks are references to the caller's callable for the length of the query (FunctionRef:
// no copy, no allocation), so that queries inside the step allocate nothing.
using RayCastCallback = FunctionRef<float(ProxyId id, float distance)>;
// Called for each proxy found by an overlap query; return false to stop the query.
using OverlapCallback = FunctionRef<bool(ProxyId id)>;

// One box of a broad phase's own structure, as visitNodes hands it out (for debug drawing).
struct BroadPhaseNode {
  Aabb box;
  int depth = 0;        // Tree: 0 at a root, a child one deeper than its parent; Grid: 0
  bool isLeaf = false;  // Tree: a proxy's box (fattened by treeMargin if movable); Grid: always
  // Tree: the tree the node is in (static and movable proxies are kept in two trees); Grid: Movable.
  MotionType tree = MotionType::Movable;
};
using NodeVisitor = FunctionRef<void(const BroadPhaseNode& node)>;

class BroadPhase {
 public:
  virtual ~BroadPhase();
  BroadPhase(const BroadPhase&) = delete;
  BroadPhase& operator=(const BroadPhase&) = delete;

  BroadPhaseType type() const { return settings_.type; }
  const BroadPhaseSettings& settings() const { return settings_; }

  // ---- Proxies. Bad boxes and unknown or stale ids throw collide::Error. ----
  ProxyId add(const ProxyDef& def);
  void remove(ProxyId id);
  void update(ProxyId id, const Aabb& bounds);
  // update() where the algorithm keeps the proxy where it is (the Tree: a movable proxy's box still
  // inside its fat box): the box is stored and true returned. Otherwise, and for an id or a box
  // update() would refuse, nothing changes and false is returned (call update()). Calls for
  // distinct proxies may run on several threads at once, while no other call runs: the world's
  // workers store most of a step's boxes this way, and update() takes the rest in order.
  bool updateInPlace(ProxyId id, const Aabb& bounds);
  // Makes this broad phase, which must hold no proxy yet, hold the same proxies as `source`: the
  // same ids (index and generation, so handles to them stay valid), boxes, layers and free slots.
  // Switches a running world to another broad-phase type or setting. Throws Error when not empty.
  void adoptProxies(const BroadPhase& source);
  // The slots free for reuse, the last one taken first.
  std::span<const std::uint32_t> freeSlots() const { return freeSlots_; }

  bool contains(ProxyId id) const;
  std::size_t proxyCount() const { return aliveCount_; }
  const Aabb& bounds(ProxyId id) const;
  MotionType motion(ProxyId id) const;
  std::uint64_t userValue(ProxyId id) const;
  std::uint32_t layer(ProxyId id) const;
  void setLayer(ProxyId id, std::uint32_t layer);  // the queries' masks see it at once
  LayerMask mask(ProxyId id) const;
  void setMask(ProxyId id, LayerMask mask);  // the next findPairs pairs by it

  // ---- Pairs. ----
  // All pairs of proxies whose boxes overlap (touching counts), at least one of them movable, whose
  // masks accept each other (ProxyDef::mask), sorted by (a.index, b.index). Every algorithm gives exactly
  // this list. Returns the counters of the call.
  const BroadPhaseStats& findPairs(Array<ProxyPair>& outPairs);
  // The same list, the algorithm's independent parts on the world's workers (the world's own call).
  const BroadPhaseStats& findPairs(Array<ProxyPair>& outPairs, detail::TaskRunner& tasks);
  // The counters of the last findPairs.
  const BroadPhaseStats& lastStats() const { return stats_; }

  // ---- Queries. A proxy takes part when (its layer & mask) != 0. ----
  // Rays must have a finite origin, a finite non-zero direction (normalised here) and a maximum
  // distance >= 0; otherwise collide::Error.
  void rayCast(const Ray& ray, LayerMask mask, const RayCastCallback& callback) const;
  // A box moved along `translation` (a shape cast's broad phase): each proxy box it touches on the
  // way, with the distance the box has moved when it first touches (0 if it starts touching), and
  // the callback's clip-or-stop answer as for rayCast (distances along the normalised translation).
  // A zero translation reports the boxes the box overlaps, at distance 0. A non-finite box or
  // translation is an Error.
  void boxCast(const Aabb& box, const Vec3& translation, LayerMask mask,
               const RayCastCallback& callback) const;
  // The closest box hit (ties: the lowest proxy index), or nothing.
  std::optional<ProxyRayHit> rayCastClosest(const Ray& ray, LayerMask mask = kAllLayers) const;
  // Every box hit, sorted by (distance, index).
  std::vector<ProxyRayHit> rayCastAll(const Ray& ray, LayerMask mask = kAllLayers) const;

  void queryAabb(const Aabb& box, LayerMask mask, const OverlapCallback& callback) const;
  // The same among the static or the movable proxies alone: the tree searches only their tree (a
  // continuous pass's search for static geometry does not walk every moving body).
  void queryAabb(const Aabb& box, LayerMask mask, MotionFilter motions,
                 const OverlapCallback& callback) const;
  // Proxies whose box touches the (solid) sphere.
  void querySphere(const BoundingSphere& sphere, LayerMask mask, const OverlapCallback& callback) const;
  // Proxies whose box is not entirely outside one of the six planes (Frustum::intersects): the usual
  // conservative culling test.
  void queryFrustum(const Frustum& frustum, LayerMask mask, const OverlapCallback& callback) const;
  // The same three, collected and sorted by proxy index.
  std::vector<ProxyId> overlapAabb(const Aabb& box, LayerMask mask = kAllLayers) const;
  std::vector<ProxyId> overlapSphere(const BoundingSphere& sphere, LayerMask mask = kAllLayers) const;
  std::vector<ProxyId> cullFrustum(const Frustum& frustum, LayerMask mask = kAllLayers) const;

  // Line of sight (lecture: AI senses): does any box of the given layers touch the segment from
  // `from` to `to`? Stops at the first blocker. A zero-length segment asks whether a box holds it.
  bool isSegmentBlocked(const Vec3& from, const Vec3& to, LayerMask mask = kAllLayers) const;
  bool hasLineOfSight(const Vec3& from, const Vec3& to, LayerMask mask = kAllLayers) const {
    return !isSegmentBlocked(from, to, mask);
  }

  // The heap it holds, in bytes: the proxies, the algorithm's structure and its pair scratch, as
  // reserved (World::memoryUse).
  std::size_t memoryBytes() const;
  // Room for `count` proxies in all, as std::vector::reserve (World::reserveBodies).
  void reserveProxies(std::size_t count) { proxies_.reserve(count); }

  // Structural self-check for tests; throws collide::Error naming the broken invariant.
  virtual void validate() const {}

  // Visits the boxes the algorithm keeps besides the proxies' own, read-only, in no particular
  // order: every node of the Tree's two dynamic trees with its depth, every occupied cell of the
  // Grid. SweepAndPrune and BruteForce keep none and visit nothing. For drawing, not for queries.
  virtual void visitNodes(const NodeVisitor& visit) const { (void)visit; }

  // Per-proxy storage shared by all algorithms (public so the algorithms, which live in src/, can
  // read it; user code should use the accessors above).
  struct ProxyRecord {
    Aabb bounds;
    std::uint64_t userValue = 0;
    std::uint32_t layer = 0;
    std::uint32_t generation = 1;
    LayerMask mask = kAllLayers;
    MotionType motion = MotionType::Movable;
    bool alive = false;
  };
  const Array<ProxyRecord>& records() const { return proxies_; }
  // adoptProxies from a list of records and free slots (a world snapshot): throws Error, and adopts
  // nothing, when this broad phase has proxies already, or for an alive proxy whose box is not
  // finite or has min > max, or a free slot out of range, alive or listed twice.
  void adoptProxies(std::span<const ProxyRecord> records, std::span<const std::uint32_t> freeSlots);

 protected:
  explicit BroadPhase(const BroadPhaseSettings& settings) : settings_(settings) {}

  // The algorithm's part. The record is already written when onAdd and onUpdate run; onRemove runs
  // before the record is cleared.
  virtual void onAdd(std::uint32_t index) = 0;
  virtual void onRemove(std::uint32_t index) = 0;
  virtual void onUpdate(std::uint32_t index, const Aabb& oldBounds) = 0;
  // Whether onUpdate would leave the algorithm's structure as it is for this new box (read-only,
  // called concurrently for distinct proxies); updateInPlace then stores the box alone.
  virtual bool keepsInPlace(std::uint32_t index, const Aabb& bounds) const {
    (void)index;
    (void)bounds;
    return false;
  }
  // The proxy's layer or mask changed (the record holds the new ones).
  virtual void onFilterChange(std::uint32_t index) { (void)index; }
  // Appends pair keys (a << 32 | b, a < b) of all overlapping pairs, each once, and returns whether
  // they are already sorted. Adds its box tests to outBoxTests.
  virtual bool findPairKeys(Array<std::uint64_t>& outKeys, std::uint64_t& outBoxTests) = 0;
  // The heap the algorithm's own members hold (memoryBytes adds the records).
  virtual std::size_t algorithmMemoryBytes() const = 0;

  struct RayQuery;  // defined in src/broadphase/broad_phase_internal.h
  virtual void rayCastImpl(RayQuery& query) const = 0;
  virtual void queryAabbImpl(const Aabb& box, LayerMask mask, const OverlapCallback& callback) const = 0;
  // By default the query over all proxies, the others skipped.
  virtual void queryAabbByMotionImpl(const Aabb& box, LayerMask mask, MotionFilter motions,
                                     const OverlapCallback& callback) const;
  virtual void querySphereImpl(const BoundingSphere& sphere, LayerMask mask,
                               const OverlapCallback& callback) const = 0;
  virtual void queryFrustumImpl(const Frustum& frustum, LayerMask mask,
                                const OverlapCallback& callback) const = 0;

  ProxyId idOf(std::uint32_t index) const { return {index, proxies_[index].generation}; }

  BroadPhaseSettings settings_;
  Array<ProxyRecord> proxies_;
  Array<std::uint32_t> freeSlots_;
  std::size_t aliveCount_ = 0;
  BroadPhaseStats stats_;
  detail::TaskRunner* tasks_ = nullptr;  // during findPairs(outPairs, tasks) only

 private:
  std::uint32_t resolve(ProxyId id, const char* operation) const;
  Array<std::uint64_t> keys_;
};

// Throws collide::Error on invalid settings (negative margin or cell size, zero cells per axis).
std::unique_ptr<BroadPhase> createBroadPhase(const BroadPhaseSettings& settings = {});

}  // namespace collide
