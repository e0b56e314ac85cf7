// World snapshots (World::saveSnapshot, loadSnapshot; docs/snapshots.md): the world's state as bytes
// and back, so that a world loaded from them continues bit-identically.
//
// Every struct is written field by field (its `fields` function below lists them once for both
// directions), little-endian, without padding: the same state gives the same bytes, and a field
// read back is checked as it is read (a bool is 0 or 1, an enum one of its values, a count no more
// than the bytes left). Then the contents are checked as a whole (every index in range) before the
// world takes them. The format:
//
//   "COLLIDE\x1a"  format version (u32)  library version (u32)  layout (u64)  payload bytes (u64)
//   payload checksum (u64, FNV-1a)  payload
//
// `layout` is a fingerprint of the fields this build writes: a snapshot of a build whose fields
// differ is refused by name, not misread.
#include "base/fail.h"
#include "world_impl.h"

#include "bodies/body_def.h"
#include "bodies/body_parts.h"
#include "shapes/hull_builder.h"

#include <collide/version.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>

namespace collide {

namespace {

static_assert(std::endian::native == std::endian::little,
              "snapshots are written little-endian, as this host is");

constexpr char kMagic[8] = {'C', 'O', 'L', 'L', 'I', 'D', 'E', '\x1a'};
constexpr std::uint32_t kFormatVersion = 2;
constexpr std::uint32_t kLibraryVersion =
    (COLLIDE_VERSION_MAJOR << 16) | (COLLIDE_VERSION_MINOR << 8) | COLLIDE_VERSION_PATCH;
constexpr std::size_t kHeaderBytes = sizeof(kMagic) + 4 + 4 + 8 + 8 + 8;

std::uint64_t fnv1a(std::span<const std::uint8_t> bytes, std::uint64_t hash = 0xcbf29ce484222325ull) {
  for (const std::uint8_t byte : bytes) hash = (hash ^ byte) * 0x100000001b3ull;
  return hash;
}

// ---- How many values each enum has: a byte read back must be one of them. ----
template <typename E>
constexpr std::uint32_t kEnumValues = 0;
template <>
constexpr std::uint32_t kEnumValues<BodyType> = 3;
template <>
constexpr std::uint32_t kEnumValues<MotionType> = 2;
template <>
constexpr std::uint32_t kEnumValues<PairKind> = 2;
template <>
constexpr std::uint32_t kEnumValues<JointType> = 6;
template <>
constexpr std::uint32_t kEnumValues<ShapeType> = kShapeTypeCount;
template <>
constexpr std::uint32_t kEnumValues<BroadPhaseType> = kBroadPhaseTypeCount;
template <>
constexpr std::uint32_t kEnumValues<CombineRule> = 4;
template <>
constexpr std::uint32_t kEnumValues<ImpactModel> = 2;
template <>
constexpr std::uint32_t kEnumValues<FrictionModel> = 4;
template <>
constexpr std::uint32_t kEnumValues<PenetrationResponse> = 3;
template <>
constexpr std::uint32_t kEnumValues<ContactEvent::Type> = 3;
template <>
constexpr std::uint32_t kEnumValues<SensorEvent::Type> = 2;

// ---- The fields of each struct, in the order they are written. ----
// A struct that gains a field must gain it here too: the size checks below fail to compile until
// it does (on the 64-bit hosts they were measured on).
#if defined(__x86_64__) || defined(__aarch64__)
#define COLLIDE_SNAPSHOT_SIZE(Type, bytes) \
  static_assert(sizeof(Type) == (bytes), #Type " changed: update its fields in src/world_snapshot.cpp")
#else
#define COLLIDE_SNAPSHOT_SIZE(Type, bytes) static_assert(true)
#endif

template <typename A>
void fields(A& a, BodyId& v) {
  a(v.index, v.generation);
}
template <typename A>
void fields(A& a, JointId& v) {
  a(v.index, v.generation);
}
template <typename A>
void fields(A& a, ProxyId& v) {
  a(v.index, v.generation);
}
template <typename A>
void fields(A& a, Aabb& v) {
  a(v.min, v.max);
}
template <typename A>
void fields(A& a, Transform& v) {
  a(v.position, v.rotation, v.scale);
}
template <typename A>
void fields(A& a, Plane& v) {
  a(v.normal, v.distance);
}
COLLIDE_SNAPSHOT_SIZE(BodyMaterial, 12);
template <typename A>
void fields(A& a, BodyMaterial& v) {
  a(v.friction, v.bounciness, v.rollingResistance);
}
COLLIDE_SNAPSHOT_SIZE(detail::PartRecord, 40);
template <typename A>
void fields(A& a, detail::PartRecord& v) {
  a(v.material, v.density, v.sensor, v.layer, v.mask, v.group, v.userData);
}
COLLIDE_SNAPSHOT_SIZE(detail::BodyState, 120);
template <typename A>
void fields(A& a, detail::BodyState& v) {
  a(v.centerOfMass, v.rotation, v.linearVelocity, v.angularVelocity, v.inverseInertiaWorld, v.inverseMass,
    v.centerOfMass0, v.rotation0);
}
// The record's shape is written apart (the shape table); the rest here.
COLLIDE_SNAPSHOT_SIZE(detail::BodyRecord, 384);
template <typename A>
void fields(A& a, detail::BodyRecord& v) {
  a(v.type, v.sensor, v.alive, v.awake, v.faulted, v.enabled, v.particle, v.ccd, v.isotropicInertia,
    v.generation, v.layer, v.mask, v.group, v.scale, v.boundingRadius, v.originRadius, v.bounciness,
    v.friction, v.rollingResistance, v.gravityScale, v.linearDamping, v.angularDamping, v.localCenterOfMass,
    v.proxy, v.mass, v.minExtent, v.sleepTime, v.island, v.inertiaLocal, v.inverseInertiaLocal, v.bounds,
    v.boundsCenter, v.boundsRotation, v.boundsValid, v.validCenterOfMass, v.validRotation, v.force, v.torque,
    v.name, v.userData, v.parts, v.givenMass, v.density);
}
template <typename A>
void fields(A& a, ContactPoint& v) {
  a(v.pointOnA, v.pointOnB, v.depth, v.featureId);
}
COLLIDE_SNAPSHOT_SIZE(Manifold, 144);
template <typename A>
void fields(A& a, Manifold& v) {
  a(v.normal, v.points, v.count);
}
template <typename A>
void fields(A& a, detail::ContactPointState& v) {
  a(v.normalImpulse, v.totalNormalImpulse, v.maxNormalImpulse, v.relativeVelocity);
}
COLLIDE_SNAPSHOT_SIZE(detail::ManifoldCache, 152);
template <typename A>
void fields(A& a, detail::ManifoldCache& v) {
  a(v.normal, v.pointsOnA, v.pointsOnB, v.relativePosition, v.relativeRotation, v.separatingAxis, v.valid,
    v.hasAxis);
}
COLLIDE_SNAPSHOT_SIZE(detail::Contact, 480);
template <typename A>
void fields(A& a, detail::Contact& v) {
  a(v.key, v.bodyA, v.bodyB, v.partA, v.partB, v.generationA, v.generationB, v.manifold, v.points, v.friction,
    v.rollingResistance, v.restitution, v.impactBounciness, v.surfaceVelocity, v.sensor, v.enabled, v.asleep,
    v.touching, v.wasTouching, v.stuck, v.sliding, v.prolongedPoints, v.consecutiveSteps, v.impactSpeed,
    v.impactImpulse, v.frictionImpulse, v.twistImpulse, v.stickLocalA, v.stickLocalB, v.cache);
}
COLLIDE_SNAPSHOT_SIZE(detail::ApartCache, 56);
template <typename A>
void fields(A& a, detail::ApartCache& v) {
  a(v.normal, v.relativePosition, v.relativeRotation, v.separatingAxis, v.valid, v.hasAxis);
}
COLLIDE_SNAPSHOT_SIZE(detail::ApartPair, 80);
template <typename A>
void fields(A& a, detail::ApartPair& v) {
  a(v.key, v.bodyA, v.bodyB, v.generationA, v.generationB, v.cache);
}
template <typename A>
void fields(A& a, JointSoftness& v) {
  a(v.hertz, v.dampingRatio);
}
template <typename A>
void fields(A& a, JointLimits& v) {
  a(v.enabled, v.lower, v.upper);
}
template <typename A>
void fields(A& a, JointMotor& v) {
  a(v.enabled, v.speed, v.maxForce);
}
template <typename A>
void fields(A& a, JointSpring& v) {
  a(v.enabled, v.hertz, v.dampingRatio, v.target);
}
COLLIDE_SNAPSHOT_SIZE(detail::Joint, 236);
template <typename A>
void fields(A& a, detail::Joint& v) {
  a(v.type, v.bodyA, v.bodyB, v.localAnchorA, v.localAnchorB, v.localFrameA, v.localFrameB,
    v.collideConnected, v.alive, v.active, v.inTree, v.treeLimits, v.generation, v.softness,
    v.angularSoftness, v.limits, v.motor, v.spring, v.swingLimit, v.friction, v.breakForce, v.breakTorque,
    v.length, v.compliance, v.dampingRatio, v.axis, v.linearImpulse, v.angularImpulse, v.impulse,
    v.springImpulse, v.motorImpulse, v.lowerImpulse, v.upperImpulse, v.swingImpulse, v.frictionImpulse);
}
COLLIDE_SNAPSHOT_SIZE(BroadPhase::ProxyRecord, 48);
template <typename A>
void fields(A& a, BroadPhase::ProxyRecord& v) {
  a(v.bounds, v.userValue, v.layer, v.generation, v.mask, v.motion, v.alive);
}
template <typename A>
void fields(A& a, ProxyPair& v) {
  a(v.a, v.b, v.kind);
}
template <typename A>
void fields(A& a, BroadPhaseSettings& v) {
  a(v.type, v.treeMargin, v.gridCellSize, v.gridMaxCellsPerAxis);
}
COLLIDE_SNAPSHOT_SIZE(ContactTuning, 40);
template <typename A>
void fields(A& a, ContactTuning& v) {
  a(v.hertz, v.dampingRatio, v.pushOutSpeed, v.restitutionThreshold, v.linearSlop, v.speculativeDistance,
    v.relaxPasses, v.supportMasses, v.frictionAnchorReach, v.manifoldCacheDistance);
}
template <typename A>
void fields(A& a, SleepTuning& v) {
  a(v.linearSpeed, v.angularSpeed, v.timeToSleep);
}
// The task settings (workerCount and the job system's callbacks) are the loading world's own.
COLLIDE_SNAPSHOT_SIZE(WorldDef, 120);
template <typename A>
void fields(A& a, WorldDef& v) {
  a(v.gravity, v.substeps, v.broadPhase, v.bouncinessCombine, v.frictionCombine, v.impactModel,
    v.frictionModel, v.penetrationResponse, v.sleeping, v.ccd, v.persistEvents, v.sleep, v.contact);
}
// The counters of the world's pairs, so that the same state gives the same bytes. Not the stage times
// (the clock's) nor the broad phase's box tests (the work of its structure, which a loading world
// builds anew from the proxies' boxes): both are zero in a loaded world until it steps.
COLLIDE_SNAPSHOT_SIZE(StepStats, 112);
template <typename A>
void fields(A& a, StepStats& v) {
  a(v.proxies, v.potentialPairs, v.keptPairs, v.filteredPairs, v.narrowPhaseTests, v.reusedManifolds,
    v.contactPairs);
}
COLLIDE_SNAPSHOT_SIZE(ContactEvent, 60);
template <typename A>
void fields(A& a, ContactEvent& v) {
  a(v.type, v.a, v.b, v.partA, v.partB, v.point, v.normal, v.impulse, v.speed);
}
template <typename A>
void fields(A& a, SensorEvent& v) {
  a(v.type, v.sensor, v.visitor, v.sensorPart, v.visitorPart);
}
template <typename A>
void fields(A& a, FaultEvent& v) {
  a(v.body, v.fields);
}
template <typename A>
void fields(A& a, JointBreakEvent& v) {
  a(v.joint, v.a, v.b, v.force, v.torque);
}
template <typename A>
void fields(A& a, ConvexHull::HalfEdge& v) {
  a(v.origin, v.twin, v.next, v.face);
}
template <typename A>
void fields(A& a, ConvexHull::Face& v) {
  a(v.plane, v.firstEdge, v.edgeCount, v.firstVertex);
}
template <typename A>
void fields(A& a, MeshTriangle& v) {
  a(v.v);
}

template <typename T, typename A>
concept HasFields = requires(A& a, T& v) {
  fields(a, v);
};

void clearUnusedPoints(Manifold& manifold,
                       std::array<detail::ContactPointState, Manifold::kMaxPoints>& states,
                       detail::ManifoldCache& cache, int count) {
  for (int i = std::max(count, 0); i < Manifold::kMaxPoints; ++i) {
    manifold.points[i] = ContactPoint{};
    states[i] = detail::ContactPointState{};
    cache.pointsOnA[i] = cache.pointsOnB[i] = Vec3(0.0f);
  }
}

// ---- Writing. ----
class Writer {
 public:
  template <typename... T>
  void operator()(const T&... values) {
    (put(values), ...);
  }

  void put(bool value) { put(static_cast<std::uint8_t>(value ? 1 : 0)); }
  template <typename T>
  requires std::is_arithmetic_v<T>
  void put(T value) {
    const auto* bytes = reinterpret_cast<const std::uint8_t*>(&value);
    out_.insert(out_.end(), bytes, bytes + sizeof(T));
  }
  template <typename E>
  requires std::is_enum_v<E>
  void put(E value) { put(static_cast<std::underlying_type_t<E>>(value)); }
  void put(const Vec3& v) { (*this)(v.x, v.y, v.z); }
  void put(const Quat& q) { (*this)(q.x, q.y, q.z, q.w); }
  void put(const Mat3& m) {
    for (int c = 0; c < 3; ++c) put(m[c]);
  }
  template <typename T, std::size_t N>
  void put(const std::array<T, N>& values) {
    for (const T& value : values) put(value);
  }
  template <typename T, typename Alloc>
  void put(const std::vector<T, Alloc>& values) {
    put(static_cast<std::uint64_t>(values.size()));
    for (const T& value : values) put(value);
  }
  void put(const std::string& text) {
    put(static_cast<std::uint64_t>(text.size()));
    out_.insert(out_.end(), text.begin(), text.end());
  }
  template <typename T>
  void put(const std::optional<T>& value) {
    put(value.has_value());
    if (value) put(*value);
  }
  // A contact as its meaning has it: the points beyond the manifold's count hold whatever an
  // earlier manifold or another worker's scratch left there, which nothing reads; written as
  // defaults, so that the same state gives the same bytes at any worker count.
  void put(const detail::Contact& contact) {
    detail::Contact canonical = contact;
    clearUnusedPoints(canonical.manifold, canonical.points, canonical.cache, contact.manifold.count);
    fields(*this, canonical);
  }
  template <typename T>
  requires HasFields<T, Writer>
  void put(const T& value) {
    fields(*this, const_cast<T&>(value));  // fields() only reads through a Writer
  }

  std::vector<std::uint8_t>& bytes() { return out_; }

 private:
  std::vector<std::uint8_t> out_;
};

// ---- Reading: every value checked as it comes. ----
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> bytes) : in_(bytes) {}

