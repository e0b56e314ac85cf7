// The narrow phase: for one pair of placed proxies, the two questions of the lecture (slide 50).
//   overlap():  bounding-volume semantics. Cheap and conservative: false means "certainly apart",
//               true means "maybe" (an early reject, never a false negative).
//   collide():  collider semantics. A contact manifold: one normal from A to B and up to four contact
//               points with depths and feature ids.
//   distance(): closest points and distance of two separated convex shapes (for continuous detection
//               and speculative contacts), or the penetration when they overlap.
// The pair is answered by a table indexed by the two shape types (docs/narrowphase.md).
#pragma once

#include <collide/error.h>
#include <collide/math.h>
#include <collide/shapes.h>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace collide {

// One contact of a manifold. pointOnA is the point of A deepest inside B (or nearest to B when
// apart); pointOnB likewise for B. depth = dot(pointOnA - pointOnB, normal): positive when the
// shapes penetrate, negative for a speculative contact that is still apart by -depth.
struct ContactPoint {
  Vec3 pointOnA{0.0f};
  Vec3 pointOnB{0.0f};
  float depth = 0.0f;
  // Names the features that made this point (e.g. box vertex, capsule end), so that the contact
  // cache can match a point with last step's: stable while the same features touch. The low 16 bits
  // belong to A, the high 16 bits to B (see docs/narrowphase.md for the codes).
  std::uint32_t featureId = 0;

  Vec3 midpoint() const { return 0.5f * (pointOnA + pointOnB); }
};

// Up to four contacts sharing one unit normal that points from A to B: moving B along +normal by
// depth (or A along -normal) separates the pair at that point.
struct Manifold {
  static constexpr int kMaxPoints = 4;

  Vec3 normal{0.0f, 1.0f, 0.0f};
  std::array<ContactPoint, kMaxPoints> points{};
  int count = 0;

  float maxDepth() const {
    float deepest = -1e30f;
    for (int i = 0; i < count; ++i) deepest = points[i].depth > deepest ? points[i].depth : deepest;
    return deepest;
  }
};

// Signed distance between two convex shapes (or a convex shape and a plane). When they are apart,
// distance > 0 and the points are the closest pair. When they overlap, overlapping is true,
// distance = -(penetration depth) <= 0 and the points are the deepest pair. normal is the unit
// direction from A to B (from pointOnA towards pointOnB when apart).
struct DistanceResult {
  float distance = 0.0f;
  Vec3 pointOnA{0.0f};
  Vec3 pointOnB{0.0f};
  Vec3 normal{0.0f, 1.0f, 0.0f};
  bool overlapping = false;
};

// Bounding-volume semantics: conservative overlap of the two proxies' bounds. Never false for a
// pair that collide() reports as penetrating. Throws Error for an invalid transform.
bool overlap(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
             const Transform& transformB);

// Collider semantics: fills `out` with the contacts of A and B and returns out.count > 0. With
// speculativeMargin > 0, also reports pairs that are apart by at most that distance (negative
// depths). Throws Error for an invalid transform, a negative or non-finite margin, or a pair that
// cannot occur (plane–plane: two infinite static half-spaces).
bool collide(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
             const Transform& transformB, Manifold& out, float speculativeMargin = 0.0f);

// Closest points and distance of convex shapes (sphere, capsule, box, k-DOP, ellipsoid, cylinder,
// hull) and of a plane with a convex shape. Throws Error for a mesh or a compound, for plane–plane
// and for an invalid transform.
DistanceResult distance(const Shape& shapeA, const Transform& transformA, const Shape& shapeB,
                        const Transform& transformB);

// ---- Time of impact (continuous collision detection, docs/ccd.md) ----

// A body's motion over one step, as Box2D's b2Sweep: the body turns about a centre (its centre of
// mass) that moves in a straight line from center0 to center1, while its rotation goes from
// rotation0 to rotation1 along the shortest arc at constant rate (slerp). localCenter is that centre
// in the body's frame, in world units (already scaled): the shape's placement at t is
// {center(t) - rotation(t) * localCenter, rotation(t), scale}.
struct Sweep {
  Vec3 localCenter{0.0f};
  Vec3 center0{0.0f};
  Vec3 center1{0.0f};
  Quat rotation0{1.0f, 0.0f, 0.0f, 0.0f};
  Quat rotation1{1.0f, 0.0f, 0.0f, 0.0f};
  float scale = 1.0f;

