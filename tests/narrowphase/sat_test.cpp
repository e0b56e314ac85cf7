// Polyhedron pairs by SAT with face clipping: known configurations (a box resting on a box, edges
// crossing, a corner in a face, apart), cube hulls against boxes, and random pairs against EPA
// (distance()) and libccd.
#include <collide/narrowphase.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>

#include "narrowphase/pair_functions.h"
#include "support/ccd_reference.h"
#include "support/flat_grid.h"
#include "support/narrowphase_helpers.h"

using namespace collide;
using namespace collide::test;

namespace {

#if defined(NDEBUG)
constexpr int kRandomPairs = 2000;
#else
constexpr int kRandomPairs = 400;
#endif

// The local corner of a box named by its feature code (three ternary digits, no 1 among them).
Vec3 boxCorner(const Vec3& halfExtents, std::uint32_t code) {
  const int dx = code % 3, dy = (code / 3) % 3, dz = code / 9;
  return Vec3(float(dx - 1), float(dy - 1), float(dz - 1)) * halfExtents;
}

ConvexHull cubeHull(const Vec3& h) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i)
    corners.emplace_back((i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z);
  return ConvexHull::fromPoints(corners);
}

}  // namespace

TEST(SatPolyhedra, TableUsesSatForBoxKdopAndHullPairs) {
  for (const ShapeType a : {ShapeType::Box, ShapeType::Kdop, ShapeType::ConvexHull}) {
    for (const ShapeType b : {ShapeType::Box, ShapeType::Kdop, ShapeType::ConvexHull}) {
      EXPECT_EQ(pairInfo(a, b).algorithm, PairAlgorithm::Sat) << toString(a) << " x " << toString(b);
    }
  }
}

TEST(SatPolyhedra, BoxRestingOnABoxGivesFourStableCorners) {
  // A small box face-down on a large one, sunk 0.02: four points (its bottom corners), normal +y
  // from the ground (A) to the box (B), ids naming the ground's top face and the corners; under 200
  // random small wobbles the same four ids, each point at the corner its id names.
  const Vec3 ground(3.0f, 0.5f, 3.0f), h(0.5f, 0.3f, 0.4f);
  const Shape shapeA = Box{ground}, shapeB = Box{h};
  const Transform ta = Transform::identity();
  const float depth = 0.02f;
  Manifold m;
  ASSERT_TRUE(collide::collide(shapeA, ta, shapeB, at({0.2f, 0.5f + h.y - depth, -0.1f}), m));
  ASSERT_EQ(m.count, 4);
  EXPECT_NEAR(m.normal.y, 1.0f, 1e-6f);
  std::set<std::uint32_t> ids;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].depth, depth, 1e-5f);
    EXPECT_NEAR(m.points[i].pointOnA.y, 0.5f, 1e-5f);
    ids.insert(m.points[i].featureId);
  }
  ASSERT_EQ(ids.size(), 4u);
  for (const std::uint32_t id : ids) EXPECT_EQ(id & 0xffffu, detail::boxFeature(1, 2, 1));  // top face

  std::mt19937 rng(7);
  std::uniform_real_distribution<float> small(-1.0f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    const Quat wobble = axisAngle(randomUnit(rng), 0.5f * small(rng));
    const Transform tb =
        at({0.2f + 0.05f * small(rng), 0.5f + h.y - depth + 0.005f * small(rng), -0.1f + 0.05f * small(rng)},
           wobble);
    ASSERT_TRUE(collide::collide(shapeA, ta, shapeB, tb, m)) << "trial " << trial;
    ASSERT_EQ(m.count, 4) << "trial " << trial;
    std::set<std::uint32_t> now;
    for (int i = 0; i < 4; ++i) {
      now.insert(m.points[i].featureId);
      const Vec3 corner = tb.applyToPoint(boxCorner(h, m.points[i].featureId >> 16));
      EXPECT_LT(glm::length(m.points[i].pointOnB - corner), 1e-5f) << "trial " << trial;
      EXPECT_NEAR(m.points[i].depth, 0.5f - corner.y, 1e-5f) << "trial " << trial;
    }
    EXPECT_EQ(now, ids) << "trial " << trial;
  }
}

