// Matching a new manifold's points with last step's by feature id (new vs prolonged contacts).
#include "contacts/contact_cache.h"

#include <gtest/gtest.h>

#include <initializer_list>

namespace collide::detail {
namespace {

ContactPoint pointAt(float x, std::uint32_t id) {
  ContactPoint p;
  p.pointOnA = p.pointOnB = Vec3(x, 0.0f, 0.0f);
  p.featureId = id;
  return p;
}

// A contact whose manifold holds `points`, point i with normal impulse impulses[i] (0 past the list).
Contact contactWith(std::initializer_list<ContactPoint> points, std::initializer_list<float> impulses = {}) {
  Contact contact;
  for (const ContactPoint& point : points) contact.manifold.points[contact.manifold.count++] = point;
  int i = 0;
  for (const float impulse : impulses) contact.points[i++].normalImpulse = impulse;
  return contact;
}

TEST(ContactCache, PointsMatchByFeatureIdAndInheritImpulses) {
  Contact previous = contactWith({pointAt(0.0f, 7), pointAt(1.0f, 9), pointAt(2.0f, 11)}, {1.0f, 2.0f, 3.0f});

  Contact current = contactWith({pointAt(1.1f, 9),     // same feature, moved a little
                                 pointAt(0.0f, 42)});  // a new feature at an old position
  matchContactPoints(previous, current);
  EXPECT_TRUE(current.prolonged(0));
  EXPECT_EQ(current.points[0].normalImpulse, 2.0f);
  EXPECT_FALSE(current.prolonged(1));
  EXPECT_EQ(current.points[1].normalImpulse, 0.0f);
}

TEST(ContactCache, SharedIdsMatchTheNearestOldPointOnce) {
  Contact previous = contactWith({pointAt(0.0f, 0), pointAt(1.0f, 0)}, {1.0f, 2.0f});
  Contact current = contactWith({pointAt(0.9f, 0), pointAt(0.8f, 0)});
  matchContactPoints(previous, current);
  EXPECT_EQ(current.points[0].normalImpulse, 2.0f);  // nearest is the old point at 1.0
  EXPECT_EQ(current.points[1].normalImpulse, 1.0f);  // which is taken: the other one
}

// Two equal boxes resting face to face may trade the reference face between steps: the same four
// places then come with new ids, and must keep their impulses (else the stack loses its warm start).
TEST(ContactCache, RenamedPointWithinMatchDistanceInheritsItsImpulse) {
  Contact previous = contactWith({pointAt(0.0f, 7), pointAt(1.0f, 9)}, {1.0f, 2.0f});
  Contact current = contactWith({pointAt(0.003f, 70),   // renamed, 3 mm away
                                 pointAt(1.02f, 90)});  // renamed, 2 cm away
  matchContactPoints(previous, current, 0.005f);
  EXPECT_TRUE(current.prolonged(0));
  EXPECT_EQ(current.points[0].normalImpulse, 1.0f);
  EXPECT_FALSE(current.prolonged(1));  // beyond the match distance: a new contact
  EXPECT_EQ(current.points[1].normalImpulse, 0.0f);
}

TEST(ContactCache, FeatureIdMatchesComeBeforePositionMatches) {
  Contact previous = contactWith({pointAt(0.0f, 7)}, {1.0f});
  Contact current = contactWith({pointAt(0.0f, 8),      // renamed, at the old point's very place
                                 pointAt(0.004f, 7)});  // the old point's id, a little further
  matchContactPoints(previous, current, 0.005f);
  EXPECT_FALSE(current.prolonged(0));  // the old point went to its id
  EXPECT_TRUE(current.prolonged(1));
  EXPECT_EQ(current.points[1].normalImpulse, 1.0f);
}

}  // namespace
}  // namespace collide::detail

namespace collide::detail {
namespace {

// The friction patch is the manifold's, not a point's: its impulse and static anchor carry over with
// the contact whatever happens to the points' names.
TEST(ContactCache, InheritedContactKeepsItsFrictionPatch) {
  Contact previous = contactWith({pointAt(0.0f, 7)});
  previous.frictionImpulse = Vec3(0.5f, 0.0f, -0.25f);
  previous.twistImpulse = 0.125f;
  previous.stickLocalA = Vec3(1.0f, 2.0f, 3.0f);
  previous.stickLocalB = Vec3(-1.0f, 0.0f, 0.5f);
  previous.stuck = true;
  Contact current = contactWith({pointAt(0.5f, 8)});  // neither the id nor the place matches
  inheritContact(previous, current, 0.005f);
  EXPECT_FALSE(current.prolonged(0));
  EXPECT_EQ(current.frictionImpulse, previous.frictionImpulse);
  EXPECT_EQ(current.twistImpulse, 0.125f);
  EXPECT_EQ(current.stickLocalA, previous.stickLocalA);
  EXPECT_EQ(current.stickLocalB, previous.stickLocalB);
  EXPECT_TRUE(current.stuck);
}

// A manifold placed again from the cache is last step's point for point, whatever the points'
// names and however far the pair carried them: point i keeps point i's impulse. A search would
// pair these wrongly (shared ids, each new point nearer the other old one).
TEST(ContactCache, ReusedManifoldKeepsEachPointsOwnImpulse) {
  Contact previous = contactWith({pointAt(0.0f, 0), pointAt(1.0f, 0)}, {1.0f, 2.0f});
  previous.points[1].totalNormalImpulse = 5.0f;
  Contact current = contactWith({pointAt(0.9f, 0), pointAt(1.9f, 0)});
  Contact searched = current;
  inheritContact(previous, current, 0.005f, true);
  EXPECT_EQ(current.points[0].normalImpulse, 1.0f);
  EXPECT_EQ(current.points[1].normalImpulse, 2.0f);
  EXPECT_TRUE(current.prolonged(0));
  EXPECT_TRUE(current.prolonged(1));
  EXPECT_EQ(current.points[1].totalNormalImpulse, 0.0f);  // per step, not carried
  inheritContact(previous, searched, 0.005f, false);
  EXPECT_EQ(searched.points[0].normalImpulse, 2.0f);  // the nearest old point with the same id
}

}  // namespace
}  // namespace collide::detail