  // A shape that does not move.
  static Sweep fixed(const Transform& transform);
  // From the start and end placements of the shape, turning about `localCenter` (body frame,
  // world units; the origin by default).
  static Sweep between(const Transform& start, const Transform& end, const Vec3& localCenter = Vec3(0.0f));

  // The placement at t in [0, 1].
  Transform at(float t) const;
  // The angle turned over the whole sweep, radians in [0, pi].
  float angle() const;
};

struct ToiSettings {
  // The gap left between the shapes at the returned time: the world uses its linear slop, so the
  // next step's contact sees them touching without penetration (Catto, GDC 2013). May be negative
  // (a depth of penetration allowed), as the world does for pairs that start touching.
  float targetSeparation = 0.005f;
  // Accepted above the target: the search stops once the gap is below target + tolerance.
  float tolerance = 0.00125f;
  // Conservative advancement gives up after this many distance queries, at a time that is still
  // safe (the gap there is above the target).
  int maxIterations = 64;
};

struct ToiResult {
  enum class State : std::uint8_t {
    Separated,      // no contact within [0, 1]; t = 1
    Hit,            // the gap reaches the target at t (within the tolerance)
    Overlapping,    // closer than target + tolerance already at t = 0; t = 0
    MaxIterations,  // the search stopped early at t, a pose still apart by more than the target
  };
  State state = State::Separated;
  float t = 1.0f;
  Vec3 normal{0.0f, 1.0f, 0.0f};  // unit, from A to B at t (when not Separated)
  Vec3 point{0.0f};               // midway between the two surfaces at t (when not Separated)
  float separation = 0.0f;        // the signed gap at t (when not Separated)
  int iterations = 0;             // distance queries (conservative advancement) or 1 (exact sweep)

  // Hit or MaxIterations: both give a safe time at which to stop.
  bool hit() const { return state == State::Hit || state == State::MaxIterations; }
};

// The first time in [0, 1] at which A and B, moving by their sweeps, come within
// settings.targetSeparation of each other (the earliest over a mesh's triangles or a compound's children).
// Any shapes but two planes: a sphere whose centre moves in a straight line relative to a plane, box,
// triangle (of a mesh), sphere or capsule that does not turn is swept exactly (a ray against the other shape
// grown by the radius: the Minkowski sum); everything else by conservative advancement on the distance query,
// bounding the motion of any point by |delta x| + angle * r_max (Mirtich 1996; Catto, "Continuous Collision",
// GDC 2013). Meshes and compounds are swept per triangle / child (meshes are two-sided); the earliest hit
// wins. Throws Error for invalid sweeps or settings, two planes, or a turning plane.
ToiResult timeOfImpact(const Shape& shapeA, const Sweep& sweepA, const Shape& shapeB, const Sweep& sweepB,
                       const ToiSettings& settings = {});

// ---- The pair table, for tools and docs. ----

enum class PairAlgorithm : std::uint8_t {
  Analytic,      // closed form for this pair
  Sat,           // separating-axis test and face clipping
  GjkEpa,        // generic: GJK distance on the core shapes, EPA when the cores overlap
  GjkEpaClip,    // GJK/EPA on the core shapes, the core then clipped to the face it lies on
  Mesh,          // per triangle of the mesh's BVH against the other shape
  Compound,      // per child against the other shape, manifolds merged
  NotSupported,  // the pair cannot occur; collide() throws
};

std::string_view toString(PairAlgorithm algorithm);

struct PairInfo {
  PairAlgorithm algorithm = PairAlgorithm::NotSupported;
  std::string_view description;  // what the cell does, or why it is not supported
};

// The table cell for (a, b); cells are filled for both orders.
PairInfo pairInfo(ShapeType a, ShapeType b);
// The whole table as text, one line per ordered pair: "sphere × box: analytic (…)".
std::string describePairTable();

}  // namespace collide