TEST(SatPolyhedra, CrossedEdgesGiveOnePointAtTheirCrossing) {
  // Two unit cubes turned 45° about z (A) and about x (B): A's top edge runs along z at height
  // √2/2, B's bottom edge along x at yB - √2/2. They cross at the y axis with depth √2 - yB.
  const float half = 0.5f, reach = half * std::sqrt(2.0f);
  const float yB = 2.0f * reach - 0.1f;
  Manifold m;
  ASSERT_TRUE(collide::collide(Box{Vec3(half)}, at({0, 0, 0}, axisAngle({0, 0, 1}, 45.0f)), Box{Vec3(half)},
                               at({0, yB, 0}, axisAngle({1, 0, 0}, 45.0f)), m));
  ASSERT_EQ(m.count, 1);
  EXPECT_LT(angleDegrees(m.normal, Vec3(0, 1, 0)), 0.01f);
  EXPECT_NEAR(m.points[0].depth, 0.1f, 1e-5f);
  EXPECT_LT(glm::length(m.points[0].pointOnA - Vec3(0, reach, 0)), 1e-5f);
  EXPECT_LT(glm::length(m.points[0].pointOnB - Vec3(0, yB - reach, 0)), 1e-5f);
  // Both halves of the id name an edge: exactly one ternary digit is 1.
  for (const std::uint32_t code : {m.points[0].featureId & 0xffffu, m.points[0].featureId >> 16}) {
    const int ones = int(code % 3 == 1) + int((code / 3) % 3 == 1) + int(code / 9 == 1);
    EXPECT_EQ(ones, 1) << code;
  }
}

TEST(SatPolyhedra, HullRestingOnARidgeKeepsItsDeepestVertex) {
  // A hull resting on a ridge edge from v0 = (0, 0, 0) to v3 = (1, 0.002, 0), the ridge's two faces
  // at 45°, and beyond v3 a flatter face (normal 31° from -y) that does not contain v0: the face
  // most anti-parallel to the ground's normal is that one, and clipping it alone loses v0, the
  // deepest vertex (R4: a hull whose lowest vertex sank 5 cm into the terrain, held only at the
  // other end of its edge). Sunk 0.01 at v0 into a box, a flat grid and a hull: two points, v0 at
  // depth 0.01 and v3 at 0.008.
  const std::vector<Vec3> points = {{0.0f, 0.0f, 0.0f},  {1.0f, 0.002f, 0.0f}, {1.5f, 0.3f, 0.1f},
                                    {1.5f, 0.3f, -0.1f}, {0.5f, 0.5f, 0.5f},   {0.5f, 0.5f, -0.5f},
                                    {0.6f, 1.0f, 0.0f}};
  const Shape hull(ConvexHull::fromPoints(points));
  const Transform pose = at({0.2f, -0.01f, 0.3f});
  const std::vector<Vec3> slab = {{-4, -1, -4}, {4, -1, -4}, {-4, -1, 4}, {4, -1, 4},
                                  {-4, 0, -4},  {4, 0, -4},  {-4, 0, 4},  {4, 0, 4}};
  const Shape grounds[] = {Box{Vec3(5.0f, 0.5f, 5.0f)}, Shape(test::flatGrid(8)),
                           Shape(ConvexHull::fromPoints(slab))};
  const Transform groundPoses[] = {at({0.0f, -0.5f, 0.0f}), Transform{}, Transform{}};
  for (int g = 0; g < 3; ++g) {
    for (const bool mirrored : {false, true}) {
      Manifold m;
      const bool hit = mirrored ? collide::collide(hull, pose, grounds[g], groundPoses[g], m)
                                : collide::collide(grounds[g], groundPoses[g], hull, pose, m);
      ASSERT_TRUE(hit) << "ground " << g;
      ASSERT_EQ(m.count, 2) << "ground " << g << (mirrored ? " mirrored" : "");
      EXPECT_LT(angleDegrees(m.normal, mirrored ? Vec3(0, -1, 0) : Vec3(0, 1, 0)), 1e-3f);
      EXPECT_NEAR(m.maxDepth(), 0.01f, 1e-6f) << "ground " << g;
      for (const Vec3& local : {points[0], points[1]}) {
        const Vec3 vertex = pose.applyToPoint(local);
        bool found = false;
        for (int k = 0; k < m.count; ++k) {
          const Vec3 onHull = mirrored ? m.points[k].pointOnA : m.points[k].pointOnB;
          if (glm::length(onHull - vertex) < 1e-5f) {
            found = true;
            EXPECT_NEAR(m.points[k].depth, -vertex.y, 1e-6f);
          }
        }
        EXPECT_TRUE(found) << "ground " << g << ": no point at (" << vertex.x << ", " << vertex.y << ", "
                           << vertex.z << ")";
      }
    }
  }
}

