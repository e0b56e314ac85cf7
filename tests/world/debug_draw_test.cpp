// Debug drawing (collide/debug_draw.h): every proxy's wireframe lies on its surface, a box draws its
// twelve edges and a hull its edges, and World::draw hands a recording implementation what the
// world holds: each part in its body's colour, the boxes, the contacts with their normals and
// impulses, the constraints and the centres of mass.
#include "support/collide_error.h"
#include "support/test_meshes.h"
#include "support/world_helpers.h"

#include <collide/debug_draw.h>
#include <collide/world.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace collide {
namespace {

using test::kDt;

struct Line {
  Vec3 from, to;
  DebugColor color;
};

class RecordingDraw : public DebugDraw {
 public:
  void drawLine(const Vec3& from, const Vec3& to, const DebugColor& color) override {
    lines.push_back({from, to, color});
  }
  void drawPoint(const Vec3& point, float size, const DebugColor& color) override {
    points.push_back({point, Vec3(size), color});
  }
  void drawTriangle(const Vec3&, const Vec3&, const Vec3&, const DebugColor&) override { ++triangles; }
  void drawText(const Vec3&, std::string_view text, const DebugColor&) override { texts.emplace_back(text); }

  std::size_t count(const DebugColor& color) const {
    return std::count_if(lines.begin(), lines.end(), [&](const Line& l) { return l.color == color; });
  }
  std::vector<Line> lines;
  std::vector<Line> points;  // point, (size, size, size), colour
  int triangles = 0;
  std::vector<std::string> texts;
};

const Transform kPose{Vec3(1.0f, -2.0f, 3.0f), glm::normalize(Quat(0.9f, 0.2f, -0.3f, 0.1f)), 1.5f};

std::vector<Shape> everyConvexShape() {
  const std::vector<Vec3> points = {Vec3(0.0f), Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f),
                                    Vec3(0.0f, 0.0f, 1.0f), Vec3(0.7f, 0.7f, 0.7f)};
  return {Shape(Sphere{0.7f}),
          Shape(Box{Vec3(0.3f, 0.5f, 0.9f)}),
          Shape(Capsule{0.3f, 0.6f}),
          Shape(Cylinder{0.4f, 0.5f}),
          Shape(Ellipsoid{Vec3(0.3f, 0.6f, 0.9f)}),
          Shape(ConvexHull::fromPoints(points)),
          Shape(Kdop::fromPoints(14, points))};
}

TEST(DebugDraw, EveryWireframeLiesOnItsShapesSurface) {
  // Every end of every line is on the surface (closestPoint's signed distance ~ 0), for every convex
  // proxy, a compound of them and a mesh, at a turned, scaled pose.
  std::vector<Shape> shapes = everyConvexShape();
  std::vector<Compound::Child> children;
  for (std::size_t k = 0; k < 3; ++k)
    children.push_back({shapes[k], Transform{Vec3(3.0f * float(k), 0, 0), Quat(1, 0, 0, 0), 1.0f}});
  shapes.push_back(Shape(Compound::fromChildren(children)));
  shapes.push_back(Shape(test::boxMesh(Vec3(0.5f))));
  for (const Shape& shape : shapes) {
    RecordingDraw draw;
    drawShape(draw, shape, kPose, DebugColors::kDynamic);
    ASSERT_FALSE(draw.lines.empty()) << toString(shape.type());
    for (const Line& line : draw.lines) {
      for (const Vec3& end : {line.from, line.to}) {
        EXPECT_NEAR(closestPoint(shape, kPose, end).signedDistance, 0.0f, 2e-5f * 3.0f * kPose.scale)
            << toString(shape.type());
      }
      EXPECT_EQ(line.color, DebugColors::kDynamic);
    }
  }
}

TEST(DebugDraw, ABoxIsItsTwelveEdgesAndAHullItsEdges) {
  const Vec3 h(0.3f, 0.5f, 0.9f);
  RecordingDraw box;
  drawShape(box, Shape(Box{h}), kPose, DebugColors::kStatic);
  ASSERT_EQ(box.lines.size(), 12u);
  std::map<int, int> lengths;  // edge length in mm, how many
  for (const Line& l : box.lines) ++lengths[int(std::lround(1000.0f * glm::length(l.to - l.from)))];
  const std::map<int, int> expected{{int(std::lround(2000.0f * h.x * kPose.scale)), 4},
                                    {int(std::lround(2000.0f * h.y * kPose.scale)), 4},
                                    {int(std::lround(2000.0f * h.z * kPose.scale)), 4}};
  EXPECT_EQ(lengths, expected);

  const Shape hull = everyConvexShape()[5];
  RecordingDraw edges;
  drawShape(edges, hull, kPose, DebugColors::kStatic);
  EXPECT_EQ(edges.lines.size(), hull.convexHull().edgeCount());

  RecordingDraw sphere;
  drawShape(sphere, Shape(Sphere{1.0f}), kPose, DebugColors::kStatic, 20.0f, 16);
  EXPECT_EQ(sphere.lines.size(), 3u * 16u);
  EXPECT_COLLIDE_ERROR(drawShape(sphere, Shape(Sphere{1.0f}), kPose, DebugColors::kStatic, 20.0f, 2));
}