  // Where reading is, for the messages: "bodies", "contacts", ...
  void section(const char* name) { section_ = name; }
  // Refuses the snapshot: Error "snapshot: <section>: <what>". Without exceptions the first refusal
  // is kept, the rest of the bytes are skipped (every later value reads as zero and every count as
  // none), and the loader stops at the next failed() before it follows an index.
#if COLLIDE_EXCEPTIONS
  [[noreturn]] void fail(const std::string& what) {
    throw Error("snapshot: " + std::string(section_) + ": " + what);
  }
#else
  void fail(const std::string& what) {
    if (failed_) return;
    detail::raiseError("snapshot: " + std::string(section_) + ": " + what);
    failed_ = true;
    at_ = in_.size();
  }
#endif
  bool failed() const { return failed_; }
  bool done() const { return at_ == in_.size(); }

  // Runs f, an Error it raises refused as the section's: "snapshot: <section>: <its message>".
  template <typename F>
  void guard(F&& f) {
#if COLLIDE_EXCEPTIONS
    try {
      f();
    } catch (const Error& e) {
      fail(e.what());
    }
#else
    if (failed_) return;
    detail::withErrorContext("snapshot: " + std::string(section_) + ": ", f);
    if (detail::errorPending()) {
      failed_ = true;
      at_ = in_.size();
    }
#endif
  }

