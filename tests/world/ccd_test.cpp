// Continuous collision in the world (docs/ccd.md): fast small spheres against thin plates and a
// one-triangle mesh over randomised shots, a thin fast-spinning plank against a ball, a fast box
// against a wall, with ccd on and off so the tests show what the time-of-impact pass buys.
#include <collide/world.h>
#include <gtest/gtest.h>

#include "support/test_random.h"
#include "support/world_helpers.h"

#include <cmath>
#include <random>

using namespace collide;
using namespace collide::test;

namespace {

using test::kDt;

using test::randomRotation;

Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (;;) {
    const Vec3 v(n(rng), n(rng), n(rng));
    if (glm::length(v) > 1e-3f) return glm::normalize(v);
  }
}

enum class Target { ThinBox, OneTriangle };

struct Shot {
  Quat plateRotation;
  Vec3 start;
  Vec3 velocity;
  Vec3 normal;  // the plate's normal on the start side
};

// A shot that reaches the plate within the first step: aimed at a point of the plate (within 80%
// of its half size), from the side of `normal`, at 50 to 500 m/s, at least 12 degrees off the plane.
Shot randomShot(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Shot shot;
  shot.plateRotation = randomRotation(rng);
  const Vec3 up = shot.plateRotation * Vec3(0, 1, 0);
  const Vec3 side = shot.plateRotation * Vec3(1, 0, 0);
  const Vec3 forward = shot.plateRotation * Vec3(0, 0, 1);
  shot.normal = u(rng) < 0.5f ? up : -up;
  const Vec3 aim = (u(rng) * 1.6f - 0.8f) * 0.5f * side + (u(rng) * 1.6f - 0.8f) * 0.5f * forward;
  Vec3 direction = randomUnit(rng);
  if (glm::dot(direction, shot.normal) < 0.0f) direction = -direction;
  if (glm::dot(direction, shot.normal) < 0.2f) direction = glm::normalize(direction + 0.3f * shot.normal);
  const float speed = 50.0f + 450.0f * u(rng);
  // Reaches the plate after 10% to 90% of the step's travel.
  const float travel = speed * kDt * (0.1f + 0.8f * u(rng));
  shot.start = aim + travel * direction;
  shot.velocity = -speed * direction;
  return shot;
}

BodyDef plateDef(Target target, const Quat& rotation) {
  BodyDef def;
  def.type = BodyType::Static;
  def.rotation = rotation;
  if (target == Target::ThinBox) {
    def.shape = Shape(Box{Vec3(0.5f, 0.01f, 0.5f)});  // 0.02 thick
  } else {
    // One triangle covering the aim square [-0.4, 0.4]^2 of the x-z plane.
    def.shape = Shape(TriangleMesh::fromTriangles(
        {Vec3(-1.0f, 0, -0.5f), Vec3(1.0f, 0, -0.5f), Vec3(0, 0, 1.5f)}, {MeshTriangle{{0, 2, 1}}}));
  }
  return def;
}

// Whether the centre's move from p to q (world) crosses the plate's mid-plane inside the plate:
// through the 1 x 1 square of the box, or through the triangle. A ball going around the plate's
// edge (after a speculative contact stopped it short and it slid on) crosses outside and does not
// count; a ball whose centre crosses inside has certainly gone through.
bool crossesPlate(Target target, const Quat& rotation, const Vec3& p, const Vec3& q) {
  const Vec3 a = glm::conjugate(rotation) * p;
  const Vec3 b = glm::conjugate(rotation) * q;
  if ((a.y > 0.0f) == (b.y > 0.0f)) return false;
  const float s = a.y / (a.y - b.y);
  const Vec3 x = a + s * (b - a);
  if (target == Target::ThinBox) return std::abs(x.x) <= 0.5f && std::abs(x.z) <= 0.5f;
  // Inside the triangle (-1, 0, -0.5), (1, 0, -0.5), (0, 0, 1.5).
  const auto edge = [&](float ax, float az, float bx, float bz) {
    return (bx - ax) * (x.z - az) - (bz - az) * (x.x - ax);
  };
  const float e0 = edge(-1, -0.5f, 1, -0.5f), e1 = edge(1, -0.5f, 0, 1.5f), e2 = edge(0, 1.5f, -1, -0.5f);
  return (e0 >= 0 && e1 >= 0 && e2 >= 0) || (e0 <= 0 && e1 <= 0 && e2 <= 0);
}