TEST(SatPolyhedra, CornerIntoAFaceGivesOnePoint) {
  // A cube standing on a corner: the rotation taking (-1, -1, -1)/√3 to -y puts that corner lowest,
  // √3/2 below the centre.
  const Vec3 down = glm::normalize(Vec3(-1.0f));
  const Quat rotation = glm::angleAxis(std::acos(glm::dot(down, Vec3(0, -1, 0))),
                                       glm::normalize(glm::cross(down, Vec3(0, -1, 0))));
  const float yB = 0.5f + 0.5f * std::sqrt(3.0f) - 0.05f;
  Manifold m;
  const Transform tb = at({0.3f, yB, 0.2f}, rotation);
  ASSERT_TRUE(collide::collide(Box{Vec3(2.0f, 0.5f, 2.0f)}, Transform::identity(), Box{Vec3(0.5f)}, tb, m));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.normal.y, 1.0f, 1e-5f);
  EXPECT_NEAR(m.points[0].depth, 0.05f, 1e-5f);
  EXPECT_LT(glm::length(m.points[0].pointOnB - tb.applyToPoint(Vec3(-0.5f))), 1e-5f);
  EXPECT_EQ(m.points[0].featureId >> 16, detail::boxFeature(0, 0, 0));
}

TEST(SatPolyhedra, SeparatedBoxesGiveNoContactUnlessWithinTheMargin) {
  // Face to face 0.1 apart: nothing, then four speculative points at -0.1 with a margin of 0.15.
  Manifold m;
  const Transform tb = at({0.1f, 1.1f, 0.0f}, axisAngle({0, 1, 0}, 30.0f));
  EXPECT_FALSE(collide::collide(Box{Vec3(1.0f, 0.5f, 1.0f)}, Transform::identity(), Box{Vec3(0.5f)}, tb, m));
  EXPECT_EQ(m.count, 0);
  ASSERT_TRUE(
      collide::collide(Box{Vec3(1.0f, 0.5f, 1.0f)}, Transform::identity(), Box{Vec3(0.5f)}, tb, m, 0.15f));
  ASSERT_EQ(m.count, 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].depth, -0.1f, 1e-5f);
  // Edge to edge 0.05 apart (the crossed cubes above, lifted): nothing, then one point at -0.05.
  const float reach = 0.5f * std::sqrt(2.0f);
  const Transform ta = at({0, 0, 0}, axisAngle({0, 0, 1}, 45.0f));
  const Transform tc = at({0, 2.0f * reach + 0.05f, 0}, axisAngle({1, 0, 0}, 45.0f));
  EXPECT_FALSE(collide::collide(Box{Vec3(0.5f)}, ta, Box{Vec3(0.5f)}, tc, m));
  ASSERT_TRUE(collide::collide(Box{Vec3(0.5f)}, ta, Box{Vec3(0.5f)}, tc, m, 0.1f));
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].depth, -0.05f, 1e-5f);
}

TEST(SatPolyhedra, AHullBuiltWhereAFreedOneWasIsPlacedAnew) {
  // The SAT keeps placed hulls in a cache. A cube hull is placed under a box, then freed, and a
  // taller hull with the same first vertex is built, most likely at the freed one's address (the
  // allocator reuses a block of the same size): at the same pose it must be placed anew, its top
  // 0.8 m into the box, not 0.2 m under it as the freed cube's was.
  const Shape box = Box{Vec3(0.5f)};
  const Transform boxAt = at({0.0f, 1.2f, 0.0f});
  auto cuboid = [](float top) {
    std::vector<Vec3> points;
    for (const float x : {0.5f, -0.5f})
      for (const float y : {top, -0.5f})
        for (const float z : {0.5f, -0.5f}) points.emplace_back(x, y, z);
    return Shape(std::make_shared<const ConvexHull>(ConvexHull::fromPoints(points)));
  };
  Manifold m;
  const ConvexHull* firstAddress = nullptr;
  Vec3 firstVertex;
  {
    const Shape cube = cuboid(0.5f);
    firstAddress = &cube.convexHull();
    firstVertex = cube.convexHull().vertices()[0];
    ASSERT_TRUE(collide::collide(cube, Transform::identity(), box, boxAt, m, 0.5f));
    EXPECT_NEAR(m.maxDepth(), -0.2f, 1e-5f);
  }
  const Shape tall = cuboid(1.5f);
  ASSERT_EQ(tall.convexHull().vertices()[0], firstVertex);
  if (&tall.convexHull() != firstAddress) GTEST_SKIP() << "the allocator did not reuse the address";
  ASSERT_TRUE(collide::collide(tall, Transform::identity(), box, boxAt, m, 0.5f));
  EXPECT_NEAR(m.maxDepth(), 0.8f, 1e-5f);
}