  template <typename... T>
  void operator()(T&... values) {
    (get(values), ...);
  }

  void get(bool& value) {
    std::uint8_t byte = 0;
    get(byte);
    if (byte > 1) fail("a flag holds " + std::to_string(byte) + ", not 0 or 1");
    value = byte == 1;
  }
  template <typename T>
  requires std::is_arithmetic_v<T>
  void get(T& value) { take(&value, sizeof(T)); }
  template <typename E>
  requires std::is_enum_v<E>
  void get(E& value) {
    std::underlying_type_t<E> raw{};
    get(raw);
    static_assert(kEnumValues<E> > 0, "an enum without its count of values (kEnumValues)");
    if (static_cast<std::uint64_t>(raw) >= kEnumValues<E>) {
      fail("value " + std::to_string(+raw) + " is not one of the " + std::to_string(kEnumValues<E>) +
           " values of its kind");
      raw = 0;
    }
    value = static_cast<E>(raw);
  }
  void get(Vec3& v) { (*this)(v.x, v.y, v.z); }
  void get(Quat& q) { (*this)(q.x, q.y, q.z, q.w); }
  void get(Mat3& m) {
    for (int c = 0; c < 3; ++c) get(m[c]);
  }
  template <typename T, std::size_t N>
  void get(std::array<T, N>& values) {
    for (T& value : values) get(value);
  }
  template <typename T, typename Alloc>
  void get(std::vector<T, Alloc>& values) {
    const std::size_t count = countOf(leastBytes<T>());
    values.clear();
    values.resize(count);
    for (T& value : values) get(value);
  }
  void get(std::string& text) {
    const std::size_t count = countOf(1);
    text.assign(reinterpret_cast<const char*>(in_.data() + at_), count);
    at_ += count;
  }
  template <typename T>
  void get(std::optional<T>& value) {
    bool present = false;
    get(present);
    value.reset();
    if (present) get(value.emplace());
  }
  template <typename T>
  requires HasFields<T, Reader>
  void get(T& value) { fields(*this, value); }