// Fires the shot for two steps; returns whether the ball's centre went through the plate.
bool passesThrough(Target target, const Shot& shot, bool ccd) {
  WorldDef worldDef = zeroGravityWorld();
  worldDef.ccd = ccd;
  World world(worldDef);
  world.createBody(plateDef(target, shot.plateRotation));
  BodyDef ball = sphereBody(shot.start, 0.05f, 0.1f, shot.velocity);
  ball.ccd = true;
  const BodyId id = world.createBody(ball);
  Vec3 previous = shot.start;
  bool crossed = false;
  for (int i = 0; i < 2; ++i) {
    world.step(kDt);
    crossed = crossed || crossesPlate(target, shot.plateRotation, previous, world.centerOfMass(id));
    previous = world.centerOfMass(id);
  }
  return crossed;
}

int countPasses(Target target, int trials, bool ccd, std::uint32_t seed) {
  std::mt19937 rng(seed);
  int passes = 0;
  for (int i = 0; i < trials; ++i) passes += passesThrough(target, randomShot(rng), ccd) ? 1 : 0;
  return passes;
}

}  // namespace

TEST(WorldCcd, FastSmallSphereNeverPassesThinBoxOrTriangle) {
  // 10,000 random shots in all (5,000 per target): radius 0.05 at 50 to 500 m/s.
  EXPECT_EQ(countPasses(Target::ThinBox, 5000, true, 1), 0);
  EXPECT_EQ(countPasses(Target::OneTriangle, 5000, true, 2), 0);
}

TEST(WorldCcd, StraightShotAt300IsStoppedAtTheSurfaceFromBothSidesOfAMesh) {
  for (Target target : {Target::ThinBox, Target::OneTriangle}) {
    for (float side : {1.0f, -1.0f}) {
      for (bool ccd : {true, false}) {
        WorldDef worldDef = zeroGravityWorld();
        worldDef.ccd = ccd;
        World world(worldDef);
        world.createBody(plateDef(target, Quat(1, 0, 0, 0)));
        BodyDef ball = sphereBody(Vec3(0.1f, 3.0f * side, 0.0f), 0.05f, 0.1f, Vec3(0, -300.0f * side, 0));
        ball.ccd = true;
        const BodyId id = world.createBody(ball);
        for (int i = 0; i < 3; ++i) world.step(kDt);
        // Stopped on its own side, resting on the surface (within the slop), whether by the time of
        // impact or by the speculative contact: a straight shot at a convex surface is the case
        // speculative contacts handle alone (docs/ccd.md).
        const float surface = target == Target::ThinBox ? 0.01f : 0.0f;
        EXPECT_NEAR(world.centerOfMass(id).y * side, surface + 0.05f, 0.006f) << ccd << " " << side;
      }
    }
  }
}