TEST(SatPolyhedra, CubeHullsAndKdopsAgreeWithBoxes) {
  // The same geometry as a box, a hull of its corners and a 6-DOP: the same manifold (depths and
  // normal), in every combination, for random poses.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int contacts = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 hA(0.2f + unit(rng), 0.2f + unit(rng), 0.2f + unit(rng));
    const Vec3 hB(0.2f + unit(rng), 0.2f + unit(rng), 0.2f + unit(rng));
    const float slabMin[3] = {-hB.x, -hB.y, -hB.z}, slabMax[3] = {hB.x, hB.y, hB.z};
    const Shape boxA = Box{hA}, boxB = Box{hB}, hullA = cubeHull(hA), hullB = cubeHull(hB),
                kdopB = Kdop::fromSlabs(6, slabMin, slabMax);
    const Transform ta = at(Vec3(unit(rng), unit(rng), unit(rng)), uniformRotation(rng));
    const Transform tb =
        at(ta.position + randomUnit(rng) * (1.5f * unit(rng) * (glm::length(hA) + glm::length(hB))),
           uniformRotation(rng));
    Manifold reference;
    const bool hit = collide::collide(boxA, ta, boxB, tb, reference);
    contacts += hit;
    for (const auto& [a, b] : {std::pair{&hullA, &hullB}, {&boxA, &hullB}, {&boxA, &kdopB}}) {
      Manifold m;
      ASSERT_EQ(collide::collide(*a, ta, *b, tb, m), hit) << "trial " << trial;
      if (!hit) continue;
      EXPECT_LT(angleDegrees(m.normal, reference.normal), 0.05f) << "trial " << trial;
      ASSERT_EQ(m.count, reference.count) << "trial " << trial;
      const auto depths = sortedDepths(m), expected = sortedDepths(reference);
      for (int i = 0; i < m.count; ++i) EXPECT_NEAR(depths[i], expected[i], 1e-4f) << "trial " << trial;
    }
  }
  EXPECT_GT(contacts, 50);
}

namespace {

struct SatTally {
  int compared = 0, failures = 0, normalFailures = 0, preferred = 0, verdictMismatches = 0;
  std::string firstFailure;
  void note(const std::string& text) {
    if (firstFailure.empty()) firstFailure = text;
  }
};

// Checks one penetrating pair against a reference depth and normal (EPA or libccd).
// 1. The separating-axis test itself (the largest separation over the axes it tries) must find the
//    reference depth (1e-3 relative) and normal (1 degree; where the normals differ, both must
//    separate equally well: a tie between two axes).
// 2. The manifold's normal may be a face preferred over a barely better axis: its directional depth
//    (the translation along it that separates the shapes) is at least the SAT depth and at most the
//    preference above it (2% plus 1e-3 of the size); no contact point is deeper than it. Counted
//    as "preferred" when it is not the SAT axis.
void judge(const detail::ConvexSupport& a, const detail::ConvexSupport& b, const Manifold& m,
           const detail::SatAxis& sat, float referenceDepth, const Vec3& referenceNormal, float size,
           const char* where, SatTally& tally) {
  ++tally.compared;
  const float satDepth = -sat.separation;
  const float tolerance = 1e-3f * std::max(satDepth, referenceDepth) + 1e-5f;
  const float ours = directionalDepth(a, b, m.normal);
  if (std::abs(satDepth - referenceDepth) > tolerance) {
    ++tally.failures;
    tally.note(std::string(where) + ": SAT depth " + std::to_string(satDepth) + ", reference " +
               std::to_string(referenceDepth));
  } else if (angleDegrees(sat.axis, referenceNormal) > 1.0f &&
             std::abs(directionalDepth(a, b, sat.axis) - directionalDepth(a, b, referenceNormal)) >
                 tolerance) {
    ++tally.normalFailures;
    tally.note(std::string(where) + ": SAT axis " + std::to_string(angleDegrees(sat.axis, referenceNormal)) +
               " degrees from the reference");
  } else if (m.maxDepth() > ours + tolerance || m.maxDepth() <= 0.0f || ours < satDepth - tolerance ||
             ours > (satDepth + 1e-3f * size) / 0.98f + tolerance) {
    ++tally.failures;
    tally.note(std::string(where) + ": manifold depth " + std::to_string(m.maxDepth()) +
               ", its normal's depth " + std::to_string(ours) + ", SAT depth " + std::to_string(satDepth));
  } else if (angleDegrees(m.normal, sat.axis) > 1e-3f) {
    ++tally.preferred;
  }
}

}  // namespace