  // The fewest bytes a T takes (a default one: its arrays and strings empty), so that a count read
  // back never asks for more elements than the bytes left could describe.
  template <typename T>
  static std::size_t leastBytes();

  // A count of things of at least `bytesEach` bytes: no more than the bytes left can hold.
  std::size_t countOf(std::size_t bytesEach) {
    std::uint64_t count = 0;
    get(count);
    if (count > (in_.size() - at_) / bytesEach) {
      fail("a count of " + std::to_string(count) + " is more than the " + std::to_string(in_.size() - at_) +
           " bytes left could hold");
      return 0;
    }
    return static_cast<std::size_t>(count);
  }

 private:
  void take(void* out, std::size_t bytes) {
    if (in_.size() - at_ < bytes) {
      std::memset(out, 0, bytes);
      fail("truncated: the payload ends inside it");
      return;
    }
    std::memcpy(out, in_.data() + at_, bytes);
    at_ += bytes;
  }

  std::span<const std::uint8_t> in_;
  std::size_t at_ = 0;
  const char* section_ = "header";
  bool failed_ = false;
};

template <typename T>
std::size_t Reader::leastBytes() {
  static const std::size_t bytes = [] {
    Writer w;
    w.put(T{});
    return std::max<std::size_t>(1, w.bytes().size());
  }();
  return bytes;
}

// The layout fingerprint: the fields this build writes, as the bytes a default of each struct takes.
// Two builds that write the same fields in the same order and types agree.
std::uint64_t layoutFingerprint() {
  Writer w;
  w(detail::BodyRecord{}, detail::BodyState{}, detail::Contact{}, detail::ApartPair{}, detail::Joint{},
    BroadPhase::ProxyRecord{}, ProxyPair{}, WorldDef{}, StepStats{}, ContactEvent{}, SensorEvent{},
    FaultEvent{}, JointBreakEvent{}, ConvexHull::HalfEdge{}, ConvexHull::Face{});
  return fnv1a(w.bytes());
}

// ---- Shapes: a table of the shapes the bodies use, each written once (shared polyhedra stay shared),
// children before the compounds that hold them. A body refers to its shape by its place in the table.
class ShapeTableWriter {
 public:
  explicit ShapeTableWriter(Writer& w) : w_(w) {}

  std::uint32_t add(const Shape& shape) {
    const void* identity = sharedIdentity(shape);
    if (identity) {
      const auto found = index_.find(identity);
      if (found != index_.end()) return found->second;
    }
    Writer entry;
    entry.put(shape.type());
    switch (shape.type()) {
      case ShapeType::Sphere:
        entry(shape.sphere().radius);
        break;
      case ShapeType::Capsule:
        entry(shape.capsule().radius, shape.capsule().halfHeight);
        break;
      case ShapeType::Plane:
        entry(shape.plane());
        break;
      case ShapeType::Box:
        entry(shape.box().halfExtents);
        break;
      case ShapeType::Kdop: {
        const Kdop& kdop = shape.kdop();
        entry(static_cast<std::int32_t>(kdop.k()));
        for (int i = 0; i < kdop.axisCount(); ++i) entry(kdop.slabMin(i), kdop.slabMax(i));
        break;
      }
      case ShapeType::Ellipsoid:
        entry(shape.ellipsoid().radii);
        break;
      case ShapeType::Cylinder:
        entry(shape.cylinder().radius, shape.cylinder().halfHeight);
        break;
      case ShapeType::ConvexHull: {
        const ConvexHull& hull = shape.convexHull();
        entry.put(std::vector<Vec3>(hull.vertices().begin(), hull.vertices().end()));
        entry.put(std::vector<ConvexHull::Face>(hull.faces().begin(), hull.faces().end()));
        entry.put(std::vector<ConvexHull::HalfEdge>(hull.halfEdges().begin(), hull.halfEdges().end()));
        break;
      }
      case ShapeType::Mesh: {
        const TriangleMesh& mesh = shape.mesh();
        entry.put(std::vector<Vec3>(mesh.vertices().begin(), mesh.vertices().end()));
        entry.put(std::vector<MeshTriangle>(mesh.triangles().begin(), mesh.triangles().end()));
        break;
      }
      case ShapeType::Compound: {
        const auto children = shape.compound().children();
        entry.put(static_cast<std::uint64_t>(children.size()));
        for (const Compound::Child& child : children) entry(add(child.shape), child.transform);
        break;
      }
    }
    const std::uint32_t index = count_++;
    entries_.insert(entries_.end(), entry.bytes().begin(), entry.bytes().end());
    if (identity) index_.emplace(identity, index);
    return index;
  }

