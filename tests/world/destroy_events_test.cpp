// Destroying a body ends its touching contacts and sensor overlaps: the End events open the next
// step's events and carry the destroyed body's (now stale) id.
#include "support/world_helpers.h"

#include <gtest/gtest.h>

namespace collide {
namespace {

using test::kDt;

TEST(DestroyEvents, TouchingContactsEndOnTheNextStep) {
  World world;
  const BodyId ground = world.createBody(test::groundBox());
  const BodyId ball = world.createBody(test::sphereBody(Vec3(0.0f, 0.5f, 0.0f), 0.5f, 1.0f));
  const BodyId far = world.createBody(test::sphereBody(Vec3(10.0f, 0.5f, 0.0f), 0.5f, 1.0f));
  for (int step = 0; step < 10; ++step) world.step(kDt);
  ASSERT_EQ(world.touchingContactCount(), 2u);
  const std::size_t before = world.contactEvents().size();
  world.destroyBody(ball);
  EXPECT_EQ(world.contactEvents().size(), before);  // the last step's events are not rewritten
  world.step(kDt);
  ASSERT_EQ(world.contactEvents().size(), 1u);
  const ContactEvent& e = world.contactEvents()[0];
  EXPECT_EQ(e.type, ContactEvent::Type::End);
  EXPECT_TRUE((e.a == ground && e.b == ball) || (e.a == ball && e.b == ground));
  EXPECT_FALSE(world.isValid(ball));
  EXPECT_EQ(world.touchingContactCount(), 1u);  // far still rests
  world.step(kDt);
  EXPECT_TRUE(world.contactEvents().empty());  // reported once
  (void)far;
}

TEST(DestroyEvents, SensorOverlapsEndOnTheNextStep) {
  World world(test::zeroGravityWorld());
  BodyDef sensorDef;
  sensorDef.type = BodyType::Static;
  sensorDef.shape = Shape(Box{Vec3(2.0f)});
  sensorDef.sensor = true;
  const BodyId sensor = world.createBody(sensorDef);
  const BodyId visitor = world.createBody(test::sphereBody(Vec3(0.5f, 0.0f, 0.0f), 0.5f, 1.0f));
  world.step(kDt);
  ASSERT_EQ(world.sensorEvents().size(), 1u);
  EXPECT_EQ(world.sensorEvents()[0].type, SensorEvent::Type::Begin);
  world.step(kDt);
  EXPECT_TRUE(world.sensorEvents().empty());
  world.destroyBody(visitor);
  world.step(kDt);
  ASSERT_EQ(world.sensorEvents().size(), 1u);
  EXPECT_EQ(world.sensorEvents()[0].type, SensorEvent::Type::End);
  EXPECT_EQ(world.sensorEvents()[0].sensor, sensor);
  EXPECT_EQ(world.sensorEvents()[0].visitor, visitor);
}

}  // namespace
}  // namespace collide