TEST(SatPolyhedra, RandomBoxPairsAgreeWithEpaAndAreSymmetric) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  SatTally tally;
  int symmetryFailures = 0, separatedSpeculative = 0;
  for (int i = 0; i < kRandomPairs; ++i) {
    const Shape shapeA = randomPrimitive(ShapeType::Box, rng), shapeB = randomPrimitive(ShapeType::Box, rng);
    const float reach = glm::length(shapeA.box().halfExtents) + glm::length(shapeB.box().halfExtents);
    const Transform ta = at(Vec3(unit(rng), unit(rng), unit(rng)) - 0.5f, uniformRotation(rng));
    const Transform tb = at(ta.position + randomUnit(rng) * (1.3f * reach * unit(rng)), uniformRotation(rng));
    const DistanceResult reference = collide::distance(shapeA, ta, shapeB, tb);
    Manifold m, mirrored;
    const bool hit = collide::collide(shapeA, ta, shapeB, tb, m);
    char where[96];
    std::snprintf(where, sizeof where, "pair %d: distance %.6f", i, reference.distance);
    if (std::abs(reference.distance) > 1e-4f && hit != reference.overlapping) {
      ++tally.verdictMismatches;
      tally.note(std::string(where) + ": SAT verdict differs");
    }
    if (!reference.overlapping && reference.distance > 1e-4f) {
      // Within a margin just above the distance, a speculative contact, apart (negative depth).
      if (collide::collide(shapeA, ta, shapeB, tb, m, reference.distance + 0.01f)) {
        ++separatedSpeculative;
        EXPECT_LE(m.maxDepth(), 1e-5f) << where;
      }
      continue;
    }
    if (!hit || -reference.distance < 1e-4f) continue;
    judge(detail::makeConvexSupport(shapeA, ta), detail::makeConvexSupport(shapeB, tb), m,
          detail::polyhedraSeparation(shapeA, ta, shapeB, tb), -reference.distance, reference.normal,
          std::min(glm::length(shapeA.box().halfExtents), glm::length(shapeB.box().halfExtents)), where,
          tally);
    // collide(B, A): the same points swapped, the opposite normal (the reference face does not
    // depend on the order).
    ASSERT_TRUE(collide::collide(shapeB, tb, shapeA, ta, mirrored)) << where;
    const std::vector<float> depths = sortedDepths(m), mirroredDepths = sortedDepths(mirrored);
    if (mirrored.count != m.count || glm::dot(mirrored.normal, m.normal) > -1.0f + 1e-4f ||
        !std::equal(depths.begin(), depths.end(), mirroredDepths.begin(),
                    [](float x, float y) { return std::abs(x - y) <= 1e-5f + 1e-4f * std::abs(x); })) {
      ++symmetryFailures;
      tally.note(std::string(where) + ": collide(B, A) differs");
    }
  }
  std::printf(
      "box x box (SAT)      compared %d, %d fail, %d normal fail, %d preferred faces, %d verdicts differ, %d "
      "asymmetric, %d speculative\n",
      tally.compared, tally.failures, tally.normalFailures, tally.preferred, tally.verdictMismatches,
      symmetryFailures, separatedSpeculative);
  SCOPED_TRACE(tally.firstFailure);
  EXPECT_EQ(tally.failures, 0);
  EXPECT_EQ(tally.normalFailures, 0);
  EXPECT_EQ(tally.verdictMismatches, 0);
  EXPECT_EQ(symmetryFailures, 0);
  EXPECT_GT(tally.compared, kRandomPairs / 4);
  EXPECT_GT(separatedSpeculative, kRandomPairs / 10);
}