  // The table: its entry count, then the entries.
  void finish() {
    w_.put(static_cast<std::uint64_t>(count_));
    w_.bytes().insert(w_.bytes().end(), entries_.begin(), entries_.end());
  }

 private:
  static const void* sharedIdentity(const Shape& shape) {
    switch (shape.type()) {
      case ShapeType::Kdop:
        return &shape.kdop();
      case ShapeType::ConvexHull:
        return &shape.convexHull();
      case ShapeType::Mesh:
        return &shape.mesh();
      case ShapeType::Compound:
        return &shape.compound();
      default:
        return nullptr;
    }
  }

  Writer& w_;
  std::vector<std::uint8_t> entries_;
  std::uint32_t count_ = 0;
  std::unordered_map<const void*, std::uint32_t> index_;
};

// Each shape through its validating constructor or factory: a value no shape could have is refused
// with the shape's own message.
std::vector<Shape> readShapeTable(Reader& r) {
  r.section("shapes");
  const std::size_t count = r.countOf(1);
  std::vector<Shape> shapes;
  shapes.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    ShapeType type{};
    r.get(type);
    const auto readShape = [&] {
      switch (type) {
        case ShapeType::Sphere: {
          Sphere sphere;
          r(sphere.radius);
          shapes.emplace_back(sphere);
          break;
        }
        case ShapeType::Capsule: {
          Capsule capsule;
          r(capsule.radius, capsule.halfHeight);
          shapes.emplace_back(capsule);
          break;
        }
        case ShapeType::Plane: {
          Plane plane;
          r(plane);
          shapes.emplace_back(plane);
          break;
        }
        case ShapeType::Box: {
          Box box;
          r(box.halfExtents);
          shapes.emplace_back(box);
          break;
        }
        case ShapeType::Kdop: {
          std::int32_t k = 0;
          r(k);
          if (k != 6 && k != 14 && k != 18 && k != 26)
            return r.fail("shape " + std::to_string(i) + ": no " + std::to_string(k) + "-DOP");
          std::vector<float> slabMin(static_cast<std::size_t>(k / 2)),
              slabMax(static_cast<std::size_t>(k / 2));
          for (int axis = 0; axis < k / 2; ++axis) r(slabMin[axis], slabMax[axis]);
          shapes.emplace_back(Kdop::fromSlabs(k, slabMin, slabMax));
          break;
        }
        case ShapeType::Ellipsoid: {
          Ellipsoid ellipsoid;
          r(ellipsoid.radii);
          shapes.emplace_back(ellipsoid);
          break;
        }
        case ShapeType::Cylinder: {
          Cylinder cylinder;
          r(cylinder.radius, cylinder.halfHeight);
          shapes.emplace_back(cylinder);
          break;
        }
        case ShapeType::ConvexHull: {
          std::vector<Vec3> vertices;
          std::vector<ConvexHull::Face> faces;
          std::vector<ConvexHull::HalfEdge> halfEdges;
          r(vertices, faces, halfEdges);
          shapes.emplace_back(HullBuilder::restore(vertices, faces, halfEdges));
          break;
        }
        case ShapeType::Mesh: {
          std::vector<Vec3> vertices;
          std::vector<MeshTriangle> triangles;
          r(vertices, triangles);
          shapes.emplace_back(TriangleMesh::fromTriangles(std::move(vertices), std::move(triangles)));
          break;
        }
        case ShapeType::Compound: {
          const std::size_t childCount = r.countOf(4 + 32);
          std::vector<Compound::Child> children;
          children.reserve(childCount);
          for (std::size_t c = 0; c < childCount; ++c) {
            std::uint32_t child = 0;
            Transform transform;
            r(child, transform);
            if (child >= shapes.size())
              return r.fail("shape " + std::to_string(i) + ": a child that comes after it");
            children.push_back({shapes[child], transform});
          }
          shapes.emplace_back(Compound::fromChildren(std::move(children)));
          break;
        }
      }
    };
    // A shape's own refusal (a radius, a hull) comes out as the snapshot's, naming the shape.
#if COLLIDE_EXCEPTIONS
    try {
      readShape();
    } catch (const Error& e) {
      if (std::string_view(e.what()).starts_with("snapshot: ")) throw;
      r.fail("shape " + std::to_string(i) + ": " + e.what());
    }
#else
    if (!r.failed()) {
      const detail::ErrorScope scope;
      readShape();
      if (detail::errorPending() && !r.failed()) {
        detail::wrapPendingError("snapshot: shapes: shape " + std::to_string(i) + ": ", "");
        r.fail("");  // stops the reading; the pending message is the shape's
      }
    }
    if (r.failed()) return shapes;
#endif
  }
  return shapes;
}

// Whether any float of a value is NaN, through its fields: NaN is no state a world can be in.
class NanCheck {
 public:
  bool found = false;