TEST(WorldCcd, SpinningThinPlankDoesNotPassTheBallWithCcdAndDoesWithout) {
  // A plank 2 m long and 2 cm thick spins about z at 150 rad/s (143 degrees per step); a static ball
  // of radius 0.1 stands at 60 degrees, 0.8 m from the axis. With ccd the plank stops against the
  // ball; without, its speculative contact (linearised at the step's start) lets it sweep through.
  const auto finalAngles = [](bool ccd) {
    WorldDef worldDef = zeroGravityWorld();
    worldDef.ccd = ccd;
    World world(worldDef);
    BodyDef ball;
    ball.type = BodyType::Static;
    ball.shape = Shape(Sphere{0.1f});
    ball.position = 0.8f * Vec3(std::cos(kPi / 3.0f), std::sin(kPi / 3.0f), 0.0f);
    world.createBody(ball);
    BodyDef plank = boxBody(Vec3(0.0f), Vec3(1.0f, 0.01f, 0.1f), 2.0f);
    plank.angularVelocity = Vec3(0, 0, 150.0f);
    plank.ccd = true;
    const BodyId id = world.createBody(plank);
    float largest = 0.0f;
    for (int i = 0; i < 1; ++i) {
      world.step(kDt);
      const Quat q = world.transform(id).rotation;
      largest = std::max(largest, 2.0f * std::atan2(q.z, q.w));
    }
    return largest;
  };
  const float ballAngle = kPi / 3.0f;
  // The plank's face meets the ball when 0.8 sin(60° - phi) = 0.01 + 0.1 (+ the slop).
  const float contactAngle = ballAngle - std::asin(0.11f / 0.8f);
  const float withCcd = finalAngles(true);
  EXPECT_LT(withCcd, contactAngle + 1e-3f);
  EXPECT_GT(withCcd, contactAngle - 0.02f);  // not stopped early either
  EXPECT_GT(finalAngles(false), ballAngle) << "ccd off: the plank passes the ball (what ccd buys)";
}

TEST(WorldCcd, FastSpinningBoxAgainstThinWall) {
  // A box of half size 0.1 thrown at 200 m/s while spinning at 200 rad/s at a 5 cm wall.
  std::mt19937 rng(5);
  int passesWithout = 0;
  for (int trial = 0; trial < 100; ++trial) {
    for (bool ccd : {true, false}) {
      std::mt19937 shotRng(1000 + trial);
      WorldDef worldDef = zeroGravityWorld();
      worldDef.ccd = ccd;
      World world(worldDef);
      BodyDef wall;
      wall.type = BodyType::Static;
      wall.shape = Shape(Box{Vec3(0.025f, 2.0f, 2.0f)});
      world.createBody(wall);
      BodyDef box = boxBody(Vec3(-1.0f - 2.0f * std::uniform_real_distribution<float>(0, 1)(shotRng), 0, 0),
                            Vec3(0.1f), 1.0f);
      box.rotation = randomRotation(shotRng);
      box.linearVelocity = Vec3(200.0f, 0, 0);
      box.angularVelocity = 200.0f * randomUnit(shotRng);
      box.ccd = true;
      const BodyId id = world.createBody(box);
      bool passed = false;
      for (int i = 0; i < 3; ++i) {
        world.step(kDt);
        passed = passed || world.centerOfMass(id).x > 0.0f;
      }
      if (ccd) {
        EXPECT_FALSE(passed) << "trial " << trial;
      } else {
        passesWithout += passed ? 1 : 0;
      }
    }
  }
  (void)rng;
  EXPECT_GT(passesWithout, 0) << "ccd off: the same throws pass the wall (what ccd buys)";
  RecordProperty("passesWithoutCcd", passesWithout);
  std::printf("fast spinning box vs wall, ccd off: %d of 100 pass\n", passesWithout);
}

TEST(WorldCcd, AgainstKinematicAndDynamicBodies) {
  for (BodyType type : {BodyType::Kinematic, BodyType::Dynamic}) {
    World world(zeroGravityWorld());
    BodyDef plate;
    plate.type = type;
    plate.shape = Shape(Box{Vec3(0.01f, 0.5f, 0.5f)});
    plate.mass = 1.0f;
    plate.linearVelocity = Vec3(-1.0f, 0, 0);  // drifting towards the ball
    plate.angularVelocity = Vec3(3.0f, 0, 0);  // and turning: no exact sweep, conservative advancement
    const BodyId plateId = world.createBody(plate);
    BodyDef ball = sphereBody(Vec3(-2.0f, 0.05f, 0.0f), 0.05f, 0.01f, Vec3(400.0f, 0, 0));
    ball.ccd = true;
    const BodyId ballId = world.createBody(ball);
    for (int i = 0; i < 3; ++i) {
      world.step(kDt);
      EXPECT_LT(world.centerOfMass(ballId).x, world.centerOfMass(plateId).x)
          << toString(type) << " step " << i;
    }
  }
}