#if defined(COLLIDE_HAVE_CCD)
TEST(SatPolyhedra, RandomHullPairsAgreeWithLibccd) {
  // Hulls of 6 to 20 random points in ellipsoids of random radii; libccd's GJK verdict and
  // GJK+EPA penetration fed with the same support mappings.
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  ccd_t ccd = makeCcd();
  SatTally tally;
  int referenceErrors = 0;
  const int pairs = kRandomPairs / 2;
  for (int i = 0; i < pairs; ++i) {
    auto randomHull = [&] {
      const Vec3 radii(0.2f + unit(rng), 0.2f + unit(rng), 0.2f + unit(rng));
      std::vector<Vec3> points(6 + rng() % 15);
      for (Vec3& p : points) p = radii * randomUnit(rng) * std::cbrt(unit(rng));
      return Shape(ConvexHull::fromPoints(points));
    };
    const Shape shapeA = randomHull(), shapeB = randomHull();
    const float sizeA = glm::length(shapeA.convexHull().bounds().halfExtents());
    const float sizeB = glm::length(shapeB.convexHull().bounds().halfExtents());
    const Transform ta = at(Vec3(unit(rng), unit(rng), unit(rng)) - 0.5f, uniformRotation(rng));
    const Transform tb =
        at(ta.position + randomUnit(rng) * (1.3f * (sizeA + sizeB) * unit(rng)), uniformRotation(rng));
    const detail::ConvexSupport a = detail::makeConvexSupport(shapeA, ta),
                                b = detail::makeConvexSupport(shapeB, tb);
    Manifold m;
    const bool hit = collide::collide(shapeA, ta, shapeB, tb, m);
    const bool theirs = ccdGJKIntersect(&a, &b, &ccd) != 0;
    char where[64];
    std::snprintf(where, sizeof where, "pair %d", i);
    const DistanceResult ours = collide::distance(shapeA, ta, shapeB, tb);
    if (std::abs(ours.distance) > 1e-4f && hit != theirs) {
      ++tally.verdictMismatches;
      tally.note(std::string(where) + ": libccd verdict differs, distance " + std::to_string(ours.distance) +
                 " SAT " + std::to_string(hit) + " SAT separation " +
                 std::to_string(detail::polyhedraSeparation(shapeA, ta, shapeB, tb).separation));
    }
    if (!hit || !theirs || -ours.distance < 1e-4f) continue;
    ccd_real_t depth = 0;
    ccd_vec3_t direction, position;
    if (ccdGJKPenetration(&a, &b, &ccd, &depth, &direction, &position) != 0) continue;
    const Vec3 theirNormal = glm::normalize(Vec3(direction.v[0], direction.v[1], direction.v[2]));
    // libccd's EPA may stop early; where its depth is not its own normal's, it is no reference.
    if (std::abs(directionalDepth(a, b, theirNormal) - float(depth)) > 1e-3f * float(depth) + 1e-5f) {
      ++referenceErrors;
      continue;
    }
    judge(a, b, m, detail::polyhedraSeparation(shapeA, ta, shapeB, tb), float(depth), theirNormal,
          std::min(sizeA, sizeB), where, tally);
  }
  std::printf(
      "hull x hull (SAT)    compared %d, %d fail, %d normal fail, %d preferred faces, %d verdicts differ, %d "
      "libccd errors\n",
      tally.compared, tally.failures, tally.normalFailures, tally.preferred, tally.verdictMismatches,
      referenceErrors);
  SCOPED_TRACE(tally.firstFailure);
  EXPECT_EQ(tally.failures, 0);
  EXPECT_EQ(tally.normalFailures, 0);
  EXPECT_EQ(tally.verdictMismatches, 0);
  EXPECT_GT(tally.compared, pairs / 5);
}
#endif

// ---- The box–box fast path (box_box.cpp) against the generic polyhedron routine ----