  template <typename... T>
  void operator()(T&... values) {
    (check(values), ...);
  }
  void check(float value) { found = found || std::isnan(value); }
  void check(double value) { found = found || std::isnan(value); }
  void check(Vec3& v) { (*this)(v.x, v.y, v.z); }
  void check(Quat& q) { (*this)(q.x, q.y, q.z, q.w); }
  void check(Mat3& m) {
    for (int c = 0; c < 3; ++c) check(m[c]);
  }
  template <typename T, std::size_t N>
  void check(std::array<T, N>& values) {
    for (T& value : values) check(value);
  }
  template <typename T, typename Alloc>
  void check(std::vector<T, Alloc>& values) {
    for (T& value : values) check(value);
  }
  template <typename T>
  void check(std::optional<T>& value) {
    if (value) check(*value);
  }
  template <typename T>
  requires HasFields<T, NanCheck>
  void check(T& value) { fields(*this, value); }
  template <typename T>
  void check(T&) {}  // integers, flags, enums, strings
};

template <typename T>
bool hasNan(const T& value) {
  NanCheck check;
  check.check(const_cast<T&>(value));
  return check.found;
}

bool isUnit(const Quat& q) { return isFinite(q) && std::abs(glm::dot(q, q) - 1.0f) < 1e-3f; }
bool isBox(const Aabb& box) {
  return isFinite(box.min) && isFinite(box.max) && box.min.x <= box.max.x && box.min.y <= box.max.y &&
         box.min.z <= box.max.z;
}

// ---- The world. ----

struct SavedBodies {
  Array<detail::BodyRecord> records;
  Array<detail::BodyState> states;
  Array<std::uint32_t> freeSlots;
};

bool checkBody(Reader& r, const Array<detail::BodyRecord>& records, std::uint32_t index,
               std::uint32_t generation, const char* what) {
  if (index >= records.size() || !records[index].alive || records[index].generation != generation) {
    r.fail(std::string(what) + " refers to body " + std::to_string(index) +
           ", which the snapshot does not have alive");
    return false;
  }
  return true;
}