TEST(DebugDraw, APlaneIsASquareOnItsSurface) {
  const Plane plane{glm::normalize(Vec3(0.2f, 1.0f, -0.1f)), 0.5f};
  RecordingDraw draw;
  drawShape(draw, Shape(plane), Transform{}, DebugColors::kStatic, 8.0f);
  ASSERT_EQ(draw.lines.size(), 7u);  // four sides, two diagonals, the normal
  for (int k = 0; k < 6; ++k) {
    for (const Vec3& end : {draw.lines[k].from, draw.lines[k].to})
      EXPECT_NEAR(glm::dot(plane.normal, end), plane.distance, 1e-5f);
  }
  EXPECT_NEAR(glm::length(draw.lines[0].to - draw.lines[0].from), 8.0f, 1e-4f);
}

TEST(WorldDraw, EachPartIsDrawnInItsBodysColour) {
  WorldDef def;
  def.sleeping = true;
  World world(def);
  world.createBody(test::groundBox());  // static: 12 lines
  const BodyId crate = world.createBody(test::boxBody(Vec3(0.0f, 5.0f, 0.0f), Vec3(0.5f), 1.0f));
  BodyDef lift = test::boxBody(Vec3(5.0f, 1.0f, 0.0f), Vec3(0.5f), 1.0f);
  lift.type = BodyType::Kinematic;
  world.createBody(lift);
  BodyDef trigger;
  trigger.type = BodyType::Static;
  PartDef solid, zone;
  solid.shape = Box{Vec3(0.5f)};
  zone.shape = Box{Vec3(1.0f)};
  zone.position = Vec3(0.0f, 2.0f, 0.0f);
  zone.sensor = true;
  trigger.parts = {solid, zone};
  trigger.position = Vec3(-5.0f, 0.5f, 0.0f);
  world.createBody(trigger);
  RecordingDraw draw;
  world.draw(draw);
  EXPECT_EQ(draw.count(DebugColors::kStatic), 24u);  // the ground and the trigger's solid part
  EXPECT_EQ(draw.count(DebugColors::kDynamic), 12u);
  EXPECT_EQ(draw.count(DebugColors::kKinematic), 12u);
  EXPECT_EQ(draw.count(DebugColors::kSensor), 12u);
  EXPECT_EQ(draw.lines.size(), 60u);  // shapes only, by default

  // The crate falls asleep on the ground: its colour says so.
  for (int s = 0; s < 300; ++s) world.step(kDt);
  ASSERT_FALSE(world.isAwake(crate));
  RecordingDraw asleep;
  world.draw(asleep);
  EXPECT_EQ(asleep.count(DebugColors::kSleeping), 12u);
  EXPECT_EQ(asleep.count(DebugColors::kDynamic), 0u);
  world.setEnabled(crate, false);
  RecordingDraw disabled;
  world.draw(disabled);
  EXPECT_EQ(disabled.count(DebugColors::kDisabled), 12u);
}