namespace {

struct FastPathTally {
  int pairs = 0, hits = 0, faceContacts = 0, edgeContacts = 0, multiPoint = 0, failures = 0, ties = 0;
  std::string firstFailure;
  void fail(const std::string& text) {
    ++failures;
    if (firstFailure.empty()) firstFailure = text;
  }
};

// Runs both routines on one pair and compares: the same verdict; the same number of points; the
// deepest depth within 1e-4 relative (1e-5 absolute near zero); the normals within 1e-3 rad, unless
// both separate the boxes equally well (a tie, counted); and, but for a tie, each point (both pointOnA and
// pointOnB, up to order) matched by one of the other within 1e-4 of the boxes' size.
void compareFastPath(const Shape& a, const Transform& ta, const Shape& b, const Transform& tb, float margin,
                     const char* where, FastPathTally& tally) {
  ++tally.pairs;
  Manifold fast, generic;
  const bool fastHit = detail::collideBoxBox(a, ta, b, tb, margin, fast);
  const bool genericHit = detail::collidePolyhedra(a, ta, b, tb, margin, generic);
  if (fastHit != genericHit) {
    tally.fail(std::string(where) + ": verdicts differ (fast " + std::to_string(fastHit) + ")");
    return;
  }
  if (!fastHit) return;
  ++tally.hits;
  (generic.count == 1 ? tally.edgeContacts : tally.faceContacts) += 1;
  tally.multiPoint += generic.count > 1;
  if (fast.count != generic.count) {
    tally.fail(std::string(where) + ": " + std::to_string(fast.count) + " points, generic " +
               std::to_string(generic.count));
    return;
  }
  const float depth = generic.maxDepth();
  const float depthTolerance = 1e-4f * std::abs(depth) + 1e-5f;
  if (std::abs(fast.maxDepth() - depth) > depthTolerance) {
    tally.fail(std::string(where) + ": depth " + std::to_string(fast.maxDepth()) + ", generic " +
               std::to_string(depth));
    return;
  }
  const float angle = std::acos(std::clamp(glm::dot(fast.normal, generic.normal), -1.0f, 1.0f));
  if (angle > 1e-3f) {
    // Two axes (a face of A and a nearly parallel face of B, say) may separate the boxes equally
    // well; then either routine may pick either, rounding decides, and the points lie on different
    // reference faces. Otherwise one of the normals is wrong.
    const detail::ConvexSupport sa = detail::makeConvexSupport(a, ta), sb = detail::makeConvexSupport(b, tb);
    const auto directional = [&](const Vec3& n) {
      return glm::dot(sa.supportCore(n) - sb.supportCore(-n), n);
    };
    if (std::abs(directional(fast.normal) - directional(generic.normal)) > depthTolerance) {
      tally.fail(std::string(where) + ": normals " + std::to_string(angle) + " rad apart");
    } else {
      ++tally.ties;
    }
    return;
  }
  const float size =
      std::min(glm::length(a.box().halfExtents) * ta.scale, glm::length(b.box().halfExtents) * tb.scale);
  for (int i = 0; i < generic.count; ++i) {
    bool matched = false;
    for (int k = 0; k < fast.count && !matched; ++k) {
      matched = glm::length(fast.points[k].pointOnA - generic.points[i].pointOnA) <= 1e-4f * size &&
                glm::length(fast.points[k].pointOnB - generic.points[i].pointOnB) <= 1e-4f * size &&
                std::abs(fast.points[k].depth - generic.points[i].depth) <= 1e-4f * size;
    }
    if (!matched) {
      tally.fail(std::string(where) + ": generic point " + std::to_string(i) + " has no match");
      return;
    }
  }
}

}  // namespace

TEST(BoxBox, TableUsesTheBoxPathForBoxPairs) {
  // The cell is SAT and its description names the box-specific axes.
  const PairInfo info = pairInfo(ShapeType::Box, ShapeType::Box);
  EXPECT_EQ(info.algorithm, PairAlgorithm::Sat);
  EXPECT_NE(info.description.find("9 edge directions"), std::string_view::npos) << info.description;
}

TEST(BoxBox, RandomPairsAgreeWithTheGenericRoutine) {
  // Random boxes (half extents 0.2 to 1.2, scale 0.5 to 2) in random poses at centre distances up
  // to 1.3 × the sum of their half diagonals, with and without a speculative margin.
  std::mt19937 rng(4242);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  FastPathTally tally;
  for (int i = 0; i < 2 * kRandomPairs; ++i) {
    const Shape a = randomPrimitive(ShapeType::Box, rng), b = randomPrimitive(ShapeType::Box, rng);
    const float scaleA = 0.5f + 1.5f * unit(rng), scaleB = 0.5f + 1.5f * unit(rng);
    const float reach = glm::length(a.box().halfExtents) * scaleA + glm::length(b.box().halfExtents) * scaleB;
    const Transform ta = at(Vec3(unit(rng), unit(rng), unit(rng)) - 0.5f, uniformRotation(rng), scaleA);
    const Transform tb =
        at(ta.position + randomUnit(rng) * (1.3f * reach * unit(rng)), uniformRotation(rng), scaleB);
    const float margin = (i % 3 == 0) ? 0.1f * reach * unit(rng) : 0.0f;
    char where[64];
    std::snprintf(where, sizeof where, "random pair %d", i);
    compareFastPath(a, ta, b, tb, margin, where, tally);
  }
  std::printf("box x box fast path, random: %d pairs, %d hits (%d face, %d edge), %d ties, %d failures\n",
              tally.pairs, tally.hits, tally.faceContacts, tally.edgeContacts, tally.ties, tally.failures);
  SCOPED_TRACE(tally.firstFailure);
  EXPECT_EQ(tally.failures, 0);
  EXPECT_LE(tally.ties, tally.hits / 100);  // a tie is a coincidence, not a way out
  EXPECT_GT(tally.hits, tally.pairs / 4);
  EXPECT_GT(tally.edgeContacts, tally.pairs / 50);
}