// The contents as a whole: every index a stage follows is in range, so that no step can read outside
// an array however the bytes were made. (A template: World::Impl is World's own to name.)
template <typename WorldImpl>
void checkWorld(Reader& r, const WorldImpl& w) {
  const auto& records = w.bodies.records;
  const auto& proxies = w.broadPhase->records();
  r.section("bodies");
  for (std::uint32_t i = 0; i < records.size(); ++i) {
    const detail::BodyRecord& body = records[i];
    if (!body.alive) continue;
    const std::string name = "body " + std::to_string(i);
    const detail::BodyState& state = w.bodies.states[i];
    // The pose every query and bound takes (isValid(Transform)); the rest without NaN.
    if (hasNan(body) || hasNan(state)) return r.fail(name + ": a value that is not a number");
    if (!detail::hasValidPose(state) || !isFinite(state.centerOfMass0) || !isUnit(state.rotation0) ||
        !(std::isfinite(body.scale) && body.scale > 0.0f) || !isFinite(body.localCenterOfMass))
      return r.fail(name + ": a pose that is not a finite position with a unit rotation and a scale > 0");
    if (!isFinite(state.linearVelocity) || !isFinite(state.angularVelocity) || !(state.inverseMass >= 0.0f) ||
        !std::isfinite(state.inverseMass))
      return r.fail(name + ": a velocity or a mass that is not finite");
    if ((body.boundsValid &&
         (!isBox(body.bounds) || !isFinite(body.boundsCenter) || !isUnit(body.boundsRotation))) ||
        !isFinite(body.validCenterOfMass) || !isUnit(body.validRotation))
      return r.fail(name + ": a kept box or pose that is not one");
    // What the stages grow boxes and margins by, and the material: what no body has is refused.
    const auto nonNegative = [](float value) { return std::isfinite(value) && value >= 0.0f; };
    const auto material = [&](const BodyMaterial& m) {
      return nonNegative(m.friction) && nonNegative(m.bounciness) && m.bounciness <= 1.0f &&
             nonNegative(m.rollingResistance);
    };
    bool materials = material({body.friction, body.bounciness, body.rollingResistance});
    for (const detail::PartRecord& part : body.parts)
      materials = materials && material(part.material) && std::isfinite(part.density) && part.density > 0.0f;
    if (!nonNegative(body.boundingRadius) || !nonNegative(body.originRadius) ||
        !nonNegative(body.minExtent) || !nonNegative(body.mass) || !nonNegative(body.linearDamping) ||
        !nonNegative(body.angularDamping) || !std::isfinite(body.gravityScale) ||
        !(std::isfinite(body.density) && body.density > 0.0f) || !materials ||
        !nonNegative(body.sleepTime == std::numeric_limits<float>::infinity() ? 0.0f : body.sleepTime))
      return r.fail(name + ": a radius, mass, damping, material or timer out of its range");
    if (!body.parts.empty() && (body.shape.type() != ShapeType::Compound ||
                                body.shape.compound().children().size() != body.parts.size()))
      return r.fail(name + ": " + std::to_string(body.parts.size()) +
                    " parts but not a compound of as many children");
    if (body.island >= records.size()) return r.fail(name + ": its island's body is out of range");
    // The shapes each body type may have, as createBody and setType hold them.
    if (body.type != BodyType::Static && body.shape.type() == ShapeType::Plane)
      return r.fail(name + ": a plane on a body that is not static");
    if (body.particle && body.type != BodyType::Dynamic)
      return r.fail(name + ": a particle that is not dynamic");
    if (body.type == BodyType::Dynamic) {
      if (body.parts.empty() && !body.sensor && body.shape.type() == ShapeType::Mesh &&
          !body.shape.mesh().isClosed())
        return r.fail(name + ": a dynamic body of an open mesh");
      for (std::uint32_t k = 0; k < body.parts.size(); ++k) {
        if (detail::partShape(body, k).type() == ShapeType::Mesh)
          return r.fail(name + ": a dynamic body with a mesh part");
      }
    }
    r.guard([&] { detail::requireRepresentableBounds(body, state, name); });
    if (r.failed()) return;
    const bool inBroadPhase = body.enabled;
    if (inBroadPhase && (body.proxy.index >= proxies.size() || !proxies[body.proxy.index].alive ||
                         proxies[body.proxy.index].generation != body.proxy.generation ||
                         proxies[body.proxy.index].userValue != i))
      return r.fail(name + ": its broad-phase proxy is not the one the broad phase holds for it");
  }
  r.section("pairs");
  for (const ProxyPair& pair : w.pairs) {
    if (pair.a.index >= proxies.size() || pair.b.index >= proxies.size() || !proxies[pair.a.index].alive ||
        !proxies[pair.b.index].alive)
      return r.fail("a pair of proxies the broad phase does not hold");
  }
  // A manifold cache's directions and turn, as the narrow phase takes them: a separating axis is a
  // unit direction (a support query along it refuses a zero one), a kept pose has a unit rotation.
  const auto checkCache = [&](const auto& cache) {  // a contact's ManifoldCache or an ApartCache
    if (cache.hasAxis &&
        !(isFinite(cache.separatingAxis) && std::abs(glm::length(cache.separatingAxis) - 1.0f) < 1e-3f))
      return r.fail("a separating axis that is not a unit direction");
    if (cache.valid && !(isFinite(cache.relativePosition) && isUnit(cache.relativeRotation)))
      return r.fail("a manifold cache whose pose is not finite with a unit rotation");
  };
  const auto checkContacts = [&](const Array<detail::Contact>& contacts, const char* section) {
    r.section(section);
    // A contact's numbers are not checked: a world can hold NaN in them after extreme but finite
    // input, and the step takes that (the fault guard freezes a body a NaN reaches). Its indices are.
    for (const detail::Contact& c : contacts) {
      checkCache(c.cache);
      if (!checkBody(r, records, c.bodyA, c.generationA, "a contact") ||
          !checkBody(r, records, c.bodyB, c.generationB, "a contact"))
        return;
      const auto partCount = [&](std::uint32_t body) {
        return std::max<std::size_t>(1, records[body].parts.size());
      };
      if (c.partA >= partCount(c.bodyA) || c.partB >= partCount(c.bodyB))
        return r.fail("a contact of a part out of range");
      if (c.manifold.count < 0 || c.manifold.count > Manifold::kMaxPoints)
        return r.fail("a manifold of " + std::to_string(c.manifold.count) + " points");
    }
  };
  checkContacts(w.contacts, "contacts");
  if (r.failed()) return;
  r.section("pairs apart");
  for (const detail::ApartPair& p : w.apartPairs) {
    checkCache(p.cache);
    if (!checkBody(r, records, p.bodyA, p.generationA, "a pair apart") ||
        !checkBody(r, records, p.bodyB, p.generationB, "a pair apart"))
      return;
  }
  r.section("joints");
  std::size_t alive = 0;
  for (const detail::Joint& joint : w.joints) {
    if (!joint.alive) continue;
    ++alive;
    if (!isFinite(joint.localAnchorA) || !isFinite(joint.localAnchorB) || !isUnit(joint.localFrameA) ||
        !isUnit(joint.localFrameB))
      return r.fail("a joint whose anchors or frames are not finite");
    if (joint.bodyA >= records.size() || joint.bodyB >= records.size() || !records[joint.bodyA].alive ||
        !records[joint.bodyB].alive || joint.bodyA == joint.bodyB)
      return r.fail("a joint between bodies the snapshot does not have alive");
  }
  if (alive != w.jointCount) return r.fail("the joint count does not match the joints alive");
  Array<std::uint8_t> free(w.joints.size(), 0);
  for (const std::uint32_t slot : w.freeJoints) {
    if (slot >= w.joints.size() || w.joints[slot].alive || free[slot])
      return r.fail("free joint slot " + std::to_string(slot) + " is out of range, alive or listed twice");
    free[slot] = 1;
  }
  r.section("events");
  for (const std::uint32_t contact : w.events.contactOfEvent) {
    if (contact != detail::StepEvents::kNoContact && contact >= w.contacts.size())
      return r.fail("an event of a contact out of range");
  }
  if (w.events.contactOfEvent.size() != w.events.contacts.size())
    return r.fail("the contact events and their contacts differ in number");
}

}  // namespace

std::vector<std::uint8_t> World::saveSnapshot() const {
  const Impl& w = *impl_;
  Writer payload;
  payload.put(w.def);
  // Shapes first, so that a reader has them when the bodies refer to them.
  Writer shapeTable;
  ShapeTableWriter shapes(shapeTable);
  std::vector<std::uint32_t> bodyShapes;
  bodyShapes.reserve(w.bodies.records.size());
  for (const detail::BodyRecord& record : w.bodies.records) bodyShapes.push_back(shapes.add(record.shape));
  shapes.finish();
  payload.bytes().insert(payload.bytes().end(), shapeTable.bytes().begin(), shapeTable.bytes().end());
  payload(bodyShapes, w.bodies.records, w.bodies.states, w.bodies.freeSlots());
  payload(w.broadPhase->records(),
          std::vector<std::uint32_t>(w.broadPhase->freeSlots().begin(), w.broadPhase->freeSlots().end()));
  payload(w.pairs, w.contacts, w.apartPairs);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> apart(w.jointedApart.begin(), w.jointedApart.end());
  std::sort(apart.begin(), apart.end());  // the map's order is its own: the bytes must not depend on it
  payload(w.joints, w.freeJoints, static_cast<std::uint64_t>(w.jointCount));
  payload.put(static_cast<std::uint64_t>(apart.size()));
  for (const auto& [key, count] : apart) payload(key, count);
  payload(w.events.contacts, w.events.contactOfEvent, w.events.sensors, w.events.faults, w.events.jointBreaks,
          w.events.pendingContacts, w.events.pendingSensors);
  payload(w.lastStats, w.totalStats, static_cast<std::uint64_t>(w.touchingCount), w.lastSubstep,
          w.callbackError);

  Writer out;
  for (const char c : kMagic) out.put(c);
  out(kFormatVersion, kLibraryVersion, layoutFingerprint(),
      static_cast<std::uint64_t>(payload.bytes().size()), fnv1a(payload.bytes()));
  out.bytes().insert(out.bytes().end(), payload.bytes().begin(), payload.bytes().end());
  return std::move(out.bytes());
}