TEST(WorldCcd, HitWithoutBouncinessAddsNoKineticEnergy) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 200; ++trial) {
    const Shot shot = randomShot(rng);
    World world(zeroGravityWorld());
    world.createBody(plateDef(Target::ThinBox, shot.plateRotation));
    BodyDef ball = sphereBody(shot.start, 0.05f, 0.1f, shot.velocity);
    ball.ccd = true;
    ball.bounciness = 0.0f;
    const BodyId id = world.createBody(ball);
    float energy = world.kineticEnergy();
    for (int i = 0; i < 3; ++i) {
      world.step(kDt);
      const float now = world.kineticEnergy();
      EXPECT_LE(now, energy * (1.0f + 1e-5f)) << "trial " << trial << " step " << i;
      energy = now;
    }
    (void)id;
  }
}

TEST(WorldCcd, FlagsDefaultAndWorldSwitch) {
  EXPECT_FALSE(BodyDef{}.ccd);
  EXPECT_TRUE(WorldDef{}.ccd);
  // The spinning plank is the case only the time of impact catches. With the world switch on, every
  // body is stopped by static geometry; only a body flagged ccd is stopped by a moving (here
  // kinematic, held still) one. With the world switch off, nothing is.
  struct Variant {
    bool worldCcd;
    bool bodyCcd;
    BodyType obstacle;
    bool stopped;
  };
  const Variant variants[] = {
      {true, true, BodyType::Static, true},    {false, true, BodyType::Static, false},
      {true, false, BodyType::Static, true},   {true, false, BodyType::Kinematic, false},
      {true, true, BodyType::Kinematic, true}, {false, false, BodyType::Static, false},
  };
  for (const Variant& v : variants) {
    SCOPED_TRACE(::testing::Message() << "world " << v.worldCcd << ", body " << v.bodyCcd << ", obstacle "
                                      << toString(v.obstacle));
    WorldDef worldDef = zeroGravityWorld();
    worldDef.ccd = v.worldCcd;
    World world(worldDef);
    BodyDef ball;
    ball.type = v.obstacle;
    ball.shape = Shape(Sphere{0.1f});
    ball.position = 0.8f * Vec3(std::cos(kPi / 3.0f), std::sin(kPi / 3.0f), 0.0f);
    world.createBody(ball);
    BodyDef plank = boxBody(Vec3(0.0f), Vec3(1.0f, 0.01f, 0.1f), 2.0f);
    plank.angularVelocity = Vec3(0, 0, 150.0f);
    plank.ccd = v.bodyCcd;
    const BodyId id = world.createBody(plank);
    world.step(kDt);
    const Quat q = world.transform(id).rotation;
    const bool stopped = 2.0f * std::atan2(q.z, q.w) < kPi / 3.0f;
    EXPECT_EQ(stopped, v.stopped);
  }
}

TEST(WorldCcd, WithoutCcdSomeOfTheSameShotsPass) {
  // The first 2,000 shots of each target above, with the world's ccd off: speculative contacts
  // alone let some through (measured: 74 through the box, 185 through the triangle; the friction
  // of the first contact spins the ball, and the solver's separation, linearised with anchors that
  // turn with the ball, then reads a gap that is not there, docs/ccd.md).
  const int box = countPasses(Target::ThinBox, 2000, false, 1);
  const int triangle = countPasses(Target::OneTriangle, 2000, false, 2);
  std::printf("ccd off: %d of 2000 shots pass the thin box, %d the triangle\n", box, triangle);
  EXPECT_GT(box, 0);
  EXPECT_GT(triangle, 0);
  RecordProperty("passesThinBox", box);
  RecordProperty("passesTriangle", triangle);
}