TEST(WorldDraw, ContactsBoundsJointsAndCentresAreWhatTheWorldHolds) {
  World world;
  world.createBody(test::groundBox());
  const BodyId crate = world.createBody(test::boxBody(Vec3(0.0f, 0.5f, 0.0f), Vec3(0.5f), 2.0f));
  const BodyId ball = world.createBody(test::sphereBody(Vec3(3.0f, 3.0f, 0.0f), 0.2f, 1.0f));
  BodyDef hook = test::sphereBody(Vec3(3.0f, 5.0f, 0.0f), 0.1f, 1.0f);
  hook.type = BodyType::Static;
  DistanceConstraintDef rope;
  rope.a = world.createBody(hook);
  rope.b = ball;
  const JointId joint = world.createDistanceConstraint(rope);
  for (int s = 0; s < 60; ++s) world.step(kDt);

  DebugDrawOptions options;
  options.shapes = false;
  options.contacts = true;
  options.normalLength = 0.4f;
  options.impulseScale = 0.5f;
  RecordingDraw draw;
  world.draw(draw, options);
  int points = 0;
  std::vector<float> impulses;
  world.visitContacts([&](const ContactData& c) {
    points += c.manifold.count;
    for (int p = 0; p < c.manifold.count; ++p) impulses.push_back(c.normalImpulses[p]);
  });
  ASSERT_EQ(points, 4);  // the crate's face on the ground
  EXPECT_EQ(draw.points.size(), 4u);
  EXPECT_EQ(draw.count(DebugColors::kContactNormal), 4u);
  ASSERT_EQ(draw.count(DebugColors::kContactImpulse), 4u);
  float drawn = 0.0f, held = 0.0f;
  for (const Line& l : draw.lines) {
    if (l.color == DebugColors::kContactNormal) {
      EXPECT_NEAR(glm::length(l.to - l.from), 0.4f, 1e-5f);
    }
    if (l.color == DebugColors::kContactImpulse) drawn += glm::length(l.to - l.from);
  }
  for (const float i : impulses) held += 0.5f * i;
  EXPECT_NEAR(drawn, held, 1e-4f * held);
  // The four impulses carry the crate's weight over the step: m g dt.
  EXPECT_NEAR(held / 0.5f, 2.0f * 9.81f * kDt, 0.05f * 2.0f * 9.81f * kDt);

  DebugDrawOptions others;
  others.shapes = false;
  others.bounds = true;
  others.joints = true;
  others.centersOfMass = true;
  RecordingDraw more;
  world.draw(more, others);
  EXPECT_EQ(more.count(DebugColors::kBounds), 4u * 12u);  // ground, crate, ball, hook
  ASSERT_EQ(more.count(DebugColors::kJoint), 1u);
  const auto line = std::find_if(more.lines.begin(), more.lines.end(),
                                 [](const Line& l) { return l.color == DebugColors::kJoint; });
  EXPECT_NEAR(glm::length(line->to - line->from), world.constraintCurrentLength(joint), 1e-5f);
  EXPECT_EQ(more.count(DebugColors::kAxisY), 2u);  // the crate and the ball move; ground and hook do not
  for (const Line& l : more.lines) {
    if (l.color == DebugColors::kAxisY && glm::length(l.from - world.centerOfMass(crate)) < 1e-6f) {
      EXPECT_NEAR(glm::length(l.to - l.from), others.normalLength, 1e-5f);
    }
  }
  EXPECT_EQ(more.count(DebugColors::kJointAxis), 0u);  // a distance constraint has no axis
  DebugDrawOptions bad;
  bad.normalLength = -1.0f;
  EXPECT_COLLIDE_ERROR(world.draw(more, bad));
}

TEST(WorldDraw, JointsDrawTheirAxesAndLimits) {
  // A hinge about z with limits [-0.5, 1], a slider along x with limits [-1, 2] and a cone about x
  // with a 0.4 swing limit: each draws its axis twice (a's and b's) and its limits, every limit
  // point normalLength (the slider: its offset) from anchor A.
  World world;
  const BodyId post = test::staticAnchor(world, Vec3(0.0f));
  const BodyId door = world.createBody(test::boxBody(Vec3(0.5f, 0.0f, 0.0f), Vec3(0.5f, 0.05f, 0.05f), 1.0f));
  const BodyId cart = world.createBody(test::boxBody(Vec3(0.0f, 3.0f, 0.0f), Vec3(0.1f), 1.0f));
  const BodyId arm = world.createBody(test::boxBody(Vec3(0.5f, -3.0f, 0.0f), Vec3(0.5f, 0.05f, 0.05f), 1.0f));
  HingeJointDef hinge{.a = post, .b = door, .anchor = Vec3(0.0f), .axis = Vec3(0.0f, 0.0f, 1.0f)};
  hinge.limits = {true, -0.5f, 1.0f};
  world.createHingeJoint(hinge);
  SliderJointDef slider{
      .a = post, .b = cart, .anchor = Vec3(0.0f, 3.0f, 0.0f), .axis = Vec3(1.0f, 0.0f, 0.0f)};
  slider.limits = {true, -1.0f, 2.0f};
  world.createSliderJoint(slider);
  world.createConeJoint({.a = post, .b = arm, .anchor = Vec3(0.0f, -3.0f, 0.0f), .swingLimit = 0.4f});
  DebugDrawOptions options;
  options.shapes = false;
  options.joints = true;
  RecordingDraw draw;
  world.draw(draw, options);
  EXPECT_EQ(draw.count(DebugColors::kJointAxis), 6u);
  int hingeSpokes = 0, coneRim = 0, sliderMarks = 0;
  for (const Line& l : draw.lines) {
    if (l.color != DebugColors::kJointLimit) continue;
    if (l.from == Vec3(0.0f)) {  // the hinge's two spokes, at the limit angles from frame A's y
      ++hingeSpokes;
      EXPECT_NEAR(glm::length(l.to), options.normalLength, 1e-5f);
      EXPECT_NEAR(l.to.z, 0.0f, 1e-6f);  // in the hinge's plane
    } else if (l.from.y < -2.0f && l.to.y < -2.0f) {
      ++coneRim;  // rim segments and spokes: at the swing angle from the cone's axis (x)
      const Vec3 d = l.to - Vec3(0.0f, -3.0f, 0.0f);
      EXPECT_NEAR(std::acos(d.x / glm::length(d)), 0.4f, 1e-4f);
    } else if (l.from.y > 2.0f) {
      ++sliderMarks;
    }
  }
  EXPECT_EQ(hingeSpokes, 2);
  EXPECT_EQ(coneRim, 12 + 4);
  EXPECT_EQ(sliderMarks, 3);  // two marks across the axis and the range along it
}

}  // namespace
}  // namespace collide