void World::loadSnapshot(std::span<const std::uint8_t> snapshot) {
  const detail::ErrorScope scope;
  if (snapshot.size() < kHeaderBytes || std::memcmp(snapshot.data(), kMagic, sizeof kMagic) != 0)
    COLLIDE_FAIL("snapshot: not a collide world snapshot (it does not begin with collide's mark)");
  Reader header(snapshot.subspan(sizeof kMagic, kHeaderBytes - sizeof kMagic));
  std::uint32_t format = 0, library = 0;
  std::uint64_t layout = 0, payloadBytes = 0, checksum = 0;
  header(format, library, layout, payloadBytes, checksum);
  const auto version = [](std::uint32_t v) {
    return std::to_string(v >> 16) + "." + std::to_string((v >> 8) & 0xFF) + "." + std::to_string(v & 0xFF);
  };
  if (format != kFormatVersion)
    COLLIDE_FAIL("snapshot: format version " + std::to_string(format) + " (collide " + version(library) +
                 "); this build reads " + std::to_string(kFormatVersion));
  if (layout != layoutFingerprint())
    COLLIDE_FAIL("snapshot: written by collide " + version(library) + " with other fields than this build (" +
                 kVersion + ") has; a snapshot loads into the build that saved it");
  const std::span<const std::uint8_t> payload = snapshot.subspan(kHeaderBytes);
  if (payload.size() != payloadBytes)
    COLLIDE_FAIL("snapshot: truncated or padded: the header promises " + std::to_string(payloadBytes) +
                 " bytes of contents, there are " + std::to_string(payload.size()));
  if (fnv1a(payload) != checksum) COLLIDE_FAIL("snapshot: corrupt: its checksum does not match its contents");

  Reader r(payload);
  auto fresh = std::make_unique<Impl>();
  Impl& w = *fresh;
  r.section("settings");
  r.get(w.def);
  w.def.workerCount = impl_->def.workerCount;
  w.def.enqueueTask = impl_->def.enqueueTask;
  w.def.finishTask = impl_->def.finishTask;
  w.def.userTaskContext = impl_->def.userTaskContext;
  r.guard([&] { validateWorldDef(w.def); });
  if (r.failed()) return;
  const std::vector<Shape> shapes = readShapeTable(r);
  if (r.failed()) return;
  r.section("bodies");
  std::vector<std::uint32_t> bodyShapes;
  SavedBodies bodies;
  r(bodyShapes, bodies.records, bodies.states, bodies.freeSlots);
  if (bodyShapes.size() != bodies.records.size()) r.fail("the bodies and their shapes differ in number");
  if (r.failed()) return;
  for (std::size_t i = 0; i < bodyShapes.size(); ++i) {
    if (bodyShapes[i] >= shapes.size())
      return r.fail("body " + std::to_string(i) + "'s shape is not in the table");
    bodies.records[i].shape = shapes[bodyShapes[i]];
  }
  r.guard([&] {
    w.bodies.restore(std::move(bodies.records), std::move(bodies.states), std::move(bodies.freeSlots));
  });
  if (r.failed()) return;
  r.section("broad phase");
  Array<BroadPhase::ProxyRecord> proxies;
  std::vector<std::uint32_t> freeProxies;
  r(proxies, freeProxies);
  r.guard([&] {
    w.broadPhase = createBroadPhase(w.def.broadPhase);
    COLLIDE_RETURN_IF_FAILED();
    w.broadPhase->adoptProxies(proxies, freeProxies);
  });
  if (r.failed()) return;
  r.section("contacts");
  r(w.pairs, w.contacts, w.apartPairs);
  r.section("joints");
  std::uint64_t jointCount = 0;
  r(w.joints, w.freeJoints, jointCount);
  w.jointCount = static_cast<std::size_t>(jointCount);
  const std::size_t apartCount = r.countOf(12);
  for (std::size_t i = 0; i < apartCount; ++i) {
    std::uint64_t key = 0;
    std::uint32_t count = 0;
    r(key, count);
    w.jointedApart[key] = count;
  }
  r.section("events");
  r(w.events.contacts, w.events.contactOfEvent, w.events.sensors, w.events.faults, w.events.jointBreaks,
    w.events.pendingContacts, w.events.pendingSensors);
  r.section("statistics");
  std::uint64_t touching = 0;
  r(w.lastStats, w.totalStats, touching, w.lastSubstep, w.callbackError);
  w.touchingCount = static_cast<std::size_t>(touching);
  if (!r.done()) r.fail("bytes left over after the last section");
  if (r.failed()) return;
  checkWorld(r, w);
  if (r.failed()) return;

  // Taken whole: this world's task system and callbacks, the snapshot's everything else.
  std::swap(w.tasks, impl_->tasks);
  w.preSolve = std::move(impl_->preSolve);
  w.pairFilter = std::move(impl_->pairFilter);
  w.contactListener = impl_->contactListener;
  impl_ = std::move(fresh);
}

}  // namespace collide