TEST(BoxBox, NearlyRestingPairsAgreeWithTheGenericRoutine) {
  // Face to face, the way stacks rest: a box over a box of random size, tilted by up to 3°,
  // turned about the vertical, shifted sideways (sometimes over the edge), sunk or lifted by a
  // little, with a margin. Mostly multi-point face contacts, where the clipping must agree.
  std::mt19937 rng(77);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  FastPathTally tally;
  for (int i = 0; i < 2 * kRandomPairs; ++i) {
    const Shape a = randomPrimitive(ShapeType::Box, rng), b = randomPrimitive(ShapeType::Box, rng);
    const Vec3 hA = a.box().halfExtents, hB = b.box().halfExtents;
    const Quat tilt = axisAngle(randomUnit(rng), 3.0f * unit(rng)) * axisAngle({0, 1, 0}, 180.0f * unit(rng));
    const Transform ta = at(Vec3(0.0f), axisAngle(randomUnit(rng), 2.0f * unit(rng)));
    const Vec3 local(hA.x * 1.2f * unit(rng), hA.y + hB.y + 0.03f * unit(rng), hA.z * 1.2f * unit(rng));
    const Transform tb = at(ta.applyToPoint(local), ta.rotation * tilt);
    char where[64];
    std::snprintf(where, sizeof where, "resting pair %d", i);
    compareFastPath(a, ta, b, tb, 0.02f, where, tally);
    std::snprintf(where, sizeof where, "resting pair %d mirrored", i);
    compareFastPath(b, tb, a, ta, 0.02f, where, tally);
  }
  std::printf("box x box fast path, resting: %d pairs, %d hits (%d with 2-4 points), %d ties, %d failures\n",
              tally.pairs, tally.hits, tally.multiPoint, tally.ties, tally.failures);
  SCOPED_TRACE(tally.firstFailure);
  EXPECT_EQ(tally.failures, 0);
  EXPECT_LE(tally.ties, tally.hits / 100);
  EXPECT_GT(tally.multiPoint, tally.pairs / 2);
}

TEST(BoxBox, BoxOverTheGroundsEdgeKeepsItsClippedIds) {
  // A box hanging over the edge of the ground (x = 1): its two corners on the ground plus two
  // points where its bottom edges cross the ground's side plane. The clipped points are named by
  // (ground edge, box edge), so under small wobbles the same four ids come back, all different.
  // Tilts stay small against the depth: a box tilted so that its edge over the ground's edge is
  // clearly shallower than its lowest corner gets the one-point edge contact, by the face
  // preference's rule.
  const Shape ground = Box{Vec3(1.0f, 0.5f, 1.0f)}, box = Box{Vec3(0.4f, 0.2f, 0.3f)};
  const float depth = 0.05f;
  Manifold m;
  ASSERT_TRUE(collide::collide(ground, Transform::identity(), box, at({1.1f, 0.7f - depth, 0.0f}), m));
  ASSERT_EQ(m.count, 4);
  std::set<std::uint32_t> ids;
  int clipped = 0;
  for (int i = 0; i < 4; ++i) {
    ids.insert(m.points[i].featureId);
    const std::uint32_t groundCode = m.points[i].featureId & 0xffffu;
    if (groundCode != detail::boxFeature(1, 2, 1)) {
      // On the ground's +x top edge, at x = 1; the box half is one of its bottom edges along x.
      ++clipped;
      EXPECT_EQ(groundCode, detail::boxFeature(2, 2, 1));
      EXPECT_NEAR(m.points[i].pointOnA.x, 1.0f, 1e-6f);
      const std::uint32_t boxCode = m.points[i].featureId >> 16;
      EXPECT_EQ(boxCode % 3, 1u) << boxCode;
      EXPECT_EQ((boxCode / 3) % 3, 0u) << boxCode;
    }
  }
  EXPECT_EQ(clipped, 2);
  ASSERT_EQ(ids.size(), 4u);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> small(-1.0f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    const Transform tb =
        at({1.1f + 0.03f * small(rng), 0.7f - depth + 0.003f * small(rng), 0.03f * small(rng)},
           axisAngle(randomUnit(rng), 0.05f * small(rng)));
    ASSERT_TRUE(collide::collide(ground, Transform::identity(), box, tb, m)) << "trial " << trial;
    ASSERT_EQ(m.count, 4) << "trial " << trial;
    std::set<std::uint32_t> now;
    for (int i = 0; i < 4; ++i) now.insert(m.points[i].featureId);
    EXPECT_EQ(now, ids) << "trial " << trial;
  }
}
